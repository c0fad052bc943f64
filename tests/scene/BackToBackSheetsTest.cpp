// Sheets that lie back to back on corners of their own (a card printed on both sides: two materials, or texture
// coordinates or colours per side): a mesh all of whose triangles' backs an opaque sheet covers is drawn from its front
// only, whatever the number and order of the sheets; meshes covered in part, and closed meshes that touch, stay
// two-sided.
#include "scene/mesh/BackToBackSheets.h"
#include "scene/MaterialIds.h"
#include "scene/ObjectIds.h"
#include "scene/Scene.h"
#include "scene/mesh/MeshOps.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace inkgraph {
namespace {

using test::TempFile;
using test::TempFolder;

const std::string kSquare = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n";

/** The cube [-1, 1]^3 moved `offset` along x, its twelve triangles wound outward on eight vertices. */
Mesh cube(float offset) {
    Mesh mesh;
    mesh.name = "cube";
    for (const glm::vec3& corner : test::cubeCorners()) mesh.positions.push_back(corner + glm::vec3(offset, 0, 0));
    for (const glm::uvec4& quad : test::cubeQuads()) { // 1-based, as an OBJ writes them
        const glm::uvec4 corners = quad - 1u;
        mesh.triangles.emplace_back(corners.x, corners.y, corners.z);
        mesh.triangles.emplace_back(corners.x, corners.z, corners.w);
    }
    mesh.normals = computeSmoothNormals(mesh.positions, mesh.triangles);
    mesh.texcoords[0].assign(mesh.positions.size(), glm::vec2(0.0f));
    return mesh;
}

/** The square [-1, 1]^2 at z = 0 facing +z, or its back sheet facing -z, on four vertices of its own. */
Mesh sheet(bool back) {
    Mesh mesh;
    mesh.name = back ? "back" : "front";
    mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    mesh.normals.assign(4, glm::vec3(0, 0, back ? -1 : 1));
    // Each side its own half of a texture, as a card printed on both sides is mapped.
    const float u = back ? 0.5f : 0.0f;
    mesh.texcoords[0] = {{u, 1}, {u + 0.5f, 1}, {u + 0.5f, 0}, {u, 0}};
    mesh.triangles =
        back ? std::vector<glm::uvec3>{{0, 2, 1}, {0, 3, 2}} : std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}};
    return mesh;
}

/** Adds `part`'s vertices (positions, normals, first texture coordinates) and triangles to `mesh`. */
void append(Mesh& mesh, const Mesh& part) {
    const auto first = std::uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), part.positions.begin(), part.positions.end());
    mesh.normals.insert(mesh.normals.end(), part.normals.begin(), part.normals.end());
    mesh.texcoords[0].insert(mesh.texcoords[0].end(), part.texcoords[0].begin(), part.texcoords[0].end());
    for (const glm::uvec3& triangle : part.triangles) mesh.triangles.push_back(triangle + first);
}

TEST(BackToBackSheets, ACardOfTwoMaterialsShowsEachFromItsOwnSide) {
    // Written by a modeller as two sheets, red and blue: both were drawn two-sided at one depth, stripes of each.
    const TempFolder folder;
    folder.write("card.mtl", "newmtl red\nKd 0.9 0.1 0.1\nnewmtl blue\nKd 0.1 0.2 0.9\n");
    const std::string model =
        folder.write("card.obj", "mtllib card.mtl\n" + kSquare + "usemtl red\nf 1 2 3 4\nusemtl blue\nf 4 3 2 1\n");
    const Scene scene = loadScene(model);
    ASSERT_EQ(scene.meshes.size(), 2u);
    for (const Mesh& mesh : scene.meshes) {
        EXPECT_TRUE(mesh.backCulled) << mesh.material.name;
        EXPECT_FALSE(mesh.drawsBackFaces()) << mesh.material.name;
        EXPECT_TRUE(mesh.material.doubleSided) << "the material stays as the file gives it";
        EXPECT_EQ(mesh.triangleCount(), 2u);
    }
    EXPECT_EQ(scene.report.backToBackOneSided, 4u);
    EXPECT_EQ(scene.report.backToBackDropped, 0u);
    EXPECT_EQ(sceneObjects(scene).objects.size(), 1u) << "still one object";
    EXPECT_EQ(materialIds(scene), (std::vector<std::uint32_t>{0, 1}));
}

TEST(BackToBackSheets, ACardWhoseSidesCarryTheirOwnColoursShowsEachFromItsOwnSide) {
    // One mesh: the back sheet's corners are vertices of their own, coloured blue; the load's weld keeps them apart
    // by colour, so they were not dropped as twins, and fought for depth with the front.
    const std::string front = "v -1 -1 0 1 0 0\nv 1 -1 0 1 0 0\nv 1 1 0 1 0 0\nv -1 1 0 1 0 0\n";
    const std::string back = "v -1 -1 0 0 0 1\nv 1 -1 0 0 0 1\nv 1 1 0 0 0 1\nv -1 1 0 0 0 1\n";
    const TempFile file("coloured.obj", front + back + "f 1 2 3 4\nf 8 7 6 5\n");
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_TRUE(scene.meshes[0].backCulled);
    EXPECT_EQ(scene.meshes[0].triangleCount(), 4u);
    EXPECT_EQ(scene.report.backToBackOneSided, 4u);
    // The same sides in one colour are one sheet: the twin adds nothing and is dropped, the mesh stays two-sided.
    const TempFile plain("plain.obj", front + front + "f 1 2 3 4\nf 8 7 6 5\n");
    const Scene single = loadScene(plain.path());
    ASSERT_EQ(single.meshes.size(), 1u);
    EXPECT_TRUE(single.meshes[0].drawsBackFaces());
    EXPECT_EQ(single.meshes[0].triangleCount(), 2u);
    EXPECT_EQ(single.report.backToBackDropped, 2u);
    EXPECT_EQ(single.report.backToBackOneSided, 0u);
}

