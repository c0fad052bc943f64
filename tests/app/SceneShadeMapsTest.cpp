// readSceneShadeMaps(): the shade maps a scene's meshes name, read once per file, with errors that name the mesh.
#include "render/SceneShadeMaps.h"

#include "render/ImageFiles.h"
#include "app/Render.h"
#include "render/StillRenderer.h"

#include "tests/support/TestFolder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

namespace fs = std::filesystem;

class SceneShadeMaps : public test::TestFolder {
protected:
    /** Writes a `rows` x `cols` PNG of one RGBA colour; returns its path. */
    std::string writeMap(const std::string& name, int rows, int cols, cv::Vec4b color) const {
        const fs::path path = directory / name;
        writeImage(path, cv::Mat(rows, cols, CV_8UC4, cv::Scalar(color[0], color[1], color[2], color[3])));
        return path.string();
    }

    static Mesh meshNaming(const std::string& name, const std::string& shadeMapPath,
                           const std::string& materialName = "") {
        Mesh mesh;
        mesh.name = name;
        mesh.material.shadeMapPath = shadeMapPath;
        mesh.material.name = materialName;
        return mesh;
    }

    /** The message of the InputFileError readSceneShadeMaps() throws. */
    static std::string errorOf(const Scene& scene, ShadingModel shading) {
        try {
            readSceneShadeMaps(scene, shading, nullptr);
        } catch (const InputFileError& error) {
            return error.what();
        }
        ADD_FAILURE() << "expected InputFileError";
        return {};
    }
};

TEST_F(SceneShadeMaps, DistinctFilesAreReadOnceAndShared) {
    const std::string warm = writeMap("warm.png", 4, 8, {200, 120, 40, 255});
    const std::string cool = writeMap("cool.png", 4, 8, {40, 120, 200, 255});
    Scene scene;
    scene.meshes = {meshNaming("Spot", warm), meshNaming("Teapot", cool), meshNaming("Suzanne", warm),
                    meshNaming("Ground", "")};
    std::vector<Warning> warnings;
    const std::vector<std::optional<ShadeMap>> maps = readSceneShadeMaps(scene, ShadingModel::Comic, &warnings);
    EXPECT_TRUE(warnings.empty());
    ASSERT_EQ(maps.size(), 4u);
    ASSERT_TRUE(maps[0] && maps[1] && maps[2]);
    EXPECT_FALSE(maps[3]) << "a mesh naming no map uses the run's";
    EXPECT_EQ(maps[0]->source, warm);
    EXPECT_EQ(maps[1]->source, cool);
    EXPECT_EQ(maps[2]->source, warm);
    // Read once: the two meshes naming warm.png hold the very same pixels, not two copies.
    EXPECT_EQ(maps[0]->texels.data, maps[2]->texels.data);
    EXPECT_NE(maps[0]->texels.data, maps[1]->texels.data);
    EXPECT_EQ(maps[0]->texels.size(), cv::Size(8, 4));
    EXPECT_EQ(maps[0]->texels.at<cv::Vec4b>(3, 7), cv::Vec4b(200, 120, 40, 255));
    EXPECT_EQ(maps[1]->texels.at<cv::Vec4b>(0, 0), cv::Vec4b(40, 120, 200, 255));
}

TEST_F(SceneShadeMaps, MissingFileNamesTheMeshItsMaterialAndTheFile) {
    const std::string missing = (directory / "missing.png").string();
    Scene scene;
    scene.meshes = {meshNaming("Spot", ""), meshNaming("Teapot", missing, "Metal")};
    EXPECT_EQ(errorOf(scene, ShadingModel::Comic),
              "mesh 'Teapot' (glTF material 'Metal') shade map: '" + missing + "': file not found");
    // Without a material name the mesh alone is named.
    scene.meshes[1].material.name.clear();
    EXPECT_EQ(errorOf(scene, ShadingModel::Cel), "mesh 'Teapot' shade map: '" + missing + "': file not found");
}

