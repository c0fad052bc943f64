#include "scene/mesh/OutwardWinding.h"

#include "scene/mesh/DisjointSets.h"
#include "scene/mesh/EdgeAdjacency.h"
#include "scene/mesh/MeshOps.h"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace inkgraph {
namespace {

constexpr double kLooseShare = 0.01;      ///< of a surface's edges: rims and fins it may have and still be closed
constexpr double kFlatVolumeShare = 1e-9; ///< of the cubed bounding-box diagonal: a volume that decides nothing

/** The tetrahedron from `apex` to the triangle, times six: positive when the triangle is wound counter-clockwise
 *  seen from the side away from the apex. Summed over a closed surface: six times the volume it encloses, positive
 *  when it is wound counter-clockwise seen from outside, whatever the apex. */
double sixTimesTetrahedron(std::span<const glm::vec3> positions, const glm::uvec3& triangle, const glm::dvec3& apex) {
    const glm::dvec3 a = glm::dvec3(positions[triangle.x]) - apex;
    const glm::dvec3 b = glm::dvec3(positions[triangle.y]) - apex;
    const glm::dvec3 c = glm::dvec3(positions[triangle.z]) - apex;
    return glm::dot(a, glm::cross(b, c));
}

/** What decides one connected surface. */
struct SurfaceTally {
    double sixVolume = 0.0;
    BoundingBox box;
    std::size_t edges = 0;
    std::size_t looseEdges = 0; ///< on a rim or shared by more than two faces
    std::size_t manifold = 0;
    std::size_t inconsistent = 0;
    bool insideOut() const {
        const double diagonal = box.diagonal();
        return edges > 0 && double(looseEdges) <= kLooseShare * double(edges) &&
               double(inconsistent) <= kLooseShare * double(manifold) &&
               sixVolume < -6.0 * kFlatVolumeShare * diagonal * diagonal * diagonal;
    }
};

} // namespace

