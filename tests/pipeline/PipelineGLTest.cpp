// Golden test of stored intermediates: the whole command line renders a fixed scene with --dump, and every buffer the
// dump writes (every file its manifest.json names) is compared with tests/golden/<case>/ under a tolerance chosen per
// buffer (see tests/golden/README.md). A dumped buffer without a tolerance entry fails the test: a new G-buffer field
// or pass output cannot be written and never compared.
// Regenerate after an intended change with:
//   INKGRAPH_UPDATE_GOLDEN=1 ./build/tests/pipeline/pipeline_gl_tests
#include "render/ImageFiles.h"
#include "app/Cli.h"
#include "app/Render.h"
#include "tests/support/ImageCompare.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
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
    {"normal.exr", {1e-4, 2e-3, 0.005}},
    {"view.exr", {1e-4, 2e-3, 0.005}},
    {"w.exr", {1e-4, 2e-3, 0.005}},
    {"ndotv.exr", {1e-4, 2e-3, 0.005}},
    {"depth.exr", {1e-4, 2e-2, 0.005}},
    // radial = (n.(c - p), (J w).x, (J w).y, |w|^2), lengths in bounding radii and J w in pixels: values reach about
    // 110 in these scenes (J w near the silhouette), so max 1e-2 is the same 1e-4 of the largest value the [-1, 1]
    // fields get. A silhouette pixel flipping coverage changes by its whole value, on average 9.2 (spot) and 11.6
    // (teapot) per channel within a pixel of the coverage boundary: 0.5% of pixels doing so gives a mean of 0.058.
    {"radial.exr", {1e-2, 6e-2, 0.005}},
    // Material ids are whole numbers (id + 1, 0 off the model), exact on any driver; only a silhouette pixel flipping
    // coverage changes, by its id + 1 (1 in these one-material scenes), so 0.5% of pixels give a mean of 0.005.
    {"materialid.exr", {0.0, 1e-2, 0.005}},
    // Object ids likewise (issue 36): each of these files is one object, so a flipped silhouette pixel changes by 1.
    {"objectid.exr", {0.0, 1e-2, 0.005}},
    // The z-buffer is window depth in [0, 1] (reversed-Z: about 0.5 on these models), float32 of the same interpolated
    // position on any driver; a silhouette pixel flipping coverage changes by its whole value, 0.5% giving 2.5e-3.
    {"zbuffer.exr", {1e-6, 1e-2, 0.005}},
    // Mesh ids (issue 37) as the object ids: one mesh per file, so a flipped silhouette pixel changes by 1.
    {"meshid.exr", {0.0, 1e-2, 0.005}},
    // Triangle ids are whole numbers (global index + 1), exact on any driver; a flipped silhouette pixel changes by its
    // whole id, up to the triangle count (5856 spot, 6320 teapot), so 0.5% of pixels give a mean up to about 30. A tie
    // on an edge between two triangles would give the neighbour's id: on one Mesa version none flips.
    {"triangleid.exr", {0.0, 32.0, 0.005}},
    // Barycentric weights in [0, 1] (alpha coverage), interpolated as the other fields, so 1e-4; a flipped silhouette
    // pixel changes each of its four channels by up to 1, 0.5% of pixels giving a mean up to 5e-3.
    {"barycentric.exr", {1e-4, 5e-3, 0.005}},
    {"coverage.png", {0.0, 2.0, 0.005}},
    {"basecolor.png", {0.0, 2.0, 0.005}},
    {"shading.png", {1.0, 2.0, 0.005}},
    {"final.png", {1.0, 2.0, 0.005}},
    // The GL bands are 0 or 255: only rasterisation ties on a band's own border may flip (see below).
    {"band-outline.png", {0.0, 2.0, 0.01}},
    {"band-silhouette.png", {0.0, 2.0, 0.01}},
    // The line layers are the bands' middle lines stroked, anti-aliased: a flipped band pixel moves the middle line by
    // half a pixel there and the stroke's rim with it, within a pixel of the layer's border; elsewhere 8-bit rounding.
    {"lines-outline.png", {1.0, 2.0, 0.02}},
    {"lines-silhouette.png", {1.0, 2.0, 0.02}},
};

