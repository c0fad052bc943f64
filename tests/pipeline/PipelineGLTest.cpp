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
};

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
        for (const auto& [file, tolerance] : kTolerances) fs::copy_file(dumpDirectory / file, goldenDirectory / file,
                                                                        fs::copy_options::overwrite_existing);
        GTEST_SKIP() << "goldens written to " << goldenDirectory << " (INKGRAPH_UPDATE_GOLDEN=1)";
    }
    // Outliers may only sit on the silhouette, within a pixel of the golden's coverage boundary.
    const cv::Mat silhouette = test::coverageEdges(readImage(goldenDirectory / "coverage.png"));
    for (const auto& [file, tolerance] : kTolerances) {
        ASSERT_TRUE(fs::exists(dumpDirectory / file)) << file << " was not dumped";
        ASSERT_TRUE(fs::exists(goldenDirectory / file)) << "missing golden " << (goldenDirectory / file);
        EXPECT_TRUE(test::imagesNear(readImage(dumpDirectory / file), readImage(goldenDirectory / file), tolerance,
                                     "PipelineGolden." + golden.name, file, silhouette));
    }
}

std::string model(const std::string& name) { return (test::sourceRoot() / "models" / name).string(); }

INSTANTIATE_TEST_SUITE_P(
    Models, PipelineGolden,
    ::testing::Values(
        // Spot from a fixed three-quarter view: smooth closed surface, computed normals, auto near/far.
        GoldenCase{"spot", {model("spot_c3d.obj"), "--size", "160x120", "--eye", "2.4,1.0,-1.6",
                            "--target", "0,0.1,0", "--fov", "35", "--light", "1,1,-0.5"}},
        // The teapot: open patches (back faces through holes), the auto-framed camera and the default light.
        GoldenCase{"teapot", {model("teapot_c3d.obj"), "--size", "128x128"}}),
    [](const ::testing::TestParamInfo<GoldenCase>& param) { return param.param.name; });

} // namespace
} // namespace inkgraph
