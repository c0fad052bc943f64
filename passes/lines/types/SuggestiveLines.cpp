#include "passes/lines/types/SuggestiveLines.h"

#include "graph/Milliseconds.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/lines/LineType.h"
#include "scene/MessageText.h"
#include "scene/mesh/MeshCurvature.h"
#include "scene/mesh/ObjectSuggestiveContours.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

using line_parameters::kDepthJump;
using line_parameters::kSuggestiveFade;
using line_parameters::kSuggestiveSeed;
using line_parameters::kSuggestiveThreshold;

/** Points of the image-space central differences: 3 (fast) or 5 (fourth order). */
const LineParameter kSuggestiveStencil{
    "suggestive-stencil",
    "N",
    "3 (default) or 5-point central differences; 5 is fourth order, more exact on clean\n"
    "data, slower, and needs two pixels of one surface on each side",
    {"3", "5"},
    std::nullopt,
    "3",
    0.0,
    0.0,
    false,
    false,
    ""};

/** Per data pixel, the smoothing's working memory for render/MemoryBudget (postfx/SuggestiveContours.cpp): the scanner
 *  smooths rows as it reads them, so only rings of rows around each band's current row are held, about a byte per
 *  pixel. Measured: +2 MiB at 2048^2 data pixels at the default smoothing, +4 MiB at 0.02. The 5-point stencil
 *  differentiates the whole smoothed field (smoothRadialField()), 4 floats per pixel more. */
constexpr std::size_t kSmoothingBytesPerPixel = 1;
constexpr std::size_t kSmoothedFieldBytesPerPixel = 16;

/** The image-space smoothing's sigma, as a fraction of the bounding radius. */
const LineParameter kSuggestiveSmoothing{
    "suggestive-smoothing",
    "S",
    "smooth the surface's n.v and w over a Gaussian of sigma S x the bounding radius\n"
    "(on the surface, not across depth breaks) before differentiating, so the lines\n"
    "follow the shape, not facets or scan noise, alike at every resolution (default {default};\n"
    "0: none)",
    {},
    kSuggestiveSmoothingFraction,
    "",
    0.0,
    1.0,
    false,
    false,
    "expected a fraction of the bounding radius from 0 to 1"};

/** The band kept clear of surface ends, in sigmas of the image-space smoothing. */
const LineParameter kSuggestiveClearance{
    "suggestive-clearance",
    "K",
    "with smoothing, drop lines within K x its sigma of where their surface ends\n"
    "(an outline, an occlusion or the image's edge), where its window sees one\n"
    "side only: the same band of surface at every resolution; lines hold better\n"
    "across sizes, a little worse across small turns (default {default}: none; try 2)",
    {},
    double(SuggestiveSettings{}.breakClearance),
    "",
    0.0,
    100.0,
    false,
    false,
    "expected a number of sigmas from 0 to 100"};

/** The band kept clear of where a smooth patch meets another, in sigmas of the image-space smoothing. */
const LineParameter kSuggestivePatchClearance{
    "suggestive-patch-clearance",
    "K",
    "with smoothing, drop lines within K x its sigma of where their smooth patch meets\n"
    "another (parts that overlap or are set into one another, hard edges), where its\n"
    "window sees one side only and no line runs on: such pieces came and went with\n"
    "the size (default {default}; 0: none)",
    {},
    double(SuggestiveSettings{}.patchClearance),
    "",
    0.0,
    100.0,
    false,
    false,
    "expected a number of sigmas from 0 to 100"};

/** The least angle between a line and the image's w direction (SuggestiveSettings::minAngleToW). */
const LineParameter kSuggestiveMinAngle{"suggestive-min-angle",
                                        "DEG",
                                        "drop lines where they run within DEG degrees of the view's direction w\n"
                                        "across the surface: there the sign of D_w D_w(n.v) is a small difference\n"
                                        "of large ones that the pixel grid decides, so such lines come and go with\n"
                                        "the size and a small turn (default {default}; 0: every line DeCarlo et al.'s\n"
                                        "test passes)",
                                        {},
                                        double(kSuggestiveMinAngleToWDegrees),
                                        "",
                                        0.0,
                                        89.0,
                                        false,
                                        false,
                                        "expected degrees from 0 to 89"};

