#pragma once
/** @file Lambert: deferred diffuse shading, the simplest finished picture.
 *
 *  | resource        | format | need     | content                                                            |
 *  |-----------------|--------|----------|--------------------------------------------------------------------|
 *  | reads           |        |          | gbuffer.normal, gbuffer.baseColor                                  |
 *  | <name>.color    | rgba8  | required | sRGB-encoded base colour x (ambient + (1 - ambient) max(n.l, 0)),  |
 *  |                 |        |          | a = coverage (0 off the model)                                     |
 */

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "graph/Pass.h"
#include "passes/FrameParams.h"

#include <memory>
#include <string>

namespace inkgraph {

class LambertPass : public Pass {
public:
    /** `normal` and `baseColor` name the resources to read (e.g. "gbuffer.normal"). */
    LambertPass(std::string name, ShaderLibrary& shaders, const FrameParams& frame, std::string normal,
                std::string baseColor, float ambient = 0.15f);

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    void prepare(PassContext& context) override;
    void execute(PassContext& context) override;

private:
    std::string mName;
    ShaderLibrary& mShaders;
    const FrameParams& mFrame;
    std::string mNormal;
    std::string mBaseColor;
    float mAmbient;
    std::unique_ptr<GlProgram> mProgram;
};

} // namespace inkgraph
