#pragma once
/** @file Object-space edges (Lander 2000, docs/lines.md) as one-pixel line skeletons: the mesh's own edges,
 *  chosen from its edge adjacency (GpuScene::edgeAdjacency()) and drawn as GL_LINES where the model does not hide
 *  them. A later CPU pass draws the skeleton at the user's width with anti-aliasing.
 *
 *  | resource            | format | need     | content                                                          |
 *  |---------------------|--------|----------|------------------------------------------------------------------|
 *  | reads               |        |          | nothing from the graph (meshes and adjacency from GpuScene)       |
 *  | <name>.silhouette   | r8 xS  | optional | 255 on visible silhouette edges (exact perspective test), else 0  |
 *  | <name>.crease       | r8 xS  | optional | 255 on visible edges whose normals meet above the crease angle    |
 *  | <name>.border       | r8 xS  | optional | 255 on visible boundary and non-manifold edges, else 0           |
 *  | <name>.hidden-silhouette, .hidden-crease, .hidden-border                                                  |
 *  |                     | r8 xS  | optional | the same edges where the model hides them (--hidden-lines)       |
 *
 *  | <name>.<kind>-points | rgba32f xS | optional | --strokes: per line pixel of output <kind>, the fragment's view |
 *  |                     |        |          | position (interpolated along its edge) and the edge's triangle (global
 * index + 1)  |
 *
 *  Every output is `supersample` (S) times the frame size. Only live outputs are computed; a plan that reads none
 *  culls the pass, and then nothing (not even the adjacency) is derived. A hidden-<kind> output draws the same edges
 *  as <kind> with the fragment shader's depth test turned round (HIDDEN in shaders/edges/edges.frag), against the one
 *  model depth both share: every fragment of an edge lands in exactly one of the two.
 *
 *  Which edges:
 *  - silhouette: manifold edges where exactly one of s_i = n_i . (E - p_a) is > 0, E the eye in model space; exact
 *    under perspective, and s = 0 (a face seen edge-on) counts as back-facing, so one line, not two, runs along an
 *    edge-on strip. Chosen on the CPU every frame (one pass over the faces, one over the edges) and uploaded as an
 *    index list. Inconsistently oriented pairs are re-oriented locally first.
 *  - crease: manifold edges whose faces' normals meet at more than `creaseAngleDegrees` (atan2(|n1 x n2|, n1 . n2):
 *    0 on a flat surface, 90 at a cube's edge), whatever the view, and only those in a chain of crease edges at least
 *    `creaseMinLength` long (scene/mesh/EdgeAdjacency.h selectProminentCreaseEdges(): edges joined where they run on
 *    straightest, so fur, braids and a scan's facets lose their short creases). Chosen once per pass object.
 *  - border: boundary edges (one face) and non-manifold edges (three or more faces): both are where the surface
 *    stops being a closed two-sided sheet, and neither has a defined silhouette or crease test. Chosen once.
 *
 *  How: first the model's depth, once for every output, into the pass's own depth texture S x the frame size (every
 *  face, no colour), with polygon offset (factor 1, units 1) pushing the fill back by about one pixel of its own depth
 *  slope, so an edge passes over the faces it lies on, valleys included; skipped, the outputs only cleared, when no
 *  live output has an edge to draw (a dense scan whose creases are all shorter than the minimum length). Then each
 *  output's edges are drawn into it alone as 1-pixel GL_LINES writing 255, and their end points as 1-pixel GL_POINTS
 *  (GL leaves out a line's last pixel, diamond exit, which opened gaps wherever two edges of a chain met head to head).
 *  The depth test is made in the fragment shader (shaders/edges/edges.frag): a fragment is kept when it is no deeper
 *  than the farthest offset depth at its pixel and its 4 edge neighbours. The offset alone failed where a line's pixel
 *  centre fell on a nearer face that does not hold the edge (the sub-pixel sliver beside a silhouette edge of a fine
 *  mesh, which broke a sphere's silhouette ring at 2x supersampling); one pixel across a silhouette edge lies the
 *  background or a farther surface. So visibility is decided to within a pixel: a line behind the surface stays hidden
 *  except within about a pixel of the occluder's outline (where a cube's hidden edges meet its visible corners). Lines
 *  are clipped by GL, so an edge passing behind the eye is cut at the near plane.
 *
 *  With the eye inside a mesh the lines are still drawn (unlike the hull and Lander's outline, where every back face
 *  would flood the frame): the depth hides what lies behind the visible inner surface. Seen from inside a closed
 *  convex mesh every face is back-facing, so its silhouette output is empty, as it should be. */

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "gl/GlPass.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

struct MeshEdgesSettings {
    /** Manifold edges whose face normals meet at more than this are creases; in [0, 180]. */
    float creaseAngleDegrees = 30.0f;
    /** Crease prominence, in model units (the scene's), >= 0: a crease is drawn only when its edges chain into a line
     *  at least this long in 3-D (selectProminentCreaseEdges()), so the choice is the same at every size and view.
     *  0 keeps every crease. */
    float creaseMinLength = 0.0f;
    /** Every output is this many times the frame size in each direction (>= 1), so the one-pixel skeleton can be
     *  drawn and filtered down at the user's width. */
    int supersample = 1;
};

