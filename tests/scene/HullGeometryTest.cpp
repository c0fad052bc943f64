// The CPU geometry behind the inflated hull and the line passes' eye-inside check: position-welded normals across
// hard edges, and ray-parity containment.
#include "scene/mesh/MeshOps.h"
#include "scene/mesh/Procedural.h"
#include "scene/Scene.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace inkgraph {
namespace {

/** The cube [-1,1]^3 with split normals: every face has its own four corners and a centre vertex, all carrying the
 *  face normal, and is a fan of four equal triangles around the centre. Each corner copy therefore sees exactly one
 *  triangle of each of its three faces, all of the same area. */
Mesh splitNormalCube() {
    Mesh mesh;
    mesh.name = "split-cube";
    const std::vector<glm::vec3>& corners = test::cubeCorners();
    for (const glm::uvec4& quad : test::cubeQuads()) {
        const glm::vec3 a = corners[quad.x - 1], b = corners[quad.y - 1], c = corners[quad.z - 1],
                        d = corners[quad.w - 1];
        const glm::vec3 normal = glm::normalize(glm::cross(b - a, c - a));
        const auto first = std::uint32_t(mesh.positions.size());
        for (const glm::vec3& p : {a, b, c, d, (a + b + c + d) * 0.25f}) {
            mesh.positions.push_back(p);
            mesh.normals.push_back(normal);
        }
        const std::uint32_t centre = first + 4;
        for (std::uint32_t edge = 0; edge < 4; ++edge)
            mesh.triangles.emplace_back(first + edge, first + (edge + 1) % 4, centre);
    }
    return mesh;
}

TEST(HullNormals, SplitCubeCornersGetTheDiagonal) {
    const Mesh cube = splitNormalCube();
    ASSERT_EQ(cube.positions.size(), 30u);
    const std::vector<glm::vec3> normals = computePositionWeldedNormals(cube.positions, cube.triangles, 1e-6 * 3.5);
    ASSERT_EQ(normals.size(), cube.positions.size());
    for (std::size_t vertex = 0; vertex < cube.positions.size(); ++vertex) {
        const glm::dvec3 position(cube.positions[vertex]);
        const glm::dvec3 normal(normals[vertex]);
        const bool isCorner = std::abs(position.x) == 1.0 && std::abs(position.y) == 1.0 && std::abs(position.z) == 1.0;
        // Corners: the three face normals summed with equal weights, i.e. the diagonal through the corner. Face
        // centres belong to one face only and keep its normal, which equals position for this cube.
        const glm::dvec3 expected = isCorner ? position / std::sqrt(3.0) : position;
        EXPECT_NEAR(glm::length(normal - expected), 0.0, 1e-6) << "vertex " << vertex;
    }
    // The loader's split normals were per face: the three copies of each corner disagreed before welding.
    EXPECT_GT(glm::length(cube.normals[0] - cube.normals[5]), 0.5);
}

TEST(HullNormals, CopiesOfAVertexShareOneOutwardNormal) {
    // A two-triangle-per-face soup (36 separate corners, as STL stores it): the triangulation weights the faces
    // unequally at some corners, but every copy of a corner agrees and points into the corner's octant.
    const std::vector<glm::vec3> soup = test::cubeTriangleSoup(2.0, glm::dvec3(10.0, -3.0, 5.0));
    std::vector<glm::uvec3> triangles;
    for (std::uint32_t i = 0; i < soup.size(); i += 3) triangles.emplace_back(i, i + 1, i + 2);
    const std::vector<glm::vec3> normals = computePositionWeldedNormals(soup, triangles, 1e-6 * 7.0);
    for (std::size_t a = 0; a < soup.size(); ++a) {
        const glm::dvec3 fromCentre = (glm::dvec3(soup[a]) - glm::dvec3(10.0, -3.0, 5.0)) / 2.0;
        EXPECT_NEAR(glm::length(glm::dvec3(normals[a])), 1.0, 1e-6);
        for (int axis = 0; axis < 3; ++axis)
            EXPECT_GT(normals[a][axis] * fromCentre[axis], 0.1) << "copy " << a << " axis " << axis;
        for (std::size_t b = 0; b < soup.size(); ++b) {
            if (soup[a] == soup[b]) {
                EXPECT_EQ(normals[a], normals[b]) << "copies " << a << " and " << b;
            }
        }
    }
}

TEST(HullNormals, VerticesFartherThanTheWeldDistanceKeepTheirOwnFaces) {
    // Two triangles folded 90 degrees along the x axis (normals +z and -y); the second one's copy of the shared edge
    // sits 1e-3 away, and welded onto the first one's it makes the two triangles equal.
    const std::vector<glm::vec3> positions = {{0, 0, 0},      {1, 0, 0},      {0, 1, 0},
                                              {0, 0, 0.001f}, {1, 0, 0.001f}, {0, 0, 1}};
    const std::vector<glm::uvec3> triangles = {{0, 1, 2}, {3, 4, 5}};
    const std::vector<glm::vec3> apart = computePositionWeldedNormals(positions, triangles, 1e-6);
    EXPECT_NEAR(glm::length(glm::dvec3(apart[0]) - glm::dvec3(0, 0, 1)), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(glm::dvec3(apart[3]) - glm::dvec3(0, -1, 0)), 0.0, 1e-6);
    // Within reach, the edge's copies share the bisector.
    const std::vector<glm::vec3> welded = computePositionWeldedNormals(positions, triangles, 0.01);
    EXPECT_EQ(welded[0], welded[3]);
    EXPECT_NEAR(glm::length(glm::dvec3(welded[0]) - glm::normalize(glm::dvec3(0, -1, 1))), 0.0, 1e-5);
}

TEST(BackToBackTwins, TheLaterOfTwoTrianglesOnTheSameCornersWoundTheOtherWay) {
    // 0: front; 1: its twin (any rotation of the reverse); 2: the front again (same winding: no twin of 0);
    // 3: another twin, taken by 2; 4: other corners.
    const std::vector<glm::uvec3> triangles = {{0, 1, 2}, {1, 0, 2}, {2, 0, 1}, {0, 2, 1}, {0, 1, 3}};
    EXPECT_EQ(backToBackTwins(triangles), (std::vector<std::uint32_t>{1, 3}));
    EXPECT_TRUE(backToBackTwins(std::vector<glm::uvec3>{{0, 1, 2}, {1, 2, 0}, {2, 0, 1}}).empty())
        << "repeats of one winding are not twins";
    EXPECT_EQ(backToBackTwins(std::vector<glm::uvec3>{{5, 6, 7}, {5, 6, 7}, {7, 6, 5}, {6, 5, 7}}),
              (std::vector<std::uint32_t>{2, 3}))
        << "each earlier triangle takes one later";
    EXPECT_TRUE(backToBackTwins(std::vector<glm::uvec3>{}).empty());
    // Many repeats in one place: every other one is a twin, found in one pass.
    std::vector<glm::uvec3> repeats;
    for (int i = 0; i < 20000; ++i) repeats.push_back(i % 2 == 0 ? glm::uvec3(0, 1, 2) : glm::uvec3(2, 1, 0));
    EXPECT_EQ(backToBackTwins(repeats).size(), 10000u);
}

TEST(RepeatedTriangles, EveryLaterTriangleOnTheSameCornersWoundTheSameWay) {
    // 0: a face; 1 and 2: it again from other corners; 3: its back (not a repeat); 4: the back again; 5: other corners.
    const std::vector<glm::uvec3> triangles = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}, {1, 0, 2}, {0, 1, 3}};
    EXPECT_EQ(repeatedTriangles(triangles), (std::vector<std::uint32_t>{1, 2, 4}));
    EXPECT_TRUE(repeatedTriangles(std::vector<glm::uvec3>{{0, 1, 2}, {2, 1, 0}}).empty()) << "twins are not repeats";
    EXPECT_TRUE(repeatedTriangles(std::vector<glm::uvec3>{}).empty());
    // Many repeats in one place, found in one pass: all but the first of each winding.
    std::vector<glm::uvec3> repeats;
    for (int i = 0; i < 20000; ++i) repeats.push_back(i % 2 == 0 ? glm::uvec3(0, 1, 2) : glm::uvec3(2, 1, 0));
    EXPECT_EQ(repeatedTriangles(repeats).size(), 19998u);
}

