#include "scene/Scene.h"

#include "scene/mesh/Procedural.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

namespace inkgraph {
namespace {

using test::TempFile;

TEST(SceneLoad, UnknownExtensionListsTheSupportedOnes) {
    const TempFile file("model.fbx", "Kaydara FBX Binary\n");
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_EQ(message.rfind("loadScene(): '" + file.path() + "'", 0), 0u) << message;
    for (const char* extension : {".gltf", ".glb", ".obj", ".stl", ".ply"}) {
        EXPECT_NE(message.find(extension), std::string::npos) << extension << " missing from: " << message;
    }
}

TEST(SceneLoad, DirectoryIsNotAModel) {
    const std::filesystem::path directory =
        std::filesystem::temp_directory_path() / ("inkgraph_scene_dir_" + std::to_string(::getpid()) + ".obj");
    std::filesystem::create_directories(directory);
    const std::string message = test::sceneErrorMessage([&] { loadScene(directory.string()); });
    std::filesystem::remove(directory);
    EXPECT_NE(message.find("not a regular file"), std::string::npos) << message;
}

TEST(SceneLoad, OverlongFileNameIsASceneErrorNamingTheFile) {
    // 300 characters exceed NAME_MAX (255): stat() fails with ENAMETOOLONG rather than ENOENT.
    for (const char* extension : {".stl", ".obj", ".gltf", ".glb"}) {
        const std::string path =
            (std::filesystem::temp_directory_path() / (std::string(300 - std::strlen(extension), 'n') + extension))
                .string();
        const std::string message = test::sceneErrorMessage([&] { loadScene(path); });
        EXPECT_EQ(message.rfind("loadScene(): '" + path + "': ", 0), 0u) << message;
    }
}

TEST(SceneLoad, GlbContentInAGltfFileIsReadAsBinary) {
    test::GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const std::string body =
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
        "}}]}], \"nodes\": [{\"mesh\": 0}]";
    const TempFile file("binary_inside.gltf", writer.glb(body));
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.report.format, "glb");
    EXPECT_EQ(scene.triangleCount(), 1u); // no scenes array: every root node is walked
}

TEST(SceneBounds, CountsAndBoundingSphereCoverEveryMesh) {
    Scene scene = makeScene(makeUvSphere({0, 0, 0}, 1.0f, 8, 4));
    scene.meshes.push_back(makeUvSphere({10, 0, 0}, 2.0f, 6, 4));
    EXPECT_EQ(scene.triangleCount(), 2u * 8 * 3 + 2u * 6 * 3);
    EXPECT_EQ(scene.vertexCount(), (8u * 3 + 2) + (6u * 3 + 2));

    const BoundingSphere sphere = computeBoundingSphere(scene);
    // Box: x from -1 to 12 (the spheres' poles are on z, so their equators reach the full radius in x).
    EXPECT_NEAR(sphere.center.x, 5.5, 1e-6);
    EXPECT_NEAR(sphere.center.y, 0.0, 1e-6);
    EXPECT_NEAR(sphere.center.z, 0.0, 1e-6);
    EXPECT_NEAR(sphere.radius, 6.5, 1e-6);
}

TEST(SceneBounds, RadiusReachesTheFarthestVertexNotTheBoxCorner) {
    // Bounding box [-1, 1]^3, whose corners are sqrt(3) from the centre; every vertex is sqrt(2) from it.
    const TempFile file("tilted.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex -1 -1 0\nvertex 1 0 1\n"
                                      "vertex 0 1 -1\nendloop\nendfacet\nendsolid t\n");
    const BoundingSphere sphere = computeBoundingSphere(loadScene(file.path()));
    EXPECT_EQ(sphere.center, glm::dvec3(0.0));
    EXPECT_NEAR(sphere.radius, std::sqrt(2.0), 1e-12);
}

TEST(SceneBounds, EmptySceneThrows) { EXPECT_THROW(computeBoundingSphere(Scene{}), SceneError); }

} // namespace
} // namespace inkgraph
