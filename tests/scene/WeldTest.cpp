#include "scene/mesh/MeshOps.h"
#include "scene/Scene.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <random>
#include <sstream>

namespace inkgraph {
namespace {

using test::TempFile;

/** The cube as 36 separate OBJ vertices (one triangle per face line), each moved by up to `jitter` x scale. */
std::string jitteredCubeObj(double scale, double jitter, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::ostringstream obj;
    obj.precision(17);
    const std::vector<glm::vec3> soup = test::cubeTriangleSoup();
    for (const glm::vec3& corner : soup) {
        const glm::dvec3 moved =
            glm::dvec3(corner) * scale + glm::dvec3(unit(random), unit(random), unit(random)) * (jitter * scale);
        obj << "v " << moved.x << ' ' << moved.y << ' ' << moved.z << '\n';
    }
    for (std::size_t i = 0; i < soup.size(); i += 3) {
        obj << "f " << i + 1 << ' ' << i + 2 << ' ' << i + 3 << '\n';
    }
    return obj.str();
}

TEST(SceneWeld, ToleranceIsRelativeToModelSize) {
    // 1e-7 survives float rounding at every scale; 1e-9 is below float precision and must weld too.
    for (double scale : {1e-4, 1.0, 1e5}) {
        for (double jitter : {1e-9, 1e-7}) {
            const TempFile file("jittered.obj", jitteredCubeObj(scale, jitter, 7));
            const Scene scene = loadScene(file.path());
            EXPECT_EQ(scene.report.verticesBeforeWeld, 36u);
            EXPECT_EQ(scene.vertexCount(), 8u) << "scale " << scale << ", jitter " << jitter;
            EXPECT_EQ(scene.triangleCount(), 12u) << "scale " << scale << ", jitter " << jitter;
            test::expectOutwardWinding(scene.meshes.at(0), glm::dvec3(0.0));
        }
    }
}

TEST(SceneWeld, VerticesFartherThanTheToleranceStaySeparate) {
    // Two corners 1e-4 x (model size) apart are distinct features at the default tolerance of 1e-6.
    const TempFile file("near.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1.0001 0 0\nv 1 1 0\nf 1 2 3\nf 4 5 3\n");
    EXPECT_EQ(loadScene(file.path()).vertexCount(), 5u);

    LoadOptions loose;
    loose.weldTolerance = 1e-3;
    EXPECT_EQ(loadScene(file.path(), loose).vertexCount(), 4u);

    LoadOptions invalid;
    invalid.weldTolerance = -1.0;
    EXPECT_THROW(loadScene(file.path(), invalid), std::invalid_argument);
}

TEST(SceneWeld, PointsStraddlingACellBorderMerge) {
    // With distance 1 the grid cells are 2.5 wide; 2.4999 and 2.5001 sit in different cells yet must merge.
    const std::vector<glm::vec3> positions = {
        {0, 0, 0}, {2.4999f, 0, 0}, {2.5001f, 0, 0}, {2.5001f, 2.4999f, 2.5001f}, {2.4999f, 2.5001f, 2.4999f}};
    const WeldMap map = weldVertices(positions, {}, 1.0);
    ASSERT_EQ(map.kept.size(), 3u);
    EXPECT_EQ(map.outputOf[1], map.outputOf[2]);
    EXPECT_EQ(map.outputOf[3], map.outputOf[4]);
    EXPECT_NE(map.outputOf[0], map.outputOf[1]);
}

TEST(SceneWeld, JoinsTheNearestRepresentative) {
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1.5f, 0, 0}, {0.8f, 0, 0}};
    const WeldMap map = weldVertices(positions, {}, 1.0);
    ASSERT_EQ(map.kept.size(), 2u);
    EXPECT_EQ(map.outputOf[2], map.outputOf[1]); // 0.8 is within reach of both; (1.5, 0, 0) is nearer
}

