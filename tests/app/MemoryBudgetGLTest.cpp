// --memory-limit bounds the whole process (issue 16, item 9): through the real executable, the measured peak resident
// set (--stats peak_rss_mib) stays under the estimate (estimated_peak_mib) at several sizes and supersamplings, a
// limit just under the estimate is refused naming the flags that make the run that large, and one just over it runs
// and stays under it. Needs a GL context (llvmpipe in CI); the largest case is about 1.2 GB resident.
#include "CliTestSupport.h"
#include "passes/GpuScene.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::Cli;
using test::CliRun;
using test::readText;

/** The estimate bounds the program as built for users. Under AddressSanitizer the process also holds the sanitizer's
 *  shadow memory, redzones and quarantine (about 1.2-1.5x more here), so the sanitized suite checks every refusal and
 *  message but compares the measured peak only in the Release suite, which CI runs as well. */
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kPeakIsComparable = false;
#else
constexpr bool kPeakIsComparable = true;
#endif

class MemoryBudget : public Cli {
protected:
    struct Peak {
        double estimatedMib = 0.0;
        double measuredMib = 0.0;
        double meshesMib = 0.0;  ///< of the estimate: the model's meshes
        double derivedMib = 0.0; ///< of the estimate: what the passes derive from them
    };

    /** Renders with --stats and returns the estimate, its model's parts and the measured peak it reports. */
    Peak renderWithStats(const std::string& arguments) {
        const CliRun result = run("render " + arguments + " -o out.png --stats stats.json -q");
        EXPECT_EQ(result.exitCode, 0) << arguments << "\n" << result.err;
        if (result.exitCode != 0) return {};
        const auto stats = nlohmann::json::parse(readText(directory / "stats.json"));
        return {stats["estimated_peak_mib"].get<double>(), stats["peak_rss_mib"].get<double>(),
                stats["estimated_meshes_mib"].get<double>(), stats["estimated_derived_mib"].get<double>()};
    }

    /** The MiB the refusal says the run needs (what --memory-limit is checked against, rounded up), found by asking
     *  for the smallest limit. */
    int neededMib(const std::string& arguments) {
        const CliRun result = run("render " + arguments + " -o out.png --memory-limit 64");
        EXPECT_EQ(result.exitCode, 2) << result.err;
        std::smatch match;
        if (!std::regex_search(result.err, match, std::regex("needs? about ([0-9]+) MiB"))) {
            ADD_FAILURE() << "no 'need(s) about N MiB' in: " << result.err;
            return 0;
        }
        return std::stoi(match[1]);
    }
};

TEST_F(MemoryBudget, MeasuredPeakStaysUnderTheEstimateAtEverySupersampling) {
    const std::string spot = model("spot_c3d.obj");
    const std::string bunny = model("bunny_c3d_70k.obj");
    for (const std::string& arguments : {
             spot + " --size 256x256 --lines none",
             bunny + " --size 512x512 --lines outline,silhouette,contour,suggestive,crease",
             spot + " --size 512x512 --supersample 2 --lines contour --dump dump",
             bunny + " --size 256x256 --supersample 8 --lines suggestive",
             spot + " --size 1024x1024 --supersample 4 --lines contour,suggestive",
             // The forward shading's multisampled target is kept to the still's end: it was counted only at the
             // post stage's largest moment, and this still peaked 20 MiB above its estimate (277 against 257 MiB).
             model("characters/expressions-binary-overrides.vrm") + " --size 1536x1536 --msaa 4 --shading mtoon",
         }) {
        const Peak peak = renderWithStats(arguments);
        EXPECT_GT(peak.measuredMib, 50.0) << arguments; // the process itself: a real measurement, not zero
        if (!kPeakIsComparable) continue;
        EXPECT_LE(peak.measuredMib, peak.estimatedMib) << arguments;
        // A bound, not a wild guess: within 1.6 x of what was measured (docs/batch.md has the whole table).
        EXPECT_LE(peak.estimatedMib, 1.6 * peak.measuredMib) << arguments;
    }
}

/** Writes a rippled grid of `cells` x `cells` squares (2 cells^2 triangles) as OBJ: a large scan-like mesh. */
void writeRippledGrid(const std::filesystem::path& path, int cells) {
    std::ofstream out(path);
    for (int row = 0; row <= cells; ++row)
        for (int column = 0; column <= cells; ++column) {
            const double x = double(column) / cells, y = double(row) / cells;
            out << "v " << x << ' ' << y << ' ' << 0.05 * std::sin(12.0 * x) * std::cos(9.0 * y) << '\n';
        }
    for (int row = 0; row < cells; ++row)
        for (int column = 0; column < cells; ++column) {
            const int corner = row * (cells + 1) + column + 1; // OBJ counts from 1
            out << "f " << corner << ' ' << corner + 1 << ' ' << corner + cells + 2 << '\n'
                << "f " << corner << ' ' << corner + cells + 2 << ' ' << corner + cells + 1 << '\n';
        }
}