OutwardTurn orientMeshOutward(std::span<const glm::vec3> positions, std::vector<glm::uvec3>& triangles,
                              std::vector<glm::vec3>& normals, double weldDistance) {
    OutwardTurn turn;
    if (triangles.empty()) return turn;
    // Cheap first: only a mesh whose triangles enclose a negative volume in all pays for the weld and the edges. A
    // mesh with an inside-out surface and a larger outward one is missed; none is turned wrongly, since each
    // connected surface is judged alone below (an open floor under a closed figure adds a volume of either sign).
    const BoundingBox meshBox = computeBoundingBox(positions);
    double sixVolume = 0.0;
    for (const glm::uvec3& triangle : triangles)
        sixVolume += sixTimesTetrahedron(positions, triangle, meshBox.center());
    const double diagonal = meshBox.diagonal();
    if (sixVolume >= -6.0 * kFlatVolumeShare * diagonal * diagonal * diagonal) return turn;

    const WeldMap weld = weldVertices(positions, {}, weldDistance);
    DisjointSets surfaces(weld.kept.size()); // over welded vertex ids
    for (const glm::uvec3& triangle : triangles) {
        surfaces.join(weld.outputOf[triangle.x], weld.outputOf[triangle.y]);
        surfaces.join(weld.outputOf[triangle.x], weld.outputOf[triangle.z]);
    }
    std::vector<std::uint32_t> surfaceOfTriangle(triangles.size());
    std::vector<std::uint32_t> tallyOfRoot(weld.kept.size(), UINT32_MAX);
    std::vector<SurfaceTally> tallies;
    for (std::size_t face = 0; face < triangles.size(); ++face) {
        const std::uint32_t root = surfaces.find(weld.outputOf[triangles[face].x]);
        if (tallyOfRoot[root] == UINT32_MAX) {
            tallyOfRoot[root] = std::uint32_t(tallies.size());
            tallies.emplace_back();
        }
        surfaceOfTriangle[face] = tallyOfRoot[root];
        SurfaceTally& tally = tallies[tallyOfRoot[root]];
        for (const std::uint32_t corner : {triangles[face].x, triangles[face].y, triangles[face].z})
            tally.box.add(glm::dvec3(positions[corner]));
    }
    // The volume about each surface's own centre: exact for a closed one, and small terms.
    for (std::size_t face = 0; face < triangles.size(); ++face) {
        SurfaceTally& tally = tallies[surfaceOfTriangle[face]];
        tally.sixVolume += sixTimesTetrahedron(positions, triangles[face], tally.box.center());
    }
    const EdgeAdjacency adjacency = buildEdgeAdjacency(positions, triangles, weld);
    for (const MeshEdge& edge : adjacency.edges) {
        SurfaceTally& tally = tallies[surfaceOfTriangle[adjacency.faceUses[edge.firstFaceUse].face]];
        ++tally.edges;
        if (edge.kind != EdgeKind::Manifold) ++tally.looseEdges;
        if (edge.kind == EdgeKind::Manifold) ++tally.manifold;
        if (edge.inconsistentOrientation) ++tally.inconsistent;
    }

    std::vector<bool> turned(triangles.size(), false);
    for (std::size_t face = 0; face < triangles.size(); ++face) {
        if (!tallies[surfaceOfTriangle[face]].insideOut()) continue;
        std::swap(triangles[face].y, triangles[face].z);
        turned[face] = true;
        turn.windingReversed = true;
        turn.turnedTriangles.push_back(std::uint32_t(face));
    }
    if (!turn.windingReversed || normals.empty()) return turn;
    // Given normals that point against the turned faces (the sum over their corners of n . (b - a) x (c - a) is
    // negative) were inward too: those of the turned surfaces' vertices are negated. A vertex belongs to one surface.
    double agreement = 0.0;
    std::vector<bool> onTurned(positions.size(), false);
    for (std::size_t face = 0; face < triangles.size(); ++face) {
        if (!turned[face]) continue;
        const glm::uvec3& t = triangles[face];
        const glm::dvec3 a(positions[t.x]);
        const glm::dvec3 side = glm::cross(glm::dvec3(positions[t.y]) - a, glm::dvec3(positions[t.z]) - a);
        agreement += glm::dot(side, glm::dvec3(normals[t.x]) + glm::dvec3(normals[t.y]) + glm::dvec3(normals[t.z]));
        onTurned[t.x] = onTurned[t.y] = onTurned[t.z] = true;
    }
    if (agreement < 0.0) {
        for (std::size_t vertex = 0; vertex < normals.size(); ++vertex)
            if (onTurned[vertex]) normals[vertex] = -normals[vertex];
        turn.normalsFlipped = true;
    }
    return turn;
}

