#pragma once
/** @file The inflated hull of Qu, Chen & Zwicker §3.6 as a line mask: the meshes pushed out along position-welded
 *  smooth normals (so hard edges and split normals do not crack the hull), back faces drawn where the model does
 *  not cover them.
 *
 *  | resource      | format | need     | content                                          |
 *  |---------------|--------|----------|--------------------------------------------------|
 *  | reads         |        |          | HullSettings::modelDepth when it runs anyway,      |
 *  |               |        |          | "gbuffer.zBuffer"); meshes from GpuScene           |
 *  | <name>.lines  | r8     | required | 255 where the hull outline shows, else 0          |
 *
 *  Two draws into the mask with the pass's own depth attachment: the model's depth (every face, no colour), then
 *  the hull's back faces (front faces culled, a strictly-nearer depth test against the model: GL_GREATER with
 *  reversed-Z, gl/GlObjects.h; depth not written), each fragment writing 255. Inside the model's silhouette the
 *  hull's back faces lie behind the model, so only the ring outside it, and the hull of nearer parts over farther
 *  ones, shows. When the G-buffer has drawn that same depth anyway, the hull is tested against its z-buffer instead
 *  and the first draw is left out (passes/StillGraph.cpp decides; both vertex shaders keep gl_Position invariant, so
 *  the model's depth is the same to the bit where the hull meets it).
 *
 *  Width: in screen space (default) the offset is applied in clip space, so the line is `widthPixels` wide at any
 *  distance, field of view and resolution; in object space the hull is offset by `objectWidth` model units. A
 *  vertex whose hull normal points along the line of sight has no screen direction and is not moved.
 *
 *  With the eye inside a mesh every back face would show and flood the frame, so the mask is left empty
 *  (skippedEyeInside(); checked when the pass runs, by ray parity on the CPU). */

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "gl/GlPass.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/WidthMap.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

struct HullSettings {
    float widthPixels = 2.0f;
    std::optional<float> objectWidth; ///< model units; when set, the hull is offset in object space instead
    /** Offset along GpuScene::hullNormals() (true) or along the mesh's own, possibly split, normals (false). Only
     *  tests turn this off, to show the cracks that welding closes. */
    bool weldNormals = true;
    /** A Format::Depth32F graph texture of the mask's size holding the depth of every face
     *  (GBufferPass::zBufferHoldsEveryFace(), "gbuffer.zBuffer") that the hull is tested against instead of a depth
     *  the pass draws itself, when its writer runs anyway (declare() asks the compiler): one draw of the meshes
     *  fewer. Empty: the pass always draws its own. */
    std::string modelDepth{};
    /** Scales either width per vertex (--outline-width-map, shaders/common/width_map.glsl): a vertex at 0 stays on
     *  the surface, and the hull shows nothing there. */
    WidthMap widthMap{};
};

class SilhouettePass : public GlPass {
public:
    /** Throws std::invalid_argument for a negative or non-finite width. */
    SilhouettePass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame,
                   HullSettings settings);

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
    HullSettings mSettings;
    std::unique_ptr<GlProgram> mDepthProgram; ///< the model as it is, depth only
    std::unique_ptr<GlProgram> mHullProgram;  ///< the offset hull
    PassDepthBuffer mDepth;                   ///< the pass's own depth attachment, kept between runs
    std::string mModelDepthResource;          ///< the plan being run reads HullSettings::modelDepth: it, else empty
    bool mSkippedEyeInside = false;
};

} // namespace inkgraph