/** The object-space curvature smoothing's sigma, as a fraction of the bounding radius. */
const LineParameter kSuggestiveObjectSmoothing{
    "suggestive-object-smoothing",
    "S",
    "smooth the mesh's normals, curvature and its derivative over a Gaussian of sigma\n"
    "S x the bounding radius on the surface (rtsc's diffusion) before finding lines\n"
    "(default {default}; 0: none). One whose windows would take more than about a minute, each\n"
    "window over a sixteenth of its mesh, fails the still at once, naming one that fits",
    {},
    kSuggestiveObjectSmoothingFraction,
    "",
    0.0,
    1.0,
    false,
    false,
    "expected a fraction of the bounding radius from 0 to 1"};

/** Per data pixel, the 5-point stencil's maps (postfx/SuggestiveContours.cpp: dw, dwdw and the normal distance as
 *  float, two byte masks): working memory beyond the stroke's, for render/MemoryBudget. */
constexpr std::size_t kWideStencilBytesPerPixel = 14;

/** The settings both types share; featureSize in model units. */
SuggestiveSettings sharedSettings(const Look& look, const BoundingSphere& sphere) {
    SuggestiveSettings settings;
    settings.depthJump = float(look.lineParameters.number(kDepthJump));
    settings.threshold = float(look.lineParameters.number(kSuggestiveThreshold));
    settings.fade = float(look.lineParameters.number(kSuggestiveFade));
    settings.featureSize = float(kSuggestiveFeatureSizeFraction * sphere.radius);
    return settings;
}

/** Hysteresis for the stroke stage: the drawn strength (q - T) / (q - T + F) of a line at the seed Q. */
LineTypeStrokeRules seedRules(const Look& look) {
    const double threshold = look.lineParameters.number(kSuggestiveThreshold);
    const double fade = look.lineParameters.number(kSuggestiveFade);
    const double seed = look.lineParameters.number(kSuggestiveSeed);
    LineTypeStrokeRules rules;
    if (seed > threshold)
        rules.seedStrength = fade > 0.0 ? float((seed - threshold) / (seed - threshold + fade)) : 1.0f;
    return rules;
}

/** Per data pixel, the surface ids the kernel makes from the triangle ids (one float). */
constexpr std::size_t kSurfaceIdBytesPerPixel = 4;

/** The settings both types report; feature_size in model units, as the kernel holds it (in float). */
void describeShared(const LineStatsSource& source, nlohmann::ordered_json& entry, bool imageSpace) {
    const SuggestiveSettings settings = sharedSettings(source.look, source.sphere);
    entry["depth_jump"] = source.look.lineParameters.number(kDepthJump);
    entry["supersample"] = source.look.supersample;
    entry["threshold"] = settings.threshold;
    entry["fade"] = settings.fade;
    entry["seed"] = source.look.lineParameters.number(kSuggestiveSeed);
    const double featureSize = kSuggestiveFeatureSizeFraction * source.sphere.radius;
    const double unit = source.radialLengthUnit;
    entry["feature_size"] = imageSpace ? double(float(featureSize / unit)) * unit : double(float(featureSize));
}

/** Per covered pixel (depth > 0), the smooth patch of its triangle (`patchOfTriangle`, GpuScene::SurfacePatches);
 *  0 elsewhere, where the G-buffer may have left the triangle ids uncleared. Each row's work is its covered span (the
 *  background around it only zeroed): about 1 ms at 1024^2 on one core, which is why it is not split over threads
 *  (waking OpenCV's pool cost as much). */