TEST(HullNormals, ADoubleFacedCardKeepsTheNormalOfItsFirstSide) {
    // Two sheets on copies of one square's corners, the second wound the other way and carrying -z: welded, every
    // face of the pair cancelled its twin, leaving the sums pointing either way (a hull folded through the card).
    const std::vector<glm::vec3> positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0},
                                              {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    const std::vector<glm::uvec3> triangles = {{0, 1, 2}, {0, 2, 3}, {7, 6, 4}, {6, 5, 4}};
    const std::vector<glm::vec3> normals = computePositionWeldedNormals(positions, triangles, 1e-6);
    ASSERT_EQ(normals.size(), positions.size());
    for (const glm::vec3& normal : normals) EXPECT_EQ(normal, glm::vec3(0, 0, 1));
}

TEST(HullNormals, RejectsOutOfRangeIndices) {
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<glm::uvec3> triangles = {{0, 1, 3}};
    EXPECT_THROW(computePositionWeldedNormals(positions, triangles, 1e-6), std::out_of_range);
}

TEST(PointInsideMesh, SphereParityMatchesTheRadius) {
    const glm::dvec3 centre(1.0, 2.0, -3.0);
    const double radius = 2.0;
    const Mesh sphere = makeUvSphere(glm::vec3(centre), float(radius), 64, 32);
    EXPECT_TRUE(isPointInsideMesh(sphere, centre));
    // The poles and the seam are where rays through vertices and shared edges are likeliest.
    EXPECT_TRUE(isPointInsideMesh(sphere, centre + glm::dvec3(0.0, 0.0, 0.9 * radius)));
    EXPECT_FALSE(isPointInsideMesh(sphere, centre + glm::dvec3(0.0, 0.0, 1.1 * radius)));
    EXPECT_FALSE(isPointInsideMesh(sphere, centre + glm::dvec3(5.0 * radius, 0.0, 0.0)));
    std::mt19937 random(3);
    std::normal_distribution<double> gaussian;
    int checked = 0;
    for (int i = 0; i < 200; ++i) {
        const glm::dvec3 direction = glm::normalize(glm::dvec3(gaussian(random), gaussian(random), gaussian(random)));
        // 0.98 and 1.02: the 64 x 32 polygon lies within R (1 - cos(pi / 32)) ~ 0.005 R of the sphere.
        EXPECT_TRUE(isPointInsideMesh(sphere, centre + direction * (0.98 * radius))) << "sample " << i;
        EXPECT_FALSE(isPointInsideMesh(sphere, centre + direction * (1.02 * radius))) << "sample " << i;
        EXPECT_TRUE(isPointInsideMesh(sphere, centre + direction * (0.3 * radius))) << "sample " << i;
        ++checked;
    }
    EXPECT_EQ(checked, 200);
}