TEST_F(SceneShadeMaps, TheFlagsMessagesStartWithTheFlagAndTheFile) {
    // They started "--shademap: readPngImage():" and "--shademap: shadeMapFromImage():"; --style's and --list's name
    // the flag and the file alone.
    const std::string missing = (directory / "missing.png").string();
    const std::string square = writeMap("square.png", 4, 8, {90, 90, 90, 255});
    const auto refusal = [](const std::string& path, bool oneDimensional) -> std::string {
        try {
            readShadeMapFile(path, oneDimensional);
        } catch (const InputFileError& error) {
            return error.what();
        }
        return "accepted";
    };
    EXPECT_EQ(refusal(missing, false), "--shademap: '" + missing + "': file not found");
    EXPECT_EQ(refusal(square, true), "--shademap: '" + square + "' has 4 rows; a 1-D shade map must be a single row");
    std::ofstream(directory / "bad.png") << "not a PNG";
    EXPECT_EQ(refusal((directory / "bad.png").string(), false)
                  .rfind("--shademap: '" + (directory / "bad.png").string() + "': ", 0),
              0u)
        << refusal((directory / "bad.png").string(), false);
}

TEST_F(SceneShadeMaps, CelRefusesATwoDimensionalMapAndTakesAOneRowMap) {
    const std::string square = writeMap("square.png", 4, 8, {90, 90, 90, 255});
    const std::string row = writeMap("row.png", 1, 8, {90, 90, 90, 255});
    Scene scene;
    scene.meshes = {meshNaming("Spot", row), meshNaming("Suzanne", square, "Fur")};
    EXPECT_EQ(errorOf(scene, ShadingModel::Cel), "mesh 'Suzanne' (glTF material 'Fur') shade map: '" + square +
                                                     "' has 4 rows; a 1-D shade map must be a single row");
    // Comic takes both: a one-row map is a comic map whose specular axis has one texel.
    const std::vector<std::optional<ShadeMap>> maps = readSceneShadeMaps(scene, ShadingModel::Comic, nullptr);
    ASSERT_TRUE(maps[0] && maps[1]);
    EXPECT_EQ(maps[0]->texels.rows, 1);
    EXPECT_EQ(maps[1]->texels.rows, 4);
    scene.meshes.pop_back();
    EXPECT_EQ(readSceneShadeMaps(scene, ShadingModel::Cel, nullptr).at(0)->texels.rows, 1);
}

TEST_F(SceneShadeMaps, ModesWithoutMapsReadNothingAndWarn) {
    // The files do not even exist: nothing is read, so nothing fails.
    Scene scene;
    scene.meshes = {meshNaming("Spot", (directory / "a.png").string()), meshNaming("Teapot", ""),
                    meshNaming("Suzanne", (directory / "b.png").string())};
    for (ShadingModel mode :
         {ShadingModel::None, ShadingModel::Flat, ShadingModel::Gouraud, ShadingModel::Lambert, ShadingModel::Phong}) {
        std::vector<Warning> warnings;
        const std::vector<std::optional<ShadeMap>> maps = readSceneShadeMaps(scene, mode, &warnings);
        ASSERT_EQ(maps.size(), 3u);
        for (const std::optional<ShadeMap>& map : maps) EXPECT_FALSE(map);
        EXPECT_EQ(warnings, std::vector<Warning>{makeWarning(
                                WarningKind::ShadeMapUnused,
                                "2 meshes name shade maps, which only --shading cel, comic and auto use")})
            << traitsOf(mode).name;
    }
    std::vector<Warning> warnings;
    scene.meshes.pop_back();
    readSceneShadeMaps(scene, ShadingModel::Phong, &warnings);
    EXPECT_EQ(warnings, std::vector<Warning>{makeWarning(WarningKind::ShadeMapUnused,
                                                         "1 mesh names a shade map, which only --shading cel, comic "
                                                         "and auto use")});
    // No warnings list: nothing to say it to, still no error.
    EXPECT_EQ(readSceneShadeMaps(scene, ShadingModel::Lambert, nullptr).size(), 2u);
    // Nothing named, nothing said.
    warnings.clear();
    scene.meshes = {meshNaming("Teapot", "")};
    readSceneShadeMaps(scene, ShadingModel::Flat, &warnings);
    EXPECT_TRUE(warnings.empty());
}

} // namespace
} // namespace inkgraph
