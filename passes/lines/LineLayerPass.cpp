#include "passes/lines/LineLayerPass.h"

#include "gl/GraphExecutor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace inkgraph {
namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

LineLayerPass::LineLayerPass(std::string name, std::unique_ptr<LineKernel> kernel, int supersample)
    : mName(std::move(name)), mKernel(std::move(kernel)), mSupersample(supersample) {
    if (mSupersample < 1) throw std::invalid_argument("LineLayerPass(): '" + mName + "' supersample must be >= 1");
    if (!mKernel) throw std::invalid_argument("LineLayerPass(): '" + mName + "' has no kernel");
    if (mKernel->inputs().empty()) throw std::invalid_argument("LineLayerPass(): '" + mName + "' kernel reads nothing");
}

void LineLayerPass::declare(PassBuilder& builder) const {
    for (const std::string& input : mKernel->inputs()) builder.read(input);
    builder.write("skeleton", {Format::R8, mSupersample}, Need::Required,
                  {"skeleton-" + mName + ".png", Appearance::Lines,
                   "the one-pixel skeleton " + mName + " found, before the stroke stage, at the --supersample size"});
}

void LineLayerPass::prepare(GlPassContext& context) {
    (void)context;
    mKernel->prepare();
}

void LineLayerPass::execute(GlPassContext& gl) {
    mReport = {};
    const std::vector<std::string> inputs = mKernel->inputs();
    mReport.supersample = gl.scaleOf(inputs.front());
    // Every input is brought to the CPU before the kernel's clock starts, so kernel times are the post stage alone.
    auto start = std::chrono::steady_clock::now();
    std::vector<cv::Mat> images;
    for (const std::string& input : inputs) images.push_back(gl.inputImage(input));
    mReport.readbackMilliseconds = millisecondsSince(start);

    start = std::chrono::steady_clock::now();
    mSkeleton = mKernel->find(images);
    mReport.kernelMilliseconds = millisecondsSince(start);
    mReport.skeletonPixels = std::size_t(cv::countNonZero(mSkeleton.mask));
    mReport.points = mSkeleton.points.size();
    if (mSkeleton.mask.size() != cv::Size(gl.widthOf("skeleton"), gl.heightOf("skeleton")))
        throw std::runtime_error("LineLayerPass::execute(): '" + mName + "' inputs are not " +
                                 std::to_string(mSupersample) + " times the frame size");
    gl.outputImage("skeleton") = mSkeleton.mask;
}

void LineLayerPass::describe(nlohmann::ordered_json& report) const {
    report["type"] = mName;
    report["skeleton_pixels"] = mReport.skeletonPixels;
    report["points"] = mReport.points;
    report["readback_ms"] = mReport.readbackMilliseconds;
    report["kernel_ms"] = mReport.kernelMilliseconds;
    mKernel->describe(report);
}

} // namespace inkgraph
