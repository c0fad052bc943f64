#pragma once
/** @file The inflated hull of seed 003 §3.6 as a line mask: the meshes pushed out along position-welded smooth
 *  normals (so hard edges and split normals do not crack the hull), back faces drawn where the model does not
 *  cover them.
 *
 *  | resource      | format | need     | content                                          |
 *  |---------------|--------|----------|--------------------------------------------------|
 *  | reads         |        |          | nothing from the graph (meshes from GpuScene)     |
 *  | <name>.lines  | r8     | required | 255 where the hull outline shows, else 0          |
 *
 *  Width: in screen space (default) the offset is applied in clip space, so the line is `widthPixels` wide at any
 *  distance, field of view and resolution; in object space the hull is offset by `objectWidth` model units. */

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "graph/Pass.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"

#include <memory>
#include <optional>
#include <string>

namespace inkgraph {

struct HullSettings {
    float widthPixels = 2.0f;
    std::optional<float> objectWidth; ///< model units; when set, the hull is offset in object space instead
};

class SilhouettePass : public Pass {
public:
    SilhouettePass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame,
                   HullSettings settings);

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    void prepare(PassContext& context) override;
    void execute(PassContext& context) override;

private:
    std::string mName;
    ShaderLibrary& mShaders;
    GpuScene& mScene;
    const FrameParams& mFrame;
    HullSettings mSettings;
};

} // namespace inkgraph