TEST_F(MemoryBudget, ALargeMeshIsEstimatedByWhatItsLineTypesDerive) {
    // A 300k-triangle mesh: the estimate charged 1024 bytes a triangle whatever the lines (every line type's data),
    // so at the default lines it was 2.2 times the measured peak, and a 2-million-triangle grid 6.5 times. Now the
    // meshes cost the same in every look and the data the passes derive (edge adjacency, curvature) is charged only
    // when they run.
    const std::filesystem::path grid = directory / "grid.obj";
    writeRippledGrid(grid, 388);
    const std::string model = grid.string() + " --size 256x256";
    std::vector<Peak> peaks;
    for (const std::string& lines : {"none", "silhouette,contour", "crease"}) {
        const Peak peak = peaks.emplace_back(renderWithStats(model + " --lines " + lines));
        EXPECT_GT(peak.measuredMib, 50.0) << lines;
        if (!kPeakIsComparable) continue;
        EXPECT_LE(peak.measuredMib, peak.estimatedMib) << lines;
        EXPECT_LE(peak.estimatedMib, 1.6 * peak.measuredMib) << lines;
    }
    // --stats parts the model's share: its meshes, the same in every look, and what the passes derive, only when they
    // run (the default lines' hull normals, crease's edge adjacency).
    ASSERT_EQ(peaks.size(), 3u);
    EXPECT_GT(peaks[0].meshesMib, 0.0);
    EXPECT_EQ(peaks[1].meshesMib, peaks[0].meshesMib);
    EXPECT_EQ(peaks[2].meshesMib, peaks[0].meshesMib);
    EXPECT_EQ(peaks[0].derivedMib, 0.0);
    EXPECT_GT(peaks[1].derivedMib, 0.0);
    EXPECT_NEAR(peaks[2].derivedMib,
                2.0 * 388 * 388 * double(SceneImport::bytesPerTriangle(SceneImport::kEdgeAdjacency)) / 1048576.0, 1e-9);
    EXPECT_GT(neededMib(model + " --lines crease"), neededMib(model + " --lines none") + 30);
}

TEST_F(MemoryBudget, LimitJustUnderTheEstimateIsRefusedNamingEveryFlagAndJustOverItHolds) {
    const std::string arguments = model("spot_c3d.obj") + " --size 512x512 --supersample 4 --lines contour,suggestive";
    const int needed = neededMib(arguments);
    ASSERT_GT(needed, 64);

    const CliRun under = run("render " + arguments + " -o out.png --memory-limit " + std::to_string(needed - 1));
    EXPECT_EQ(under.exitCode, 2) << under.err;
    for (const char* part : {"--size 512x512", "--supersample 4", "--lines contour,suggestive work at 2048x2048",
                             "needs about ", "(--memory-limit)"})
        EXPECT_NE(under.err.find(part), std::string::npos) << part << " not in: " << under.err;
    EXPECT_FALSE(std::filesystem::exists(directory / "out.png"));

    const Peak peak = renderWithStats(arguments + " --memory-limit " + std::to_string(needed));
    if (kPeakIsComparable) {
        EXPECT_LE(peak.measuredMib, double(needed));
    }
}

TEST_F(MemoryBudget, ALargeModelAtASmallSizeIsToldAsTheModelsNeed) {
    // The bunny at 64x64: its triangles are most of the estimate, which said "--size 64x64 needs about N MiB" and
    // advised a smaller image.
    const std::string arguments = model("bunny_c3d_70k.obj") + " --size 64x64";
    const int needed = neededMib(arguments);
    const CliRun under = run("render " + arguments + " -o out.png --memory-limit " + std::to_string(needed - 1));
    EXPECT_EQ(under.exitCode, 2) << under.err;
    EXPECT_TRUE(std::regex_search(under.err, std::regex("the model's [0-9]+ triangles and [0-9]+ vertices at --size "
                                                        "64x64 need about [0-9]+ MiB")))
        << under.err;
    EXPECT_NE(under.err.find("a model this large needs a higher limit"), std::string::npos) << under.err;
    EXPECT_EQ(under.err.find("make the image smaller"), std::string::npos) << under.err;
}