TEST(BackToBackSheets, MeshesCoveredInPartAndClosedMeshesThatTouchStayTwoSided) {
    // Two cubes face to face: the faces they share lie back to back, but each cube has faces nothing covers.
    std::vector<Mesh> touching{cube(0.0f), cube(2.0f)};
    EXPECT_EQ(cullBackToBackSheets(touching, 1e-6), 0u);
    EXPECT_TRUE(touching[0].drawsBackFaces());
    EXPECT_TRUE(touching[1].drawsBackFaces());

    // A cape doubled where it leaves the shoulder: its lining covers only half; the lining, all covered, culls.
    Mesh cape = sheet(false);
    cape.positions.insert(cape.positions.end(), {{-1, 3, 0}, {1, 3, 0}});
    cape.normals.insert(cape.normals.end(), 2, glm::vec3(0, 0, 1));
    cape.texcoords[0].insert(cape.texcoords[0].end(), 2, glm::vec2(0.0f));
    cape.triangles.insert(cape.triangles.end(), {{3, 2, 5}, {3, 5, 4}});
    std::vector<Mesh> coveredInPart{cape, sheet(true)};
    EXPECT_EQ(cullBackToBackSheets(coveredInPart, 1e-6), 2u);
    EXPECT_TRUE(coveredInPart[0].drawsBackFaces()) << "the cape, covered in part, stays two-sided";
    EXPECT_FALSE(coveredInPart[1].drawsBackFaces());

    // A card whose two sides are one mesh with a cube clear of it: not culled in part (left as it was).
    Mesh body = cube(3.0f);
    for (const Mesh& part : {sheet(false), sheet(true)}) append(body, part);
    std::vector<Mesh> withBody{body};
    EXPECT_EQ(cullBackToBackSheets(withBody, 1e-6), 0u);
    EXPECT_TRUE(withBody[0].drawsBackFaces());
}

TEST(BackToBackSheets, OnlyAnOpaqueSheetCoversABack) {
    // The one-sided front culls its back already; the two-sided back sheet drew its back face over the front's.
    std::vector<Mesh> oneSided{sheet(false), sheet(true)};
    oneSided[0].material.doubleSided = false;
    EXPECT_EQ(cullBackToBackSheets(oneSided, 1e-6), 2u);
    EXPECT_FALSE(oneSided[0].backCulled) << "a one-sided material culls its back by itself";
    EXPECT_TRUE(oneSided[1].backCulled);
    // Behind a blended or alpha-masked front the opaque back's own back face shows through it (found by a hostile
    // pass: a masked back sheet that cut out every fragment made the card vanish from behind): the opaque back stays
    // two-sided, while the front, covered by the opaque back, culls.
    for (const AlphaMode seeThrough : {AlphaMode::Blend, AlphaMode::Mask}) {
        std::vector<Mesh> meshes{sheet(false), sheet(true)};
        meshes[0].material.alphaMode = seeThrough;
        EXPECT_EQ(cullBackToBackSheets(meshes, 1e-6), 2u);
        EXPECT_TRUE(meshes[0].backCulled);
        EXPECT_FALSE(meshes[1].backCulled);
    }
}

TEST(BackToBackSheets, EverySheetOnTheCornersCountsWhateverTheirOrder) {
    // Red front, then a blended blue back, then an opaque green back: matched one to one, the red front took the
    // blended sheet and kept both its faces (stripes of red and green from either side); in the other order it came
    // out clean. Every opaque sheet facing the other way covers.
    for (const bool blendedFirst : {true, false}) {
        std::vector<Mesh> meshes{sheet(false), sheet(true), sheet(true)};
        meshes[blendedFirst ? 1 : 2].material.alphaMode = AlphaMode::Blend;
        EXPECT_EQ(cullBackToBackSheets(meshes, 1e-6), 6u) << blendedFirst;
        for (const Mesh& mesh : meshes) EXPECT_TRUE(mesh.backCulled) << blendedFirst;
    }
    // A third sheet on the corners (red front, blue and yellow backs in one mesh of per-side colours): each back
    // faces the front, so all are culled; one to one, the yellow was left out and the mesh stayed two-sided.
    Mesh three = sheet(false);
    for (const Mesh& back : {sheet(true), sheet(true)}) append(three, back);
    three.colors.assign(three.positions.size(), glm::vec4(1.0f));
    std::vector<Mesh> one{three};
    EXPECT_EQ(cullBackToBackSheets(one, 1e-6), 6u);
    EXPECT_TRUE(one[0].backCulled);
    // Sheets within the weld of each other are back to back; apart by more, they are not.
    std::vector<Mesh> near{sheet(false), sheet(true)};
    for (glm::vec3& position : near[1].positions) position.z += 0.9e-6f;
    EXPECT_EQ(cullBackToBackSheets(near, 1e-6), 4u);
    std::vector<Mesh> apart{sheet(false), sheet(true)};
    for (glm::vec3& position : apart[1].positions) position.z += 1e-3f;
    EXPECT_EQ(cullBackToBackSheets(apart, 1e-6), 0u);
    EXPECT_TRUE(apart[0].drawsBackFaces());
    EXPECT_TRUE(apart[1].drawsBackFaces());
}

} // namespace
} // namespace inkgraph
