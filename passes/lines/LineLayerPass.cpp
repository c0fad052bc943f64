#include "passes/lines/LineLayerPass.h"

#include "gl/GraphExecutor.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "postfx/LineSkeleton.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace inkgraph {
namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/** Object-space lines are sampled at most this far apart along the image (data pixels), so the one-pixel skeleton
 *  has no gaps and the stroke's discs overlap. */
constexpr double kSampleSpacingPixels = 0.5;

} // namespace

LineLayerPass::LineLayerPass(std::string name, LineLayerSettings settings, LineSceneInputs sceneInputs)
    : mName(std::move(name)), mSettings(std::move(settings)), mSceneInputs(sceneInputs) {
    if (!(std::isfinite(mSettings.widthPixels) && mSettings.widthPixels > 0.0f))
        throw std::invalid_argument("LineLayerPass(): '" + mName + "' width must be positive and finite");
    if (mSettings.supersample < 1)
        throw std::invalid_argument("LineLayerPass(): '" + mName + "' supersample must be at least 1");
    if (mSettings.source == LineSource::Skeleton && mSettings.skeletonResource.empty())
        throw std::invalid_argument("LineLayerPass(): '" + mName + "' strokes a skeleton but names no resource");
    if (mSettings.source == LineSource::SuggestiveObject && !(mSceneInputs.scene && mSceneInputs.frame))
        throw std::invalid_argument("LineLayerPass(): '" + mName +
                                    "' finds lines on the mesh but was given no 'sceneInputs' (scene and frame)");
}

void LineLayerPass::declare(PassBuilder& builder) const {
    switch (mSettings.source) {
    case LineSource::Contour: builder.read(input("nDotV")); break;
    case LineSource::Suggestive: builder.read(input("radial")); break;
    case LineSource::SuggestiveObject: break;
    case LineSource::DepthEdge: break;
    case LineSource::NormalEdge: builder.read(input("normal")); break;
    case LineSource::Skeleton: builder.read(mSettings.skeletonResource); break;
    }
    if (mSettings.source != LineSource::Skeleton) builder.read(input("depth"));
    builder.write("lines", {Format::R8});
}

void LineLayerPass::prepare(PassContext& context) {
    (void)context;
    mCurvatureDerived = false;
    mCurvatureMilliseconds = 0.0;
    if (mSettings.source != LineSource::SuggestiveObject || mSceneInputs.scene->meshCurvatureComputed()) return;
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t mesh = 0; mesh < mSceneInputs.scene->meshCount(); ++mesh) mSceneInputs.scene->meshCurvature(mesh);
    mCurvatureDerived = true;
    mCurvatureMilliseconds = millisecondsSince(start);
}

