#include "passes/_template/TemplatePass.h"

namespace inkgraph {

TemplatePass::TemplatePass(std::string name, ShaderLibrary& shaders, std::string input)
    : mName(std::move(name)), mShaders(shaders), mInput(std::move(input)) {}

void TemplatePass::declare(PassBuilder& builder) const {
    builder.read(mInput);
    builder.write("color", {Format::RGBA8});
}

void TemplatePass::prepare(GlPassContext&) {
    // Built once per pass object, outside the timed execute().
    if (!mProgram)
        mProgram = std::make_unique<GlProgram>(mShaders.build(
            {mName, "_template/template.vert", "_template/template.frag", {}, {"common/fullscreen.glsl"}}));
}

void TemplatePass::execute(GlPassContext& gl) {
    GlFramebuffer framebuffer(mName);
    framebuffer.attachColor(0, gl.outputTexture("color"));
    framebuffer.finish({0});
    framebuffer.bind();
    glViewport(0, 0, gl.widthOf("color"), gl.heightOf("color"));
    glBindTextureUnit(0, gl.inputTexture(mInput).id());
    mProgram->use();
    // The plan knows how large the input is (a supersampled writer's scale): the pass is not told.
    glUniform1i(mProgram->uniform("inputScale"), gl.scaleOf(mInput));
    // Core profile draws nothing without a vertex array, even when the vertices come from gl_VertexID.
    GlVertexArray empty(mName + " fullscreen");
    empty.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glBindTextureUnit(0, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

} // namespace inkgraph
