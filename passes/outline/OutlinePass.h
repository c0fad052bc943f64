#pragma once
/** @file Lander's back-face outline (Winnemöller & Bangay 2002, docs/shading.md) as a line mask: the mesh's contour
 *  edges (where the surface folds away from the eye: the occluding outline, interior occluding contours included)
 *  and the borders of open sheets, drawn as wide bands on their outer side where the model does not hide them. Lines
 *  are expanded to screen-space quads (core profile has no reliable wide lines), so the width holds at every angle.
 *
 *  | resource      | format | need     | content                                                    |
 *  |---------------|--------|----------|------------------------------------------------------------|
 *  | reads         |        |          | nothing from the graph (meshes and adjacency from GpuScene) |
 *  | <name>.lines  | r8     | required | 255 where the outline shows, else 0                         |
 *
 *  `widthPixels` is the visible width outside the silhouette, scaled per vertex by `widthMap` (--outline-width-map,
 *  shaders/common/width_map.glsl): each edge's band is the width at its two ends, a trapezoid between, and nothing
 *  where both ends are 0.
 *
 *  Which edges. Lander drew every back face as thick wireframe; that also inks the interior edges of a sheet seen
 *  from behind (a double-sided card's diagonal) and lets wide edge quads of a layer just behind the visible one (a
 *  thin shell, two-layer cloth) poke through the tilted front surface as dotted ink. So each edge of the mesh's
 *  adjacency (GpuScene::edgeAdjacency(), position-welded) is drawn once, as a GL_LINES_ADJACENCY primitive
 *  (outlineEdgeIndices()): its two ends and one opposite vertex of the face on each side. The geometry shader keeps
 *  it when both opposite vertices lie on the same side of the plane through the eye and the edge: the surface folds
 *  back there, the exact perspective contour test (for a consistently oriented manifold edge it is "one face front,
 *  one back", docs/lines.md), needing no orientation, so flipped faces and double-sided sheets need no care. A border
 *  (one face) repeats its opposite vertex and is always kept; a non-manifold edge whose faces span less than half a
 *  turn around it is sent with its two outermost faces, one whose faces span more never folds and is not sent.
 *
 *  How: two draws with the pass's own depth attachment: the model's depth (every face, no colour), then the edges,
 *  each kept one turned into a quad widthPixels wide on the side away from its faces (the band the front faces would
 *  have hidden half of is not drawn at all, so nothing lies on the surface to z-fight with it), with square caps
 *  closing the joins, a nearer-or-equal depth test against the model (GL_GEQUAL: reversed-Z, gl/GlObjects.h),
 *  writing 255. An edge seen end-on becomes a square around its point. Edges are clipped to the near plane before the
 *  perspective divide, so an edge that passes behind the eye never smears across the frame. A material's cut-out
 *  cuts the edges through it (the ends carry the surface's texture coordinates to common/line_mask.frag).
 *
 *  The CPU face orientation (GpuScene::cpuOrientation()) plays no part: its back sets were a saving on submitting
 *  faces, and edges are chosen per view in the geometry shader.
 *
 *  With the eye inside a mesh most of the surface folds around the eye and the frame would fill with lines, so the
 *  mask is left empty (skippedEyeInside(); checked when the pass runs, by ray parity on the CPU). */

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "gl/GlPass.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/WidthMap.h"
#include "scene/mesh/EdgeAdjacency.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace inkgraph {

/** The outline's candidate edges of one mesh as GL_LINES_ADJACENCY indices, four per edge: (opposite vertex of one
 *  face, first end, second end, opposite vertex of another face), mesh vertex ids. A boundary edge repeats its one
 *  opposite vertex; a manifold edge has its two faces'; a non-manifold edge has the two faces bounding the widest
 *  angular gap around it when that gap exceeds half a turn (then every face lies within a half-space and it can be
 *  a contour), and is left out otherwise (its faces surround it: it never folds away from the eye). `adjacency` must
 *  have been built from `positions` and `triangles` (buildEdgeAdjacency()). Throws std::invalid_argument when a face
 *  it names is out of range. */
std::vector<std::uint32_t> outlineEdgeIndices(std::span<const glm::vec3> positions,
                                              std::span<const glm::uvec3> triangles, const EdgeAdjacency& adjacency);

class OutlinePass : public GlPass {
public:
    /** Throws std::invalid_argument for a negative or non-finite width. */
    OutlinePass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame, float widthPixels,
                WidthMap widthMap = {});

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    /** Builds the programs, uploads the meshes and, once per pass object, derives the adjacency and uploads each
     *  mesh's edge list (outside the timed execute()). */
    void prepare(GlPassContext& context) override;
    void execute(GlPassContext& context) override;

    /** "skipped_eye_inside": skippedEyeInside(); "width_map": the width map's flag value, when there is one. */
    void describe(nlohmann::ordered_json& report) const override;

    /** True when the last execute() left the mask empty because the eye was inside a mesh (for --stats). */
    bool skippedEyeInside() const { return mSkippedEyeInside; }

private:
    /** One mesh's edges: outlineEdgeIndices() on the mesh's own position buffer and material attributes. */
    struct EdgeList {
        std::optional<GlBuffer> indices; ///< empty when the mesh has no candidate edges (GL refuses empty buffers)
        std::optional<GlVertexArray> vertexArray;
        GLsizei indexCount = 0;
    };

    std::string mName;
    ShaderLibrary& mShaders;
    GpuScene& mScene;
    const FrameParams& mFrame;
    float mWidthPixels;
    WidthMap mWidthMap;
    std::unique_ptr<GlProgram> mDepthProgram; ///< the model, depth only
    std::unique_ptr<GlProgram> mLineProgram;  ///< contour and border edges as quads
    std::vector<EdgeList> mEdges;             ///< one per mesh once prepared, else empty
    PassDepthBuffer mDepth;                   ///< the pass's own depth attachment, kept between runs
    bool mSkippedEyeInside = false;
};

} // namespace inkgraph