std::vector<std::uint32_t> turnMixedWinding(std::span<const glm::vec3> positions, std::vector<glm::uvec3>& triangles,
                                            std::span<const glm::vec3> normals, double weldDistance) {
    if (triangles.empty()) return {};
    const EdgeAdjacency adjacency = buildEdgeAdjacency(positions, triangles, weldDistance);
    if (adjacency.counts.inconsistent == 0) return {};
    // Per face its neighbours across manifold edges, and whether the pair runs the edge the same way (disagrees).
    struct Neighbour {
        std::uint32_t face;
        bool disagrees;
    };
    std::vector<std::uint32_t> firstOf(triangles.size() + 1, 0);
    for (const MeshEdge& edge : adjacency.edges)
        if (edge.kind == EdgeKind::Manifold)
            for (const EdgeFaceUse& use : adjacency.facesOf(edge)) ++firstOf[use.face + 1];
    for (std::size_t face = 0; face < triangles.size(); ++face) firstOf[face + 1] += firstOf[face];
    std::vector<Neighbour> neighbours(firstOf.back());
    std::vector<std::uint32_t> filled(firstOf.begin(), firstOf.end() - 1);
    for (const MeshEdge& edge : adjacency.edges) {
        if (edge.kind != EdgeKind::Manifold) continue;
        const std::span<const EdgeFaceUse> uses = adjacency.facesOf(edge);
        const bool disagrees = uses[0].againstKey == uses[1].againstKey;
        neighbours[filled[uses[0].face]++] = {uses[1].face, disagrees};
        neighbours[filled[uses[1].face]++] = {uses[0].face, disagrees};
    }

    // Each surface walked from its first face: `turn` says which faces wind the other way from it.
    constexpr std::uint8_t kUnseen = 2;
    std::vector<std::uint8_t> turn(triangles.size(), kUnseen);
    std::vector<std::uint32_t> surface, queue;
    std::vector<std::uint32_t> turned;
    for (std::size_t seed = 0; seed < triangles.size(); ++seed) {
        if (turn[seed] != kUnseen) continue;
        surface.clear();
        queue.assign(1, std::uint32_t(seed));
        turn[seed] = 0;
        bool mixed = false;
        while (!queue.empty()) {
            const std::uint32_t face = queue.back();
            queue.pop_back();
            surface.push_back(face);
            for (std::uint32_t k = firstOf[face]; k < firstOf[face + 1]; ++k) {
                const Neighbour& next = neighbours[k];
                mixed = mixed || next.disagrees;
                if (turn[next.face] != kUnseen) continue;
                turn[next.face] = std::uint8_t(turn[face] ^ std::uint8_t(next.disagrees));
                queue.push_back(next.face);
            }
        }
        if (!mixed) continue;
        // Which way to wind it: along the given normals where there are some, else as most of its area is.
        double keptVote = 0.0;
        for (const std::uint32_t face : surface) {
            const glm::uvec3& t = triangles[face];
            const glm::dvec3 a(positions[t.x]);
            const glm::dvec3 side = glm::cross(glm::dvec3(positions[t.y]) - a, glm::dvec3(positions[t.z]) - a);
            const double vote =
                normals.size() == positions.size()
                    ? glm::dot(side, glm::dvec3(normals[t.x]) + glm::dvec3(normals[t.y]) + glm::dvec3(normals[t.z]))
                    : glm::length(side);
            keptVote += turn[face] == 0 ? vote : -vote;
        }
        const std::uint8_t turnedWay = keptVote >= 0.0 ? 1 : 0;
        for (const std::uint32_t face : surface)
            if (turn[face] == turnedWay) turned.push_back(face);
    }
    std::sort(turned.begin(), turned.end());
    for (const std::uint32_t face : turned) std::swap(triangles[face].y, triangles[face].z);
    return turned;
}

std::size_t turnNormalsAlongWinding(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                    std::vector<glm::vec3>& normals) {
    if (normals.size() != positions.size()) return 0;
    double area = 0.0;    // twice the corner area, over every corner
    double against = 0.0; // of the corners whose normal points against their face
    std::vector<double> agreement(positions.size(), 0.0);
    for (const glm::uvec3& t : triangles) {
        const glm::dvec3 a(positions[t.x]);
        const glm::dvec3 side = glm::cross(glm::dvec3(positions[t.y]) - a, glm::dvec3(positions[t.z]) - a);
        const double sideLength = glm::length(side);
        for (const std::uint32_t corner : {t.x, t.y, t.z}) {
            const double dot = glm::dot(side, glm::dvec3(normals[corner]));
            agreement[corner] += dot;
            area += sideLength;
            if (dot < 0.0) against += sideLength;
        }
    }
    if (!(against > 0.9 * area)) return 0;
    std::size_t negated = 0;
    for (std::size_t vertex = 0; vertex < normals.size(); ++vertex) {
        if (!(agreement[vertex] < 0.0)) continue;
        normals[vertex] = -normals[vertex];
        ++negated;
    }
    return negated;
}

} // namespace inkgraph
