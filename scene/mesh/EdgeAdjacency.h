#pragma once
/** @file Edge adjacency of a triangle mesh for object-space lines (docs/lines.md, Lander 2000 done the modern
 *  way): which faces share each edge, with their direction, the edge's kind, and the angle between the normals of
 *  the two faces of a manifold edge. No GL.
 *
 *  Edges are keyed on position-welded vertex ids, not on the mesh's own ids: loaders weld positions but keep a vertex
 *  per distinct normal, so a hard edge (a cube's, a flat-shaded model's) has two copies of each end, and keyed on
 *  those copies every crease would read as two borders. */

#include "scene/mesh/MeshOps.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace inkgraph {

enum class EdgeKind : std::uint8_t {
    Boundary,    ///< one face: the rim of an open surface
    Manifold,    ///< two faces
    NonManifold, ///< three or more faces (fins, T-junction sheets)
};

/** One face using an edge. */
struct EdgeFaceUse {
    std::uint32_t face; ///< index into the mesh's triangles
    bool againstKey;    ///< false when the face runs the edge from its smaller welded id to the larger
};

struct MeshEdge {
    /** The ends as the mesh's own vertex ids, as the first face using the edge names them (in its direction): what a
     *  draw call indexes. Any copy of a welded vertex would do, since copies share a position. */
    glm::uvec2 vertices;
    /** The same ends as position-welded ids (in the same order): one id per point, so edges that meet at a point
     *  share it whichever copies their faces name (chainEdges() follows lines through them). */
    glm::uvec2 welded;
    EdgeKind kind;
    /** Manifold edges whose two faces run it in the same direction: their normals disagree about which side is out.
     *  the s1 x s2 test of the comic-renderer write-up after Lander 2000 would fire everywhere or nowhere there; see
     * normalAngle and isSilhouetteEdge(). */
    bool inconsistentOrientation = false;
    /** Manifold edges only (0 otherwise): the angle between the two faces' unit normals, atan2(|n1 x n2|, n1 . n2),
     *  in radians: 0 across a flat surface, pi/2 at a cube's edge. This is pi minus the interior dihedral angle (a
     *  regular tetrahedron's interior angle is 70.53 degrees, its normals meet at 109.47). atan2 stays accurate near
     *  0, where acos(n1 . n2) loses half its digits. With inconsistent orientation the second normal is turned
     *  round first, as if the faces were re-oriented to agree. */
    float normalAngle = 0.0f;
    std::uint32_t firstFaceUse; ///< the faces using the edge are faceUses[firstFaceUse, firstFaceUse + faceCount)
    std::uint32_t faceCount;
};

struct EdgeAdjacencyCounts {
    std::size_t boundary = 0;
    std::size_t manifold = 0;
    std::size_t nonManifold = 0;
    std::size_t inconsistent = 0;    ///< manifold edges with inconsistent orientation
    std::size_t degenerateFaces = 0; ///< faces skipped: a repeated welded vertex, or zero area
    std::size_t edges() const { return boundary + manifold + nonManifold; }
};

struct EdgeAdjacency {
    std::vector<MeshEdge> edges;       ///< in order of first use (face order, then the face's edge order)
    std::vector<EdgeFaceUse> faceUses; ///< grouped by edge, in face order within an edge
    /** One per mesh triangle: the unit normal of its counter-clockwise winding, zero for a skipped degenerate face. */
    std::vector<glm::vec3> faceNormals;
    /** One per mesh triangle: n . p for its normal n and first vertex p, in double, so the face's plane is
     *  n . x = offset and n . (E - p) = n . E - offset for any eye E. Zero for a skipped face. */
    std::vector<double> facePlaneOffsets;
    EdgeAdjacencyCounts counts;

    std::span<const EdgeFaceUse> facesOf(const MeshEdge& edge) const {
        return std::span<const EdgeFaceUse>(faceUses).subspan(edge.firstFaceUse, edge.faceCount);
    }
};

/** Builds the adjacency of a triangle list. Vertices closer than `weldDistance` (absolute, >= 0; MeshOps
 *  weldVertices, ignoring normals) count as one. A face is skipped when two of its corners weld together or its area
 *  is at most 1e-14 x (bounding-box diagonal)^2 (the loaders' rule), so it has no normal and adds no edges. Every
 *  edge of every other face is filed on its own (Lander 2000's Templist stopped at a face's first match and lost its
 *  other edges) under its welded pair (min, max): a counting sort by the smaller id, which keeps face order, then
 *  each id's few entries sorted by the larger; equal pairs are one edge, numbered in order of first use. Faces and
 *  edges are processed in parallel where they are independent; the result does not depend on the split. Throws
 *  std::out_of_range for an index past the positions, std::invalid_argument for a negative or non-finite weld
 *  distance, and std::length_error from 715,827,883 triangles (edge uses are numbered in 32 bits). */
EdgeAdjacency buildEdgeAdjacency(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                 double weldDistance);
/** The same with the position weld given (weldVertices() of `positions` ignoring normals, or weldMeshPositions()),
 *  so the data derived from one mesh share one weld. Throws std::invalid_argument when the map is not one entry per
 *  position. */
EdgeAdjacency buildEdgeAdjacency(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                 const WeldMap& weld);

