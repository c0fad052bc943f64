#include "passes/StillGraph.h"

#include "graph/GraphCompiler.h"
#include "passes/composite/CompositePass.h"
#include "passes/composite/GpuCompositePass.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/lines/LineLayerPass.h"
#include "passes/lines/LineTypes.h"
#include "passes/lines/StrokesPass.h"
#include "passes/mtoon/MToonOutlinePass.h"
#include "passes/orientation/SceneOrientation.h"
#include "passes/shade/ShadePass.h"
#include "scene/MeshLabels.h"
#include "scene/MessageText.h"

#include <nlohmann/json.hpp>

#include <algorithm>

namespace inkgraph {
namespace {

using Json = nlohmann::ordered_json;

cv::Vec4f displayColor(const glm::dvec4& color) {
    return cv::Vec4f(float(color.r), float(color.g), float(color.b), float(color.a));
}

/** MToon's outlines as a layer of their own (passes/mtoon/MToonOutlinePass.h), registered whenever the model draws
 *  the materials' outlines. Returns the layer the shade pass is to read: the pass's name when some material asks
 *  for an outline, else empty, and the unread pass is culled. */
std::string addMToonOutline(const StillGraphSetup& setup, StillGraph& graph) {
    if (!traitsOf(graph.shadingModel).materialOutlines) return {};
    graph.passes.push_back(std::make_unique<MToonOutlinePass>(
        kMToonOutlinePass, setup.shaders, setup.gpuScene, setup.frame, setup.look.msaa, setup.look.outlineWidthMap));
    return MToonOutlinePass::drawsAnyOutline(setup.gpuScene.scene()) ? kMToonOutlinePass : "";
}

/** The shading model's pass, when it has one (else null), laying in the layer of material outlines `outlines` names
 *  (addMToonOutline()); fills the graph's shading facts. */
ShadePass* addShading(const StillGraphSetup& setup, StillGraph& graph, const std::string& outlines,
                      const GBufferPass& gbuffer) {
    const Look& look = setup.look;
    const ShadingModelTraits& traits = traitsOf(graph.shadingModel);
    if (traits.define == nullptr) return nullptr; // none: paper and lines only
    ShadeSettings settings;
    settings.model = graph.shadingModel;
    settings.shininess = look.shininess;
    settings.materialOutlines = outlines;
    settings.msaa = look.msaa;
    // Deferred where the G-buffer runs anyway: the shade pass asks the compiler (ShadePass::forwardReason()).
    if (setup.allowDeferredShading)
        settings.deferred = {std::string(gbuffer.name()), gbuffer.supersample(), gbuffer.precision()};
    if (traits.faceOrientation) {
        settings.view =
            chooseViewVector(look.viewVector, setup.frame.camera.eye, setup.sphere.center, setup.sphere.radius);
        settings.faceOrientation = look.faceOrientation;
    }
    std::optional<ShadeMap> shadeMap = setup.shadeMap;
    if (!shadeMap && traits.bands) shadeMap = makeBandShadeMap(look.bands.value_or(5));
    if (!shadeMap && traits.shadeMap) shadeMap = makeDefaultComicShadeMap();
    if (shadeMap) graph.shadeMapSource = shadeMap->source;
    if (traits.shadeMap) {
        // Per-mesh maps replace the run's map on their meshes; the models without a map have nothing to replace.
        settings.meshShadeMaps = setup.meshShadeMaps;
        for (std::size_t i = 0; i < setup.meshShadeMaps.size() && i < setup.scene.meshes.size(); ++i)
            if (setup.meshShadeMaps[i])
                graph.meshShadeMapSources.emplace_back(setup.scene.meshes[i].name, setup.meshShadeMaps[i]->source);
    }
    auto pass =
        std::make_unique<ShadePass>("shade", setup.shaders, setup.gpuScene, setup.frame, settings, std::move(shadeMap));
    ShadePass* shade = pass.get();
    graph.passes.push_back(std::move(pass));
    graph.shadingResource = "shade.color";
    return shade;
}

} // namespace

OrientationSettings orientationSettingsOf(const Look& look) {
    // The face-orientation methods (Winnemöller & Bangay 2002) are comic's; the others draw with GPU culling.
    OrientationSettings orientation;
    orientation.method =
        traitsOf(look.shading).faceOrientation ? look.faceOrientation : FaceOrientationMethod::Standard;
    orientation.viewVector = look.viewVector;
    orientation.frontRule = look.frontRule;
    orientation.shininess = look.shininess;
    return orientation;
}

std::unique_ptr<GpuScene> makeSceneImport(const Scene& scene, glm::dvec3 worldOrigin, const FrameParams& frame,
                                          const Look& look, std::shared_ptr<SceneDerivedData> derived) {
    auto gpuScene = std::make_unique<GpuScene>(scene, worldOrigin, std::move(derived));
    gpuScene->setOrientation(frame, orientationSettingsOf(look));
    gpuScene->materials().setTime(frame.time);
    return gpuScene;
}

std::vector<const Pass*> StillGraph::view() const {
    std::vector<const Pass*> result;
    for (const auto& pass : passes) result.push_back(pass.get());
    return result;
}

std::vector<GlPass*> StillGraph::mutableView() const {
    std::vector<GlPass*> result;
    for (const auto& pass : passes) result.push_back(pass.get());
    return result;
}

const Pass* StillGraph::findPass(std::string_view name) const {
    for (const auto& pass : passes)
        if (pass->name() == name) return pass.get();
    return nullptr;
}

StillGraph buildStillGraph(const StillGraphSetup& setup) {
    const Look& look = setup.look;
    StillGraph graph;
    graph.mLook = &look;
    graph.mSphere = setup.sphere;
    graph.mRadialLengthUnit = setup.frame.radialLengthUnit;
    graph.shadingModel = shadingModelFor(look.shading, setup.scene);
    graph.postStageDevice = resolvePostStage(look.postStage, setup.glRenderer);

    auto gbufferPass = std::make_unique<GBufferPass>(kGBufferPass, setup.shaders, setup.gpuScene, setup.frame,
                                                     look.supersample, look.gbufferPrecision);
    const GBufferPass& gbuffer = *gbufferPass;
    graph.passes.push_back(std::move(gbufferPass));
    graph.mShade = addShading(setup, graph, addMToonOutline(setup, graph), gbuffer);

    // Every line type registers its passes, drawn or not: one the composite does not read is culled, and --stats
    // says so.
    LineGraphSetup lineSetup{look, setup.shaders, setup.gpuScene, setup.frame, setup.sphere};
    lineSetup.postStage = graph.postStageDevice;
    // The silhouette tests its hull against the G-buffer's z-buffer instead of a depth of its own when the G-buffer
    // runs anyway (it asks the compiler), at the mask's size (no supersampling), and its z-buffer holds every face the
    // silhouette would draw (GBufferPass::zBufferHoldsEveryFace()): one draw of the meshes fewer, the same mask
    // (SilhouetteGLTest).
    if (gbuffer.supersample() == 1 && gbuffer.zBufferHoldsEveryFace())
        lineSetup.modelDepth = std::string(gbuffer.name()) + "." + GBufferPass::kZBuffer;
    LineGraphBuilder builder(lineSetup, graph.passes);
    for (const LineType& type : lineTypes()) type.build(type.name, builder);
    graph.mLineLayers = builder.finish();

    // Every drawn type's lines become strokes together, and the composite draws the strokes.
    std::vector<CompositePass::LineInput> lines;
    StrokesPassSettings strokes;
    strokes.supersample = look.supersample;
    for (const LineType& type : lineTypes()) {
        if (!look.draws(type.name)) continue;
        StrokeInput input;
        input.type = type.name;
        input.skeleton = graph.mLineLayers.count(type.name) != 0;
        input.resource = type.name + (input.skeleton ? ".skeleton" : ".lines");
        input.widthPixels = float(look.styleOf(type.name).widthPixels);
        const LineTypeStrokeRules rules = type.strokeRules ? type.strokeRules(look) : LineTypeStrokeRules{};
        input.minLength = look.strokes.minLength;
        input.seedStrength = rules.seedStrength;
        input.bandOfOneWidth = !input.skeleton && rules.bandOfOneWidth;
        input.bandWidthInModelUnits = !input.skeleton && rules.bandWidthInModelUnits;
        input.dashed = type.hiddenLines;
        strokes.inputs.push_back(input);
        lines.push_back({std::string(kStrokesPass) + "." + type.name, displayColor(look.styleOf(type.name).color)});
    }
    if (!strokes.inputs.empty()) {
        strokes.weightByDepth = look.strokes.weightByDepth;
        strokes.depthResource = std::string(kGBufferPass) + "." + GBufferPass::kDepth;
        strokes.weightByStrength = look.strokes.weightByStrength;
        strokes.taperEnds = look.strokes.taperEnds;
        strokes.mergeOverlaps = look.strokes.mergeOverlaps;
        strokes.dash = {look.strokes.hiddenDashOn, look.strokes.hiddenDashOff};
        const double eyeToCentre = glm::length(setup.frame.camera.eye - setup.sphere.center);
        strokes.nearDepth = std::max(eyeToCentre - setup.sphere.radius, 0.0);
        strokes.farDepth = eyeToCentre + setup.sphere.radius;
        auto pass = std::make_unique<StrokesPass>(kStrokesPass, std::move(strokes));
        graph.mStrokes = pass.get();
        graph.passes.push_back(std::move(pass));
    }
    // The composite goes to the GPU only when asked for by name: its stroke layers are CPU images and its picture is
    // read back to be encoded anyway, and a plan that ends on the GPU has no host tail for a batch to run on a worker
    // while the next still draws (Plan::hostTailStart()).
    if (setup.look.postStage == PostStageDevice::Gpu)
        graph.passes.push_back(std::make_unique<GpuCompositePass>("composite", setup.shaders, setup.frame,
                                                                  graph.shadingResource, std::move(lines)));
    else
        graph.passes.push_back(
            std::make_unique<CompositePass>("composite", setup.frame, graph.shadingResource, std::move(lines)));
    return graph;
}

Plan StillGraph::compilePlan(const std::vector<std::string>& requested) const {
    return compile(view(), requested, {finalResource});
}

std::string StillGraph::shadingModeIn(const Plan& plan) const {
    if (!mShade) return {};
    return mShade->modeIn(plan) == ShadeMode::Deferred ? "deferred" : "forward";
}

std::string StillGraph::shadingForwardReasonIn(const Plan& plan) const {
    return mShade ? mShade->forwardReasonIn(plan) : std::string();
}

std::string StillGraph::describeShading(const Plan& plan) const {
    const std::string mode = shadingModeIn(plan);
    if (mode.empty()) return {};
    const std::string reason = shadingForwardReasonIn(plan);
    return "shading: " + mode + (reason.empty() ? "" : " (" + reason + ")") + "\n";
}

Json StillGraph::describeLines() const {
    Json lines = Json::array();
    const LineStatsSource source{*mLook, mSphere, mRadialLengthUnit,
                                 [this](std::string_view name) { return findPass(name); }};
    for (const LineType& type : lineTypes()) {
        if (!mLook->draws(type.name)) continue;
        const LineStyle style = mLook->styleOf(type.name);
        Json line = {{"type", type.name},
                     {"width_pixels", style.widthPixels},
                     {"color", Json::array({style.color.r, style.color.g, style.color.b, style.color.a})}};
        if (type.describe) type.describe(source, line);
        // Every hidden-lines type is dashed alike (--hidden-dash; off 0: solid).
        if (type.hiddenLines)
            line["dash_pixels"] = {{"on", mLook->strokes.hiddenDashOn}, {"off", mLook->strokes.hiddenDashOff}};
        lines.push_back(line);
    }
    return lines;
}

std::vector<Warning> StillGraph::lineWarnings() const {
    std::vector<Warning> warnings;
    for (const Json& line : describeLines()) {
        if (!line.value("skipped_eye_inside", false)) continue;
        const std::string type = line.value("type", std::string());
        warnings.push_back(makeWarning(
            WarningKind::LinesSkipped,
            "the " + type + " lines are not drawn: the eye is inside the model" +
                (type == "silhouette" ? " or the silhouette's hull" : "") +
                ", where their bands would cover the whole picture; move the eye out (--eye, --orbit) or draw contour "
                "lines, which need no outside"));
    }
    return warnings;
}

std::vector<Warning> StillGraph::emptyLineWarnings() const {
    std::vector<Warning> warnings;
    if (mStrokes == nullptr || mLook == nullptr) return warnings;
    const std::vector<StrokeInput>& inputs = mStrokes->settings().inputs;
    const StrokesReport& report = mStrokes->report();
    if (report.keptPerInput.size() != inputs.size()) return warnings; // the stroke stage did not run (buffers alone)
    const auto say = [&](const std::string& message) {
        warnings.push_back(makeWarning(WarningKind::LinesEmpty, message));
    };
    const StrokeStyle defaults;
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const std::string& type = inputs[i].type;
        const std::size_t kept = report.keptPerInput[i], found = report.foundPerInput[i];
        if (mLook->styleOf(type).color.a == 0.0 && kept > 0) {
            say("the " + type + " lines are drawn transparent: --" + type +
                "-color has alpha 0, so the picture shows none of their " + std::to_string(kept) + " strokes");
            continue;
        }
        if (kept > 0) continue;
        // The type's own settings given, each with its default.
        std::vector<std::string> given;
        const LineType* lineType = findLineType(type);
        if (lineType != nullptr)
            for (const LineParameter* parameter : lineType->parameters) {
                if (!mLook->lineParameters.isGiven(*parameter)) continue;
                const bool choice = parameter->isChoice();
                const std::string value = choice ? mLook->lineParameters.choice(*parameter)
                                                 : detail::formatNumber(mLook->lineParameters.number(*parameter));
                const std::string byDefault = choice ? parameter->defaultChoice
                                              : parameter->defaultNumber
                                                  ? detail::formatNumber(*parameter->defaultNumber)
                                                  : std::string();
                given.push_back("--" + parameter->name + " " + value +
                                (byDefault.empty() ? "" : " (default " + byDefault + ")"));
            }
        std::string settings;
        for (std::size_t g = 0; g < given.size(); ++g)
            settings += (g == 0 ? "" : g + 1 == given.size() ? " and " : ", ") + given[g];
        const std::string strokes = std::to_string(found) + " stroke" + (found == 1 ? "" : "s");
        // Only what a setting given did is said: a type empty at its defaults is the model's (a sphere has no
        // creases), and a hidden-lines type's is the view's (nothing hidden).
        if (report.droppedShortPerInput[i] == found && found > 0 && mLook->strokes.minLength != defaults.minLength)
            say("the " + type + " lines drew nothing in this view: --min-stroke-length " +
                detail::formatNumber(mLook->strokes.minLength) + " (default " +
                detail::formatNumber(defaults.minLength) + ") dropped all " + strokes + " as too short");
        else if (report.droppedWeakPerInput[i] > 0 && !given.empty())
            say("the " + type + " lines drew nothing in this view: at " + settings + " none of their " + strokes +
                " reaches the seed strength");
        else if (found == 0 && !given.empty() && !(lineType != nullptr && lineType->hiddenLines))
            say("the " + type + " lines found none in this view at " + settings);
    }
    return warnings;
}

