#include "scene/mesh/Procedural.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <set>
#include <tuple>

namespace inkgraph {
namespace {

TEST(Procedural, UvSphereCountsNormalsAndWinding) {
    const glm::vec3 center(1.0f, -2.0f, 3.0f);
    const float radius = 2.5f;
    for (const glm::ivec2 shape : {glm::ivec2(3, 2), glm::ivec2(8, 5), glm::ivec2(64, 32)}) {
        const Mesh mesh = makeUvSphere(center, radius, shape.x, shape.y);
        SCOPED_TRACE(testing::Message() << shape.x << " segments, " << shape.y << " rings");
        EXPECT_EQ(mesh.triangleCount(), std::size_t(2 * shape.x * (shape.y - 1)));
        EXPECT_EQ(mesh.positions.size(), std::size_t(shape.x * (shape.y - 1) + 2)); // shared seam, single poles
        ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            const glm::dvec3 expected = (glm::dvec3(mesh.positions[i]) - glm::dvec3(center)) / double(radius);
            EXPECT_NEAR(mesh.normals[i].x, expected.x, 1e-6);
            EXPECT_NEAR(mesh.normals[i].y, expected.y, 1e-6);
            EXPECT_NEAR(mesh.normals[i].z, expected.z, 1e-6);
        }
        test::expectUnitNormals(mesh, 1e-6);
        test::expectOutwardWinding(mesh, glm::dvec3(center));
        for (const glm::uvec3& triangle : mesh.triangles) {
            EXPECT_LT(glm::max(triangle.x, glm::max(triangle.y, triangle.z)), mesh.positions.size());
        }
    }
}

TEST(Procedural, UvSphereIsClosedAndEveryEdgeIsSharedOnce) {
    // A watertight, consistently wound surface uses each directed edge exactly once.
    const Mesh mesh = makeUvSphere({0, 0, 0}, 1.0f, 12, 7);
    std::set<std::pair<std::uint32_t, std::uint32_t>> directedEdges;
    for (const glm::uvec3& t : mesh.triangles) {
        for (int corner = 0; corner < 3; ++corner) {
            EXPECT_TRUE(directedEdges.emplace(t[corner], t[(corner + 1) % 3]).second);
        }
    }
    for (const auto& [from, to] : directedEdges) {
        EXPECT_TRUE(directedEdges.count({to, from})) << "edge " << from << "-" << to << " has no twin";
    }
}

TEST(Procedural, TorusCountsNormalsAndWinding) {
    const float major = 3.0f;
    const float minor = 1.0f;
    const Mesh mesh = makeTorus(major, minor, 24, 12);
    EXPECT_EQ(mesh.triangleCount(), 2u * 24 * 12);
    EXPECT_EQ(mesh.positions.size(), 24u * 12);
    test::expectUnitNormals(mesh, 1e-6);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        // The normal points from the tube's centre circle to the surface point.
        const glm::dvec3 p(mesh.positions[i]);
        const glm::dvec3 tubeCenter = double(major) * glm::normalize(glm::dvec3(p.x, p.y, 0.0));
        const glm::dvec3 expected = (p - tubeCenter) / double(minor);
        EXPECT_NEAR(mesh.normals[i].x, expected.x, 1e-6);
        EXPECT_NEAR(mesh.normals[i].y, expected.y, 1e-6);
        EXPECT_NEAR(mesh.normals[i].z, expected.z, 1e-6);
    }
    for (const glm::uvec3& triangle : mesh.triangles) {
        const glm::dvec3 averageNormal = glm::dvec3(mesh.normals[triangle.x]) + glm::dvec3(mesh.normals[triangle.y]) +
                                         glm::dvec3(mesh.normals[triangle.z]);
        EXPECT_GT(glm::dot(test::triangleCross(mesh, triangle), averageNormal), 0.0);
    }
}

TEST(Procedural, MakeSceneReportsLikeALoader) {
    const Scene scene = makeScene(makeTorus(2.0f, 0.5f, 16, 8));
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.report.format, "procedural");
    EXPECT_EQ(scene.report.trianglesRead, 256u);
    EXPECT_EQ(scene.report.verticesBeforeWeld, 128u);
    EXPECT_EQ(scene.report.verticesAfterWeld, 128u);
    EXPECT_FALSE(scene.report.normalsComputed);
    EXPECT_FALSE(scene.camera.has_value());
    EXPECT_FALSE(scene.light.has_value());
    EXPECT_EQ(scene.triangleCount(), 256u);

    // A hand-built mesh without normals gets smooth ones, as a loaded one would.
    Mesh bare;
    bare.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    bare.triangles = {{0, 1, 2}};
    const Scene wrapped = makeScene(bare);
    EXPECT_TRUE(wrapped.report.normalsComputed);
    EXPECT_EQ(wrapped.meshes.at(0).normals, std::vector<glm::vec3>(3, glm::vec3(0, 0, 1)));
}

TEST(Procedural, CubeHasSplitNormalsAndOutwardWinding) {
    const glm::vec3 center(0.5f, -1.0f, 2.0f);
    const Mesh mesh = makeCube(center, 2.0f);
    EXPECT_EQ(mesh.positions.size(), 24u);
    EXPECT_EQ(mesh.triangleCount(), 12u);
    test::expectUnitNormals(mesh, 1e-6);
    test::expectOutwardWinding(mesh, glm::dvec3(center));
    std::set<std::tuple<float, float, float>> corners;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3 offset = mesh.positions[i] - center;
        EXPECT_EQ(glm::abs(offset), glm::vec3(2.0f));
        // The vertex carries its face's normal: the one axis along which the corner lies on that face.
        EXPECT_EQ(glm::dot(offset, mesh.normals[i]), 2.0f);
        corners.emplace(offset.x, offset.y, offset.z);
    }
    EXPECT_EQ(corners.size(), 8u);
    EXPECT_THROW(makeCube(center, 0.0f), std::invalid_argument);
}

TEST(Procedural, InvalidShapesThrow) {
    EXPECT_THROW(makeUvSphere({0, 0, 0}, 1.0f, 2, 4), std::invalid_argument);
    EXPECT_THROW(makeUvSphere({0, 0, 0}, 1.0f, 8, 1), std::invalid_argument);
    EXPECT_THROW(makeUvSphere({0, 0, 0}, 0.0f, 8, 4), std::invalid_argument);
    EXPECT_THROW(makeTorus(1.0f, 2.0f, 8, 8), std::invalid_argument);
    EXPECT_THROW(makeTorus(2.0f, 1.0f, 8, 2), std::invalid_argument);
}

} // namespace
} // namespace inkgraph