/** The buffers a dump wrote: every file its manifest.json names. */
std::set<std::string> dumpedBuffers(const fs::path& dumpDirectory) {
    std::ifstream file(dumpDirectory / "manifest.json");
    const nlohmann::json manifest = nlohmann::json::parse(file, nullptr, false);
    std::set<std::string> files;
    if (!manifest.is_object() || !manifest.contains("files") || !manifest["files"].is_array()) {
        ADD_FAILURE() << dumpDirectory / "manifest.json"
                      << " is missing or has no \"files\" list";
        return files;
    }
    for (const nlohmann::json& entry : manifest["files"]) files.insert(entry.at("file").get<std::string>());
    return files;
}

/** The regular files of a folder (a golden folder holds buffers only; a dump folder also its manifest.json). */
std::set<std::string> filesIn(const fs::path& folder) {
    std::set<std::string> files;
    if (!fs::is_directory(folder)) return files;
    for (const auto& entry : fs::directory_iterator(folder))
        if (entry.is_regular_file()) files.insert(entry.path().filename().string());
    return files;
}

std::string joined(const std::set<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
    return text.empty() ? "(none)" : text;
}

/** The names in `a` that are not in `b`. */
std::set<std::string> without(const std::set<std::string>& a, const std::set<std::string>& b) {
    std::set<std::string> rest;
    for (const std::string& name : a)
        if (!b.count(name)) rest.insert(name);
    return rest;
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

    // Every buffer the dump wrote, and nothing else beside the manifest; each needs a tolerance entry, even when
    // regenerating, so that a new buffer gets a stated tolerance before it gets a golden.
    const std::set<std::string> files = dumpedBuffers(dumpDirectory);
    ASSERT_FALSE(files.empty()) << "the dump wrote no buffers";
    std::set<std::string> expectedInDump = files;
    expectedInDump.insert("manifest.json");
    ASSERT_EQ(filesIn(dumpDirectory), expectedInDump) << "the dump folder holds files its manifest.json does not name";
    std::set<std::string> withTolerance;
    for (const auto& [file, tolerance] : kTolerances) withTolerance.insert(file);
    const std::set<std::string> untolerated = without(files, withTolerance);
    ASSERT_TRUE(untolerated.empty()) << "dumped buffers without a tolerance entry: " << joined(untolerated)
                                     << " (add one to kTolerances in tests/pipeline/PipelineGLTest.cpp with its "
                                        "reason, and to the table in tests/golden/README.md)";

    const fs::path goldenDirectory = test::sourceRoot() / "tests" / "golden" / golden.name;
    if (test::updatingGoldens()) {
        fs::create_directories(goldenDirectory);
        for (const std::string& file : files)
            fs::copy_file(dumpDirectory / file, goldenDirectory / file, fs::copy_options::overwrite_existing);
        GTEST_SKIP() << "goldens written to " << goldenDirectory << " (INKGRAPH_UPDATE_GOLDEN=1)";
    }
    // The same buffers, no more and no fewer.
    const std::set<std::string> goldenFiles = filesIn(goldenDirectory);
    ASSERT_EQ(files, goldenFiles) << "dumped but no golden: " << joined(without(files, goldenFiles))
                                  << "; golden but not dumped: " << joined(without(goldenFiles, files));
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
        GoldenCase{"spot",
                   {model("spot_c3d.obj"), "--size", "160x120", "--eye", "2.4,1.0,-1.6", "--target", "0,0.1,0", "--fov",
                    "35", "--light", "1,1,-0.5", "--shading", "lambert", "--lines", "none"}},
        // The teapot: open patches (back faces through holes), the auto-framed camera and the default light.
        GoldenCase{"teapot", {model("teapot_c3d.obj"), "--size", "128x128", "--shading", "lambert", "--lines", "none"}},
        // The default look: Qu, Chen & Zwicker's five cel bands, Lander's outline and the inflated hull (3 px, red).
        GoldenCase{"spot_cel_lines",
                   {model("spot_c3d.obj"), "--size", "160x120", "--eye", "2.4,1.0,-1.6", "--target", "0,0.1,0", "--fov",
                    "35", "--light", "1,1,-0.5", "--lines", "outline,silhouette", "--silhouette-width", "3",
                    "--silhouette-color", "1,0,0"}},
        // Specular comic with Winnemöller & Bangay 2002's CPU marking (after-vertices, constant view vector, rule 1).
        GoldenCase{"teapot_comic_after_vertices",
                   {model("teapot_c3d.obj"), "--size", "128x128", "--shading", "comic", "--shininess", "16",
                    "--view-vector", "constant", "--face-orientation", "after-vertices", "--front-rule", "1", "--lines",
                    "outline"}}),
    [](const ::testing::TestParamInfo<GoldenCase>& param) { return param.param.name; });

} // namespace
} // namespace inkgraph