Json StillGraph::describePostStage(const std::vector<PassTiming>& timings) const {
    Json layers = Json::array();
    double kernels = 0.0, readback = 0.0, composite = 0.0;
    for (const PassTiming& timing : timings) {
        if (timing.pass == "composite") composite = timing.milliseconds;
        const auto layer = mLineLayers.find(timing.pass);
        if (layer == mLineLayers.end()) continue;
        Json entry;
        layer->second->describe(entry);
        layers.push_back(entry);
        const LineLayerReport& report = layer->second->report();
        kernels += report.kernelMilliseconds;
        readback += report.readbackMilliseconds;
    }
    Json result;
    result["device"] = postStageDeviceName(postStageDevice);
    result["requested"] = postStageDeviceName(mLook ? mLook->postStage : postStageDevice);
    result["lines"] = layers;
    if (mStrokes && std::any_of(timings.begin(), timings.end(),
                                [](const PassTiming& timing) { return timing.pass == kStrokesPass; })) {
        Json strokes;
        mStrokes->describe(strokes);
        const StrokesReport& report = mStrokes->report();
        kernels += report.thinMilliseconds + report.chainMilliseconds + report.strokeMilliseconds;
        result["strokes"] = strokes;
    }
    result["kernels_ms"] = kernels;
    result["readback_ms"] = readback;
    result["composite_ms"] = composite;
    return result;
}

