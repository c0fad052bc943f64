#include "passes/lambert/LambertPass.h"

#include "gl/GraphExecutor.h"

#include <glm/gtc/type_ptr.hpp>

namespace inkgraph {

LambertPass::LambertPass(std::string name, ShaderLibrary& shaders, const FrameParams& frame, std::string normal,
                         std::string baseColor, float ambient)
    : mName(std::move(name)), mShaders(shaders), mFrame(frame), mNormal(std::move(normal)),
      mBaseColor(std::move(baseColor)), mAmbient(ambient) {}

void LambertPass::declare(PassBuilder& builder) const {
    builder.read(mNormal);
    builder.read(mBaseColor);
    builder.write("color", {Format::RGBA8});
}

void LambertPass::prepare(PassContext&) {
    if (!mProgram)
        mProgram = std::make_unique<GlProgram>(mShaders.build(
            {mName, "lambert/lambert.vert", "lambert/lambert.frag", {}, {"common/fullscreen.glsl", "common/color.glsl"}}));
}

void LambertPass::execute(PassContext& context) {
    GlPassContext& gl = GlPassContext::from(context);
    GlFramebuffer framebuffer(mName);
    framebuffer.attachColor(0, gl.outputTexture("color"));
    framebuffer.finish({0});
    framebuffer.bind();
    glViewport(0, 0, gl.width(), gl.height());

    glBindTextureUnit(0, gl.inputTexture(mNormal).id());
    glBindTextureUnit(1, gl.inputTexture(mBaseColor).id());
    mProgram->use();
    glUniform3fv(mProgram->uniform("towardLightView"), 1, glm::value_ptr(mFrame.towardLightView()));
    glUniform1f(mProgram->uniform("ambient"), mAmbient);

    GlVertexArray empty(mName + " fullscreen");
    empty.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glBindTextureUnit(0, 0);
    glBindTextureUnit(1, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

} // namespace inkgraph
