#pragma once
/** @file The smooth patches of a mesh: the triangles joined across edges where the mesh's normals are continuous. A
 *  loader keeps a vertex per distinct normal, so a hard edge (a cube's, every edge of a flat-shaded model) has two
 *  copies of each end with different normals, and the surface's normal field steps there: n.v is not differentiable
 *  across it, and an image-space derivative taken over it measures the step, not the surface's curvature. No GL. */

#include "scene/mesh/EdgeAdjacency.h"
#include "scene/mesh/MeshOps.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace inkgraph {

/** Normals at an edge's end closer than this many degrees count as one (a loader's copies of a vertex at a texture
 *  seam carry the same normal, bit for bit or within the rounding of a quantised file). */
constexpr double kSmoothPatchNormalDegrees = 1.0;

struct SmoothPatches {
    /** Per triangle, its patch, named by the patch's smallest triangle index. */
    std::vector<std::uint32_t> patchOf;
    /** Edges shared by two or more faces where the normals step (a face of the edge is not joined to its first):
     *  0 for a mesh smooth everywhere. */
    std::size_t seamEdges = 0;
};

/** Whether the mesh is one smooth patch, found without building any adjacency: no two copies of a welded point
 *  (`weld`, one entry per position) carry normals more than `normalDegrees` apart (one pass over the vertices), and
 *  its triangles are one connected surface through shared welded points (union-find over them). Then smoothPatches()
 *  has one patch. False says only that it may have more (a mesh of several loose parts, a flat-shaded one). */
bool isOneSmoothPatch(std::span<const glm::vec3> normals, std::span<const glm::uvec3> triangles, const WeldMap& weld,
                      double normalDegrees = kSmoothPatchNormalDegrees);

/** The smooth patches of a mesh: two triangles sharing an edge (buildEdgeAdjacency(), on the position
 *  weld `weld`) are in one patch when, at both ends of the edge, the normals their own corners carry (`normals`, one
 *  per position) are within `normalDegrees` of each other; patches are the connected sets of such joins. A patch is
 *  named by its smallest triangle index, so the answer does not depend on the order of the joins. A face the
 *  adjacency skipped (degenerate) is a patch of its own. Throws std::invalid_argument when `normals` or the weld are
 *  not one entry per position, or the adjacency is not of these triangles. */
SmoothPatches smoothPatches(std::span<const glm::vec3> normals, std::span<const glm::uvec3> triangles,
                            const WeldMap& weld, const EdgeAdjacency& adjacency,
                            double normalDegrees = kSmoothPatchNormalDegrees);

} // namespace inkgraph
