#pragma once
/** @file MToon's outlines (VRMC_materials_mtoon-1.0, docs/mtoon.md): each mesh whose material asks for one drawn
 *  again as its inflated hull, front faces culled, each as wide as its material says and in its outline colour, lit
 *  as far as its lighting mix says. A layer of its own, which the shade pass lays into the shading with a depth test.
 *
 *  | resource              | format   | need     | content                                                       |
 *  |-----------------------|----------|----------|---------------------------------------------------------------|
 *  | reads                 |          |          | nothing from the graph (meshes, hulls, materials from GpuScene) |
 *  | <name>.color          | rgba8    | required | sRGB outline colour, a = 255 where a shell is drawn, else 0;   |
 *  |                       |          |          | with samples > 1, per sample                                  |
 *  | <name>.depth          | depth32f | required | window depth of the nearest shell (reversed-Z, gl/GlObjects.h), |
 *  |                       |          |          | 0 (far) where none is                                         |
 *
 *  The shells are the meshes pushed out along GpuScene::hullNormals() (position-welded, so hard edges do not crack
 *  them): `worldCoordinates` by the width in model units, `screenCoordinates` by the width x the frame height in
 *  pixels along the normal's screen direction (shaders/mtoon/outline.vert). Only their back faces are drawn (where a
 *  shell sticks out beyond its surface), with a strictly-nearer depth test among themselves, so at each pixel the
 *  nearest shell wins and, of equal depths, the first mesh drawn. The shade pass (ShadeSettings::materialOutlines)
 *  then draws this layer after its opaque surfaces and before its blended ones, testing the depth here against its
 *  own strictly-nearer: the picture is the one the shells drawn among the surfaces would give, to the bit.
 *
 *  With the eye inside a mesh (a camera in a character's head) that mesh's shell is not drawn: every back face of it
 *  would face the eye and flood the picture in the outline colour. The other meshes' shells are drawn.
 *
 *  With samples above 1 (--msaa) both fields are multisampled graph textures, drawn with the samples of the shade
 *  pass's target and read by it sample by sample, so the shells' edges are anti-aliased as the surfaces' are and the
 *  picture stays the one the shells drawn among the surfaces would give. The layer goes through the graph as
 *  multisampled textures rather than being resolved here: a resolved colour and one depth per pixel could not be
 *  laid in at an edge where a shell's samples meet a surface's, and drawing the shells inside the shade pass would
 *  hide a layer the plan, --stats and --dump show. --dump writes the colour resolved (the samples' average) and one
 *  sample's depth.
 *
 *  The still graph registers the pass whenever the look is mtoon; the shade pass reads it only when some material
 *  asks for an outline (decided when the graph is built), so otherwise it is culled. */

#include "gl/GlObjects.h"
#include "gl/GlPass.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/WidthMap.h"

#include <memory>
#include <string>

namespace inkgraph {

/** The pass's name in the still graph, and so its resources' namespace: "mtoon-outline.color". */
inline constexpr const char* kMToonOutlinePass = "mtoon-outline";

class MToonOutlinePass : public GlPass {
public:
    /** `samples`: per pixel of both fields, the shade pass's (ShadeSettings::msaa): 1, 2, 4 or 8; std::invalid_argument
     *  otherwise. `widthMap` (--outline-width-map) scales each shell's width per vertex, times the material's own
     *  width texture (shaders/common/width_map.glsl). */
    MToonOutlinePass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame,
                     int samples = 1, WidthMap widthMap = {});

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    void prepare(GlPassContext& context) override;
    void execute(GlPassContext& context) override;
    /** What the last run did: the meshes whose shells it drew and their triangles, those not drawn because the eye
     *  is inside their mesh, and the width map's flag value when there is one. */
    void describe(nlohmann::ordered_json& report) const override;

    /** Whether some mesh's material of `scene` asks for an outline (outlineOf(), passes/material/SceneMaterials.h):
     *  the one question the still graph asks, when it is built, before it has the shade pass read the layer. */
    static bool drawsAnyOutline(const Scene& scene);

    std::size_t shellsDrawn() const { return mShellsDrawn; }
    std::size_t trianglesDrawn() const { return mTrianglesDrawn; }

private:
    std::string mName;
    ShaderLibrary& mShaders;
    GpuScene& mScene;
    const FrameParams& mFrame;
    int mSamples = 1;
    WidthMap mWidthMap;
    std::unique_ptr<GlProgram> mProgram;
    std::size_t mShellsDrawn = 0;
    std::size_t mTrianglesDrawn = 0;
    std::size_t mShellsSkippedEyeInside = 0; ///< meshes whose shell was not drawn: the eye is inside them
};

} // namespace inkgraph
