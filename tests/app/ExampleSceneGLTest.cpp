// examples/still-life/still-life.gltf through the real `inkgraph` executable: the file's camera and light are used,
// each material's shade map reaches the shading (--stats), and maps that do not fit the mode are reported naming the
// mesh, its material and the file. Needs a GL context (llvmpipe in CI).
#include "render/ImageFiles.h"
#include "CliTestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

namespace inkgraph {
namespace {

using test::Cli;
using test::CliRun;
using test::readText;
namespace fs = std::filesystem;

std::string stillLife() {
    return test::shellQuoted(fs::path(INKGRAPH_SOURCE_ROOT) / "examples" / "still-life" / "still-life.gltf");
}

TEST_F(Cli, StillLifeUsesItsCameraLightAndAShadeMapPerMaterial) {
    const CliRun result =
        run("render " + stillLife() + " --shading comic --lines outline --size 160x100 -o s.png --stats s.json -q");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const auto stats = nlohmann::json::parse(readText(directory / "s.json"));
    EXPECT_EQ(stats["camera_source"], "gltf");
    EXPECT_EQ(stats["scene"]["meshes"], 4);
    const auto& maps = stats["look"]["mesh_shademaps"];
    ASSERT_EQ(maps.size(), 4u);
    const std::vector<std::pair<std::string, std::string>> expected = {{"Spot", "duotone-warm.png"},
                                                                       {"Teapot", "metallic.png"},
                                                                       {"Suzanne", "duotone-cool.png"},
                                                                       {"Torus knot", "three-bands.png"}};
    for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(maps[i]["mesh"], expected[i].first);
        EXPECT_EQ(fs::path(maps[i]["shademap"].get<std::string>()).filename(), expected[i].second);
    }

    // Shading without maps reads none of them, and says so.
    const CliRun plain = run("render " + stillLife() + " --shading phong --size 160x100 -o p.png");
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    EXPECT_NE(plain.err.find("4 meshes name shade maps, which only --shading cel, comic and auto use"),
              std::string::npos)
        << plain.err;
}

TEST_F(Cli, AMaterialShadeMapThatDoesNotFitTheModeNamesMeshMaterialAndFile) {
    const CliRun result = run("render " + stillLife() + " --shading cel --size 64x40 -o c.png");
    EXPECT_EQ(result.exitCode, 3) << result.err;
    EXPECT_NE(result.err.find("mesh 'Spot' (glTF material 'Spot material') shade map:"), std::string::npos)
        << result.err;
    EXPECT_NE(result.err.find("duotone-warm.png' has 64 rows"), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(directory / "c.png"));
}

} // namespace
} // namespace inkgraph