LineSkeleton LineLayerPass::findObjectSuggestiveContours(const cv::Mat& depth) {
    const Camera& camera = mSceneInputs.frame->camera;
    const glm::dmat4 view = camera.viewMatrix();
    const glm::dmat4 projection = camera.projectionMatrix();
    const int width = depth.cols, height = depth.rows;
    const double tolerance = 1.0 + double(mSettings.suggestive.depthJump);
    ObjectSuggestiveSettings settings;
    settings.featureSize = mSettings.suggestive.featureSize;
    settings.threshold = mSettings.suggestive.threshold;
    settings.fade = mSettings.suggestive.fade;

    LineSkeleton skeleton;
    skeleton.mask = cv::Mat::zeros(depth.size(), CV_8UC1);
    // The rule in the header: some surface pixel centre of the 2 x 2 around the point is not nearer than it by more
    // than the tolerance.
    auto isVisible = [&](double x, double y, double pointDepth) {
        const int left = int(std::floor(x)), top = int(std::floor(y));
        for (int row = top; row <= top + 1; ++row)
            for (int col = left; col <= left + 1; ++col) {
                if (row < 0 || col < 0 || row >= height || col >= width) continue;
                const double surface = depth.at<float>(row, col);
                if (surface > 0.0 && pointDepth <= surface * tolerance) return true;
            }
        return false;
    };
    // Pixel coordinates of a clip-space point: x right, y down, pixel centres at integers.
    auto toPixel = [&](const glm::dvec4& clip) {
        return glm::dvec2((clip.x / clip.w + 1.0) * 0.5 * width - 0.5, (1.0 - clip.y / clip.w) * 0.5 * height - 0.5);
    };

    for (std::size_t mesh = 0; mesh < mSceneInputs.scene->meshCount(); ++mesh) {
        const std::vector<SuggestiveSegment> segments =
            extractObjectSuggestiveContours(mSceneInputs.scene->meshCurvature(mesh), camera.eye, settings);
        mReport.segments += segments.size();
        for (const SuggestiveSegment& segment : segments) {
            const glm::dvec4 viewA = view * glm::dvec4(segment.ends[0], 1.0);
            const glm::dvec4 viewB = view * glm::dvec4(segment.ends[1], 1.0);
            const glm::dvec4 clipA = projection * viewA, clipB = projection * viewB;
            // Clip to GL's near (z >= -w) and far (z <= w) planes, as the rasteriser does.
            double from = 0.0, to = 1.0;
            bool outside = false;
            for (const double side : {1.0, -1.0}) {
                const double a = clipA.w + side * clipA.z, b = clipB.w + side * clipB.z;
                if (a < 0.0 && b < 0.0) outside = true;
                else if (a < 0.0) from = std::max(from, a / (a - b));
                else if (b < 0.0) to = std::min(to, a / (a - b));
            }
            if (outside || !(to > from)) continue;
            const glm::dvec2 start = toPixel(clipA + from * (clipB - clipA));
            const glm::dvec2 end = toPixel(clipA + to * (clipB - clipA));
            // Linear view depth at the clipped ends; its reciprocal is linear along the image under perspective.
            const double startDepth = -(viewA.z + from * (viewB.z - viewA.z));
            const double endDepth = -(viewA.z + to * (viewB.z - viewA.z));
            const int steps = std::max(1, int(std::ceil(glm::length(end - start) / kSampleSpacingPixels)));
            for (int step = 0; step <= steps; ++step) {
                const double s = double(step) / double(steps);
                const double inverseDepth = (1.0 - s) / startDepth + s / endDepth;
                const double pointDepth = 1.0 / inverseDepth;
                // Where along the 3-D segment the sample lies, for the strength (linear there, as extracted).
                const double along = from + (to - from) * (s / endDepth) / inverseDepth;
                const double strength =
                    std::min(1.0, segment.strengths[0] + along * (segment.strengths[1] - segment.strengths[0]));
                if (!(strength > 0.0)) continue; // a cut end at the threshold: nothing to draw
                const glm::dvec2 pixel = start + s * (end - start);
                const int col = int(std::lround(pixel.x)), row = int(std::lround(pixel.y));
                if (col < 0 || row < 0 || col >= width || row >= height) continue;
                if (!isVisible(pixel.x, pixel.y, pointDepth)) continue;
                skeleton.points.push_back({cv::Point2f(float(pixel.x), float(pixel.y)), float(strength)});
                skeleton.mask.at<uchar>(row, col) = 255;
            }
        }
    }
    return skeleton;
}

void LineLayerPass::execute(PassContext& context) {
    GlPassContext& gl = GlPassContext::from(context);
    mReport = {};
    mReport.curvatureDerived = mCurvatureDerived;
    mReport.curvatureMilliseconds = mCurvatureMilliseconds;
    // Every input is brought to the CPU before the kernel's clock starts, so kernel times are the post stage alone.
    auto start = std::chrono::steady_clock::now();
    const cv::Mat depth = mSettings.source == LineSource::Skeleton ? cv::Mat() : gl.inputImage(input("depth"));
    cv::Mat field; // the kernel's other input
    switch (mSettings.source) {
    case LineSource::Contour: field = gl.inputImage(input("nDotV")); break;
    case LineSource::Suggestive: field = gl.inputImage(input("radial")); break;
    case LineSource::SuggestiveObject: break;
    case LineSource::DepthEdge: break;
    case LineSource::NormalEdge: field = gl.inputImage(input("normal")); break;
    case LineSource::Skeleton: field = gl.inputImage(mSettings.skeletonResource); break;
    }
    mReport.readbackMilliseconds = millisecondsSince(start);

    start = std::chrono::steady_clock::now();
    switch (mSettings.source) {
    case LineSource::Contour: mSkeleton = extractContours(field, depth, mSettings.contour); break;
    case LineSource::Suggestive: mSkeleton = extractSuggestiveContours(field, depth, mSettings.suggestive); break;
    case LineSource::SuggestiveObject: mSkeleton = findObjectSuggestiveContours(depth); break;
    case LineSource::DepthEdge: mSkeleton = extractDepthEdges(depth, mSettings.depthEdge); break;
    case LineSource::NormalEdge: mSkeleton = extractNormalEdges(field, depth, mSettings.normalEdge); break;
    case LineSource::Skeleton: mSkeleton = skeletonFromMask(field); break;
    }
    mReport.kernelMilliseconds = millisecondsSince(start);
    mReport.skeletonPixels = std::size_t(cv::countNonZero(mSkeleton.mask));
    mReport.points = mSkeleton.points.size();

    start = std::chrono::steady_clock::now();
    cv::Mat lines = strokeLines(mSkeleton, mSettings.widthPixels, mSettings.supersample);
    if (lines.size() != cv::Size(gl.width(), gl.height()))
        throw std::runtime_error("LineLayerPass::execute(): '" + mName + "' inputs are not " +
                                 std::to_string(mSettings.supersample) + " times the frame size");
    gl.outputImage("lines") = std::move(lines);
    mReport.strokeMilliseconds = millisecondsSince(start);
}

} // namespace inkgraph
