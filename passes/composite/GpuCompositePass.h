#pragma once
/** @file Composite on the GPU (--post-stage gpu, passes/PostStage.h): what CompositePass does, as a compute shader
 *  (shaders/composite/composite.comp) in compositeFinal()'s 8-bit integer arithmetic, so the picture is the same to
 *  the byte. The shading stays where it was drawn; the line layers (the stroke stage's CPU images) are uploaded.
 *  Resources as CompositePass; the final picture is a texture, read back by whoever reads it. A multisampled
 *  shading (--msaa) is composited on the CPU (compositeFinal()), as a sampler cannot read it per pixel. */

#include "gl/GlPass.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameParams.h"
#include "passes/composite/CompositePass.h"

#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

class GpuCompositePass : public GlPass {
public:
    /** As CompositePass. Throws std::invalid_argument naming the layer for a colour channel outside [0, 1]. */
    GpuCompositePass(std::string name, ShaderLibrary& shaders, const FrameParams& frame, std::string shading,
                     std::vector<CompositePass::LineInput> lines = {});

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    void prepare(GlPassContext& context) override;
    void execute(GlPassContext& context) override;

private:
    std::string mName;
    ShaderLibrary& mShaders;
    const FrameParams& mFrame;
    std::string mShading;
    std::vector<CompositePass::LineInput> mLines;
    std::optional<GlProgram> mBase;  ///< paper and shading
    std::optional<GlProgram> mLayer; ///< one line layer over the picture
};

} // namespace inkgraph
