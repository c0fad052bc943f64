#pragma once
/** @file The G-buffer: float32 view-space data of the visible surface, one MRT draw, no MSAA.
 *
 *  | resource           | format  | need     | content                                                           |
 *  |--------------------|---------|----------|-------------------------------------------------------------------|
 *  | gbuffer.normal     | rgba32f | optional | unit view-space normal (turned toward the viewer), a = coverage   |
 *  | gbuffer.view       | rgba32f | optional | unit view vector, surface -> eye, a = coverage                    |
 *  | gbuffer.wVec       | rgba32f | optional | w = v - (n.v) n, unnormalised so |w| = sin(theta), a = coverage   |
 *  | gbuffer.nDotV      | r32f    | optional | n . v                                                             |
 *  | gbuffer.depth      | r32f    | optional | linear view depth (distance along -z in view space), 0 off-model  |
 *  | gbuffer.coverage   | r8      | optional | 255 where the model covers the pixel centre                       |
 *  | gbuffer.baseColor  | rgba8   | optional | sRGB-encoded material base colour, a = coverage                         |
 *
 *  Reads: nothing from the graph; the meshes come from GpuScene. Background pixels are all zero.
 *  Only live outputs are bound as draw buffers, and the shader is compiled with matching OUT_* defines. */

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "graph/Pass.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"

#include <map>
#include <memory>
#include <string>

namespace inkgraph {

class GBufferPass : public Pass {
public:
    struct Field {
        const char* name;   ///< "normal"
        Format format;
        const char* define; ///< "NORMAL": OUT_NORMAL / LOC_NORMAL in gbuffer.frag
    };
    /** Every field the pass can write, in attachment order. */
    static const std::vector<Field>& fields();

    GBufferPass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame);

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    void prepare(PassContext& context) override;
    void execute(PassContext& context) override;

private:
    /** OUT_* / LOC_* defines for the live outputs, in attachment order. */
    static std::vector<std::string> definesFor(const PassContext& context);
    GlProgram& programFor(const std::vector<std::string>& defines);

    std::string mName;
    ShaderLibrary& mShaders;
    GpuScene& mScene;
    const FrameParams& mFrame;
    std::map<std::string, std::unique_ptr<GlProgram>> mPrograms; ///< keyed by the live-output defines
    PassDepthBuffer mDepth; ///< the pass's own depth attachment, kept between runs
};

} // namespace inkgraph