std::string StillGraph::strokePathsResource() const {
    return mStrokes ? std::string(kStrokesPass) + "." + kStrokePathsField : std::string();
}

std::vector<SvgLineLayer> StillGraph::svgLayers(ResourceStore& store, double tolerancePixels) const {
    if (!mStrokes) return {};
    const DrawnStrokes& drawn = store.object<DrawnStrokes>(strokePathsResource());
    std::vector<std::array<double, 4>> colors;
    for (const StrokeInput& input : drawn.inputs) {
        const glm::dvec4 color = mLook->styleOf(input.type).color;
        colors.push_back({color.r, color.g, color.b, color.a});
    }
    return svgLayersOf(drawn, tolerancePixels, colors);
}

namespace {

/** The G-buffer's triangle id field (global triangle index + 1): the triangle under an image-space stroke point. */
std::string triangleIdResource() { return std::string(kGBufferPass) + ".triangleId"; }

} // namespace

std::vector<std::string> StillGraph::strokePointResources() const {
    if (!mStrokes) return {};
    std::vector<std::string> resources = {strokePathsResource(), std::string(kGBufferPass) + "." + GBufferPass::kDepth};
    resources.push_back(triangleIdResource());
    for (const StrokeInput& input : mStrokes->settings().inputs) {
        const LineType* type = findLineType(input.type);
        if (type == nullptr) continue;
        if (type->family == LineFamily::ObjectSpace) resources.push_back(input.resource);
        if (!type->strokePointsImage.empty()) resources.push_back(type->strokePointsImage);
    }
    return resources;
}