TEST(PointInsideMesh, APointAnOpenMeshCoversOnOneSideIsOutside) {
    // Under a dome (a sphere's upper half, no floor) two of the three rays pointed up through it, one down past its
    // rim: parity said inside, and the outline and silhouette of everything in the scene were skipped (the eye under
    // a roof, an umbrella, a hat's brim). Every ray now has its opposite, and five of the six must say inside.
    const Mesh sphere = makeUvSphere(glm::vec3(0.0f), 3.0f, 64, 32);
    Mesh dome = sphere;
    std::erase_if(dome.triangles, [&](const glm::uvec3& t) {
        return sphere.positions[t.x].y < 0.0f || sphere.positions[t.y].y < 0.0f || sphere.positions[t.z].y < 0.0f;
    });
    ASSERT_LT(dome.triangles.size(), sphere.triangles.size());
    Mesh cup = sphere; // the lower half: open at the top
    std::erase_if(cup.triangles, [&](const glm::uvec3& t) {
        return sphere.positions[t.x].y > 0.0f || sphere.positions[t.y].y > 0.0f || sphere.positions[t.z].y > 0.0f;
    });
    for (const glm::dvec3 point : {glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.3, 0.5, -0.7), glm::dvec3(1.0, 0.2, 1.0)}) {
        EXPECT_TRUE(isPointInsideMesh(sphere, point));
        EXPECT_FALSE(isPointInsideMesh(dome, point)) << point.x << "," << point.y << "," << point.z;
        EXPECT_FALSE(isPointInsideMesh(cup, -point)) << point.x << "," << point.y << "," << point.z;
    }
}

TEST(PointInsideMesh, HardEdgedCubeAndEmptyMesh) {
    const Mesh cube = splitNormalCube();
    EXPECT_TRUE(isPointInsideMesh(cube, glm::dvec3(0.0)));
    // On the diagonals and the face centres' axes, where rays hit edges and the fan's shared vertices.
    EXPECT_TRUE(isPointInsideMesh(cube, glm::dvec3(0.99, 0.99, 0.99)));
    EXPECT_TRUE(isPointInsideMesh(cube, glm::dvec3(0.0, 0.0, 0.999)));
    EXPECT_FALSE(isPointInsideMesh(cube, glm::dvec3(0.0, 0.0, 1.001)));
    EXPECT_FALSE(isPointInsideMesh(cube, glm::dvec3(1.01, 0.5, 0.5)));
    EXPECT_FALSE(isPointInsideMesh(Mesh{}, glm::dvec3(0.0)));
}

} // namespace
} // namespace inkgraph
