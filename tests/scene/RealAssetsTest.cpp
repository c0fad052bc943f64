// The real third-party files of models/characters/ (credits in its README) through the loader, against what their
// files say (counted from their JSON): textures, texture coordinates, alpha modes, sides, VRM fronts, MToon materials
// with their outlines, animations. The GL side renders them in tests/app/RealAssetsGLTest.cpp.
#include "scene/Scene.h"
#include "tests/scene/SceneTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace inkgraph {
namespace {

std::string asset(const std::string& file) { return test::sourcePath("models/characters/" + file); }

const Mesh& meshNamed(const Scene& scene, const std::string& name) {
    const auto found =
        std::find_if(scene.meshes.begin(), scene.meshes.end(), [&](const Mesh& mesh) { return mesh.name == name; });
    if (found == scene.meshes.end()) throw std::runtime_error("no mesh '" + name + "'");
    return *found;
}

TEST(RealAssets, TexturedPropsCarryTheirTextureAndCoordinates) {
    for (const std::string file : {"box-textured.glb", "duck.glb", "fox.glb"}) {
        const Scene scene = loadScene(asset(file));
        ASSERT_EQ(scene.meshes.size(), 1u) << file;
        const Mesh& mesh = scene.meshes[0];
        EXPECT_EQ(scene.images.size(), 1u) << file;
        EXPECT_EQ(mesh.material.baseColorTexture.image, 0) << file;
        EXPECT_EQ(mesh.texcoords[0].size(), mesh.positions.size()) << file;
        EXPECT_FALSE(mesh.material.doubleSided) << file << ": glTF's default";
        EXPECT_TRUE(scene.report.warnings.empty()) << file;
        ASSERT_TRUE(scene.images[0].encoded) << file << ": embedded in the GLB, kept encoded";
        // A PNG or JPEG signature: the bytes are the file's, not decoded pixels.
        const std::vector<unsigned char>& bytes = *scene.images[0].encoded;
        ASSERT_GE(bytes.size(), 4u);
        EXPECT_TRUE((bytes[0] == 0x89 && bytes[1] == 'P') || (bytes[0] == 0xFF && bytes[1] == 0xD8)) << file;
    }
    // The box's 6 faces each own 4 corners with their own coordinates: 24 vertices, no seam welded away.
    EXPECT_EQ(loadScene(asset("box-textured.glb")).meshes[0].positions.size(), 24u);
}

TEST(RealAssets, FoxAnimationsPoseTheMesh) {
    const Scene rest = loadScene(asset("fox.glb"));
    LoadOptions walking;
    walking.animation = "Walk";
    walking.time = 0.5;
    const Scene walk = loadScene(asset("fox.glb"), walking);
    ASSERT_EQ(walk.meshes[0].positions.size(), rest.meshes[0].positions.size());
    double moved = 0.0;
    for (std::size_t i = 0; i < rest.meshes[0].positions.size(); ++i)
        moved = std::max(moved, glm::length(glm::dvec3(test::worldPosition(walk, walk.meshes[0].positions[i]) -
                                                       test::worldPosition(rest, rest.meshes[0].positions[i]))));
    EXPECT_GT(moved, 1.0) << "a walking leg moves (the fox is about 150 units long)";
    LoadOptions jumping;
    jumping.animation = "Jump";
    const std::string message = test::sceneErrorMessage([&] { loadScene(asset("fox.glb"), jumping); });
    EXPECT_NE(message.find("'Survey'"), std::string::npos) << message;
    EXPECT_NE(message.find("'Walk'"), std::string::npos) << message;
}

TEST(RealAssets, GodetteIsAVrm0CharacterWithMToonAndOutlines) {
    const Scene scene = loadScene(asset("godette.vrm"));
    EXPECT_EQ(scene.triangleCount(), 3439u);
    EXPECT_EQ(scene.images.size(), 5u);
    ASSERT_TRUE(scene.front.has_value());
    EXPECT_EQ(*scene.front, glm::dvec3(0.0, 0.0, -1.0)) << "VRM 0.x faces -Z";
    for (const std::string name : {"Face", "Body primitive 0"}) {
        const Mesh& mesh = meshNamed(scene, name);
        ASSERT_TRUE(mesh.material.mtoon.has_value()) << name;
        EXPECT_EQ(mesh.material.mtoon->specVersion, "0.x");
        EXPECT_EQ(mesh.material.mtoon->outlineWidthMode, MToonMaterial::OutlineWidthMode::ScreenCoordinates);
        EXPECT_GT(mesh.material.mtoon->outlineWidthFactor, 0.0f);
        EXPECT_TRUE(mesh.material.mtoon->shadeMultiplyTexture.present()) << name;
    }
    const Mesh& logo = meshNamed(scene, "Body primitive 1");
    EXPECT_EQ(logo.material.alphaMode, AlphaMode::Blend);
    EXPECT_TRUE(logo.material.doubleSided);
    EXPECT_FALSE(logo.material.mtoon.has_value()) << "VRM_USE_GLTFSHADER keeps the glTF material";
    for (const Mesh& mesh : scene.meshes) EXPECT_FALSE(mesh.nodePath.empty()) << mesh.name;
}

TEST(RealAssets, Vrm1SamplesReadTheirMToonAndCutOuts) {
    const Scene scrolling = loadScene(asset("mtoon-uv-animation-test.vrm"));
    ASSERT_TRUE(scrolling.front.has_value());
    EXPECT_EQ(*scrolling.front, glm::dvec3(0.0, 0.0, 1.0)) << "VRM 1.0 faces +Z";
    ASSERT_EQ(scrolling.meshes.size(), 3u);
    for (const Mesh& mesh : scrolling.meshes) {
        ASSERT_TRUE(mesh.material.mtoon.has_value()) << mesh.name;
        EXPECT_EQ(mesh.material.mtoon->specVersion, "1.0");
        EXPECT_TRUE(mesh.material.baseColorTexture.present()) << mesh.name;
    }
    const Scene labels = loadScene(asset("expressions-binary-overrides.vrm"));
    const std::size_t masked = std::count_if(labels.meshes.begin(), labels.meshes.end(), [](const Mesh& mesh) {
        return mesh.material.alphaMode == AlphaMode::Mask;
    });
    EXPECT_EQ(masked, 3u) << "the text and the two meters are cut out";
}

} // namespace
} // namespace inkgraph