class MeshEdgesPass : public GlPass {
public:
    /** The outputs' field names, in the order the pass draws them. */
    static constexpr std::array<const char*, 6> kFields = {"silhouette",        "crease",        "border",
                                                           "hidden-silhouette", "hidden-crease", "hidden-border"};

    /** "<kind>-points": the field with each line fragment's 3-D point, drawn with <kind> only when live. */
    static constexpr const char* kPointsSuffix = "-points";

    /** Throws std::invalid_argument for a crease angle outside [0, 180] or not finite, a crease minimum length
     *  negative or not finite, or supersample < 1. */
    MeshEdgesPass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame,
                  MeshEdgesSettings settings = {});

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    /** Builds the program, uploads the meshes and, when some output is live, derives the adjacency and uploads the
     *  crease and border index lists (once per pass object). */
    void prepare(GlPassContext& context) override;
    void execute(GlPassContext& context) override;

    /** Edges submitted to each output in the last execute(), over all meshes (before the depth test decides which
     *  pixels show); empty for an output that was not live. For --stats. */
    struct EdgeCounts {
        std::optional<std::size_t> silhouette;
        std::optional<std::size_t> crease;
        std::optional<std::size_t> border;
        std::optional<std::size_t> hiddenSilhouette;
        std::optional<std::size_t> hiddenCrease;
        std::optional<std::size_t> hiddenBorder;
    };
    const EdgeCounts& edgesDrawn() const { return mEdgesDrawn; }
    /** Over all meshes, once the crease edges are chosen (prepare() with the crease output live). */
    struct CreaseCounts {
        std::size_t edgesByAngle = 0; ///< manifold edges above the crease angle
        std::size_t edgesKept = 0;    ///< of those, the ones in a chain at least creaseMinLength long
        std::size_t chains = 0;
        std::size_t chainsKept = 0;
    };
    const std::optional<CreaseCounts>& creaseCounts() const { return mCreaseCounts; }
    /** "edges_drawn": {"crease": n, "border": n, "silhouette": n, "hidden-crease": n, ...} for the outputs the last
     * execute() drew, and with the crease edges chosen "crease_edges": {"by_angle", "kept", "chains", "chains_kept"}.
     */
    void describe(nlohmann::ordered_json& report) const override;

    const MeshEdgesSettings& settings() const { return mSettings; }

private:
    /** One mesh's edges for one output: an index list of vertex pairs on the mesh's own position buffer. */
    struct EdgeLines {
        std::optional<GlBuffer> indices; ///< empty when the mesh has no such edges (GL refuses empty buffers)
        std::optional<GlVertexArray> vertexArray;
        GLsizei indexCount = 0;
        /** Per edge, the global index + 1 of a triangle holding it (float), for the "-points" outputs; empty unless
         *  one is live. */
        std::optional<GlBuffer> triangles;
    };

    EdgeLines uploadEdgeLines(const std::string& output, std::size_t meshIndex,
                              const std::vector<std::uint32_t>& indices) const;
    /** Per edge of `indices` (vertex pairs of mesh `meshIndex`), the global index + 1 of a triangle holding it. */
    std::vector<float> edgeTriangles(std::size_t meshIndex, const std::vector<std::uint32_t>& indices) const;
    /** Draws `lines` (one per mesh) as GL_LINES with `program` (in use); returns the number of edges. */
    std::size_t drawEdgeLines(const GlProgram& program, const std::vector<EdgeLines>& lines);

    std::string mName;
    ShaderLibrary& mShaders;
    GpuScene& mScene;
    const FrameParams& mFrame;
    MeshEdgesSettings mSettings;
    std::unique_ptr<GlProgram> mDepthProgram;  ///< the model's depth
    std::unique_ptr<GlProgram> mLineProgram;   ///< edges as lines, tested against that depth in the shader
    std::unique_ptr<GlProgram> mHiddenProgram; ///< the same with the test turned round (HIDDEN); built when live
    std::vector<EdgeLines> mCreaseLines;       ///< one per mesh once uploaded: view-independent
    std::vector<EdgeLines> mBorderLines;       ///< one per mesh once uploaded: view-independent
    std::vector<EdgeLines> mSilhouetteLines;   ///< one per mesh, chosen and uploaded every execute()
    PassDepthBuffer mDepth;                    ///< the pass's own depth attachment, kept between runs
    EdgeCounts mEdgesDrawn;
    std::optional<CreaseCounts> mCreaseCounts;
    std::optional<GlBuffer> mNoTriangles; ///< bound for the shader's edge triangles when no "-points" output is live
    bool mPointsWanted = false;           ///< some "-points" output is live (prepare()): the edge lists carry triangles
};

} // namespace inkgraph
