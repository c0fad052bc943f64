#include "passes/composite/GpuCompositePass.h"

#include "gl/GraphExecutor.h"
#include "gl/Readback.h"
#include "postfx/Composite.h"

#include <epoxy/gl.h>

#include <stdexcept>

namespace inkgraph {
namespace {

constexpr int kGroupSide = 16; ///< the shader's local size

/** compositeFinal()'s rounding of a display colour to bytes. */
glm::uvec4 bytesOf(const cv::Vec4f& color) {
    glm::uvec4 bytes;
    for (int channel = 0; channel < 4; ++channel)
        bytes[channel] = cv::saturate_cast<uchar>(color[channel] * 255.0f + 0.5f);
    return bytes;
}

bool isUnitColor(const cv::Vec4f& color) {
    for (int channel = 0; channel < 4; ++channel)
        if (!(color[channel] >= 0.0f && color[channel] <= 1.0f)) return false;
    return true;
}

void dispatchOver(const GlProgram& program, int width, int height) {
    glProgramUniform2i(program.id(), program.uniform("size"), width, height);
    glUseProgram(program.id());
    glDispatchCompute(GLuint((width + kGroupSide - 1) / kGroupSide), GLuint((height + kGroupSide - 1) / kGroupSide), 1);
    // The next layer reads what this one wrote; the read-back of the final picture too.
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

} // namespace

GpuCompositePass::GpuCompositePass(std::string name, ShaderLibrary& shaders, const FrameParams& frame,
                                   std::string shading, std::vector<CompositePass::LineInput> lines)
    : mName(std::move(name)), mShaders(shaders), mFrame(frame), mShading(std::move(shading)), mLines(std::move(lines)) {
    for (const CompositePass::LineInput& line : mLines)
        if (!isUnitColor(line.color))
            throw std::invalid_argument("GpuCompositePass(): line layer '" + line.resource +
                                        "' colour channels must lie in [0, 1]");
}

void GpuCompositePass::declare(PassBuilder& builder) const {
    if (!mShading.empty()) builder.read(mShading);
    for (const CompositePass::LineInput& line : mLines) builder.read(line.resource);
    builder.write("final", {Format::RGBA8}, Need::Required, {"final.png", Appearance::Color, "the finished picture"});
}

void GpuCompositePass::prepare(GlPassContext&) {
    ProgramDesc base;
    base.label = "composite-gpu-base";
    base.computeFile = "composite/composite.comp";
    base.defines = {"BASE 1"};
    mBase.emplace(mShaders.build(base));
    ProgramDesc layer;
    layer.label = "composite-gpu-layer";
    layer.computeFile = "composite/composite.comp";
    mLayer.emplace(mShaders.build(layer));
}

void GpuCompositePass::execute(GlPassContext& gl) {
    const cv::Vec4f paperColor(mFrame.background.r, mFrame.background.g, mFrame.background.b, mFrame.background.a);
    if (!isUnitColor(paperColor))
        throw std::invalid_argument("GpuCompositePass::execute(): 'paper' channels must lie in [0, 1]");
    if (!mShading.empty() && gl.samplesOf(mShading) > 1) {
        // A multisampled shading is resolved by its read-back; the CPU composite takes it from there.
        CompositeInputs inputs;
        inputs.size = cv::Size(gl.width(), gl.height());
        inputs.paper = paperColor;
        inputs.shading = gl.inputImage(mShading);
        for (const CompositePass::LineInput& line : mLines)
            inputs.lines.push_back({ResourceName::split(line.resource).pass, gl.inputImage(line.resource), line.color});
        uploadImage(gl.outputTexture("final"), compositeFinal(inputs));
        return;
    }
    if (!mBase) prepare(gl);
    const int width = gl.width();
    const int height = gl.height();
    GlTexture& target = gl.outputTexture("final");
    glBindImageTexture(0, target.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8);

    const glm::uvec4 paper = bytesOf(paperColor);
    glProgramUniform4ui(mBase->id(), mBase->uniform("paper"), paper.r, paper.g, paper.b, paper.a);
    glProgramUniform1i(mBase->id(), mBase->uniform("hasShading"), mShading.empty() ? 0 : 1);
    if (!mShading.empty()) glBindTextureUnit(0, gl.inputTexture(mShading).id());
    dispatchOver(*mBase, width, height);

    for (const CompositePass::LineInput& line : mLines) {
        const glm::uvec4 color = bytesOf(line.color);
        glProgramUniform4ui(mLayer->id(), mLayer->uniform("lineColor"), color.r, color.g, color.b, color.a);
        glBindTextureUnit(0, gl.inputTexture(line.resource).id()); // uploads the stroke stage's image
        dispatchOver(*mLayer, width, height);
    }
    glBindTextureUnit(0, 0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8);
    glUseProgram(0);
}

} // namespace inkgraph
