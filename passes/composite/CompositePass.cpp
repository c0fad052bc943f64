#include "passes/composite/CompositePass.h"

#include "gl/GraphExecutor.h"
#include "postfx/Composite.h"

namespace inkgraph {

CompositePass::CompositePass(std::string name, const FrameParams& frame, std::string shading)
    : mName(std::move(name)), mFrame(frame), mShading(std::move(shading)) {}

void CompositePass::declare(PassBuilder& builder) const {
    if (!mShading.empty()) builder.read(mShading);
    builder.write("final", {Format::RGBA8});
}

void CompositePass::execute(PassContext& context) {
    GlPassContext& gl = GlPassContext::from(context);
    CompositeInputs inputs;
    inputs.size = cv::Size(gl.width(), gl.height());
    inputs.paper = cv::Vec4f(mFrame.background.r, mFrame.background.g, mFrame.background.b, mFrame.background.a);
    if (!mShading.empty()) inputs.shading = gl.inputImage(mShading);
    gl.outputImage("final") = compositeFinal(inputs);
}

} // namespace inkgraph
