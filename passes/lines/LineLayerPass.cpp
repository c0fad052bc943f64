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
    // Every input is brought to the CPU before the kernel's clock starts, so kernel times are the post stage alone.
    auto start = std::chrono::steady_clock::now();
    const cv::Mat depth = mSettings.source == LineSource::Skeleton ? cv::Mat() : gl.inputImage(input("depth"));
    cv::Mat field; // the kernel's other input
    switch (mSettings.source) {
    case LineSource::Contour: field = gl.inputImage(input("nDotV")); break;
    case LineSource::Suggestive: field = gl.inputImage(input("radial")); break;
    case LineSource::DepthEdge: break;
    case LineSource::NormalEdge: field = gl.inputImage(input("normal")); break;
    case LineSource::Skeleton: field = gl.inputImage(mSettings.skeletonResource); break;
    }
    mReport.readbackMilliseconds = millisecondsSince(start);

    start = std::chrono::steady_clock::now();
    switch (mSettings.source) {
    case LineSource::Contour: mSkeleton = extractContours(field, depth, mSettings.contour); break;
    case LineSource::Suggestive: mSkeleton = extractSuggestiveContours(field, depth, mSettings.suggestive); break;
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
