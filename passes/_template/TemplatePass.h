#pragma once
/** @file Copy-me skeleton of a GL pass (not compiled). Checklist for a new pass `foo`:
 *   1. passes/foo/FooPass.{h,cpp} from this file; the header opens with the I/O table below.
 *   2. shaders/foo/foo.vert, foo.frag (fullscreen passes take common/fullscreen.glsl as a snippet).
 *   3. passes/CMakeLists.txt: add FooPass.cpp.
 *   4. passes/README.md: a paragraph and a row per resource.
 *   5. The app registers the pass and names what requests it; nothing inside a pass checks the scene.
 *   6. A no-GL graph test if it changes what gets culled; tests/passes/FooGLTest.cpp against analytic values; a golden
 *      case in tests/pipeline/ if its output is a stored intermediate.
 *
 *  | resource       | format  | need     | content                    |
 *  |----------------|---------|----------|----------------------------|
 *  | reads          |         |          | gbuffer.normal             |
 *  | <name>.color   | rgba8   | required | what it writes             |
 */

#include "gl/GlObjects.h"
#include "gl/GraphExecutor.h"
#include "gl/ShaderLibrary.h"
#include "graph/Pass.h"

#include <memory>
#include <string>

namespace inkgraph {

class TemplatePass : public Pass {
public:
    /** Input names come from the constructor so the pass can be used twice in one graph. */
    TemplatePass(std::string name, ShaderLibrary& shaders, std::string input)
        : mName(std::move(name)), mShaders(shaders), mInput(std::move(input)) {}

    std::string_view name() const override { return mName; }

    void declare(PassBuilder& builder) const override {
        builder.read(mInput);
        builder.write("color", {Format::RGBA8});
    }

    void prepare(PassContext&) override {
        if (!mProgram)
            mProgram = std::make_unique<GlProgram>(
                mShaders.build({mName, "template/template.vert", "template/template.frag", {}, {"common/fullscreen.glsl"}}));
    }

    void execute(PassContext& context) override {
        GlPassContext& gl = GlPassContext::from(context);
        GlFramebuffer framebuffer(mName);
        framebuffer.attachColor(0, gl.outputTexture("color"));
        framebuffer.finish({0});
        framebuffer.bind();
        glViewport(0, 0, gl.width(), gl.height());
        glBindTextureUnit(0, gl.inputTexture(mInput).id());
        mProgram->use();
        GlVertexArray empty(mName + " fullscreen");
        empty.bind();
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindVertexArray(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }

private:
    std::string mName;
    ShaderLibrary& mShaders;
    std::string mInput;
    std::unique_ptr<GlProgram> mProgram;
};

} // namespace inkgraph
