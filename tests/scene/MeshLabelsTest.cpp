// The scene's mesh and material labels (scene/MeshLabels.h, issue 37): per mesh its ids in the G-buffer's id fields
// and its range of triangle ids, per material its name; and the one global numbering of triangles.
#include "scene/MeshLabels.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace inkgraph {
namespace {

/** A mesh of `triangles` triangles (indices only: the labels read nothing else) of material `material`. */
Mesh meshOf(std::string name, std::vector<std::string> nodePath, std::size_t triangles, std::string material,
            float red = 0.5f) {
    Mesh mesh;
    mesh.name = std::move(name);
    mesh.nodePath = std::move(nodePath);
    mesh.triangles.assign(triangles, glm::uvec3(0, 1, 2));
    mesh.material.name = std::move(material);
    mesh.material.baseColorFactor = {red, 0.5f, 0.5f, 1.0f};
    return mesh;
}

TEST(MeshLabels, MeshesCountTheirTrianglesInOrderAndNameTheirMaterials) {
    Scene scene;
    // Two primitives of node "body" (one object, two materials), then a "hat" in the first material again, then an
    // unnamed material.
    scene.meshes = {meshOf("body 0", {"body"}, 3, "skin"), meshOf("body 1", {"body"}, 5, "cloth"),
                    meshOf("hat", {"hat"}, 2, "skin"), meshOf("plain", {"plain"}, 4, "", 0.9f)};
    const SceneLabels labels = sceneLabels(scene);
    ASSERT_EQ(labels.meshes.size(), 4u);
    const std::vector<std::size_t> first = {0, 3, 8, 10};
    const std::vector<std::uint32_t> objects = {1, 1, 2, 3};
    const std::vector<std::uint32_t> materials = {1, 2, 1, 3};
    for (std::size_t index = 0; index < 4; ++index) {
        SCOPED_TRACE(index);
        const MeshLabel& mesh = labels.meshes[index];
        EXPECT_EQ(mesh.id, index + 1);
        EXPECT_EQ(mesh.name, scene.meshes[index].name);
        EXPECT_EQ(mesh.nodePath, scene.meshes[index].nodePath);
        EXPECT_EQ(mesh.firstTriangle, first[index]);
        EXPECT_EQ(mesh.triangleCount, scene.meshes[index].triangles.size());
        EXPECT_EQ(mesh.objectId, objects[index]);
        EXPECT_EQ(mesh.materialId, materials[index]);
        EXPECT_EQ(globalTriangleIndex(scene, index, 0), first[index]);
    }
    ASSERT_EQ(labels.materials.size(), 3u);
    EXPECT_EQ(labels.materials[0].id, 1u);
    EXPECT_EQ(labels.materials[0].name, "skin");
    EXPECT_EQ(labels.materials[1].name, "cloth");
    EXPECT_EQ(labels.materials[2].id, 3u);
    EXPECT_EQ(labels.materials[2].name, "") << "an unnamed material keeps no name";
    // The last triangle of the last mesh is the scene's last: 3 + 5 + 2 + 4 = 14 triangles.
    EXPECT_EQ(globalTriangleIndex(scene, 3, 3), 13u);
}

TEST(MeshLabels, AnEmptySceneHasNoLabelsAndBadIndicesAreRefused) {
    const SceneLabels none = sceneLabels(Scene{});
    EXPECT_TRUE(none.meshes.empty());
    EXPECT_TRUE(none.materials.empty());
    Scene scene;
    scene.meshes = {meshOf("only", {}, 2, "m")};
    try {
        globalTriangleIndex(scene, 0, 2);
        FAIL() << "no triangle 2";
    } catch (const std::out_of_range& error) {
        EXPECT_STREQ(error.what(), "globalTriangleIndex(): triangle 2 of mesh 0, which has 2");
    }
    EXPECT_THROW(globalTriangleIndex(scene, 1, 0), std::out_of_range);
}

TEST(MeshLabels, TriangleIdsBeyondFloat32sExactIntegersAreWarnedAbout) {
    // Ids are index + 1, so 2^24 triangles still have exact ids (the largest, 2^24, is a float32); one more does not.
    EXPECT_EQ(float(kExactTriangleIds), float(kExactTriangleIds - 1) + 1.0f);
    EXPECT_EQ(float(kExactTriangleIds + 1), float(kExactTriangleIds)) << "2^24 + 1 rounds: why the warning exists";
    EXPECT_FALSE(triangleIdWarning(0).has_value());
    EXPECT_FALSE(triangleIdWarning(kExactTriangleIds).has_value());
    const std::optional<Warning> warning = triangleIdWarning(kExactTriangleIds + 1);
    ASSERT_TRUE(warning.has_value());
    EXPECT_EQ(warning->code, "triangle-id-inexact");
    EXPECT_EQ(warning->message, "the scene has 16777217 triangles: gbuffer.triangleId (float32) is exact only up to "
                                "16777216, so larger ids round to a neighbour's");
}

} // namespace
} // namespace inkgraph
