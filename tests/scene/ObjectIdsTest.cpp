// The scene's objects (scene/ObjectIds.h): node instances in order of first appearance, from hand-made scenes and
// from OBJ files with several `o` objects (issue 36's objectId field and object-boundary lines).
#include "scene/ObjectIds.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

namespace inkgraph {
namespace {

using Ids = std::vector<std::uint32_t>;
using Path = std::vector<std::string>;

Mesh meshAt(std::string name, Path nodePath, std::size_t nodeInstance = 0) {
    Mesh mesh;
    mesh.name = std::move(name);
    mesh.nodePath = std::move(nodePath);
    mesh.nodeInstance = nodeInstance;
    return mesh;
}

TEST(ObjectIds, EmptySceneHasNoObjects) {
    const SceneObjects objects = sceneObjects(Scene{});
    EXPECT_TRUE(objects.ofMesh.empty());
    EXPECT_TRUE(objects.objects.empty());
}

TEST(ObjectIds, NodeInstancesInOrderOfFirstAppearance) {
    Scene scene;
    // Two primitives of node "body" (one object), an unnamed sibling pair told apart by instance, then "body" again.
    scene.meshes = {meshAt("body primitive 0", {"root", "body"}, 1), meshAt("hat", {"root", ""}, 3),
                    meshAt("hat", {"root", ""}, 4), meshAt("body primitive 1", {"root", "body"}, 1)};
    const SceneObjects objects = sceneObjects(scene);
    EXPECT_EQ(objects.ofMesh, (Ids{0, 1, 2, 0}));
    ASSERT_EQ(objects.objects.size(), 3u);
    EXPECT_EQ(objects.objects[0].name, "body");
    EXPECT_EQ(objects.objects[0].nodePath, (Path{"root", "body"}));
    EXPECT_EQ(objects.objects[0].meshes, (std::vector<std::size_t>{0, 3}));
    EXPECT_EQ(objects.objects[1].name, "hat") << "an unnamed node is named by its first mesh";
    EXPECT_EQ(objects.objects[2].meshes, std::vector<std::size_t>{2});
}

TEST(ObjectIds, MeshesWithoutNodesAreOneObject) {
    Scene scene;
    scene.meshes = {meshAt("part", {}), meshAt("part/red", {})};
    const SceneObjects objects = sceneObjects(scene);
    EXPECT_EQ(objects.ofMesh, (Ids{0, 0}));
    ASSERT_EQ(objects.objects.size(), 1u);
    EXPECT_EQ(objects.objects[0].name, "part");
}

TEST(ObjectIds, AnObjFilesObjectsAreItsObjects) {
    // Two `o` objects, the second with two materials (which carry over from the first object's `usemtl`), and an
    // `o` repeated by name: each `o` line is an object of its own.
    const test::TempFile file("parts.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                           "o lid\nusemtl red\nf 1 2 3\n"
                                           "o box\nf 2 4 3\nusemtl blue\nf 1 3 4\n"
                                           "o lid\nf 1 2 4\n");
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 4u);
    EXPECT_EQ(scene.meshes[0].name, "lid");
    EXPECT_EQ(scene.meshes[1].name, "box/red");
    EXPECT_EQ(scene.meshes[2].name, "box/blue");
    EXPECT_EQ(scene.meshes[3].name, "lid");
    EXPECT_EQ(scene.meshes[1].material.name, "red");
    const SceneObjects objects = sceneObjects(scene);
    EXPECT_EQ(objects.ofMesh, (Ids{0, 1, 1, 2}));
    ASSERT_EQ(objects.objects.size(), 3u);
    EXPECT_EQ(objects.objects[1].name, "box");
    EXPECT_EQ(objects.objects[1].nodePath, Path{"box"});
}

TEST(ObjectIds, AnObjFileWithOneObjectKeepsItsMeshesAsBefore) {
    // Faces in one object only: one mesh per material named after the first `o`, as the reader always made them.
    const test::TempFile file("one.obj", "o empty\no thing\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                         "usemtl red\nf 1 2 3\nusemtl blue\nf 2 4 3\n");
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 2u);
    EXPECT_EQ(scene.meshes[0].name, "empty/red");
    EXPECT_EQ(scene.meshes[0].nodePath, Path{"empty"});
    EXPECT_EQ(sceneObjects(scene).objects.size(), 1u);
}

} // namespace
} // namespace inkgraph
