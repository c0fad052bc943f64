// The scene's mesh and material labels (scene/MeshLabels.h, issue 37): per mesh its ids in the G-buffer's id fields
// and its range of triangle ids, per material its name; and the one global numbering of triangles.
#include "scene/MeshLabels.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <tuple>

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
        EXPECT_EQ(TriangleNumbering(scene).global(index, 0), first[index]);
    }
    ASSERT_EQ(labels.materials.size(), 3u);
    EXPECT_EQ(labels.materials[0].id, 1u);
    EXPECT_EQ(labels.materials[0].name, "skin");
    EXPECT_EQ(labels.materials[1].name, "cloth");
    EXPECT_EQ(labels.materials[2].id, 3u);
    EXPECT_EQ(labels.materials[2].name, "") << "an unnamed material keeps no name";
    // The last triangle of the last mesh is the scene's last: 3 + 5 + 2 + 4 = 14 triangles.
    EXPECT_EQ(TriangleNumbering(scene).global(3, 3), 13u);
    EXPECT_EQ(TriangleNumbering(scene).total(), 14u);
}

TEST(MeshLabels, TrianglesTheLoaderDroppedKeepTheirNumbersUnused) {
    Scene scene;
    // The file gave "first" 5 triangles, of which the loader dropped 1 and 3; "second" 4, of which it dropped the
    // last; "third" 2 and dropped none.
    scene.meshes = {meshOf("first", {"a"}, 3, "m"), meshOf("second", {"b"}, 3, "m"), meshOf("third", {"c"}, 2, "m")};
    scene.meshes[0].fileTriangles = {0, 2, 4};
    scene.meshes[0].fileTriangleCount = 5;
    scene.meshes[1].fileTriangles = {0, 1, 2};
    scene.meshes[1].fileTriangleCount = 4;
    const SceneLabels labels = sceneLabels(scene);
    EXPECT_EQ(labels.meshes[0].triangleCount, 5u);
    EXPECT_EQ(labels.meshes[1].firstTriangle, 5u);
    EXPECT_EQ(labels.meshes[1].triangleCount, 4u);
    EXPECT_EQ(labels.meshes[2].firstTriangle, 9u);
    const TriangleNumbering numbering(scene);
    EXPECT_EQ(numbering.total(), 11u);
    const std::vector<std::size_t> global = {numbering.global(0, 0), numbering.global(0, 1), numbering.global(0, 2),
                                             numbering.global(1, 2), numbering.global(2, 0), numbering.global(2, 1)};
    EXPECT_EQ(global, (std::vector<std::size_t>{0, 2, 4, 7, 9, 10}));
    // Back from a number: a kept triangle's, a dropped one's (its mesh known, no triangle), one beyond the scene.
    for (std::size_t mesh = 0; mesh < 3; ++mesh)
        for (std::size_t triangle = 0; triangle < scene.meshes[mesh].triangleCount(); ++triangle) {
            const auto back = numbering.loaded(numbering.global(mesh, triangle));
            ASSERT_TRUE(back);
            EXPECT_EQ(back->mesh, mesh);
            EXPECT_EQ(back->triangle, triangle);
        }
    for (const std::size_t dropped : {1u, 3u, 8u}) {
        EXPECT_FALSE(numbering.loaded(dropped)) << dropped;
        EXPECT_EQ(numbering.meshNumberOf(dropped), dropped < 5 ? 0u : 1u) << dropped;
    }
    EXPECT_FALSE(numbering.loaded(11));
    EXPECT_FALSE(numbering.meshNumberOf(11));
}

