#include "passes/lines/LineLayerPass.h"

#include "gl/GraphExecutor.h"
#include "postfx/LineSkeleton.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace inkgraph {
namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

LineLayerPass::LineLayerPass(std::string name, LineLayerSettings settings)
    : mName(std::move(name)), mSettings(std::move(settings)) {
    if (!(std::isfinite(mSettings.widthPixels) && mSettings.widthPixels > 0.0f))
        throw std::invalid_argument("LineLayerPass(): '" + mName + "' width must be positive and finite");
    if (mSettings.supersample < 1)
        throw std::invalid_argument("LineLayerPass(): '" + mName + "' supersample must be at least 1");
    if (mSettings.source == LineSource::Skeleton && mSettings.skeletonResource.empty())
        throw std::invalid_argument("LineLayerPass(): '" + mName + "' strokes a skeleton but names no resource");
}

void LineLayerPass::declare(PassBuilder& builder) const {
    switch (mSettings.source) {
    case LineSource::Contour: builder.read(input("nDotV")); break;
    case LineSource::Suggestive: builder.read(input("radial")); break;
    case LineSource::DepthEdge: break;
    case LineSource::NormalEdge: builder.read(input("normal")); break;
    case LineSource::Skeleton: builder.read(mSettings.skeletonResource); break;
    }
    if (mSettings.source != LineSource::Skeleton) builder.read(input("depth"));
    builder.write("lines", {Format::R8});
}

void LineLayerPass::execute(PassContext& context) {
    GlPassContext& gl = GlPassContext::from(context);
    mReport = {};
    auto start = std::chrono::steady_clock::now();
    // Every input is brought to the CPU before the kernel's clock starts, so kernel times are the post stage alone.
    const cv::Mat depth = mSettings.source == LineSource::Skeleton ? cv::Mat() : gl.inputImage(input("depth"));
    LineSkeleton& skeleton = mSkeleton;
    switch (mSettings.source) {
    case LineSource::Contour: {
        const cv::Mat& nDotV = gl.inputImage(input("nDotV"));
        mReport.readbackMilliseconds = millisecondsSince(start);
        start = std::chrono::steady_clock::now();
        skeleton = extractContours(nDotV, depth, mSettings.contour);
        break;
    }
    case LineSource::Suggestive: {
        const cv::Mat& radial = gl.inputImage(input("radial"));
        mReport.readbackMilliseconds = millisecondsSince(start);
        start = std::chrono::steady_clock::now();
        skeleton = extractSuggestiveContours(radial, depth, mSettings.suggestive);
        break;
    }
    case LineSource::DepthEdge:
        mReport.readbackMilliseconds = millisecondsSince(start);
        start = std::chrono::steady_clock::now();
        skeleton = extractDepthEdges(depth, mSettings.depthEdge);
        break;
    case LineSource::NormalEdge: {
        const cv::Mat& normal = gl.inputImage(input("normal"));
        mReport.readbackMilliseconds = millisecondsSince(start);
        start = std::chrono::steady_clock::now();
        skeleton = extractNormalEdges(normal, depth, mSettings.normalEdge);
        break;
    }
    case LineSource::Skeleton: {
        const cv::Mat& mask = gl.inputImage(mSettings.skeletonResource);
        mReport.readbackMilliseconds = millisecondsSince(start);
        start = std::chrono::steady_clock::now();
        skeleton = skeletonFromMask(mask);
        break;
    }
    }
    mReport.kernelMilliseconds = millisecondsSince(start);
    mReport.skeletonPixels = std::size_t(cv::countNonZero(skeleton.mask));
    mReport.points = skeleton.points.size();

    start = std::chrono::steady_clock::now();
    cv::Mat lines = strokeLines(skeleton, mSettings.widthPixels, mSettings.supersample);
    if (lines.size() != cv::Size(gl.width(), gl.height()))
        throw std::runtime_error("LineLayerPass::execute(): '" + mName + "' inputs are not " +
                                 std::to_string(mSettings.supersample) + " times the frame size");
    gl.outputImage("lines") = std::move(lines);
    mReport.strokeMilliseconds = millisecondsSince(start);
}

} // namespace inkgraph