/** s = n . (E - p) for face `face`'s unit normal n, a point p of its plane and the eye E (model space): positive
 *  when the eye is in front of the face's plane. Exact under perspective (n . (E - x) is the same for every x on the
 *  plane); Lander 2000's -n . d with the view direction d is the orthographic special case. Zero for a skipped face. */
inline double eyeSideOfFace(const EdgeAdjacency& adjacency, std::uint32_t face, const glm::dvec3& eye) {
    return glm::dot(glm::dvec3(adjacency.faceNormals[face]), eye) - adjacency.facePlaneOffsets[face];
}

/** Whether a face with eyeSideOfFace() `side` faces the eye, after turning it round when `turned`. Zero (the eye in
 *  the face's plane, the face seen edge-on) is back-facing either way: the symbolic tie-break that makes exactly one
 *  edge of an edge-on strip fire, where Lander 2000's "include ties" drew two. */
inline bool facesEye(double side, bool turned) { return turned ? side < 0.0 : side > 0.0; }

/** Whether manifold `edge` is a silhouette edge seen from `eye` (model space): exactly one of its faces faces the
 *  eye (facesEye(), ties back-facing). With inconsistent orientation one face's normal points inward, so its
 *  answer is inverted first (re-orienting it locally, which is all the test needs). False for other kinds: the test
 *  is undefined for a boundary edge, and non-manifold edges are drawn as borders. */
bool isSilhouetteEdge(const EdgeAdjacency& adjacency, const MeshEdge& edge, const glm::dvec3& eye);

/** The silhouette edges seen from `eye` (model space) as pairs of mesh vertex ids, ready for GL_LINES. Classifies
 *  each face once, then each manifold edge. */
std::vector<std::uint32_t> selectSilhouetteEdges(const EdgeAdjacency& adjacency, const glm::dvec3& eye);

/** The manifold edges whose normal angle exceeds `creaseAngleRadians`, as pairs of mesh vertex ids. */
std::vector<std::uint32_t> selectCreaseEdges(const EdgeAdjacency& adjacency, double creaseAngleRadians);

/** Edges chained into lines through the points they share (MeshEdge::welded): at each point the incident edges are
 *  paired greedily, the pair that runs on straightest first (the smallest turn between the two edge directions, in
 *  3-D), while the turn is at most `maxTurnRadians`; so a line runs on through a point and stops where it branches
 *  off, and a point with one edge ends a line. Each edge then has at most one neighbour per end, so the chains are
 *  paths or closed loops. */
struct EdgeChains {
    std::vector<std::uint32_t> edges;   ///< the edges chained, as indices into EdgeAdjacency::edges, in the given order
    std::vector<std::uint32_t> chainOf; ///< one per entry of `edges`: its chain, numbered in order of first edge
    std::vector<double> chainLength;    ///< one per chain: the sum of its edges' 3-D lengths
    /** One per chain: the mean MeshEdge::normalAngle of its edges, weighted by their lengths (radians). */
    std::vector<double> chainNormalAngle;
};

/** Chains `edges` (indices into adjacency.edges; see EdgeChains). `positions` are the mesh's, as given to
 *  buildEdgeAdjacency(). Throws std::out_of_range for an edge index past the adjacency's edges or an end past the
 *  positions, and std::invalid_argument for a turn outside [0, pi]. */
EdgeChains chainEdges(const EdgeAdjacency& adjacency, std::span<const glm::vec3> positions,
                      std::span<const std::uint32_t> edges, double maxTurnRadians);

/** The largest turn, at a shared point, between two crease edges that chain into one line: 60 degrees, so a line
 *  runs on round a coarse mesh's bends (a hexagon turns 60 degrees per corner) while a branch leaving at a right
 *  angle ends a line. */
inline constexpr double kCreaseChainMaxTurnRadians = 60.0 * 3.14159265358979323846 / 180.0;

/** What selectProminentCreaseEdges() chose. */
struct CreaseSelection {
    std::vector<std::uint32_t> indices; ///< the kept edges as pairs of mesh vertex ids, ready for GL_LINES
    std::size_t edgesByAngle = 0;       ///< manifold edges above the crease angle
    std::size_t edgesKept = 0;          ///< of those, the ones in a long enough chain
    std::size_t chains = 0;             ///< chains the edges above the angle form
    std::size_t chainsKept = 0;         ///< chains at least the minimum length long
};

/** Crease prominence, decided on the mesh: the crease edges (selectCreaseEdges()) chained into lines (chainEdges(),
 *  kCreaseChainMaxTurnRadians), keeping only the edges of chains at least `minChainLength` long in 3-D (model units,
 *  >= 0; 0 keeps every crease). Dense detail (fur, braids, a scan's facets) has many short creases; an artist draws
 *  the long ones. In model units, so the same edges at every size and view. Throws std::invalid_argument for a
 *  negative or non-finite length. */
CreaseSelection selectProminentCreaseEdges(const EdgeAdjacency& adjacency, std::span<const glm::vec3> positions,
                                           double creaseAngleRadians, double minChainLength);

/** The boundary and non-manifold edges, as pairs of mesh vertex ids: both are places where the surface is not a
 *  closed two-sided sheet, and both are drawn as borders. */
std::vector<std::uint32_t> selectBorderEdges(const EdgeAdjacency& adjacency);

} // namespace inkgraph
