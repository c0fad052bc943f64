#pragma once
/** @file Copy-me skeleton of a fullscreen GL pass: copies an rgba8 input, point-sampled to the frame size. Built
 *  (inkgraph_template_pass, not linked by the app) and tested (tests/passes/TemplatePassGLTest.cpp), so it stays
 *  true. Checklist for a new pass `foo`:
 *   1. passes/foo/FooPass.{h,cpp} from these two files; the header opens with the I/O table below. Derive from
 *      GlPass (gl/GlPass.h): prepare() builds programs and uploads, execute() draws through the GlPassContext.
 *   2. shaders/foo/foo.vert, foo.frag from shaders/_template/ (fullscreen passes take common/fullscreen.glsl as a
 *      snippet); a row in shaders/README.md.
 *   3. passes/CMakeLists.txt: add foo/FooPass.cpp to inkgraph_passes.
 *   4. passes/README.md: a paragraph and a row per resource.
 *   5. If the pass has numbers for --stats, override Pass::describe(). passes/StillGraph.cpp registers it (or, for a
 *      line type, its room in passes/lines/types/: docs/contributing.md); nothing inside a pass checks the scene.
 *   6. tests/passes/FooGLTest.cpp (listed in tests/passes/CMakeLists.txt) against analytic values, run through
 *      GraphExecutor as TemplatePassGLTest does; a no-GL graph test if it changes what gets culled; a golden case in
 *      tests/pipeline/ if its output is a stored intermediate.
 *
 *  | resource       | format | need     | content                                                    |
 *  |----------------|--------|----------|------------------------------------------------------------|
 *  | reads          |        |          | `input`, any rgba8 resource, at any scale                  |
 *  | <name>.color   | rgba8  | required | the input, point-sampled: the lower-left texel (GL's       |
 *  |                |        |          | origin) of each pixel's scale x scale block; scale 1 copies |
 */

#include "gl/GlObjects.h"
#include "gl/GlPass.h"
#include "gl/ShaderLibrary.h"

#include <memory>
#include <string>

namespace inkgraph {

class TemplatePass : public GlPass {
public:
    /** Input names come from the constructor so the pass can be used twice in one graph. */
    TemplatePass(std::string name, ShaderLibrary& shaders, std::string input);

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    void prepare(GlPassContext& context) override;
    void execute(GlPassContext& gl) override;

private:
    std::string mName;
    ShaderLibrary& mShaders;
    std::string mInput;
    std::unique_ptr<GlProgram> mProgram;
};

} // namespace inkgraph