TEST(MeshLabels, AMeshTheLoaderSkippedKeepsItsNumbersSoTheOthersKeepTheirs) {
    // At rest: a body, a prop (its own node and material), a hat, a prop's second primitive.
    Scene rest;
    rest.meshes = {meshOf("body", {"body"}, 3, "skin"), meshOf("prop", {"prop"}, 2, "wood"),
                   meshOf("hat", {"hat"}, 4, "felt"), meshOf("prop 1", {"prop"}, 5, "wood")};
    // Posed: the prop scaled to 0, so the loader skipped both its meshes, each where it stood in the file.
    Scene posed;
    posed.meshes = {rest.meshes[0], rest.meshes[2]};
    for (const std::size_t file : {1u, 3u}) {
        Mesh skipped = rest.meshes[file];
        skipped.fileTriangleCount = skipped.triangles.size();
        skipped.triangles.clear();
        posed.skippedMeshes.push_back({file == 1 ? 1u : 2u, std::move(skipped)});
    }
    const MeshNumbering numbering(posed);
    ASSERT_EQ(numbering.size(), 4u);
    EXPECT_EQ(numbering.drawnIndex(0), 0u);
    EXPECT_FALSE(numbering.drawnIndex(1));
    EXPECT_EQ(numbering.drawnIndex(2), 1u);
    EXPECT_FALSE(numbering.drawnIndex(3));
    EXPECT_EQ(numbering.numberOf(1), 2u);
    EXPECT_EQ(numbering.mesh(3).name, "prop 1");

    const SceneLabels atRest = sceneLabels(rest);
    const SceneLabels labels = sceneLabels(posed);
    ASSERT_EQ(labels.meshes.size(), 4u);
    for (std::size_t number = 0; number < 4; ++number) {
        SCOPED_TRACE(number);
        const MeshLabel &mesh = labels.meshes[number], &before = atRest.meshes[number];
        EXPECT_EQ(mesh.drawn, number % 2 == 0);
        EXPECT_TRUE(before.drawn);
        EXPECT_EQ(std::tie(mesh.id, mesh.name, mesh.nodePath, mesh.objectId, mesh.materialId, mesh.firstTriangle,
                           mesh.triangleCount),
                  std::tie(before.id, before.name, before.nodePath, before.objectId, before.materialId,
                           before.firstTriangle, before.triangleCount));
    }
    EXPECT_EQ(labels.materials.size(), atRest.materials.size());
    // The hat's triangles keep the numbers they have at rest; the prop's name none.
    const TriangleNumbering posedTriangles(posed), restTriangles(rest);
    EXPECT_EQ(posedTriangles.total(), 14u);
    for (std::size_t triangle = 0; triangle < 4; ++triangle) {
        EXPECT_EQ(posedTriangles.global(1, triangle), restTriangles.global(2, triangle));
        const auto back = posedTriangles.loaded(posedTriangles.global(1, triangle));
        ASSERT_TRUE(back);
        EXPECT_EQ(back->mesh, 1u);
    }
    EXPECT_EQ(posedTriangles.meshNumberOf(3), 1u);
    EXPECT_FALSE(posedTriangles.loaded(3)) << "the prop's triangle 0 is drawn nowhere";
    EXPECT_FALSE(posedTriangles.loaded(13));

    // Skipped meshes out of order are refused, naming the numbering.
    Scene disordered = posed;
    std::swap(disordered.skippedMeshes[0], disordered.skippedMeshes[1]);
    EXPECT_THROW(MeshNumbering{disordered}, std::invalid_argument);
    disordered.skippedMeshes = {posed.skippedMeshes[0]};
    disordered.skippedMeshes[0].before = 3;
    try {
        MeshNumbering{disordered};
        FAIL() << "a skipped mesh beyond the two drawn ones";
    } catch (const std::invalid_argument& error) {
        EXPECT_STREQ(
            error.what(),
            "MeshNumbering(): skipped mesh 0 stands before drawn mesh 3, out of order among the 2 drawn meshes");
    }
}

TEST(MeshLabels, AnEmptySceneHasNoLabelsAndBadIndicesAreRefused) {
    const SceneLabels none = sceneLabels(Scene{});
    EXPECT_TRUE(none.meshes.empty());
    EXPECT_TRUE(none.materials.empty());
    Scene scene;
    scene.meshes = {meshOf("only", {}, 2, "m")};
    const TriangleNumbering numbering(scene);
    try {
        numbering.global(0, 2);
        FAIL() << "no triangle 2";
    } catch (const std::out_of_range& error) {
        EXPECT_STREQ(error.what(), "TriangleNumbering::global(): triangle 2 of mesh 0, which has 2");
    }
    EXPECT_THROW(numbering.global(1, 0), std::out_of_range);
    EXPECT_EQ(TriangleNumbering(Scene{}).total(), 0u);
    EXPECT_FALSE(TriangleNumbering(Scene{}).meshNumberOf(0));
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
    EXPECT_EQ(
        warning->message,
        "the scene's files give 16777217 triangles: the triangle ids of gbuffer.triangleId and "
        "gbuffer.barycentric's alpha (float32) are exact only up to 16777216, so larger ids round to a neighbour's");
}

} // namespace
} // namespace inkgraph
