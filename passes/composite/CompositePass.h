#pragma once
/** @file Composite: the final picture on the CPU (postfx/Composite), shading over the paper colour.
 *  Later line types are layered here too.
 *
 *  | resource         | format | need     | content                                              |
 *  |------------------|--------|----------|------------------------------------------------------|
 *  | reads            |        |          | the shading colour (rgba8), if any                   |
 *  | <name>.final     | rgba8  | required | sRGB picture, opaque                                 |
 */

#include "graph/Pass.h"
#include "passes/FrameParams.h"

#include <optional>
#include <string>

namespace inkgraph {

class CompositePass : public Pass {
public:
    /** `shading` names an rgba8 colour resource, or is empty for paper only (--shading none). */
    CompositePass(std::string name, const FrameParams& frame, std::string shading);

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    void execute(PassContext& context) override;

private:
    std::string mName;
    const FrameParams& mFrame;
    std::string mShading;
};

} // namespace inkgraph