cv::Mat surfaceIdsOf(const cv::Mat& triangleIds, const cv::Mat& depth, const std::vector<float>& patchOfTriangle) {
    cv::Mat surface(triangleIds.size(), CV_32FC1);
    const float triangles = float(patchOfTriangle.size());
    bool outOfRange = false;
    for (int row = 0; row < triangleIds.rows; ++row) {
        const float* ids = triangleIds.ptr<float>(row);
        const float* z = depth.ptr<float>(row);
        float* out = surface.ptr<float>(row);
        int begin = 0;
        int end = triangleIds.cols;
        while (begin < end && !(z[begin] > 0.0f)) ++begin;
        while (end > begin && !(z[end - 1] > 0.0f)) --end;
        std::fill(out, out + begin, 0.0f);
        std::fill(out + end, out + triangleIds.cols, 0.0f);
        for (int col = begin; col < end; ++col) {
            // An id the G-buffer wrote is an exact float in [1, triangles]; anything else is a bug upstream.
            const float id = z[col] > 0.0f ? ids[col] : 0.0f;
            outOfRange |= !(id >= 0.0f && id < triangles);
            out[col] = outOfRange ? 0.0f : patchOfTriangle[std::size_t(id)];
        }
    }
    if (outOfRange)
        throw std::logic_error("SuggestiveKernel::find(): 'triangleId' holds an id beyond the scene's " +
                               std::to_string(patchOfTriangle.size() - 1) + " triangles");
    return surface;
}

} // namespace

int suggestiveFieldDivisor(int width, int height) {
    if (width < 1 || height < 1)
        throw std::invalid_argument("suggestiveFieldDivisor(): the picture's sides must be at least 1, got " +
                                    std::to_string(width) + "x" + std::to_string(height));
    for (int divisor = height / kSuggestiveFieldMinRows; divisor > 1; --divisor)
        if (height % divisor == 0 && width % divisor == 0) return divisor;
    return 1;
}

std::vector<std::string> SuggestiveKernel::inputs() const {
    std::vector<std::string> names{mGBuffer + ".radial", mGBuffer + ".depth"};
    if (mSurfaces) names.push_back(mGBuffer + ".triangleId");
    return names;
}

void SuggestiveKernel::describe(nlohmann::ordered_json& entry) const {
    entry["surface_ids"] = mSurfaces != nullptr;
    if (mSurfaces && mSurfaces->surfacePatchesComputed()) entry["seam_edges"] = mSurfaces->surfacePatches().seamEdges;
}

std::vector<std::string> SuggestiveKernel::sceneImports() const {
    if (!mSurfaces) return {};
    return {SceneImport::kSurfacePatches};
}

std::size_t SuggestiveKernel::scratchBytesPerPixel() const {
    const bool wide = mSettings.stencil == DifferenceStencil::Central5;
    const std::size_t smoothing =
        mSettings.smoothing > 0.0f ? kSmoothingBytesPerPixel + (wide ? kSmoothedFieldBytesPerPixel : 0) : 0;
    return (wide ? kWideStencilBytesPerPixel : 0) + smoothing + (mSurfaces ? kSurfaceIdBytesPerPixel : 0);
}

LineSkeleton SuggestiveKernel::find(const std::vector<cv::Mat>& inputs) {
    SuggestiveSettings settings = mSettings;
    // The data image may be supersampled: its own height gives its focal length in pixels.
    settings.focalPixels =
        float(0.5 * double(inputs[1].rows) / std::tan(0.5 * glm::radians(mFrame.camera.fovYDegrees)));
    if (!mSurfaces) return extractSuggestiveContours(inputs[0], inputs[1], settings);
    const cv::Mat surface = surfaceIdsOf(inputs[2], inputs[1], mSurfaces->surfacePatches().patchOfTriangle);
    return extractSuggestiveContours(inputs[0], inputs[1], settings, surface);
}

void ObjectSuggestiveKernel::prepare() {
    mReport.curvatureDerived = false;
    mReport.curvatureMilliseconds = 0.0;
    if (mScene.meshCurvatureComputed(mCurvatureSmoothing)) return;
    const auto start = std::chrono::steady_clock::now();
    try {
        for (std::size_t mesh = 0; mesh < mScene.meshCount(); ++mesh) mScene.meshCurvature(mesh, mCurvatureSmoothing);
    } catch (const SmoothingTooCostlyError& costly) {
        // The model's fault as much as the flag's (the same smoothing is cheap on a smaller mesh): a failed still,
        // exit 3, and a batch goes on with its next model.
        const double fits = mSmoothingShare * costly.smoothingWithinLimit() / costly.smoothing();
        throw SceneError(
            "ObjectSuggestiveKernel::prepare(): --suggestive-object-smoothing " +
            detail::formatNumber(mSmoothingShare) + " is too wide for this model: its windows would hold about " +
            detail::formatNumber(std::round(costly.estimatedVisits() / double(costly.vertexCount()))) +
            " vertices each, over a sixteenth of their mesh (" + std::to_string(costly.vertexCount()) +
            " vertices in all; " + detail::formatExtent(costly.estimatedVisits()) + " visits, over the limit of " +
            detail::formatExtent(kMaxSmoothingVisits) + ", about a minute on two cores); " +
            (fits > 0.0 ? "about " + detail::formatExtent(fits) + " or less fits, or 0 for none" : "give 0 for none"));
    }
    mReport.curvatureDerived = true;
    mReport.curvatureMilliseconds = millisecondsSince(start);
}

