#include "scene/mesh/SmoothPatches.h"

#include "scene/mesh/DisjointSets.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

/** The mesh vertex of `triangle` at welded point `welded`; the adjacency filed the edge under the triangle's own
 *  corners, so one of them welds to it. */
std::uint32_t cornerAt(const glm::uvec3& triangle, std::uint32_t welded, const WeldMap& weld) {
    for (int corner = 0; corner < 3; ++corner)
        if (weld.outputOf[triangle[corner]] == welded) return triangle[corner];
    throw std::logic_error("smoothPatches(): a face of an edge has no corner at the edge's end");
}

/** Throws std::invalid_argument, naming `function`, unless the weld and the triangles fit the mesh's normals. */
void requireMeshArrays(const char* function, std::span<const glm::vec3> normals, std::span<const glm::uvec3> triangles,
                       const WeldMap& weld) {
    if (weld.outputOf.size() != normals.size())
        throw std::invalid_argument(std::string(function) + ": the weld maps " + std::to_string(weld.outputOf.size()) +
                                    " vertices, the mesh has " + std::to_string(normals.size()) + " normals");
    for (const glm::uvec3& triangle : triangles)
        for (int corner = 0; corner < 3; ++corner)
            if (triangle[corner] >= normals.size())
                throw std::invalid_argument(std::string(function) + ": a triangle indexes vertex " +
                                            std::to_string(triangle[corner]) + " of " + std::to_string(normals.size()));
}

float cosineOf(double degrees) { return float(std::cos(degrees * 3.14159265358979323846 / 180.0)); }

} // namespace

bool isOneSmoothPatch(std::span<const glm::vec3> normals, std::span<const glm::uvec3> triangles, const WeldMap& weld,
                      double normalDegrees) {
    requireMeshArrays("isOneSmoothPatch()", normals, triangles, weld);
    const float cosLimit = cosineOf(normalDegrees);
    for (std::size_t vertex = 0; vertex < normals.size(); ++vertex) {
        const std::uint32_t kept = weld.kept[weld.outputOf[vertex]];
        if (kept != vertex && glm::dot(normals[vertex], normals[kept]) < cosLimit) return false;
    }
    DisjointSets surfaces(weld.kept.size());
    for (const glm::uvec3& triangle : triangles) {
        surfaces.join(weld.outputOf[triangle[0]], weld.outputOf[triangle[1]]);
        surfaces.join(weld.outputOf[triangle[0]], weld.outputOf[triangle[2]]);
    }
    for (const glm::uvec3& triangle : triangles)
        if (surfaces.find(weld.outputOf[triangle[0]]) != surfaces.find(weld.outputOf[triangles.front()[0]]))
            return false;
    return true;
}

SmoothPatches smoothPatches(std::span<const glm::vec3> normals, std::span<const glm::uvec3> triangles,
                            const WeldMap& weld, const EdgeAdjacency& adjacency, double normalDegrees) {
    requireMeshArrays("smoothPatches()", normals, triangles, weld);
    if (adjacency.faceNormals.size() != triangles.size())
        throw std::invalid_argument("smoothPatches(): the adjacency is of " +
                                    std::to_string(adjacency.faceNormals.size()) + " triangles, the mesh has " +
                                    std::to_string(triangles.size()));
    const float cosLimit = cosineOf(normalDegrees);
    const auto agree = [&](std::uint32_t a, std::uint32_t b) {
        // The same vertex, or copies whose normals point the same way (loaders store unit normals).
        return a == b || glm::dot(normals[a], normals[b]) >= cosLimit;
    };
    SmoothPatches result;
    DisjointSets patches(triangles.size());
    for (const MeshEdge& edge : adjacency.edges) {
        const std::span<const EdgeFaceUse> uses = adjacency.facesOf(edge);
        if (uses.size() < 2) continue;
        const glm::uvec3& first = triangles[uses[0].face];
        const std::uint32_t firstStart = cornerAt(first, edge.welded[0], weld);
        const std::uint32_t firstEnd = cornerAt(first, edge.welded[1], weld);
        bool seam = false;
        for (std::size_t use = 1; use < uses.size(); ++use) {
            const glm::uvec3& other = triangles[uses[use].face];
            if (agree(firstStart, cornerAt(other, edge.welded[0], weld)) &&
                agree(firstEnd, cornerAt(other, edge.welded[1], weld)))
                patches.join(uses[0].face, uses[use].face);
            else
                seam = true;
        }
        if (seam) ++result.seamEdges;
    }
    result.patchOf.resize(triangles.size());
    for (std::size_t face = 0; face < triangles.size(); ++face)
        result.patchOf[face] = patches.find(std::uint32_t(face));
    return result;
}

} // namespace inkgraph
