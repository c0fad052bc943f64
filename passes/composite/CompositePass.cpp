#include "passes/composite/CompositePass.h"

#include "gl/GraphExecutor.h"
#include "postfx/Composite.h"

namespace inkgraph {

CompositePass::CompositePass(std::string name, const FrameParams& frame, std::string shading,
                             std::vector<LineInput> lines)
    : mName(std::move(name)), mFrame(frame), mShading(std::move(shading)), mLines(std::move(lines)) {}

void CompositePass::declare(PassBuilder& builder) const {
    builder.runsOnHost(); // CPU work over read-back images: a batch runs it while the next still draws
    if (!mShading.empty()) builder.read(mShading);
    for (const LineInput& line : mLines) builder.read(line.resource);
    builder.write("final", {Format::RGBA8}, Need::Required, {"final.png", Appearance::Color, "the finished picture"});
}

void CompositePass::execute(GlPassContext& gl) {
    CompositeInputs inputs;
    inputs.size = cv::Size(gl.width(), gl.height());
    inputs.paper = cv::Vec4f(mFrame.background.r, mFrame.background.g, mFrame.background.b, mFrame.background.a);
    if (!mShading.empty()) inputs.shading = gl.inputImage(mShading);
    for (const LineInput& line : mLines)
        inputs.lines.push_back({ResourceName::split(line.resource).pass, gl.inputImage(line.resource), line.color});
    gl.outputImage("final") = compositeFinal(inputs);
}

} // namespace inkgraph
