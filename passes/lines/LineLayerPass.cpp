#include "passes/lines/LineLayerPass.h"

#include "gl/GraphExecutor.h"
#include "graph/Milliseconds.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace inkgraph {

LineLayerPass::LineLayerPass(std::string name, std::unique_ptr<LineKernel> kernel, int supersample, int divisor)
    : mName(std::move(name)), mKernel(std::move(kernel)), mSupersample(supersample), mDivisor(divisor) {
    if (mSupersample < 1) throw std::invalid_argument("LineLayerPass(): '" + mName + "' supersample must be >= 1");
    if (mDivisor < 1) throw std::invalid_argument("LineLayerPass(): '" + mName + "' divisor must be >= 1");
    if (!mKernel) throw std::invalid_argument("LineLayerPass(): '" + mName + "' has no kernel");
    if (mKernel->inputs().empty()) throw std::invalid_argument("LineLayerPass(): '" + mName + "' kernel reads nothing");
}

void LineLayerPass::declare(PassBuilder& builder) const {
    // A kernel over read-back images is CPU work, which a batch runs while the next still draws; one that reads the
    // textures (a compute shader: --post-stage gpu) needs the context.
    if (!mKernel->readsTextures()) builder.runsOnHost();
    const std::vector<std::string> inputs = mKernel->inputs();
    for (std::size_t input = 0; input < inputs.size(); ++input) builder.read(inputs[input], mKernel->extentOf(input));
    for (const std::string& name : mKernel->sceneImports()) builder.import(name);
    ObjectDesc skeleton;
    skeleton.type = kLineSkeletonType;
    skeleton.bytesPerPixel = kLineSkeletonBytesPerPixel;
    skeleton.scale = mSupersample;
    skeleton.divisor = mDivisor;
    skeleton.hasPicture = true;
    skeleton.pictureFormat = Format::R8;
    builder.writeObject(
        "skeleton", skeleton, Need::Required,
        {"skeleton-" + mName + ".png", Appearance::Lines,
         "the one-pixel skeleton " + mName + " found, before the stroke stage, at the --supersample size"});
    if (const std::size_t scratch = mKernel->scratchBytesPerPixel(); scratch > 0)
        builder.scratch(scratch, mSupersample, mDivisor);
}

void LineLayerPass::prepare(GlPassContext&) { mKernel->prepare(); }

void LineLayerPass::execute(GlPassContext& gl) {
    mReport = {};
    const std::vector<std::string> inputs = mKernel->inputs();
    mReport.supersample = gl.scaleOf(inputs.front());
    mReport.divisor = gl.divisorOf(inputs.front());
    // Every input is brought to the CPU before the kernel's clock starts, so kernel times are the post stage alone.
    LineSkeleton& skeleton = gl.outputObject<LineSkeleton>("skeleton");
    if (mKernel->readsTextures()) {
        // A GPU kernel reads its inputs where they are; its time includes reading back what it found.
        std::vector<const GlTexture*> textures;
        for (const std::string& input : inputs) textures.push_back(&gl.inputTexture(input));
        const auto start = std::chrono::steady_clock::now();
        skeleton = mKernel->findInTextures(textures);
        mReport.kernelMilliseconds = millisecondsSince(start);
    } else {
        auto start = std::chrono::steady_clock::now();
        std::vector<cv::Mat> images;
        for (const std::string& input : inputs) images.push_back(gl.inputImage(input));
        mReport.readbackMilliseconds = millisecondsSince(start);

        start = std::chrono::steady_clock::now();
        skeleton = mKernel->find(images);
        mReport.kernelMilliseconds = millisecondsSince(start);
    }
    mReport.skeletonPixels = std::size_t(cv::countNonZero(skeleton.mask));
    mReport.points = skeleton.points.size();
    if (skeleton.mask.size() !=
        cv::Size(scaledSide(gl.width(), mSupersample, mDivisor), scaledSide(gl.height(), mSupersample, mDivisor)))
        throw std::runtime_error("LineLayerPass::execute(): '" + mName + "' inputs are not " +
                                 std::to_string(mSupersample) + "/" + std::to_string(mDivisor) +
                                 " times the frame size");
    gl.outputPicture("skeleton", skeleton.mask);
}

void LineLayerPass::describe(nlohmann::ordered_json& report) const {
    report["type"] = mName;
    report["skeleton_pixels"] = mReport.skeletonPixels;
    report["points"] = mReport.points;
    // The kernel's field at 1/divisor of the data's sides (1: the data size itself).
    report["field_divisor"] = mReport.divisor;
    report["readback_ms"] = mReport.readbackMilliseconds;
    report["kernel_ms"] = mReport.kernelMilliseconds;
    mKernel->describe(report);
}

} // namespace inkgraph
