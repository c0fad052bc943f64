#include "scene/MaterialIds.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using Ids = std::vector<std::uint32_t>;

Mesh meshOf(std::string materialName, glm::vec4 baseColor, std::string shadeMapPath = {}) {
    Mesh mesh;
    mesh.material.name = std::move(materialName);
    mesh.material.baseColorFactor = baseColor;
    mesh.material.shadeMapPath = std::move(shadeMapPath);
    return mesh;
}

Scene sceneOf(std::vector<Mesh> meshes) {
    Scene scene;
    scene.meshes = std::move(meshes);
    return scene;
}

const glm::vec4 kRed{1.0f, 0.0f, 0.0f, 1.0f};
const glm::vec4 kBlue{0.0f, 0.0f, 1.0f, 1.0f};

TEST(MaterialIds, EmptySceneHasNoIds) { EXPECT_TRUE(materialIds(Scene{}).empty()); }

TEST(MaterialIds, SameNameColourAndMapShareAnIdInOrderOfFirstAppearance) {
    const Scene scene = sceneOf({meshOf("paint", kRed, "maps/a.png"), meshOf("metal", kBlue),
                                 meshOf("paint", kRed, "maps/a.png"), meshOf("metal", kBlue), meshOf("wood", kRed)});
    EXPECT_EQ(materialIds(scene), (Ids{0, 1, 0, 1, 2}));
}

TEST(MaterialIds, AnyDifferenceInNameColourOrMapGivesANewId) {
    const glm::vec4 almostRed{1.0f, 0.0f, 0.0f, 0.999f};
    const Scene scene = sceneOf({meshOf("paint", kRed), meshOf("lacquer", kRed), meshOf("paint", almostRed),
                                 meshOf("paint", kRed, "maps/b.png"), meshOf("paint", kRed)});
    EXPECT_EQ(materialIds(scene), (Ids{0, 1, 2, 3, 0}));
}

TEST(MaterialIds, UnnamedMeshesShareAnIdWhenTheyLookTheSame) {
    const Scene scene =
        sceneOf({meshOf("", kRed), meshOf("", kBlue), meshOf("", kRed), meshOf("", kRed, "m.png"), meshOf("", kBlue)});
    EXPECT_EQ(materialIds(scene), (Ids{0, 1, 0, 2, 1}));
}

TEST(MaterialIds, ANamedMaterialNeverSharesWithAnUnnamedOne) {
    const Scene scene = sceneOf({meshOf("", kRed), meshOf("paint", kRed), meshOf("", kRed)});
    EXPECT_EQ(materialIds(scene), (Ids{0, 1, 0}));
}

TEST(MaterialIds, OneIdPerMeshForDefaultMeshes) {
    // Meshes as OBJ and STL load them (no material name, the default grey) are one material.
    const Scene scene = sceneOf({Mesh{}, Mesh{}, Mesh{}});
    EXPECT_EQ(materialIds(scene), (Ids{0, 0, 0}));
}

} // namespace
} // namespace inkgraph
