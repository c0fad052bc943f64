// Smooth patches (scene/mesh/SmoothPatches.h): the triangles joined across edges where the normals are continuous, on
// meshes with known answers: a hard-edged cube (a patch per side), a UV sphere (one patch across its texture seam and
// poles), two loose parts, and a flat-shaded mesh (a patch per triangle).
#include "scene/mesh/SmoothPatches.h"
#include "scene/mesh/MeshOps.h"
#include "scene/mesh/Procedural.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

namespace inkgraph {
namespace {

SmoothPatches patchesOf(const Mesh& mesh) {
    const WeldMap weld = weldVertices(mesh.positions, {}, 1e-6);
    return smoothPatches(mesh.normals, mesh.triangles, weld, buildEdgeAdjacency(mesh.positions, mesh.triangles, weld));
}

bool oneSmoothPatch(const Mesh& mesh) {
    return isOneSmoothPatch(mesh.normals, mesh.triangles, weldVertices(mesh.positions, {}, 1e-6));
}

std::size_t countOf(const SmoothPatches& patches) {
    return std::set<std::uint32_t>(patches.patchOf.begin(), patches.patchOf.end()).size();
}

/** The same mesh with every triangle its own three vertices, each carrying the face's normal: flat shading. */
Mesh flatShaded(const Mesh& smooth) {
    Mesh flat;
    for (const glm::uvec3& triangle : smooth.triangles) {
        const glm::vec3 a = smooth.positions[triangle.x], b = smooth.positions[triangle.y],
                        c = smooth.positions[triangle.z];
        const glm::vec3 normal = glm::normalize(glm::cross(b - a, c - a));
        const auto first = std::uint32_t(flat.positions.size());
        for (const glm::vec3& corner : {a, b, c}) {
            flat.positions.push_back(corner);
            flat.normals.push_back(normal);
        }
        flat.triangles.push_back({first, first + 1, first + 2});
    }
    return flat;
}

TEST(SmoothPatches, AHardEdgedCubeHasAPatchPerSide) {
    const Mesh cube = makeCube(glm::vec3(0.0f), 1.0f);
    const SmoothPatches patches = patchesOf(cube);
    ASSERT_EQ(patches.patchOf.size(), 12u);
    EXPECT_EQ(countOf(patches), 6u);
    // A side's two triangles share a patch, named by the smaller of them.
    for (std::uint32_t side = 0; side < 6; ++side) {
        EXPECT_EQ(patches.patchOf[2 * side], 2 * side);
        EXPECT_EQ(patches.patchOf[2 * side + 1], 2 * side);
    }
    EXPECT_EQ(patches.seamEdges, 12u); // the cube's 12 edges; the 6 diagonals inside the sides are smooth
    EXPECT_FALSE(oneSmoothPatch(cube));
}

TEST(SmoothPatches, ASphereIsOnePatchAcrossItsTextureSeamAndPoles) {
    const Mesh sphere = makeUvSphere(glm::vec3(0.0f), 1.0f, 24, 12);
    const SmoothPatches patches = patchesOf(sphere);
    EXPECT_EQ(countOf(patches), 1u);
    EXPECT_EQ(patches.seamEdges, 0u);
    EXPECT_TRUE(oneSmoothPatch(sphere));
}

TEST(SmoothPatches, LooseSmoothPartsArePatchesOfTheirOwn) {
    Mesh two = makeUvSphere(glm::vec3(0.0f), 1.0f, 16, 8);
    const Mesh other = makeUvSphere(glm::vec3(3.0f, 0.0f, 0.0f), 1.0f, 16, 8);
    const auto offset = std::uint32_t(two.positions.size());
    const std::size_t firstOfOther = two.triangles.size();
    two.positions.insert(two.positions.end(), other.positions.begin(), other.positions.end());
    two.normals.insert(two.normals.end(), other.normals.begin(), other.normals.end());
    for (const glm::uvec3& triangle : other.triangles) two.triangles.push_back(triangle + offset);
    const SmoothPatches patches = patchesOf(two);
    EXPECT_EQ(countOf(patches), 2u);
    EXPECT_EQ(patches.patchOf.back(), firstOfOther);
    EXPECT_EQ(patches.seamEdges, 0u); // they never meet at an edge
    // Smooth everywhere, yet not one patch: the cheap test must say so without an adjacency.
    EXPECT_FALSE(oneSmoothPatch(two));
}

TEST(SmoothPatches, AFlatShadedMeshHasAPatchPerFacet) {
    const Mesh flat = flatShaded(makeUvSphere(glm::vec3(0.0f), 1.0f, 12, 6));
    ASSERT_EQ(flat.triangles.size(), 120u);
    const SmoothPatches patches = patchesOf(flat);
    // A facet is a patch: the 24 triangles at the poles each, and each of the 48 quads between two latitudes, whose
    // two triangles are coplanar (an isosceles trapezoid), so their normals agree.
    EXPECT_EQ(countOf(patches), 24u + 48u);
    EXPECT_FALSE(oneSmoothPatch(flat));
    // Normals within the tolerance count as one: the same facets with a tolerance wider than the angle between any
    // two neighbours (a 12 x 6 sphere's facets meet at 30 degrees or less) are one patch.
    const WeldMap weld = weldVertices(flat.positions, {}, 1e-6);
    const SmoothPatches lenient = smoothPatches(flat.normals, flat.triangles, weld,
                                                buildEdgeAdjacency(flat.positions, flat.triangles, weld), 60.0);
    EXPECT_EQ(countOf(lenient), 1u);
}

TEST(SmoothPatches, RejectsMismatchedInputsNamingThem) {
    const Mesh cube = makeCube(glm::vec3(0.0f), 1.0f);
    const WeldMap weld = weldVertices(cube.positions, {}, 1e-6);
    const EdgeAdjacency adjacency = buildEdgeAdjacency(cube.positions, cube.triangles, weld);
    const std::vector<glm::vec3> tooFew(cube.normals.begin(), cube.normals.end() - 1);
    EXPECT_THROW(smoothPatches(tooFew, cube.triangles, weld, adjacency), std::invalid_argument);
    EXPECT_THROW(isOneSmoothPatch(tooFew, cube.triangles, weld), std::invalid_argument);
    const std::vector<glm::uvec3> fewerTriangles(cube.triangles.begin(), cube.triangles.end() - 1);
    EXPECT_THROW(smoothPatches(cube.normals, fewerTriangles, weld, adjacency), std::invalid_argument);
}

} // namespace
} // namespace inkgraph
