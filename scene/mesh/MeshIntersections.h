#pragma once
/** @file Where the surfaces of a scene cross (the `intersection` line type, docs/lines.md): every pair of triangles
 *  that properly cross gives its intersection segment, found exactly on the mesh in double (Moller 1997, "A fast
 *  triangle-triangle intersection test": each triangle cut by the other's plane, the two cuts overlapped along the
 *  planes' common line). Between different meshes and within one mesh (self-intersection: hair cards, clothing).
 *  No GL. Blender's Line Art draws the same lines from the same test.
 *
 *  Properly cross: each triangle has a vertex strictly on each side of the other's plane, and their cuts overlap in
 *  a segment of positive length. So touching faces (coplanar), a vertex or an edge resting on a face, and edges that
 *  only meet give nothing. A vertex within rounding (1e-12 relative) of a plane is on it: positions are float, the
 *  test runs in double, so a vertex placed on another mesh's face is seen there exactly.
 *
 *  Two triangles of one mesh that share a vertex *by position* (after the position weld, so copies of a vertex split
 *  at a UV seam or a hard edge count as one) are never tested: neighbours meet at their shared edge or corner, which
 *  is no crossing.
 *
 *  Cost: a bounding volume hierarchy over the triangles' boxes (all meshes in one, median splits along the longest
 *  axis), built in O(n log n); each triangle then queries it for the boxes it overlaps, O(log n + k) for k overlaps,
 *  and only those pairs are tested. On a mesh whose triangles are about as large as their neighbours, k is the dozen
 *  or so triangles around it, so the search is O(n log n) in all, split across the cores (ParallelRanges.h) with
 *  results in triangle order, the same on every machine. */

#include "scene/mesh/MeshOps.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace inkgraph {

/** One piece of an intersection curve: where triangle triangles[0] of mesh meshes[0] crosses triangle triangles[1] of
 *  mesh meshes[1] (meshes[0] <= meshes[1]; equal for a self-intersection). */
struct IntersectionSegment {
    std::array<glm::dvec3, 2> ends; ///< in the scene's local frame, like the positions
    std::array<std::uint32_t, 2> meshes{};
    std::array<std::uint32_t, 2> triangles{};
};

/** What the search did, for --stats. */
struct IntersectionReport {
    std::size_t triangles = 0;         ///< indexed, over all meshes
    std::size_t boxPairs = 0;          ///< pairs of triangles whose boxes overlap (the index's candidates)
    std::size_t sharedVertexPairs = 0; ///< of them, pairs of one mesh skipped for sharing a welded vertex
    std::size_t pairsTested = 0;       ///< triangle-triangle tests run
    std::size_t segments = 0;          ///< segments found
    std::size_t selfSegments = 0;      ///< of them, within one mesh
    std::size_t indexNodes = 0;        ///< nodes of the hierarchy
    double indexMilliseconds = 0.0;    ///< building the index
    double searchMilliseconds = 0.0;   ///< querying it and testing the pairs
};

struct MeshIntersections {
    std::vector<IntersectionSegment> segments; ///< in order of their first triangle (mesh, then triangle)
    IntersectionReport report;
    /** The memory the segments hold (the index is freed before the search returns). */
    std::size_t bytes() const { return segments.capacity() * sizeof(IntersectionSegment); }
};

/** The segment where triangles `a` and `b` properly cross (the rule in the file comment), or nothing. In double. */
std::optional<std::array<glm::dvec3, 2>> triangleIntersectionSegment(const std::array<glm::dvec3, 3>& a,
                                                                     const std::array<glm::dvec3, 3>& b);

/** Every segment where the triangles of `meshes` properly cross, between meshes and within each; `welds` is each
 *  mesh's position weld (MeshOps weldMeshPositions(); GpuScene::positionWeld()), one per mesh, whose outputOf decides
 *  which triangles of one mesh share a vertex. Throws std::invalid_argument when `welds` is not one map per mesh, or
 *  one map has not one entry per position. */
MeshIntersections findMeshIntersections(std::span<const Mesh> meshes, std::span<const WeldMap* const> welds);

/** The same, each mesh welded by position at `weldDistance` (absolute) here. */
MeshIntersections findMeshIntersections(std::span<const Mesh> meshes, double weldDistance);

} // namespace inkgraph
