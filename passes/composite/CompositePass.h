#pragma once
/** @file Composite: the final picture on the CPU (postfx/Composite): shading over the paper colour, then every
 *  enabled line type's mask in its colour, in the order given.
 *
 *  | resource         | format | need     | content                                              |
 *  |------------------|--------|----------|------------------------------------------------------|
 *  | reads            |        |          | the shading colour (rgba8), if any                   |
 *  |                  |        |          | each line layer's mask (r8, 255 = line)              |
 *  | <name>.final     | rgba8  | required | sRGB picture, opaque                                 |
 */

#include "gl/GlPass.h"
#include "passes/FrameParams.h"

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace inkgraph {

class CompositePass : public GlPass {
public:
    struct LineInput {
        std::string resource; ///< "silhouette.lines"
        cv::Vec4f color;      ///< display RGBA in [0,1]
    };

    /** `shading` names an rgba8 colour resource, or is empty for paper only (--shading none). */
    CompositePass(std::string name, const FrameParams& frame, std::string shading, std::vector<LineInput> lines = {});

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    void execute(GlPassContext& context) override;

private:
    std::string mName;
    const FrameParams& mFrame;
    std::string mShading;
    std::vector<LineInput> mLines;
};

} // namespace inkgraph
