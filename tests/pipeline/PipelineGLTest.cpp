// Golden test of stored intermediates: the whole command line renders a fixed scene with --dump, and every dumped
// buffer is compared with tests/golden/<case>/ under a tolerance chosen per buffer (see tests/golden/README.md).
// Regenerate after an intended change with:
//   INKGRAPH_UPDATE_GOLDEN=1 ./build/tests/pipeline/pipeline_gl_tests
#include "app/ImageFiles.h"
#include "app/Render.h"
#include "tests/support/ImageCompare.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>

namespace inkgraph {
namespace {

namespace fs = std::filesystem;

struct GoldenCase {
    std::string name;
    std::vector<std::string> arguments; ///< after "inkgraph render"
};

void PrintTo(const GoldenCase& golden, std::ostream* stream) { *stream << golden.name; }

// Float buffers: llvmpipe is deterministic on one machine, but interpolation may round differently across Mesa
// versions by a few ulps, hence 1e-4 on values within [-1, 1] (and depth about 3); a pixel on the silhouette can flip
// coverage on a rasterisation tie, hence up to 0.5% outliers, all within a pixel of the silhouette. 8-bit images: one
// code of rounding.
const std::map<std::string, test::ImageTolerance> kTolerances = {
    {"normal.exr", {1e-4, 2e-3, 0.005}},   {"view.exr", {1e-4, 2e-3, 0.005}}, {"w.exr", {1e-4, 2e-3, 0.005}},
    {"ndotv.exr", {1e-4, 2e-3, 0.005}},    {"depth.exr", {1e-4, 2e-2, 0.005}},
    {"coverage.png", {0.0, 2.0, 0.005}},   {"basecolor.png", {0.0, 2.0, 0.005}},
    {"shading.png", {1.0, 2.0, 0.005}},    {"final.png", {1.0, 2.0, 0.005}},
    // Line masks are 0 or 255: only rasterisation ties on a line's own border may flip (see below).
    {"lines-outline.png", {0.0, 2.0, 0.01}}, {"lines-silhouette.png", {0.0, 2.0, 0.01}},
};

/** The dumped files a golden covers: every file with a tolerance. */
std::set<std::string> comparedFiles(const fs::path& folder) {
    std::set<std::string> files;
    for (const auto& entry : fs::directory_iterator(folder))
        if (kTolerances.count(entry.path().filename().string())) files.insert(entry.path().filename().string());
    return files;
}

class PipelineGolden : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(PipelineGolden, StoredIntermediatesMatch) {
    const GoldenCase& golden = GetParam();
    const fs::path outputDirectory = test::testOutputDirectory("PipelineGolden." + golden.name);
    fs::remove_all(outputDirectory);
    const fs::path dumpDirectory = outputDirectory / "dump";

    std::vector<std::string> arguments = {"inkgraph", "render"};
    arguments.insert(arguments.end(), golden.arguments.begin(), golden.arguments.end());
    arguments.insert(arguments.end(), {"--dump", dumpDirectory.string(), "--request", "gbuffer.*", "-q"});
    std::vector<const char*> argv;
    for (const std::string& argument : arguments) argv.push_back(argument.c_str());
    std::ostringstream out, err;
    ASSERT_EQ(runCommandLine(int(argv.size()), argv.data(), out, err), kExitOk) << err.str();

    const fs::path goldenDirectory = test::sourceRoot() / "tests" / "golden" / golden.name;
    if (test::updatingGoldens()) {
        fs::create_directories(goldenDirectory);
        for (const std::string& file : comparedFiles(dumpDirectory))
            fs::copy_file(dumpDirectory / file, goldenDirectory / file, fs::copy_options::overwrite_existing);
        GTEST_SKIP() << "goldens written to " << goldenDirectory << " (INKGRAPH_UPDATE_GOLDEN=1)";
    }
    // The same buffers, no more and no fewer.
    const std::set<std::string> files = comparedFiles(goldenDirectory);
    ASSERT_EQ(comparedFiles(dumpDirectory), files);
    // Outliers may only sit within a pixel of the golden's coverage boundary or of a line mask's border: where a
    // rasterisation tie can flip a pixel.
    cv::Mat tieZone = test::coverageEdges(readImage(goldenDirectory / "coverage.png"));
    for (const std::string& file : files)
        if (file.rfind("lines-", 0) == 0) tieZone |= test::coverageEdges(readImage(goldenDirectory / file));
    for (const std::string& file : files)
        EXPECT_TRUE(test::imagesNear(readImage(dumpDirectory / file), readImage(goldenDirectory / file),
                                     kTolerances.at(file), "PipelineGolden." + golden.name, file, tieZone));
}

std::string model(const std::string& name) { return (test::sourceRoot() / "models" / name).string(); }

INSTANTIATE_TEST_SUITE_P(
    Models, PipelineGolden,
    ::testing::Values(
        // Spot from a fixed three-quarter view: smooth closed surface, computed normals, auto near/far.
        GoldenCase{"spot", {model("spot_c3d.obj"), "--size", "160x120", "--eye", "2.4,1.0,-1.6",
                            "--target", "0,0.1,0", "--fov", "35", "--light", "1,1,-0.5", "--shading", "lambert"}},
        // The teapot: open patches (back faces through holes), the auto-framed camera and the default light.
        GoldenCase{"teapot", {model("teapot_c3d.obj"), "--size", "128x128", "--shading", "lambert"}},
        // The default look: Qu, Chen & Zwicker's five cel bands, Lander's outline and the inflated hull (3 px, red).
        GoldenCase{"spot_cel_lines",
                   {model("spot_c3d.obj"), "--size", "160x120", "--eye", "2.4,1.0,-1.6", "--target", "0,0.1,0",
                    "--fov", "35", "--light", "1,1,-0.5", "--lines", "outline,silhouette", "--silhouette-width", "3",
                    "--silhouette-color", "1,0,0"}},
        // Specular comic with Winnemöller & Bangay 2002's CPU marking (after-vertices, constant view vector, rule 1).
        GoldenCase{"teapot_comic_after_vertices",
                   {model("teapot_c3d.obj"), "--size", "128x128", "--shading", "comic", "--shininess", "16",
                    "--view-vector", "constant", "--face-orientation", "after-vertices", "--front-rule", "1",
                    "--lines", "outline"}}),
    [](const ::testing::TestParamInfo<GoldenCase>& param) { return param.param.name; });

} // namespace
} // namespace inkgraph
