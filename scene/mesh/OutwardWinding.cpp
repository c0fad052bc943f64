#include "scene/mesh/OutwardWinding.h"

#include "scene/mesh/EdgeAdjacency.h"
#include "scene/mesh/MeshOps.h"

#include <utility>

namespace inkgraph {
namespace {

/** Six times the volume the triangles enclose, positive when they are wound counter-clockwise seen from outside:
 *  the sum of the tetrahedra from `apex` to each triangle (exact for a closed mesh whatever the apex; the box's centre
 *  keeps the terms small). */
double sixTimesSignedVolume(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                            const glm::dvec3& apex) {
    double sum = 0.0;
    for (const glm::uvec3& triangle : triangles) {
        const glm::dvec3 a = glm::dvec3(positions[triangle.x]) - apex;
        const glm::dvec3 b = glm::dvec3(positions[triangle.y]) - apex;
        const glm::dvec3 c = glm::dvec3(positions[triangle.z]) - apex;
        sum += glm::dot(a, glm::cross(b, c));
    }
    return sum;
}

bool isClosedEnough(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles, double weldDistance) {
    constexpr double kLooseShare = 0.01;
    const EdgeAdjacencyCounts counts = buildEdgeAdjacency(positions, triangles, weldDistance).counts;
    const double edges = double(counts.edges());
    return edges > 0.0 && double(counts.boundary + counts.nonManifold) <= kLooseShare * edges &&
           double(counts.inconsistent) <= kLooseShare * double(counts.manifold);
}

/** Whether the normals agree with the faces' counter-clockwise sides: the sum over corners of n . (b - a) x (c - a). */
bool normalsPointWithFaces(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                           std::span<const glm::vec3> normals) {
    double agreement = 0.0;
    for (const glm::uvec3& triangle : triangles) {
        const glm::dvec3 a(positions[triangle.x]);
        const glm::dvec3 face =
            glm::cross(glm::dvec3(positions[triangle.y]) - a, glm::dvec3(positions[triangle.z]) - a);
        agreement += glm::dot(face, glm::dvec3(normals[triangle.x]) + glm::dvec3(normals[triangle.y]) +
                                        glm::dvec3(normals[triangle.z]));
    }
    return agreement >= 0.0;
}

} // namespace

OutwardTurn orientMeshOutward(std::span<const glm::vec3> positions, std::vector<glm::uvec3>& triangles,
                              std::vector<glm::vec3>& normals, double weldDistance) {
    OutwardTurn turn;
    const BoundingBox box = computeBoundingBox(positions);
    const double diagonal = box.diagonal();
    constexpr double kFlatVolumeShare = 1e-9;
    // Cheap first: only a mesh that encloses a negative volume pays for the closedness test.
    if (triangles.empty() || sixTimesSignedVolume(positions, triangles, box.center()) >=
                                 -6.0 * kFlatVolumeShare * diagonal * diagonal * diagonal)
        return turn;
    if (!isClosedEnough(positions, triangles, weldDistance)) return turn;
    for (glm::uvec3& triangle : triangles) std::swap(triangle.y, triangle.z);
    turn.windingReversed = true;
    if (!normals.empty() && !normalsPointWithFaces(positions, triangles, normals)) {
        for (glm::vec3& normal : normals) normal = -normal;
        turn.normalsFlipped = true;
    }
    return turn;
}

} // namespace inkgraph