TEST(SceneWeld, ZeroDistanceMergesExactDuplicatesOnly) {
    const std::vector<glm::vec3> positions = {{1, 2, 3}, {1, 2, 3.000001f}, {1, 2, 3}};
    const WeldMap map = weldVertices(positions, {}, 0.0);
    EXPECT_EQ(map.kept, (std::vector<std::uint32_t>{0, 1}));
    EXPECT_EQ(map.outputOf, (std::vector<std::uint32_t>{0, 1, 0}));
}

TEST(SceneWeld, DifferentNormalsAtOnePositionStaySplit) {
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    const std::vector<glm::vec3> normals = {{0, 0, 1}, {1, 0, 0}, {0, 0, 1}};
    const WeldMap map = weldVertices(positions, normals, 1e-3);
    EXPECT_EQ(map.kept.size(), 2u);
    EXPECT_EQ(map.outputOf[0], map.outputOf[2]);
    EXPECT_NE(map.outputOf[0], map.outputOf[1]);
    EXPECT_TRUE(map.splitByNormals);
    // The same normals, or none, split nothing (finalizeMesh() then finds back-to-back twins on the weld's vertices).
    EXPECT_FALSE(weldVertices(positions, std::vector<glm::vec3>(3, glm::vec3(0, 0, 1)), 1e-3).splitByNormals);
    EXPECT_FALSE(weldVertices(positions, {}, 1e-3).splitByNormals);
}

TEST(SceneWeld, ZeroLengthSmoothNormalFallsBackToAFaceNormal) {
    // Vertex 0 is shared by two coplanar triangles of opposite orientation: their cross products cancel.
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<glm::uvec3> triangles = {{0, 1, 2}, {0, 2, 1}};
    const std::vector<glm::vec3> normals = computeSmoothNormals(positions, triangles);
    for (const glm::vec3& normal : normals) {
        EXPECT_EQ(normal, glm::vec3(0, 0, 1)); // the first incident face's normal
    }
    const std::vector<glm::vec3> isolated = computeSmoothNormals(positions, std::vector<glm::uvec3>{});
    EXPECT_EQ(isolated.at(0), glm::vec3(0, 0, 1)); // no faces at all: the documented default
}

TEST(SceneWeld, CancelledSmoothNormalTakesTheFirstFaceWithADirection) {
    // Vertex 0: a zero-area face first (no direction), then two opposite faces that cancel: it takes the first of
    // those. Vertex 4 lies only on the zero-area face: the documented default. Vertex 5 is unused: the default too.
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0}, {9, 9, 9}};
    const std::vector<glm::uvec3> triangles = {{0, 1, 4}, {0, 2, 3}, {0, 3, 2}, {1, 2, 3}};
    const std::vector<glm::vec3> normals = computeSmoothNormals(positions, triangles);
    EXPECT_EQ(normals.at(0), glm::vec3(1, 0, 0)); // face {0, 2, 3}: (0, 1, 0) x (0, 0, 1)
    EXPECT_EQ(normals.at(4), glm::vec3(0, 0, 1));
    EXPECT_EQ(normals.at(5), glm::vec3(0, 0, 1));
}

TEST(SceneWeld, LargeGridWeldsEveryDuplicate) {
    // A 60 x 60 height field written as separate triangles: 21,600 corners weld back to 3,721 grid points.
    std::vector<glm::vec3> corners;
    const auto height = [](int x, int y) { return 0.1f * float((x * 7 + y * 13) % 5); };
    for (int y = 0; y < 60; ++y) {
        for (int x = 0; x < 60; ++x) {
            const glm::vec3 a(x, y, height(x, y)), b(x + 1, y, height(x + 1, y));
            const glm::vec3 c(x + 1, y + 1, height(x + 1, y + 1)), d(x, y + 1, height(x, y + 1));
            corners.insert(corners.end(), {a, b, c, a, c, d});
        }
    }
    const WeldMap map = weldVertices(corners, {}, 1e-4);
    EXPECT_EQ(map.kept.size(), 61u * 61u);
}

} // namespace
} // namespace inkgraph