TEST_F(MemoryBudget, ABatchStoppedByTheLimitNamesTheStillItStoppedAt) {
    // What a still needs depends on its model: a batch refused at one of its stills says which (it said only
    // "--size ... needs about N MiB", and with --draw-threads several such lines, none naming its model).
    const std::string size = " --size 512x512 --supersample 2";
    const std::string spot = model("spot_c3d.obj"), bunny = model("bunny_c3d_70k.obj");
    const int spotNeeds = neededMib(spot + size), bunnyNeeds = neededMib(bunny + size);
    ASSERT_LT(spotNeeds, bunnyNeeds);
    for (const char* threads : {"1", "2"}) {
        const CliRun result = run("render " + spot + " " + bunny + size + " -o 'o{index}.png' -q --memory-limit " +
                                  std::to_string(spotNeeds) + " --draw-threads " + threads);
        EXPECT_EQ(result.exitCode, 2) << result.err;
        EXPECT_TRUE(std::regex_search(
            result.err,
            std::regex("inkgraph: \\[2/2\\] '[^']*/bunny_c3d_70k.obj': (the model's .* at )?--size 512x512 with")))
            << result.err;
        EXPECT_EQ(result.err.find("[1/2]"), std::string::npos) << "the first still fits: " << result.err;
        EXPECT_TRUE(std::filesystem::exists(directory / "o1.png")) << "the still before it is kept";
    }
}

TEST_F(MemoryBudget, ABatchDrawnOnSeveralThreadsStaysUnderItsOneLimit) {
    // Six 1024^2 bunnies at --supersample 2, each still estimated at 465 MiB: under a limit of 700 two cannot draw at
    // once. Four drawing threads used to keep each its own stills within a quarter of the limit but draw a still
    // above that share alone, all four at once: 1,107 MiB resident for four such stills. They now share the limit
    // (app/MemoryLedger.h): the stills wait for each other, the waiting threads give back their textures, and the
    // pictures are those of one thread.
    const std::string bunny = model("bunny_c3d_70k.obj");
    std::string list;
    for (int still = 0; still < 6; ++still) list += bunny + " ";
    const std::string arguments =
        "render " + list +
        "--size 1024x1024 --supersample 2 --shading cel --lines silhouette,contour,suggestive --memory-limit 700 -q ";
    const CliRun one = run(arguments + "-o 'one-{index}.png' --draw-threads 1");
    ASSERT_EQ(one.exitCode, 0) << one.err;
    const CliRun four = run(arguments + "-o 'four-{index}.png' --draw-threads 4");
    ASSERT_EQ(four.exitCode, 0) << four.err;
    for (int still = 1; still <= 6; ++still) {
        const std::string index = std::to_string(still);
        EXPECT_EQ(readText(directory / ("four-" + index + ".png")), readText(directory / ("one-" + index + ".png")))
            << "still " << index;
    }
    EXPECT_GT(four.peakMib, 50.0);
    if (kPeakIsComparable) {
        EXPECT_LE(one.peakMib, 700.0);
        EXPECT_LE(four.peakMib, 700.0);
    }
}

TEST_F(MemoryBudget, IssueCaseIsRefusedRatherThanOutgrowingItsLimit) {
    // Accepted before (the plan's textures alone were 525 MiB) and peaked at 1622 MB resident.
    const CliRun result = run("render " + model("bunny_c3d_70k.obj") +
                              " -o out.png --size 1024x1024 --supersample 8 --lines contour --memory-limit 600");
    EXPECT_EQ(result.exitCode, 2) << result.err;
    for (const char* part : {"--size 1024x1024 with --supersample 8 (--lines contour works at 8192x8192)",
                             "the memory limit is 600 MiB (--memory-limit)"})
        EXPECT_NE(result.err.find(part), std::string::npos) << part << " not in: " << result.err;
}

TEST_F(MemoryBudget, OneBufferOver2GiBNamesSupersampleWhenItIsTheCause) {
    const CliRun result =
        // 2047 rows: no whole divisor, so the suggestive contours read the picture's own G-buffer (SuggestiveLines.h).
        run("render " + model("spot_c3d.obj") + " -o out.png --size 2047x2047 --supersample 8 --lines suggestive");
    EXPECT_EQ(result.exitCode, 2) << result.err;
    EXPECT_NE(result.err.find("--size 2047x2047 with --supersample 8 (16376x16376) makes 'gbuffer.radial' 4096 MiB"),
              std::string::npos)
        << result.err;
}

} // namespace
} // namespace inkgraph
