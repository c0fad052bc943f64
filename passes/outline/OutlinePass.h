#pragma once
/** @file Lander's back-face outline (seed 000, docs/algorithms.md §1.1) as a line mask: back faces drawn as thick
 *  wireframe behind the filled front faces, so about half of each line shows outside the silhouette and interior
 *  occluding contours get lines too. Lines are expanded to screen-space quads (core profile has no reliable wide
 *  lines), so the width holds at every angle.
 *
 *  | resource      | format | need     | content                                          |
 *  |---------------|--------|----------|--------------------------------------------------|
 *  | reads         |        |          | nothing from the graph (meshes from GpuScene)     |
 *  | <name>.lines  | r8     | required | 255 where the outline shows, else 0               |
 *
 *  `widthPixels` is the visible width outside the silhouette: the wireframe is drawn twice as wide. With a CPU
 *  face-orientation method (SceneOrientation) the back sets it marked are drawn; otherwise the GPU culls. */

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "graph/Pass.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/orientation/SceneOrientation.h"

#include <memory>
#include <string>

namespace inkgraph {

class OutlinePass : public Pass {
public:
    /** `orientation` may be null (GPU culling). */
    OutlinePass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame,
                float widthPixels, SceneOrientation* orientation);

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    void prepare(PassContext& context) override;
    void execute(PassContext& context) override;

private:
    std::string mName;
    ShaderLibrary& mShaders;
    GpuScene& mScene;
    const FrameParams& mFrame;
    float mWidthPixels;
    SceneOrientation* mOrientation;
};

} // namespace inkgraph