std::vector<StrokeRecord> StillGraph::strokeRecords(ResourceStore& store, const Camera& camera,
                                                    const Scene& scene) const {
    if (!mStrokes) return {};
    StrokePointSetup setup;
    setup.drawn = &store.object<DrawnStrokes>(strokePathsResource());
    setup.camera = &camera;
    setup.scene = &scene;
    setup.depth = store.image(std::string(kGBufferPass) + "." + GBufferPass::kDepth);
    setup.triangleIds = store.image(triangleIdResource());
    // The numbering of the triangleId field and the manifest's meshes (scene/MeshLabels.h), which makes it.
    const TriangleNumbering numbering(scene);
    setup.numbering = &numbering;
    for (const StrokeInput& input : setup.drawn->inputs) {
        const LineType* type = findLineType(input.type);
        StrokePointInput points;
        points.visible = type == nullptr || !type->hiddenLines;
        if (type != nullptr && type->family == LineFamily::ObjectSpace) {
            points.source = StrokePointSource::Skeleton;
            points.skeleton = &store.object<LineSkeleton>(input.resource);
        } else if (type != nullptr && !type->strokePointsImage.empty()) {
            points.source = StrokePointSource::Image;
            points.image = store.image(type->strokePointsImage);
        }
        setup.inputs.push_back(points);
    }
    return inkgraph::strokeRecords(setup);
}

const LineLayerPass* StillGraph::lineLayer(const std::string& type) const {
    auto found = mLineLayers.find(type);
    return found == mLineLayers.end() ? nullptr : found->second;
}

} // namespace inkgraph
