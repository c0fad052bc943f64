#pragma once
/** @file Lander's back-face outline (Winnemöller & Bangay 2002, docs/shading.md) as a line mask: back faces
 *  drawn as thick wireframe behind the filled front faces, so about half of each line shows outside the silhouette
 *  and interior occluding contours get lines too. Lines are expanded to screen-space quads (core profile has no
 *  reliable wide lines), so the width holds at every angle.
 *
 *  | resource      | format | need     | content                                          |
 *  |---------------|--------|----------|--------------------------------------------------|
 *  | reads         |        |          | nothing from the graph (meshes from GpuScene)     |
 *  | <name>.lines  | r8     | required | 255 where the outline shows, else 0               |
 *
 *  `widthPixels` is the visible width outside the silhouette: the wireframe is drawn twice as wide. With a CPU
 *  face-orientation method (GpuScene::cpuOrientation()) only the back sets it marked are submitted (they hold every
 *  true back face); the geometry shader's exact facing test decides in both cases.
 *
 *  Two draws with the pass's own depth attachment: the model's depth (every face, no colour), then the back faces,
 *  each triangle turned into three edge quads by a geometry shader, a nearer-or-equal depth test against the model
 *  (GL_GEQUAL: reversed-Z, gl/GlObjects.h), writing 255. GL culls what the geometry shader emits, not the triangles
 *  it receives, so the facing test is made there, on the view-space triangle. Edges are clipped to the near plane
 *  before the perspective divide, so an edge that passes behind the eye never smears across the frame. Quads get
 *  square caps, closing the joins.
 *
 *  With the eye inside a mesh every face is a back face and the frame would fill with lines, so the mask is left
 *  empty (skippedEyeInside(); checked when the pass runs, by ray parity on the CPU). */

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "gl/GlPass.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/orientation/SceneOrientation.h"

#include <memory>
#include <string>

namespace inkgraph {

class OutlinePass : public GlPass {
public:
    /** Draws the back sets of `scene.cpuOrientation()` when the scene has one (GPU culling otherwise). Throws
     *  std::invalid_argument for a negative or non-finite width. */
    OutlinePass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame, float widthPixels);

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    void prepare(GlPassContext& context) override;
    void execute(GlPassContext& context) override;

    /** "skipped_eye_inside": skippedEyeInside(). */
    void describe(nlohmann::ordered_json& report) const override;

    /** True when the last execute() left the mask empty because the eye was inside a mesh (for --stats). */
    bool skippedEyeInside() const { return mSkippedEyeInside; }

private:
    std::string mName;
    ShaderLibrary& mShaders;
    GpuScene& mScene;
    const FrameParams& mFrame;
    float mWidthPixels;
    std::unique_ptr<GlProgram> mDepthProgram; ///< the model, depth only
    std::unique_ptr<GlProgram> mLineProgram;  ///< back-face edges as quads
    PassDepthBuffer mDepth;                   ///< the pass's own depth attachment, kept between runs
    bool mSkippedEyeInside = false;
};

} // namespace inkgraph