void ObjectSuggestiveKernel::describe(nlohmann::ordered_json& entry) const {
    // The curvature is derived once per scene, before the pass's clock (in prepare): kernel_ms is per view.
    entry["segments"] = mReport.segments;
    entry["curvature_derived"] = mReport.curvatureDerived;
    entry["curvature_ms"] = mReport.curvatureMilliseconds;
}

LineSkeleton ObjectSuggestiveKernel::find(const std::vector<cv::Mat>& inputs) {
    mReport.segments = 0;
    ObjectSuggestiveSettings settings;
    settings.featureSize = mSettings.featureSize;
    settings.threshold = mSettings.threshold;
    settings.fade = mSettings.fade;
    SegmentProjector projector(mFrame.camera, inputs[0], double(mSettings.depthJump), mKeep);
    for (std::size_t mesh = 0; mesh < mScene.meshCount(); ++mesh) {
        const MeshCurvature& curvature = mScene.meshCurvature(mesh, mCurvatureSmoothing);
        const std::vector<SuggestiveSegment> segments =
            extractObjectSuggestiveContours(curvature, mFrame.camera.eye, settings);
        mReport.segments += segments.size();
        for (const SuggestiveSegment& segment : segments)
            projector.add(segment.ends[0], segment.ends[1], segment.strengths[0], segment.strengths[1], int(mesh),
                          long(curvature.sourceFace[segment.face]));
    }
    return projector.take();
}

LineType suggestiveLineType() {
    LineType type;
    type.name = "suggestive";
    type.help = "suggestive contours (DeCarlo et al. 2003): D_w(n.v) = 0 with D_w D_w(n.v) > 0,\n"
                "in the float G-buffer with v = c - p, so the lines are where kappa_r = 0";
    type.strokeRules = seedRules;
    type.parameters = {&kDepthJump,           &kSuggestiveThreshold,      &kSuggestiveFade,
                       &kSuggestiveSeed,      &kSuggestiveStencil,        &kSuggestiveSmoothing,
                       &kSuggestiveClearance, &kSuggestivePatchClearance, &kSuggestiveMinAngle};
    type.build = [](const std::string& name, LineGraphBuilder& builder) {
        const LineGraphSetup& setup = builder.setup();
        SuggestiveSettings settings = sharedSettings(setup.look, setup.sphere);
        // gbuffer.radial is in units of the bounding radius (FrameParams::radialLengthUnit), so fs is too.
        settings.featureSize =
            float(kSuggestiveFeatureSizeFraction * setup.sphere.radius / setup.frame.radialLengthUnit);
        if (setup.look.lineParameters.choice(kSuggestiveStencil) == "5") settings.stencil = DifferenceStencil::Central5;
        // In model units, like the depth it is converted to pixels with.
        settings.smoothing = float(setup.look.lineParameters.number(kSuggestiveSmoothing) * setup.sphere.radius);
        settings.breakClearance = float(setup.look.lineParameters.number(kSuggestiveClearance));
        settings.patchClearance = float(setup.look.lineParameters.number(kSuggestivePatchClearance));
        settings.minAngleToW = float(setup.look.lineParameters.number(kSuggestiveMinAngle));
        // Which crossings the kernel finds, and which of its short pieces the stroke rules keep, change with the
        // sampling of the surface (docs/strokes.md, "one sampling at every size"): from 2048 rows up it samples as at
        // 1024-2047, on a G-buffer of its own, and the strokes are drawn at the picture's size from its points.
        const int divisor = suggestiveFieldDivisor(setup.frame.camera.width, setup.frame.camera.height);
        GpuScene* surfaces = setup.scene.surfacesMeet() ? &setup.scene : nullptr;
        if (divisor == 1) {
            builder.addLayer(name, std::make_unique<SuggestiveKernel>(setup.gbuffer, settings, setup.frame, surfaces));
            return;
        }
        auto kernel = std::make_unique<SuggestiveKernel>(kSuggestiveFieldPass, settings, setup.frame, surfaces);
        auto field = std::make_unique<GBufferPass>(kSuggestiveFieldPass, setup.shaders, setup.scene, setup.frame,
                                                   setup.look.supersample, setup.look.gbufferPrecision, divisor);
        std::vector<std::string> read;
        for (const std::string& input : kernel->inputs()) read.push_back(ResourceName::split(input).field);
        field->declareOnly(std::move(read));
        builder.add(std::move(field));
        builder.addLayer(name, std::move(kernel), divisor);
    };
    type.describe = [](const LineStatsSource& source, nlohmann::ordered_json& entry) {
        describeShared(source, entry, true);
        entry["min_sin_theta"] = SuggestiveSettings{}.minSinTheta;
        entry["clearance"] = source.look.lineParameters.number(kSuggestiveClearance);
        entry["patch_clearance"] = source.look.lineParameters.number(kSuggestivePatchClearance);
        entry["min_angle_to_w"] = source.look.lineParameters.number(kSuggestiveMinAngle);
        entry["stencil_points"] = source.look.lineParameters.choice(kSuggestiveStencil) == "5" ? 5 : 3;
        entry["smoothing"] = source.look.lineParameters.number(kSuggestiveSmoothing) * source.sphere.radius;
    };
    return type;
}

