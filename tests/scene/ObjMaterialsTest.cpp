// OBJ materials, texture coordinates and vertex colours (issue 18): `mtllib` libraries and `usemtl` (one mesh per
// material), Kd, d/Tr, Ke, map_Kd with its options and map_d, `vt` flipped into the glTF convention, `v x y z r g b`,
// and the warnings for what is missing or malformed. Every model is written here, beside its .mtl and textures.

#include "scene/Scene.h"
#include "scene/formats/FormatReaders.h"

#include "SceneTestSupport.h"

#include <dirent.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <set>
#include <sstream>
#include <string>
#include <utility>

namespace inkgraph {
namespace {

using test::TempFolder;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string folderOf(const std::string& path) { return std::filesystem::path(path).parent_path().string(); }

bool anyWarningContains(const Scene& scene, const std::string& part) {
    return std::ranges::any_of(scene.report.warnings, [&](const Warning& w) { return contains(w.message, part); });
}

const Mesh& meshWithMaterial(const Scene& scene, const std::string& materialName) {
    const auto found =
        std::ranges::find_if(scene.meshes, [&](const Mesh& mesh) { return mesh.material.name == materialName; });
    if (found == scene.meshes.end()) {
        throw std::runtime_error("no mesh with material '" + materialName + "'");
    }
    return *found;
}

/** The index of the vertex at world position `world`; fails the test when there is none. */
std::size_t vertexAt(const Scene& scene, const Mesh& mesh, glm::dvec3 world) {
    for (std::size_t vertex = 0; vertex < mesh.positions.size(); ++vertex) {
        if (glm::length(test::worldPosition(scene, mesh.positions[vertex]) - world) < 1e-6) return vertex;
    }
    ADD_FAILURE() << "no vertex at (" << world.x << ", " << world.y << ", " << world.z << ")";
    return 0;
}

/** Two separate unit triangles, the first at z = 0 and the second at z = 1, each after its own `usemtl`. */
std::string twoTriangles(const std::string& first, const std::string& second) {
    return "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nusemtl " + first + "\nf 1 2 3\nusemtl " + second +
           "\nf 4 5 6\n";
}

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

TEST(ObjMaterials, KdColourPerUsemtlGroupGivesOneMeshPerMaterial) {
    const TempFolder folder;
    folder.write("paints.mtl", "# two paints\nnewmtl red\nKd 1 0 0\nKa 0 0 0\nNs 10\nillum 2\n\n"
                               "newmtl dark blue\nKd 0 0 0.25\nKe 0.5 0.25 0\n");
    const std::string model =
        folder.write("pair.obj", "mtllib paints.mtl\no pair\n" + twoTriangles("red", "dark blue"));
    const Scene scene = loadScene(model);
    ASSERT_EQ(scene.meshes.size(), 2u);
    EXPECT_TRUE(scene.report.warnings.empty()) << ::testing::PrintToString(scene.report.warnings);

    const Mesh& red = meshWithMaterial(scene, "red");
    EXPECT_EQ(red.name, "pair/red");
    EXPECT_EQ(red.triangleCount(), 1u);
    EXPECT_EQ(red.material.baseColorFactor, glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(red.material.alphaMode, AlphaMode::Opaque);
    EXPECT_EQ(red.material.emissiveFactor, glm::vec3(0.0f));
    EXPECT_FALSE(red.material.textured());
    // An OBJ material is a rough dielectric (not glTF's metallic default), so --shading mtoon does not draw it black.
    EXPECT_EQ(red.material.metallicFactor, 0.0f);
    EXPECT_EQ(red.material.roughnessFactor, 1.0f);
    EXPECT_FALSE(red.material.metallicRoughnessTexture.present());
    for (const glm::vec3& p : red.positions) EXPECT_EQ(test::worldPosition(scene, p).z, 0.0);

    const Mesh& blue = meshWithMaterial(scene, "dark blue");
    EXPECT_EQ(blue.name, "pair/dark blue");
    EXPECT_EQ(blue.triangleCount(), 1u);
    EXPECT_EQ(blue.material.baseColorFactor, glm::vec4(0, 0, 0.25f, 1));
    EXPECT_EQ(blue.material.emissiveFactor, glm::vec3(0.5f, 0.25f, 0.0f));
    for (const glm::vec3& p : blue.positions) EXPECT_EQ(test::worldPosition(scene, p).z, 1.0);
}

TEST(ObjMaterials, FacesOfOneMaterialJoinOneMeshWhereverTheyAre) {
    const TempFolder folder;
    folder.write("m.mtl", "newmtl a\nKd 0.5 0.5 0.5\nnewmtl b\nKd 0.1 0.1 0.1\n");
    const std::string model =
        folder.write("split.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\n"
                                  "f 1 2 3\nusemtl a\nf 2 4 3\nusemtl b\nf 5 6 7\nusemtl a\nf 1 3 7\n");
    const Scene scene = loadScene(model);
    ASSERT_EQ(scene.meshes.size(), 3u); // the faces before any usemtl, a, b
    EXPECT_EQ(meshWithMaterial(scene, "").material, Material{});
    EXPECT_EQ(meshWithMaterial(scene, "").name, "split");
    EXPECT_EQ(meshWithMaterial(scene, "a").triangleCount(), 2u);
    EXPECT_EQ(meshWithMaterial(scene, "a").material.baseColorFactor, glm::vec4(0.5f, 0.5f, 0.5f, 1));
    EXPECT_EQ(meshWithMaterial(scene, "b").triangleCount(), 1u);
    EXPECT_EQ(scene.triangleCount(), 4u);
}

TEST(ObjMaterials, SingleMaterialKeepsTheObjectNameAndAGreyKdReadsAsOneNumber) {
    const TempFolder folder;
    folder.write("one.mtl", "newmtl only\nKd 0.25\n");
    const std::string model = folder.write("one.obj", "mtllib one.mtl\no thing\nusemtl only\n" + kTriangle);
    const Scene scene = loadScene(model);
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].name, "thing");
    EXPECT_EQ(scene.meshes[0].material.baseColorFactor, glm::vec4(0.25f, 0.25f, 0.25f, 1));
}

TEST(ObjMaterials, DissolveBelowOneBlendsAndTrIsItsComplement) {
    const TempFolder folder;
    folder.write("alpha.mtl", "newmtl half\nKd 1 1 1\nd 0.5\n"
                              "newmtl tr\nTr 0.25\n"
                              "newmtl both\nd 1\nTr 0.75\n"
                              "newmtl halo\nd -halo 0.5\n");
    const std::string model = folder.write(
        "alpha.obj", "mtllib alpha.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl half\nf 1 2 3\nusemtl tr\nf 1 2 3\n"
                     "usemtl both\nf 1 2 3\nusemtl halo\nf 1 2 3\n");
    const Scene scene = loadScene(model);
    const Material& half = meshWithMaterial(scene, "half").material;
    EXPECT_EQ(half.baseColorFactor, glm::vec4(1, 1, 1, 0.5f));
    EXPECT_EQ(half.alphaMode, AlphaMode::Blend);
    const Material& tr = meshWithMaterial(scene, "tr").material;
    EXPECT_EQ(tr.baseColorFactor.a, 0.75f);
    EXPECT_EQ(tr.alphaMode, AlphaMode::Blend);
    const Material& both = meshWithMaterial(scene, "both").material; // d decides
    EXPECT_EQ(both.baseColorFactor.a, 1.0f);
    EXPECT_EQ(both.alphaMode, AlphaMode::Opaque);
    EXPECT_EQ(meshWithMaterial(scene, "halo").material.baseColorFactor.a, 0.5f);
}

TEST(ObjMaterials, MapKdWithOptionsAndASpaceInItsNameIsAnImageBesideTheLibrary) {
    const TempFolder folder;
    std::filesystem::create_directories(folder.path("lib/maps"));
    const std::string texture = folder.write("lib/maps/old wood.png", "not decoded here");
    const std::string library =
        folder.write("lib/wood.mtl", "newmtl wood\nKd 1 0.5 1\nmap_Kd -bm 0.3 -s 2 4 1 -o 0.5 0.25 -clamp on -mm 0 1 "
                                     "maps/old wood.png\nnewmtl again\nmap_Kd maps/old wood.png\n");
    const std::string model =
        folder.write("wood.obj", "mtllib lib/wood.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                 "usemtl wood\nf 1/1 2/2 3/3\nusemtl again\nf 1/1 3/3 2/2\n");
    const Scene scene = loadScene(model);
    EXPECT_TRUE(scene.report.warnings.empty()) << ::testing::PrintToString(scene.report.warnings);
    ASSERT_EQ(scene.images.size(), 1u); // one image for both materials
    EXPECT_EQ(scene.images[0].path, texture);
    EXPECT_EQ(scene.images[0].name, "maps/old wood.png");
    EXPECT_EQ(scene.images[0].encoded, nullptr);

    const Material& wood = meshWithMaterial(scene, "wood").material;
    EXPECT_EQ(wood.baseColorFactor, glm::vec4(1, 0.5f, 1, 1));
    EXPECT_EQ(wood.baseColorTexture.image, 0);
    EXPECT_EQ(wood.baseColorTexture.texCoord, 0);
    EXPECT_EQ(wood.baseColorTexture.sampler.wrapS, TextureWrap::ClampToEdge);
    EXPECT_EQ(wood.baseColorTexture.sampler.wrapT, TextureWrap::ClampToEdge);
    // OBJ's lookup (u 2 + 0.5, v 4 + 0.25) with v up is, on the stored (u, 1 - v): u' = 2 u + 0.5, v' = 4 v - 3.25.
    const glm::vec3 corner = wood.baseColorTexture.transform * glm::vec3(0.0f, 0.0f, 1.0f);
    const glm::vec3 far = wood.baseColorTexture.transform * glm::vec3(1.0f, 1.0f, 1.0f);
    EXPECT_EQ(corner, glm::vec3(0.5f, -3.25f, 1.0f));
    EXPECT_EQ(far, glm::vec3(2.5f, 0.75f, 1.0f));

    const Material& again = meshWithMaterial(scene, "again").material;
    EXPECT_EQ(again.baseColorTexture.image, 0);
    EXPECT_EQ(again.baseColorTexture.sampler, TextureSampler{});
    EXPECT_EQ(again.baseColorTexture.transform, glm::mat3(1.0f));

    EXPECT_EQ(scene.report.inputFiles, (std::vector<std::string>{model, library, texture}));
    EXPECT_EQ(referencedFiles(model), (std::vector<std::string>{library, texture}));
}

TEST(ObjMaterials, PathsOfTheExportingMachineFindTheFilesBesideTheModel) {
    // 3ds Max, Maya and Blender on Windows write their own folders ("C:\Users\..."), and mtllib with '\' or quotes:
    // the model was drawn untextured, or all grey, though its files lay beside it.
    const TempFolder folder;
    std::filesystem::create_directories(folder.path("mats"));
    const std::string skin = folder.write("mats/skin.png", "not decoded here"); // beside the library
    const std::string spaced = folder.write("mats/old wood.png", "not decoded here");
    const std::string library = folder.write("mats/quad.mtl", "newmtl a\nmap_Kd C:\\Users\\me\\tex\\skin.png\n"
                                                              "newmtl b\nmap_Kd /home/artist/tex/skin.png\n"
                                                              "newmtl c\nmap_Kd \"old wood.png\"\n");
    const std::string model =
        folder.write("quad.obj", "mtllib mats\\quad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                 "usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 3/3 2/2\nusemtl c\nf 2/2 1/1 3/3\n");
    const Scene scene = loadScene(model);
    EXPECT_TRUE(scene.report.warnings.empty()) << ::testing::PrintToString(scene.report.warnings);
    ASSERT_EQ(scene.images.size(), 2u);
    EXPECT_EQ(scene.images[0].path, skin);
    EXPECT_EQ(scene.images[1].path, spaced);
    for (const char* name : {"a", "b"}) EXPECT_EQ(meshWithMaterial(scene, name).material.baseColorTexture.image, 0);
    EXPECT_EQ(meshWithMaterial(scene, "c").material.baseColorTexture.image, 1);
    EXPECT_EQ(scene.report.inputFiles, (std::vector<std::string>{model, library, skin, spaced}));
    EXPECT_EQ(referencedFiles(model)[0], library) << "the batch's input files are the ones read";
    // Quoted mtllib with a space: the name whole, unquoted.
    const std::string quoted = folder.write("my model.mtl", "newmtl q\nKd 1 0 0\n");
    const Scene red = loadScene(folder.write("q.obj", "mtllib \"my model.mtl\"\nusemtl q\n" + kTriangle));
    EXPECT_TRUE(red.report.warnings.empty()) << ::testing::PrintToString(red.report.warnings);
    EXPECT_EQ(meshWithMaterial(red, "q").material.baseColorFactor, glm::vec4(1, 0, 0, 1));
}

TEST(ObjMaterials, NamesWrittenOnWindowsFindTheFileThatDiffersInCaseAlone) {
    // Windows file systems ignore case, so exports name "Textures/Skin.PNG" for textures/skin.png and "Model.MTL":
    // drawn untextured, or grey, on Linux.
    const TempFolder folder;
    std::filesystem::create_directories(folder.path("textures"));
    const std::string skin = folder.write("textures/skin.png", "not decoded here");
    const std::string eyes = folder.write("eyes.png", "not decoded here");
    folder.write("hair.png", "not decoded here");
    folder.write("HAIR.png", "not decoded here");
    const std::string library = folder.write("model.mtl", "newmtl a\nmap_Kd Textures\\Skin.PNG\n"
                                                          "newmtl b\nmap_Kd D:\\work\\EYES.png\n"
                                                          "newmtl c\nmap_Kd Hair.png\n");
    const std::string model = folder.write("case.obj", "mtllib Model.MTL\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\n"
                                                       "vt 0 1\nusemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 3/3 2/2\n"
                                                       "usemtl c\nf 2/2 1/1 3/3\n");
    const Scene scene = loadScene(model);
    ASSERT_EQ(scene.images.size(), 2u);
    EXPECT_EQ(scene.images[0].path, skin);
    EXPECT_EQ(scene.images[1].path, eyes);
    // hair.png and HAIR.png both differ from Hair.png in case alone: neither is taken, and both are named (the
    // warning said "is missing", of a file the user saw beside the model).
    EXPECT_FALSE(meshWithMaterial(scene, "c").material.textured());
    EXPECT_TRUE(anyWarningContains(scene, "map_Kd 'Hair.png': '" + folder.path("Hair.png") +
                                              "' cannot be found: the folder '" + folderOf(model) +
                                              "' holds 'HAIR.png' and 'hair.png', which differ from its name in "
                                              "case alone: rename the one meant to 'Hair.png'; material 'c' is "
                                              "drawn without it"))
        << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.report.inputFiles, (std::vector<std::string>{model, library, skin, eyes, folder.path("Hair.png")}));
    EXPECT_EQ(referencedFiles(model), (std::vector<std::string>{library, skin, eyes, folder.path("Hair.png")}));
}

TEST(ObjMaterials, NamesThatSeveralFilesOrFoldersMatchInCaseAloneAreToldSoNamingThem) {
    // Each was told as missing: a library, and a texture whose folder is written in a case three folders match.
    const TempFolder folder;
    for (const std::string name : {"tex/skin.png", "TEX/skin.png", "Tex/skin.png"}) {
        std::filesystem::create_directories(std::filesystem::path(folder.path(name)).parent_path());
        folder.write(name, "not decoded here");
    }
    folder.write("m.mtl", "newmtl a\nmap_Kd tEX/skin.png\n");
    folder.write("M.MTL", "newmtl a\nmap_Kd tEX/skin.png\n");
    const std::string model = folder.write("m.obj", "mtllib M.mtl\nusemtl a\n" + kTriangle);
    const std::string shownFolder = folderOf(model);
    const Scene scene = loadScene(model);
    EXPECT_TRUE(anyWarningContains(scene, "mtllib 'M.mtl' (line 1): '" + folder.path("M.mtl") +
                                              "' cannot be found: the folder '" + shownFolder +
                                              "' holds 'M.MTL' and 'm.mtl', which differ from its name in case "
                                              "alone: rename the one meant to 'M.mtl'; its materials are drawn in "
                                              "the default grey"))
        << ::testing::PrintToString(scene.report.warnings);
    folder.write("library.mtl", "newmtl a\nmap_Kd tEX/skin.png\n");
    const Scene textured = loadScene(folder.write("t.obj", "mtllib library.mtl\nusemtl a\n" + kTriangle));
    EXPECT_TRUE(anyWarningContains(textured, "map_Kd 'tEX/skin.png': '" + folder.path("tEX/skin.png") +
                                                 "' cannot be found: the folder '" + shownFolder +
                                                 "' holds 'TEX', 'Tex' and 'tex', which differ from its name in "
                                                 "case alone: rename the one meant to 'tEX'"))
        << ::testing::PrintToString(textured.report.warnings);
    // A name alone in its case is still taken, and a name that matches nothing is missing as before.
    std::filesystem::remove_all(folder.path("TEX"));
    std::filesystem::remove_all(folder.path("Tex"));
    EXPECT_EQ(loadScene(folder.path("t.obj")).images.at(0).path, folder.path("tex/skin.png"));
    EXPECT_EQ(detail::whyFileIsMissing(folder.path("nothing.png")), std::nullopt);
}

TEST(ObjMaterials, ATextureInAFolderThatCannotBeReadIsToldSoNotMissing) {
    // A folder without read permission hides the file differing in case alone; it was told as missing.
    const TempFolder folder;
    const std::filesystem::path locked = folder.path("locked");
    std::filesystem::create_directories(locked);
    folder.write("locked/skin.png", "not decoded here");
    const std::string library = folder.write("m.mtl", "newmtl a\nmap_Kd locked/Skin.png\n");
    const std::string expected = "map_Kd 'locked/Skin.png': '" + folder.path("locked/Skin.png") +
                                 "' cannot be looked for: the folder '" + locked.string() +
                                 "' cannot be read (Permission denied); material 'a' is drawn without it";
    const auto warned = [&] {
        detail::ObjMaterials materials;
        std::vector<Warning> warnings;
        detail::readMtl(library, "newmtl a\nmap_Kd locked/Skin.png\n", materials, warnings, folderOf(library));
        return std::ranges::any_of(warnings, [&](const Warning& w) { return contains(w.message, expected); });
    };
    std::filesystem::permissions(std::filesystem::path(folderOf(library)), std::filesystem::perms(0755));
    std::filesystem::permissions(locked, std::filesystem::perms::none);
    DIR* const stillReadable = ::opendir(locked.c_str());
    if (stillReadable == nullptr) {
        EXPECT_TRUE(warned()) << expected;
        std::filesystem::permissions(locked, std::filesystem::perms(0755));
        return;
    }
    ::closedir(stillReadable);
    // Root reads every folder whatever its permissions: the lookup is made by a child that gives up root for nobody.
    const pid_t child = ::fork();
    ASSERT_NE(child, -1);
    if (child == 0) {
        ::alarm(60); // a hang ends the child, not the test run
        if (::setgid(65534) != 0 || ::setuid(65534) != 0) ::_exit(77);
        ::_exit(warned() ? 0 : 1);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    std::filesystem::permissions(locked, std::filesystem::perms(0755));
    ASSERT_TRUE(WIFEXITED(status));
    if (WEXITSTATUS(status) == 77) GTEST_SKIP() << "root reads every folder here, and cannot become another user";
    EXPECT_EQ(WEXITSTATUS(status), 0) << "no warning: " << expected;
}

TEST(ObjMaterials, ALibraryInAFolderOfItsOwnFindsTexturesBesideTheModel) {
    // mtllib materials/model.mtl whose map_Kd names skin.png, shipped beside the model rather than the library.
    const TempFolder folder;
    std::filesystem::create_directories(folder.path("materials"));
    const std::string skin = folder.write("skin.png", "not decoded here");
    const std::string library = folder.write("materials/model.mtl", "newmtl a\nmap_Kd skin.png\n");
    const std::string model =
        folder.write("model.obj", "mtllib materials/model.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                  "vt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
    const Scene scene = loadScene(model);
    EXPECT_TRUE(scene.report.warnings.empty()) << ::testing::PrintToString(scene.report.warnings);
    ASSERT_EQ(scene.images.size(), 1u);
    EXPECT_EQ(scene.images[0].path, skin);
    EXPECT_EQ(referencedFiles(model), (std::vector<std::string>{library, skin}));
}

TEST(ObjMaterials, TheLookupBesideTheModelNeverLeadsOutOfItNorCutsANameAtANul) {
    // A library in a folder of its own names "../tex/skin.png": beside the model only "skin.png" is tried, not the
    // path from the model's folder (it reached a folder above the model). A Windows share ("\\\\host\\...") is another
    // machine's, not "//host/..." here. A NUL in a name read the file named by what came before it.
    const TempFolder folder;
    std::filesystem::create_directories(folder.path("model/mats"));
    std::filesystem::create_directories(folder.path("tex"));
    folder.write("tex/skin.png", "not decoded here"); // above the model's folder
    const std::string beside = folder.write("model/eyes.png", "not decoded here");
    folder.write("model/t.png", "not decoded here");
    std::string share = folder.path("eyes.png"); // exists only as model/eyes.png
    folder.write("eyes.png", "not decoded here");
    std::replace(share.begin(), share.end(), '/', '\\');
    const std::string library =
        folder.write("model/mats/m.mtl", "newmtl a\nmap_Kd ../tex/skin.png\nnewmtl b\nmap_Kd \\" + share +
                                             "\nnewmtl c\nmap_Kd t.png" + std::string(1, '\0') + ".jpg\n");
    const std::string model = folder.write("model/m.obj", "mtllib mats/m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n"
                                                          "vt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\nusemtl b\n"
                                                          "f 1/1 3/3 2/2\nusemtl c\nf 2/2 1/1 3/3\n");
    const Scene scene = loadScene(model);
    EXPECT_FALSE(meshWithMaterial(scene, "a").material.textured());
    ASSERT_TRUE(meshWithMaterial(scene, "b").material.textured());
    EXPECT_EQ(scene.images.at(std::size_t(meshWithMaterial(scene, "b").material.baseColorTexture.image)).path, beside);
    EXPECT_FALSE(meshWithMaterial(scene, "c").material.textured());
    EXPECT_TRUE(anyWarningContains(scene, "t.png\\0.jpg")) << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(referencedFiles(model).front(), library);
}

TEST(ObjMaterials, AFileThatAppearsIsFoundByItsNameInAnotherCase) {
    // The folders a case-blind lookup read are remembered while they stay unchanged: a file added since is seen.
    const TempFolder folder;
    const std::string library = folder.write("m.mtl", "newmtl a\nmap_Kd Late.PNG\n");
    const std::string model = folder.write("m.obj", "mtllib m.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n"
                                                    "vt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
    EXPECT_TRUE(loadScene(model).images.empty());
    const std::string late = folder.write("late.png", "not decoded here");
    const Scene scene = loadScene(model);
    ASSERT_EQ(scene.images.size(), 1u);
    EXPECT_EQ(scene.images[0].path, late);
}

TEST(ObjMaterials, MissingTextureIsAWarningAndTheMaterialKeepsItsColour) {
    const TempFolder folder;
    const std::string library = folder.write("gone.mtl", "newmtl skin\nKd 0.5 0.25 0\nmap_Kd skin.png\n");
    const std::string model = folder.write("gone.obj", "mtllib gone.mtl\nusemtl skin\n" + kTriangle);
    const Scene scene = loadScene(model);
    EXPECT_TRUE(anyWarningContains(scene, "material library '" + library + "' line 3: map_Kd 'skin.png': '" +
                                              folder.path("skin.png") + "' is missing"))
        << ::testing::PrintToString(scene.report.warnings);
    EXPECT_TRUE(scene.images.empty());
    EXPECT_FALSE(scene.meshes.at(0).material.textured());
    EXPECT_EQ(scene.meshes.at(0).material.baseColorFactor, glm::vec4(0.5f, 0.25f, 0, 1));
    // Named, so an output must not take its place.
    EXPECT_EQ(scene.report.inputFiles, (std::vector<std::string>{model, library, folder.path("skin.png")}));
}

TEST(ObjMaterials, MissingTextureIsARecordNamingTheTextureAndTheMaterial) {
    const TempFolder folder;
    const std::string library = folder.write("gone.mtl", "newmtl skin\nKd 0.5 0.25 0\nmap_Kd skin.png\n");
    const std::string model = folder.write("gone.obj", "mtllib gone.mtl\nusemtl skin\n" + kTriangle);
    const Scene scene = loadScene(model);
    const Warning expected{"texture-missing",
                           "material library '" + library + "' line 3: map_Kd 'skin.png': '" + folder.path("skin.png") +
                               "' is missing or not a regular file; material 'skin' is drawn without it",
                           folder.path("skin.png"), "skin"};
    EXPECT_EQ(scene.report.warnings, std::vector<Warning>{expected});
}

TEST(ObjMaterials, MapDOfTheMapKdImageCutsOutAndAnotherImageIsIgnored) {
    const TempFolder folder;
    folder.write("leaf.png", "png");
    folder.write("mask.png", "png");
    folder.write("cut.mtl", "newmtl leaf\nmap_d leaf.png\nmap_Kd leaf.png\n"
                            "newmtl masked\nmap_Kd leaf.png\nmap_d mask.png\n");
    const std::string model = folder.write("cut.obj", "mtllib cut.mtl\n" + twoTriangles("leaf", "masked"));
    const Scene scene = loadScene(model);
    const Material& leaf = meshWithMaterial(scene, "leaf").material;
    EXPECT_EQ(leaf.alphaMode, AlphaMode::Mask);
    EXPECT_EQ(leaf.alphaCutoff, 0.5f);
    EXPECT_EQ(meshWithMaterial(scene, "masked").material.alphaMode, AlphaMode::Opaque);
    EXPECT_TRUE(anyWarningContains(scene, "line 6: map_d 'mask.png' is not the material's map_Kd image"))
        << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.images.size(), 1u);
    EXPECT_NE(std::ranges::find(scene.report.inputFiles, folder.path("mask.png")), scene.report.inputFiles.end());
}

TEST(ObjMaterials, MalformedLibraryLinesAreWarningsWithFileAndLine) {
    const TempFolder folder;
    const std::string library = folder.write("bad.mtl", "Kd 1 1 1\nnewmtl bad\nKd 1 x 0\nd\nmap_Kd -zz 1 a.png\n"
                                                        "Kd spectral sun.rfl\nmap_Kd -clamp\nKe 0 1 0\n");
    const std::string model = folder.write("bad.obj", "mtllib bad.mtl\nusemtl bad\n" + kTriangle);
    const Scene scene = loadScene(model);
    const std::string prefix = "material library '" + library + "' line ";
    for (const std::string& expected :
         {prefix + "1: 'Kd' before any 'newmtl'; ignored", prefix + "3: cannot read 'Kd' colour '1 x 0'",
          prefix + "4: cannot read 'd' value ''", prefix + "5: 'map_Kd' unknown option '-zz'; ignored",
          prefix + "6: 'Kd spectral' colours are not supported",
          prefix + "7: 'map_Kd' option '-clamp' without 'on' or 'off'"}) {
        EXPECT_TRUE(anyWarningContains(scene, expected)) << expected << "\n"
                                                         << ::testing::PrintToString(scene.report.warnings);
    }
    const Material& bad = scene.meshes.at(0).material;
    EXPECT_EQ(bad.baseColorFactor, Material{}.baseColorFactor); // every Kd was unreadable
    EXPECT_EQ(bad.emissiveFactor, glm::vec3(0, 1, 0));          // the good line after the bad ones counts
}

TEST(ObjMaterials, MissingLibraryIsAWarningAndTheMeshIsDefaultGrey) {
    const TempFolder folder;
    const std::string model = folder.write("lost.obj", "mtllib lost.mtl\nusemtl Steel\n" + kTriangle);
    const Scene scene = loadScene(model);
    EXPECT_EQ(scene.triangleCount(), 1u);
    EXPECT_TRUE(anyWarningContains(scene, "mtllib 'lost.mtl' (line 1): '" + folder.path("lost.mtl") +
                                              "' is missing or not a regular file; its materials are drawn in the "
                                              "default grey"))
        << ::testing::PrintToString(scene.report.warnings);
    const Material& steel = scene.meshes.at(0).material;
    EXPECT_EQ(steel.name, "Steel");
    EXPECT_EQ(steel.baseColorFactor, glm::vec4(0.8f, 0.8f, 0.8f, 1.0f));
    EXPECT_EQ(scene.report.inputFiles, std::vector<std::string>{model});
}

TEST(ObjMaterials, UnknownUsemtlIsAWarningAndDefaultGrey) {
    const TempFolder folder;
    folder.write("known.mtl", "newmtl Known\nKd 0 1 0\n");
    const std::string model = folder.write("mixed.obj", "mtllib known.mtl\n" + twoTriangles("Known", "Unknown"));
    const Scene scene = loadScene(model);
    EXPECT_TRUE(anyWarningContains(scene, "usemtl names materials not defined in its mtllib files: 'Unknown' (line "
                                          "10); their faces are drawn in the default grey"))
        << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(meshWithMaterial(scene, "Known").material.baseColorFactor, glm::vec4(0, 1, 0, 1));
    EXPECT_EQ(meshWithMaterial(scene, "Unknown").material.baseColorFactor, Material{}.baseColorFactor);
}

TEST(ObjMaterials, SeveralLibrariesOnOneLineAndTheFirstDefinitionWins) {
    const TempFolder folder;
    const std::string first = folder.write("a.mtl", "newmtl shared\nKd 1 0 0\nnewmtl onlyA\nKd 0 1 0\n");
    const std::string second = folder.write("b.mtl", "newmtl shared\nKd 0 0 1\nnewmtl onlyB\nKd 1 1 0\n");
    const std::string model =
        folder.write("libs.obj", "mtllib a.mtl b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl shared\nf 1 2 3\n"
                                 "usemtl onlyA\nf 1 2 3\nusemtl onlyB\nf 1 2 3\n");
    const Scene scene = loadScene(model);
    EXPECT_EQ(meshWithMaterial(scene, "shared").material.baseColorFactor, glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(meshWithMaterial(scene, "onlyA").material.baseColorFactor, glm::vec4(0, 1, 0, 1));
    EXPECT_EQ(meshWithMaterial(scene, "onlyB").material.baseColorFactor, glm::vec4(1, 1, 0, 1));
    EXPECT_TRUE(anyWarningContains(scene, "material library '" + second +
                                              "' line 1: material 'shared' is defined again; the first definition "
                                              "is kept"))
        << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.report.inputFiles, (std::vector<std::string>{model, first, second}));
}

TEST(ObjMaterials, TextureCoordinatesAreFlippedToTheTopLeftConvention) {
    const TempFolder folder;
    const std::string model =
        folder.write("uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.25 0.75\nvt 1 0 0\nvt 0.5\nf 1/1 2/2 3/3\n");
    const Scene scene = loadScene(model);
    const Mesh& mesh = scene.meshes.at(0);
    ASSERT_EQ(mesh.texcoords[0].size(), mesh.positions.size());
    EXPECT_TRUE(mesh.texcoords[1].empty());
    EXPECT_EQ(mesh.texcoords[0][vertexAt(scene, mesh, {0, 0, 0})], glm::vec2(0.25f, 0.25f));
    EXPECT_EQ(mesh.texcoords[0][vertexAt(scene, mesh, {1, 0, 0})], glm::vec2(1.0f, 1.0f));
    EXPECT_EQ(mesh.texcoords[0][vertexAt(scene, mesh, {0, 1, 0})], glm::vec2(0.5f, 1.0f)); // v defaults to 0
}

TEST(ObjMaterials, FaceWithoutTextureCoordinatesInATexturedMeshTakesZeroAndWarnsOnce) {
    const TempFolder folder;
    const std::string model = folder.write("partial.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 0 0\n"
                                                          "vt 0.5 0.5\nf 1/1 2/1 3/1\nf 2 4 3\nf 2 5 4\n");
    const Scene scene = loadScene(model);
    const Mesh& mesh = scene.meshes.at(0);
    EXPECT_EQ(mesh.texcoords[0][vertexAt(scene, mesh, {2, 0, 0})], glm::vec2(0.0f, 0.0f));
    EXPECT_EQ(mesh.texcoords[0][vertexAt(scene, mesh, {1, 1, 0})], glm::vec2(0.0f, 0.0f));
    EXPECT_EQ(mesh.texcoords[0][vertexAt(scene, mesh, {0, 0, 0})], glm::vec2(0.5f, 0.5f));
    EXPECT_EQ(std::ranges::count_if(scene.report.warnings,
                                    [](const Warning& w) { return contains(w.message, "texture coordinates"); }),
              1);
    EXPECT_TRUE(anyWarningContains(scene, "2 faces have no texture coordinates (vt)"))
        << ::testing::PrintToString(scene.report.warnings);
}

TEST(ObjMaterials, BadTextureCoordinatesAreErrorsWithTheirLine) {
    const TempFolder folder;
    const std::string range = folder.write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n");
    EXPECT_TRUE(contains(test::sceneErrorMessage([&] { loadScene(range); }),
                         "line 5: texture coordinate index 2 out of range (file has 1 texture coordinates)"));
    const std::string word = folder.write("word.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 up\nf 1 2 3\n");
    EXPECT_TRUE(
        contains(test::sceneErrorMessage([&] { loadScene(word); }), "line 4: cannot read texture coordinate 'up'"));
    const std::string empty = folder.write("empty.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt\nf 1 2 3\n");
    EXPECT_TRUE(contains(test::sceneErrorMessage([&] { loadScene(empty); }), "line 4: 'vt' without coordinates"));
}

TEST(ObjMaterials, NonFiniteTextureCoordinatesReadAsZeroWithAWarning) {
    const TempFolder folder;
    const std::string model =
        folder.write("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt nan inf\nvt 0.5 0.5\nvt 1e39 0\nf 1/1 2/2 3/3\n");
    const Scene scene = loadScene(model);
    const Mesh& mesh = scene.meshes.at(0);
    EXPECT_EQ(mesh.texcoords[0][vertexAt(scene, mesh, {0, 0, 0})], glm::vec2(0.0f));
    EXPECT_EQ(mesh.texcoords[0][vertexAt(scene, mesh, {1, 0, 0})], glm::vec2(0.5f));
    EXPECT_EQ(mesh.texcoords[0][vertexAt(scene, mesh, {0, 1, 0})], glm::vec2(0.0f));
    EXPECT_TRUE(anyWarningContains(scene, "2 texture coordinates (vt) are not finite in float; they read as (0, 0)"))
        << ::testing::PrintToString(scene.report.warnings);
}

TEST(ObjMaterials, VertexColoursAreReadClampedAndUncolouredVerticesAreWhite) {
    const TempFolder folder;
    const std::string model = folder.write("colours.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 2 -1\nv 0 1 0\n"
                                                          "v 1 1 0 0.5 0.5 0.5 0.25\nf 1 2 3\nf 2 4 3\n");
    const Scene scene = loadScene(model);
    const Mesh& mesh = scene.meshes.at(0);
    ASSERT_EQ(mesh.colors.size(), mesh.positions.size());
    EXPECT_EQ(mesh.colors[vertexAt(scene, mesh, {0, 0, 0})], glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(mesh.colors[vertexAt(scene, mesh, {1, 0, 0})], glm::vec4(0, 1, 0, 1));
    EXPECT_EQ(mesh.colors[vertexAt(scene, mesh, {0, 1, 0})], glm::vec4(1, 1, 1, 1));
    EXPECT_EQ(mesh.colors[vertexAt(scene, mesh, {1, 1, 0})], glm::vec4(0.5f, 0.5f, 0.5f, 0.25f));
    // Without a material, the base colour that multiplies them is white, so they show as written.
    EXPECT_EQ(mesh.material.baseColorFactor, glm::vec4(1.0f));
    // The clamp is said (it was silent; a file of 0-255 colours drew in the wrong colours without a word).
    ASSERT_EQ(scene.report.warnings.size(), 1u) << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.report.warnings[0].code, "value-out-of-range");
    EXPECT_EQ(scene.report.warnings[0].message,
              "1 'v' line gives a colour outside [0, 1] (as far out as 2; colours of 0 to 255?); clamped into [0, 1]");
}

TEST(ObjMaterials, AFourthCoordinateIsWNotAColour) {
    const TempFolder folder;
    const std::string model = folder.write("w.obj", "v 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nf 1 2 3\n");
    const Scene scene = loadScene(model);
    EXPECT_TRUE(scene.meshes.at(0).colors.empty());
    EXPECT_EQ(scene.meshes.at(0).positions.size(), 3u);
}

TEST(ObjMaterials, VertexValuesThatAreNeitherWNorAColourAreSaidOnce) {
    const TempFolder folder;
    // Five numbers, a NaN colour, and one good colour: the two odd lines are counted in one warning.
    const std::string model = folder.write("odd.obj", "v 0 0 0 1 0 0 1 1\nv 1 0 0 nan 0 0\nv 0 1 0 0 1 0\nf 1 2 3\n");
    const Scene scene = loadScene(model);
    ASSERT_EQ(scene.report.warnings.size(), 1u) << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.report.warnings[0].message.rfind("2 'v' lines have values after x y z", 0), 0u)
        << scene.report.warnings[0];
    EXPECT_EQ(scene.meshes.at(0).colors.size(), 3u) << "the good colour keeps the others white";
}

TEST(ObjMaterials, DissolveOutsideZeroToOneIsClampedWithAWarning) {
    const TempFolder folder;
    folder.write("d.mtl", "newmtl glass\nd -5\n");
    const Scene scene = loadScene(folder.write("d.obj", "mtllib d.mtl\nusemtl glass\n" + kTriangle));
    ASSERT_EQ(scene.report.warnings.size(), 2u) << ::testing::PrintToString(scene.report.warnings);
    EXPECT_NE(scene.report.warnings[0].message.find("'d' -5 is outside [0, 1]; 0 is used"), std::string::npos)
        << scene.report.warnings[0];
    EXPECT_EQ(scene.report.warnings[1].code, "material-invisible");
}

TEST(ObjMaterials, AColourOutsideZeroToOneIsClampedWithAWarning) {
    // Kd -1 -1 -1 and Kd 1e300 0 0 were clamped without a word, where d and glTF's factors warn.
    const TempFolder folder;
    folder.write("m.mtl", "newmtl dark\nKd -1 0.5 0.5\nnewmtl bright\nKd 1e300 0 0\nnewmtl fine\nKd 0 1 0.5\n");
    const Scene scene = loadScene(folder.write("m.obj", "mtllib m.mtl\nusemtl dark\n" + kTriangle + "usemtl bright\n" +
                                                            kTriangle + "usemtl fine\n" + kTriangle));
    ASSERT_EQ(scene.report.warnings.size(), 2u) << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.report.warnings[0].code, "value-out-of-range");
    EXPECT_NE(scene.report.warnings[0].message.find("line 2: 'Kd' -1 is outside [0, 1]; 0 is used"), std::string::npos)
        << scene.report.warnings[0];
    EXPECT_NE(scene.report.warnings[1].message.find("line 4: 'Kd' 1e+300 is outside [0, 1]; 1 is used"),
              std::string::npos)
        << scene.report.warnings[1];
}

TEST(ObjMaterials, AMaterialUnderHalfALevelOfColourIsSaidAsInvisible) {
    // d 1e-7 changes no pixel of an 8-bit picture, and was drawn as blank paper without a word; 1/255 shows.
    const TempFolder folder;
    folder.write("m.mtl", "newmtl faint\nd 0.0000001\nnewmtl trace\nTr 0.9999\nnewmtl shows\nd 0.004\n");
    const Scene scene = loadScene(folder.write("m.obj", "mtllib m.mtl\nusemtl faint\n" + kTriangle + "usemtl trace\n" +
                                                            kTriangle + "usemtl shows\n" + kTriangle));
    ASSERT_EQ(scene.report.warnings.size(), 2u) << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.report.warnings[0].code, "material-invisible");
    EXPECT_NE(scene.report.warnings[0].message.find("material 'faint' is fully transparent (d 1"), std::string::npos)
        << scene.report.warnings[0];
    EXPECT_NE(scene.report.warnings[1].message.find("material 'trace' is fully transparent (Tr 0.9998"),
              std::string::npos)
        << scene.report.warnings[1];
}

TEST(ObjMaterials, AFullyTransparentMaterialIsSaidAndAMapWithoutKdIsDrawnAsTheImageIs) {
    // d 0 and Tr 1 draw nothing: said, since exporters disagree on Tr (some write it as opacity). A map_Kd without
    // Kd was multiplied by the 0.8 grey of a bare material, 20 % darker than the image.
    const TempFolder folder;
    folder.write("skin.png", "not decoded here");
    folder.write("m.mtl", "newmtl none\nd 0\nnewmtl tr\nTr 1\nnewmtl opaque\nTr 1\nd 1\n"
                          "newmtl image\nmap_Kd skin.png\nnewmtl tinted\nKd 0.5 0.25 1\nmap_Kd skin.png\n");
    const std::string model = folder.write(
        "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl none\nf 1/1 2/2 3/3\n"
                 "usemtl tr\nf 1/1 3/3 2/2\nusemtl opaque\nf 2/2 1/1 3/3\nusemtl image\nf 2/2 3/3 1/1\n"
                 "usemtl tinted\nf 3/3 1/1 2/2\n");
    const Scene scene = loadScene(model);
    ASSERT_EQ(scene.report.warnings.size(), 2u) << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.report.warnings[0].code, "material-invisible");
    EXPECT_EQ(scene.report.warnings[0].item, "none");
    EXPECT_NE(scene.report.warnings[0].message.find("line 1: material 'none' is fully transparent (d 0)"),
              std::string::npos)
        << scene.report.warnings[0];
    EXPECT_EQ(scene.report.warnings[1].item, "tr");
    EXPECT_NE(scene.report.warnings[1].message.find("(Tr 1, read as d 0; some exporters write Tr as opacity"),
              std::string::npos)
        << scene.report.warnings[1];
    EXPECT_EQ(meshWithMaterial(scene, "opaque").material.baseColorFactor.a, 1.0f);
    EXPECT_EQ(meshWithMaterial(scene, "image").material.baseColorFactor, glm::vec4(1.0f));
    EXPECT_EQ(meshWithMaterial(scene, "tinted").material.baseColorFactor, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
}

TEST(ObjMaterials, AMapKeIsTheEmissiveTextureAndAWhiteKeWithoutOneIsNoEmission) {
    // map_Ke was ignored, so a material with `Ke 1 1 1` and its glow in a map_Ke was drawn white; now the map is the
    // emissive texture, times Ke (1 without one). A white Ke without a map (a white emission colour at strength 0,
    // as exporters write it: Blender 4's "Kd 0, Ke 1, map_Kd") drew the material white: now it is no emission, with
    // a warning, as Blender's importer reads it; a coloured Ke stays. Kd 0 0 0 beside a map_Kd (the MTL rule would
    // draw the map black) lets the map decide, as Blender's importer does; Kd 0 alone stays black.
    const TempFolder folder;
    folder.write("skin.png", "not decoded here");
    folder.write("glow.png", "not decoded here");
    folder.write("m.mtl", "newmtl glowing\nKe 1 1 1\nmap_Kd skin.png\nmap_Ke -clamp on glow.png\n"
                          "newmtl dim\nKe 0.5 0.25 0\nmap_Ke glow.png\nnewmtl keOnly\nmap_Ke glow.png\n"
                          "newmtl white\nKd 0.2 0.4 0.6\nmap_Kd skin.png\nKe 1 1 1\n"
                          "newmtl blackKd\nKd 0 0 0\nmap_Kd skin.png\nnewmtl black\nKd 0 0 0\n"
                          "newmtl scan\nKd 0 0 0\nKe 1 1 1\nmap_Kd skin.png\nnewmtl lamp\nKe 1 0.5 0\n"
                          "newmtl gone\nKd 0 0 0\nmap_Kd gone.png\nKe 1 1 1\nmap_Ke gone.png\n"
                          "newmtl nearly\nKe 0.9995 2 1\n");
    std::string faces;
    for (const char* name : {"glowing", "dim", "keOnly", "white", "blackKd", "black", "scan", "lamp", "gone", "nearly"})
        faces += std::string("usemtl ") + name + "\nf 1/1 2/2 3/3\n";
    const std::string model = folder.write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\n"
                                                    "vt 0 1\n" +
                                                        faces);
    const Scene scene = loadScene(model);
    ASSERT_EQ(scene.report.warnings.size(), 6u) << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.report.warnings[0].code, "white-emission-ignored");
    EXPECT_EQ(scene.report.warnings[1].item, "scan");
    EXPECT_EQ(scene.report.warnings[2].code, "texture-missing");    // gone's map_Kd
    EXPECT_EQ(scene.report.warnings[3].code, "texture-missing");    // and its map_Ke
    EXPECT_EQ(scene.report.warnings[4].code, "value-out-of-range"); // nearly's Ke 2, clamped to 1
    EXPECT_EQ(scene.report.warnings[5].item, "nearly");
    EXPECT_EQ(scene.report.warnings[0].item, "white");
    EXPECT_TRUE(contains(scene.report.warnings[0].message, "line 13: material 'white': a white 'Ke' without a map_Ke "
                                                           "is read as no emission"))
        << scene.report.warnings[0];
    ASSERT_EQ(scene.images.size(), 2u);
    EXPECT_EQ(scene.images[1].name, "glow.png");

    const Material& glowing = meshWithMaterial(scene, "glowing").material;
    EXPECT_EQ(glowing.emissiveFactor, glm::vec3(1.0f));
    EXPECT_EQ(glowing.emissiveTexture.image, 1);
    EXPECT_EQ(glowing.emissiveTexture.sampler.wrapS, TextureWrap::ClampToEdge);
    EXPECT_EQ(glowing.baseColorTexture.image, 0);
    const Material& dim = meshWithMaterial(scene, "dim").material;
    EXPECT_EQ(dim.emissiveFactor, glm::vec3(0.5f, 0.25f, 0.0f));
    EXPECT_EQ(dim.emissiveTexture.image, 1);
    EXPECT_EQ(meshWithMaterial(scene, "keOnly").material.emissiveFactor, glm::vec3(1.0f));
    const Material& white = meshWithMaterial(scene, "white").material;
    EXPECT_EQ(white.emissiveFactor, glm::vec3(0.0f));
    EXPECT_FALSE(white.emissiveTexture.present());
    EXPECT_EQ(white.baseColorFactor, glm::vec4(0.2f, 0.4f, 0.6f, 1.0f));
    EXPECT_EQ(meshWithMaterial(scene, "blackKd").material.baseColorFactor, glm::vec4(1.0f));
    EXPECT_EQ(meshWithMaterial(scene, "black").material.baseColorFactor, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    const Material& scan = meshWithMaterial(scene, "scan").material; // as Blender 4 exports an unlit scan
    EXPECT_EQ(scan.baseColorFactor, glm::vec4(1.0f));
    EXPECT_EQ(scan.emissiveFactor, glm::vec3(0.0f));
    EXPECT_EQ(meshWithMaterial(scene, "lamp").material.emissiveFactor, glm::vec3(1.0f, 0.5f, 0.0f));
    // A missing map decides nothing: the Kd as written, and no emission (Ke alone would draw it white).
    const Material& gone = meshWithMaterial(scene, "gone").material;
    EXPECT_EQ(gone.baseColorFactor, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    EXPECT_EQ(gone.emissiveFactor, glm::vec3(0.0f));
    EXPECT_EQ(meshWithMaterial(scene, "nearly").material.emissiveFactor, glm::vec3(0.0f));
    EXPECT_EQ(scene.report.inputFiles, (std::vector<std::string>{model, folder.path("m.mtl"), folder.path("skin.png"),
                                                                 folder.path("glow.png"), folder.path("gone.png")}));
    EXPECT_EQ(referencedFiles(model), (std::vector<std::string>{folder.path("m.mtl"), folder.path("skin.png"),
                                                                folder.path("glow.png"), folder.path("gone.png")}));
}

TEST(ObjMaterials, AMapThatReplacesKdButCannotBeUsedLeavesTheKdAsWritten) {
    // `Kd 0 0 0` beside a map_Kd draws the map; on a mesh without `vt` the map is dropped, and the material was then
    // drawn white (the factor the map is drawn with) instead of its black.
    const TempFolder folder;
    folder.write("skin.png", "not decoded here");
    folder.write("m.mtl", "newmtl black\nKd 0 0 0\nmap_Kd skin.png\n");
    const Scene scene = loadScene(folder.write("m.obj", "mtllib m.mtl\nusemtl black\n" + kTriangle));
    const Material& black = meshWithMaterial(scene, "black").material;
    EXPECT_FALSE(black.baseColorTexture.present());
    EXPECT_EQ(black.baseColorFactor, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
}

TEST(ObjMaterials, CommentsAfterValuesAndAfterAMapsNameAreDropped) {
    // `Kd 0.8 0.8 0.8 # grey` was a malformed colour (ignored, with a warning) and `map_Kd skin.png # diffuse` a
    // missing file 'skin.png # diffuse'. A name holding " #" keeps it when such a file exists.
    const TempFolder folder;
    folder.write("skin.png", "not decoded here");
    folder.write("hash #1.png", "not decoded here");
    folder.write("other.png", "not decoded here");
    folder.write("m.mtl", "newmtl a\nKd 0.5 0.25 1 # tinted\nd 0.5 # half\nmap_Kd skin.png # diffuse map\n"
                          "newmtl b\nmap_Kd hash #1.png\nnewmtl c\nmap_Kd gone.png # was textures/other.png\n"
                          "newmtl d\nmap_Kd skin.png # was textures/other.png\n");
    const std::string model = folder.write(
        "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n"
                 "usemtl b\nf 1/1 3/3 2/2\nusemtl c\nf 2/2 1/1 3/3\nusemtl d\nf 3/3 2/2 1/1\n");
    const Scene scene = loadScene(model);
    ASSERT_EQ(scene.report.warnings.size(), 1u) << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.report.warnings[0].code, "texture-missing");
    // A comment after a missing file's name is still a comment: the file is missing as gone.png, and other.png (found
    // by the last name of the whole text) is not drawn instead.
    EXPECT_TRUE(contains(scene.report.warnings[0].message, "map_Kd 'gone.png': '" + folder.path("gone.png") + "'"))
        << scene.report.warnings[0];
    const Material& a = meshWithMaterial(scene, "a").material;
    EXPECT_EQ(a.baseColorFactor, glm::vec4(0.5f, 0.25f, 1.0f, 0.5f));
    ASSERT_EQ(scene.images.size(), 2u);
    EXPECT_EQ(scene.images[std::size_t(a.baseColorTexture.image)].name, "skin.png");
    EXPECT_EQ(scene.images[std::size_t(a.baseColorTexture.image)].path, folder.path("skin.png"));
    const Material& b = meshWithMaterial(scene, "b").material;
    EXPECT_EQ(scene.images[std::size_t(b.baseColorTexture.image)].path, folder.path("hash #1.png"));
    // The whole name counts as found only as written: its last name, other.png, is no reason to keep the comment.
    const Material& d = meshWithMaterial(scene, "d").material;
    EXPECT_EQ(scene.images[std::size_t(d.baseColorTexture.image)].path, folder.path("skin.png"));
    EXPECT_EQ(referencedFiles(model), (std::vector<std::string>{folder.path("m.mtl"), folder.path("skin.png"),
                                                                folder.path("hash #1.png"), folder.path("gone.png")}));
}

TEST(ObjMaterials, VertexColoursFollowTheirPositionsIntoEveryMaterialMesh) {
    const TempFolder folder;
    folder.write("m.mtl", "newmtl a\nnewmtl b\n");
    const std::string model = folder.write("split.obj", "mtllib m.mtl\nv 0 0 0 0 0 1\nv 1 0 0\nv 0 1 0 0 1 0\n"
                                                        "usemtl a\nvn 0 0 1\nf 1//1 2//1 3//1\nusemtl b\nf 3 2 1\n");
    const Scene scene = loadScene(model);
    for (const char* name : {"a", "b"}) {
        const Mesh& mesh = meshWithMaterial(scene, name);
        ASSERT_EQ(mesh.colors.size(), 3u) << name;
        EXPECT_EQ(mesh.colors[vertexAt(scene, mesh, {0, 0, 0})], glm::vec4(0, 0, 1, 1)) << name;
        EXPECT_EQ(mesh.colors[vertexAt(scene, mesh, {1, 0, 0})], glm::vec4(1, 1, 1, 1)) << name;
        EXPECT_EQ(mesh.colors[vertexAt(scene, mesh, {0, 1, 0})], glm::vec4(0, 1, 0, 1)) << name;
        EXPECT_EQ(mesh.material.baseColorFactor, Material{}.baseColorFactor) << name; // as the library says
    }
    EXPECT_EQ(meshWithMaterial(scene, "a").normals.at(0), glm::vec3(0, 0, 1));  // the file's
    EXPECT_EQ(meshWithMaterial(scene, "b").normals.at(0), glm::vec3(0, 0, -1)); // computed for b's winding
}

/** Two unit quads side by side sharing the edge x = 1; the right one's texture coordinates continue the left one's
 *  (`seam` false) or start over at u = 0 (`seam` true). */
std::string twoQuads(bool seam) {
    return std::string("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
                       "vt 0 0\nvt 0.5 0\nvt 0.5 1\nvt 0 1\nvt 1 0\nvt 1 1\n") +
           "f 1/1 2/2 3/3 4/4\n" + (seam ? "f 2/1 5/5 6/6 3/4\n" : "f 2/2 5/5 6/6 3/3\n");
}

TEST(ObjMaterials, TextureSeamKeepsItsSplitVerticesAndSharedCoordinatesWeld) {
    const TempFolder folder;
    const Scene joined = loadScene(folder.write("joined.obj", twoQuads(false)));
    EXPECT_EQ(joined.meshes.at(0).positions.size(), 6u);
    const Scene seamed = loadScene(folder.write("seamed.obj", twoQuads(true)));
    const Mesh& mesh = seamed.meshes.at(0);
    ASSERT_EQ(mesh.positions.size(), 8u); // the two seam corners twice, one copy per side
    std::set<std::pair<float, float>> seamCoordinates;
    for (std::size_t vertex = 0; vertex < mesh.positions.size(); ++vertex) {
        if (test::worldPosition(seamed, mesh.positions[vertex]).x == 1.0) {
            seamCoordinates.emplace(mesh.texcoords[0][vertex].x, mesh.texcoords[0][vertex].y);
        }
    }
    EXPECT_EQ(seamCoordinates,
              (std::set<std::pair<float, float>>{{0.5f, 1.0f}, {0.5f, 0.0f}, {0.0f, 1.0f}, {0.0f, 0.0f}}));
}

TEST(ObjMaterials, CubeWithAFullSquarePerFaceKeepsOneVertexPerCornerCoordinatePair) {
    // Every face maps its quad onto the whole image, so each cube corner meets three faces at (mostly) different
    // texture coordinates: the mesh keeps one vertex per distinct (corner, coordinate) pair, and the copies of a
    // corner share one smooth normal (computed across the seams, so the cube's shading does not show them).
    std::ostringstream obj;
    for (const glm::vec3& corner : test::cubeCorners()) {
        obj << "v " << corner.x << ' ' << corner.y << ' ' << corner.z << '\n';
    }
    obj << "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
    std::set<std::pair<unsigned, unsigned>> pairs;
    for (const glm::uvec4& quad : test::cubeQuads()) {
        obj << "f " << quad.x << "/1 " << quad.y << "/2 " << quad.z << "/3 " << quad.w << "/4\n";
        for (unsigned corner = 0; corner < 4; ++corner) pairs.emplace(quad[int(corner)], corner);
    }
    const TempFolder folder;
    const Scene scene = loadScene(folder.write("cube.obj", obj.str()));
    const Mesh& mesh = scene.meshes.at(0);
    EXPECT_GT(pairs.size(), 8u);
    EXPECT_EQ(mesh.positions.size(), pairs.size());
    EXPECT_EQ(mesh.triangleCount(), 12u);
    for (std::size_t a = 0; a < mesh.positions.size(); ++a) {
        for (std::size_t b = 0; b < mesh.positions.size(); ++b) {
            if (mesh.positions[a] == mesh.positions[b]) {
                EXPECT_EQ(mesh.normals[a], mesh.normals[b]);
                EXPECT_GT(glm::dot(glm::dvec3(mesh.normals[a]), glm::dvec3(mesh.positions[a])), 0.0);
            }
        }
    }
}

TEST(ObjMaterials, LibraryBytesCountAgainstTheMemoryLimit) {
    const TempFolder folder;
    folder.write("huge.mtl", "newmtl big\n" + std::string(3u << 20, '#'));
    const std::string model = folder.write("huge.obj", "mtllib huge.mtl\nusemtl big\n" + kTriangle);
    LoadOptions options;
    options.memoryLimitBytes = 2u << 20;
    const std::string message = test::sceneErrorMessage([&] { loadScene(model, options); });
    EXPECT_TRUE(contains(message, "above the memory limit of 2 MiB")) << message;
    options.memoryLimitBytes = 16u << 20;
    EXPECT_EQ(loadScene(model, options).triangleCount(), 1u);
}

} // namespace
} // namespace inkgraph
