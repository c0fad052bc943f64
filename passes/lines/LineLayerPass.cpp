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

LineLayerPass::LineLayerPass(std::string name, std::unique_ptr<LineKernel> kernel, float widthPixels)
    : mName(std::move(name)), mKernel(std::move(kernel)), mWidthPixels(widthPixels) {
    if (!(std::isfinite(mWidthPixels) && mWidthPixels > 0.0f))
        throw std::invalid_argument("LineLayerPass(): '" + mName + "' width must be positive and finite");
    if (!mKernel) throw std::invalid_argument("LineLayerPass(): '" + mName + "' has no kernel");
    if (mKernel->inputs().empty()) throw std::invalid_argument("LineLayerPass(): '" + mName + "' kernel reads nothing");
}

void LineLayerPass::declare(PassBuilder& builder) const {
    for (const std::string& input : mKernel->inputs()) builder.read(input);
    builder.write("lines", {Format::R8}, Need::Required, {"lines-" + mName + ".png", Appearance::Lines});
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

    start = std::chrono::steady_clock::now();
    cv::Mat lines = strokeLines(mSkeleton, mWidthPixels, mReport.supersample);
    if (lines.size() != cv::Size(gl.width(), gl.height()))
        throw std::runtime_error("LineLayerPass::execute(): '" + mName + "' inputs are not " +
                                 std::to_string(mReport.supersample) + " times the frame size");
    gl.outputImage("lines") = std::move(lines);
    mReport.strokeMilliseconds = millisecondsSince(start);
}

void LineLayerPass::describe(nlohmann::ordered_json& report) const {
    report["type"] = mName;
    report["skeleton_pixels"] = mReport.skeletonPixels;
    report["points"] = mReport.points;
    report["readback_ms"] = mReport.readbackMilliseconds;
    report["kernel_ms"] = mReport.kernelMilliseconds;
    report["stroke_ms"] = mReport.strokeMilliseconds;
    mKernel->describe(report);
}

} // namespace inkgraph