namespace {

/** suggestive-object, or with `keep` Hidden its occluded part (hidden-suggestive-object). */
LineType objectSuggestiveType(std::string name, std::string help, SegmentVisibility keep) {
    LineType type;
    type.name = std::move(name);
    type.family = LineFamily::ObjectSpace;
    type.help = std::move(help);
    type.hiddenLines = keep == SegmentVisibility::Hidden;
    type.strokeRules = seedRules;
    type.parameters = {&kDepthJump, &kSuggestiveThreshold, &kSuggestiveFade, &kSuggestiveSeed,
                       &kSuggestiveObjectSmoothing};
    type.build = [keep](const std::string& typeName, LineGraphBuilder& builder) {
        const LineGraphSetup& setup = builder.setup();
        const double smoothing = setup.look.lineParameters.number(kSuggestiveObjectSmoothing) * setup.sphere.radius;
        builder.addLayer(typeName,
                         std::make_unique<ObjectSuggestiveKernel>(
                             setup.gbuffer, sharedSettings(setup.look, setup.sphere), smoothing, setup.scene,
                             setup.frame, keep, setup.look.lineParameters.number(kSuggestiveObjectSmoothing)));
    };
    type.describe = [](const LineStatsSource& source, nlohmann::ordered_json& entry) {
        describeShared(source, entry, false);
        entry["curvature_smoothing"] =
            source.look.lineParameters.number(kSuggestiveObjectSmoothing) * source.sphere.radius;
    };
    return type;
}

} // namespace

LineType suggestiveObjectLineType() {
    return objectSuggestiveType("suggestive-object",
                                "the same lines found on the mesh (object space): the zero set of\n"
                                "kappa_r from per-vertex curvature (Rusinkiewicz 2004) and rtsc's per-view test,\n"
                                "projected, hidden by the G-buffer depth (within --depth-jump), sub-pixel exact",
                                SegmentVisibility::Visible);
}

LineType hiddenSuggestiveObjectLineType() {
    return objectSuggestiveType("hidden-suggestive-object",
                                "the occluded part of suggestive-object's lines: the same samples,\n"
                                "kept where the G-buffer depth hides them (beyond --depth-jump)",
                                SegmentVisibility::Hidden);
}

} // namespace inkgraph
