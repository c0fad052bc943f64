// A batch run by the real `inkgraph` executable: several models in one process give the same pictures as one
// process each, make one GL context and compile each program once, report a line per model, and keep going past
// a bad model. Needs a GL context (llvmpipe in CI).
#include "render/ImageFiles.h"
#include "CliTestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::Cli;
using test::CliRun;
using test::readText;
namespace fs = std::filesystem;

/** The look of every still here; batches run without -q, as their progress lines are checked. */
const std::string kLook = " --size 96x80 --shading comic --lines outline,contour,crease";

bool sameImage(const fs::path& a, const fs::path& b) {
    const cv::Mat left = readImage(a);
    const cv::Mat right = readImage(b);
    return left.size() == right.size() && left.type() == right.type() && cv::norm(left, right, cv::NORM_INF) == 0.0;
}

TEST_F(Cli, BatchMatchesOneProcessPerModelAndCompilesEachProgramOnce) {
    const CliRun batch = run("render " + model("spot_c3d.obj") + " " + model("teapot_c3d.obj") + " " +
                             model("fandisk_c3d.obj") + " -o 'batch-{index}-{name}.png' --stats '{name}.json'" + kLook);
    ASSERT_EQ(batch.exitCode, 0) << batch.err;
    for (const char* name : {"spot_c3d", "teapot_c3d", "fandisk_c3d"}) {
        const CliRun single =
            run("render " + model(std::string(name) + ".obj") + " -o single-" + name + ".png -q" + kLook);
        ASSERT_EQ(single.exitCode, 0) << single.err;
    }
    // Bit-identical: a kept program's uniforms and the context's state carry nothing from one still to the next.
    EXPECT_TRUE(sameImage(directory / "batch-1-spot_c3d.png", directory / "single-spot_c3d.png"));
    EXPECT_TRUE(sameImage(directory / "batch-2-teapot_c3d.png", directory / "single-teapot_c3d.png"));
    EXPECT_TRUE(sameImage(directory / "batch-3-fandisk_c3d.png", directory / "single-fandisk_c3d.png"));

    const auto first = nlohmann::json::parse(readText(directory / "spot_c3d.json"));
    EXPECT_FALSE(first["context_reused"].get<bool>());
    EXPECT_GT(first["context_ms"].get<double>(), 0.0);
    const int compiled = first["programs_compiled"].get<int>();
    EXPECT_EQ(compiled, 6); // gbuffer, shade, outline (two), mesh edges (two); the contour is a CPU pass
    EXPECT_EQ(first["programs_reused"].get<int>(), 0);
    EXPECT_EQ(first["batch"]["position"].get<int>(), 1);
    EXPECT_EQ(first["batch"]["list_length"].get<int>(), 3);
    for (const char* name : {"teapot_c3d", "fandisk_c3d"}) {
        const auto later = nlohmann::json::parse(readText(directory / (std::string(name) + ".json")));
        EXPECT_TRUE(later["context_reused"].get<bool>()) << name;
        EXPECT_EQ(later["context_ms"].get<double>(), 0.0) << name;
        EXPECT_EQ(later["programs_compiled"].get<int>(), 0) << name;
        EXPECT_EQ(later["programs_reused"].get<int>(), compiled) << name;
    }

    // One line per model, in order, with its output, then the summary.
    const std::size_t one = batch.err.find("[1/3] " + model("spot_c3d.obj") +
                                           " -> 'batch-1-spot_c3d.png': 5856 "
                                           "triangles");
    const std::size_t two = batch.err.find("[2/3] " + model("teapot_c3d.obj") + " -> 'batch-2-teapot_c3d.png'");
    const std::size_t three = batch.err.find("[3/3] " + model("fandisk_c3d.obj"));
    ASSERT_NE(one, std::string::npos) << batch.err;
    ASSERT_NE(two, std::string::npos) << batch.err;
    ASSERT_NE(three, std::string::npos) << batch.err;
    EXPECT_LT(one, two);
    EXPECT_LT(two, three);
    EXPECT_NE(batch.err.find("rendered 3 of 3 models in"), std::string::npos) << batch.err;
    EXPECT_EQ(batch.err.find("loaded '"), std::string::npos) << "a batch prints one line per model: " << batch.err;
}

TEST_F(Cli, AStillDoesNotSeeWhatTheStillBeforeItLeftOffItsModel) {
    // The G-buffer leaves the fields read only where the model covers the frame (n.v, the normal, the radial field:
    // ReadExtent::CoveredPixels) uncleared, and a batch's textures are pooled: off the bunny's surface they hold the
    // values of the torus knot, which close up covers nearly all of the frame before it. Every line type reading such
    // a field, on the CPU and as a compute shader, must draw the same bunny as a process of its own.
    const std::string look =
        " --size 128x128 --orbit 0,0,x0.3 --shading cel --lines silhouette,contour,suggestive,normal-edge -q";
    // The share of paper (white: the first three channels at 255) in a picture.
    const auto paperShare = [](const cv::Mat& picture) {
        std::vector<cv::Mat> channels;
        cv::split(picture, channels);
        cv::Mat white = channels[0] == 255;
        for (int c = 1; c < std::min(3, picture.channels()); ++c) white &= channels[std::size_t(c)] == 255;
        return double(cv::countNonZero(white)) / double(picture.total());
    };
    for (const char* postStage : {"cpu", "gpu"}) {
        const std::string device = std::string(" --post-stage ") + postStage;
        const CliRun batch = run("render " + model("torusknot_open3d.obj") + " " + model("bunny_c3d_70k.obj") +
                                 " -o 'after-{index}.png'" + look + device);
        ASSERT_EQ(batch.exitCode, 0) << postStage << ": " << batch.err;
        const CliRun alone = run("render " + model("bunny_c3d_70k.obj") + " -o alone.png" + look + device);
        ASSERT_EQ(alone.exitCode, 0) << postStage << ": " << alone.err;
        EXPECT_TRUE(sameImage(directory / "after-2.png", directory / "alone.png")) << postStage;
        // The knot leaves little paper and the bunny some: the test has something to find.
        EXPECT_LT(paperShare(readImage(directory / "after-1.png")), 0.03) << postStage;
        EXPECT_GT(paperShare(readImage(directory / "alone.png")), 0.1) << postStage;
    }
}

TEST_F(Cli, AStillAfterOneOfTheSameModelTakesItsLoadAndDrawsTheSame) {
    // app/RecentModel.h: a model listed twice in a row, and the views of --views, are read once. A model with a
    // warning, so each still tells it as if it had read the file.
    std::ofstream(directory / "warns.obj") << "mtllib missing.mtl\n"
                                           << readText(fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "spot_c3d.obj");
    const std::string spot = model("spot_c3d.obj");
    for (const char* jobs : {"0", "2"}) {
        const std::string out = std::string("jobs") + jobs;
        const CliRun batch = run("render warns.obj warns.obj " + spot + " warns.obj -o '" + out +
                                 "-{index}.png' --stats '" + out + "-{index}.json' --jobs " + jobs + kLook);
        ASSERT_EQ(batch.exitCode, 0) << batch.err;
        const auto reused = [&](int index) {
            const auto stats =
                nlohmann::json::parse(readText(directory / (out + "-" + std::to_string(index) + ".json")));
            EXPECT_EQ(stats["load_ms"].get<double>() == 0.0, stats["model_reused"].get<bool>()) << index;
            return stats["model_reused"].get<bool>();
        };
        EXPECT_FALSE(reused(1)) << jobs;
        EXPECT_TRUE(reused(2)) << jobs;
        EXPECT_FALSE(reused(3)) << jobs;
        EXPECT_FALSE(reused(4)) << jobs << ": another model came between";
        EXPECT_TRUE(sameImage(directory / (out + "-1.png"), directory / (out + "-2.png"))) << jobs;
        EXPECT_TRUE(sameImage(directory / (out + "-1.png"), directory / (out + "-4.png"))) << jobs;
        // Each still of warns.obj tells the warning before its own line.
        std::size_t from = 0;
        for (const char* still : {"[1/4]", "[2/4]", "[4/4]"}) {
            const std::size_t warning = batch.err.find("warning: 'warns.obj': mtllib 'missing.mtl'", from);
            const std::size_t line = batch.err.find(still, from);
            ASSERT_NE(line, std::string::npos) << batch.err;
            EXPECT_LT(warning, line) << still << ": " << batch.err;
            from = line + 1;
        }
    }

    // What the lines derive from the mesh goes with it (the object-space suggestive contours' curvature): the first
    // still of the model derives it, the next takes it and draws the same.
    const std::string objectLines = " --size 96x80 --shading comic --lines contour,suggestive-object -q";
    const CliRun twice =
        run("render " + spot + " " + spot + " -o 'object-{index}.png' --stats 'object-{index}.json'" + objectLines);
    ASSERT_EQ(twice.exitCode, 0) << twice.err;
    EXPECT_TRUE(sameImage(directory / "object-1.png", directory / "object-2.png"));
    EXPECT_GT(cv::countNonZero(readImage(directory / "object-1.png").reshape(1) != 255), 50) << "lines to compare";
    const auto curvatureDerived = [&](const std::string& stats) {
        const auto parsed = nlohmann::json::parse(readText(directory / stats));
        for (const auto& layer : parsed["post_stage"]["lines"])
            if (layer["type"] == "suggestive-object") return layer["curvature_derived"].get<bool>();
        ADD_FAILURE() << stats << " has no suggestive-object layer";
        return false;
    };
    EXPECT_TRUE(curvatureDerived("object-1.json"));
    EXPECT_FALSE(curvatureDerived("object-2.json"));

    // The views of one model: the first reads it, the others take it and what it derived.
    const CliRun views =
        run("render " + spot + " --views 3 -o 'view-{view}.png' --stats 'view-{view}.json'" + objectLines);
    ASSERT_EQ(views.exitCode, 0) << views.err;
    for (const char* view : {"0", "1", "2"}) {
        const std::string stats = "view-" + std::string(view) + ".json";
        const bool first = std::string(view) == "0";
        EXPECT_EQ(nlohmann::json::parse(readText(directory / stats))["model_reused"].get<bool>(), !first) << view;
        EXPECT_EQ(curvatureDerived(stats), first) << view;
    }
}

TEST_F(Cli, BatchGoesOnPastABadModelAndExitsWithItsCode) {
    std::ofstream(directory / "broken.obj") << "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n";
    const fs::path models = fs::path(INKGRAPH_SOURCE_ROOT) / "models";
    std::ofstream(directory / "models.txt") << "# a list\n"
                                            << (models / "spot_c3d.obj").string() << "\nbroken.obj\n\n"
                                            << (models / "cow_c3d.obj").string() << "\n";
    const CliRun result = run("render --list models.txt -o '{name}.png'" + kLook);
    EXPECT_EQ(result.exitCode, 3) << result.err;
    EXPECT_TRUE(fs::exists(directory / "spot_c3d.png"));
    EXPECT_TRUE(fs::exists(directory / "cow_c3d.png")) << "the model after the bad one was rendered";
    EXPECT_FALSE(fs::exists(directory / "broken.png"));
    EXPECT_NE(result.err.find("[2/3] 'broken.obj' failed: loadScene(): 'broken.obj' line 3"), std::string::npos)
        << result.err;
    EXPECT_NE(result.err.find("rendered 2 of 3 models in"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("1 failed: 'broken.obj'"), std::string::npos) << result.err;
}

TEST_F(Cli, TheSummaryNamesTheFirstTenFailedStillsAndCountsTheRest) {
    // A folder of broken files fails by the thousand: the summary stays one short line, as each failure has its own.
    std::ofstream list(directory / "models.txt");
    for (int i = 1; i <= 13; ++i) {
        const std::string name = "broken-" + std::string(i < 10 ? "0" : "") + std::to_string(i) + ".obj";
        std::ofstream(directory / name) << "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n";
        list << name << "\n";
    }
    list.close();
    const CliRun result = run("render --list models.txt -o '{name}.png'" + kLook);
    EXPECT_EQ(result.exitCode, 3) << result.err;
    EXPECT_NE(result.err.find("[13/13] 'broken-13.obj' failed: loadScene()"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("rendered 0 of 13 models in"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("; 13 failed: 'broken-01.obj', 'broken-02.obj', 'broken-03.obj', 'broken-04.obj', "
                              "'broken-05.obj', 'broken-06.obj', 'broken-07.obj', 'broken-08.obj', 'broken-09.obj', "
                              "'broken-10.obj' and 3 more (named above)\n"),
              std::string::npos)
        << result.err;
    EXPECT_EQ(result.err.find("'broken-11.obj' and"), std::string::npos) << result.err;
}

TEST_F(Cli, AFileNamesLineBreaksAndTabsStayOnTheLinesNamingIt) {
    // Scripts read the progress lines one line per still: a line break in a model's or an output's name split them.
    const std::string good = "tri\tan\ngle";
    const std::string bad = "bro\nken";
    std::ofstream(directory / (good + ".obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(directory / (bad + ".obj")) << "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n";
    const CliRun result = run("render " + test::shellQuoted(good + ".obj") + " " + test::shellQuoted(bad + ".obj") +
                              " -o 'out-{name}.png' --size 32x32 --lines contour");
    EXPECT_EQ(result.exitCode, 3) << result.err;
    EXPECT_TRUE(fs::exists(directory / ("out-" + good + ".png"))) << "the file keeps its name";
    for (const std::string expected :
         {"inkgraph: [1/2] 'tri\\x09an\\x0agle.obj' -> 'out-tri\\x09an\\x0agle.png': 1 triangles",
          "inkgraph: [2/2] 'bro\\x0aken.obj' failed: loadScene(): 'bro\\x0aken.obj' line 3",
          "; 1 failed: 'bro\\x0aken.obj'"})
        EXPECT_NE(result.err.find(expected), std::string::npos) << expected << " in\n" << result.err;
    std::istringstream lines(result.err);
    for (std::string line; std::getline(lines, line);)
        EXPECT_EQ(line.rfind("inkgraph", 0), 0u) << "a line that is not the program's own: " << line;
}

TEST_F(Cli, ABatchStoppedByALaterStillKeepsTheStillsBeforeIt) {
    // Each still's picture is encoded while the next renders and is committed after it (app/Render.h): a later still
    // that stops the batch (a usage error, not bad input) must not take the earlier still's outputs with it.
    // --eye 0,0,0 is the second model's centre, where its target is (a usage error at that still alone).
    const std::string tetrahedron = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    const std::string centred = "v -1 -1 -1\nv 1 -1 -1\nv 0 1 -1\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    // With two drawing threads the second still fails on its own thread, and waits for the first one's commit.
    for (const char* threads : {"1", "2"}) {
        SCOPED_TRACE(std::string("--draw-threads ") + threads);
        fs::remove_all(directory);
        fs::create_directories(directory);
        std::ofstream(directory / "named.obj") << tetrahedron;
        std::ofstream(directory / "unnamed.obj") << centred;
        const CliRun result = run("render named.obj unnamed.obj -o '{name}.png' --stats '{name}.json' --eye 0,0,0 "
                                  "--size 48x40 --draw-threads " +
                                  std::string(threads));
        EXPECT_EQ(result.exitCode, 2) << result.err;
        EXPECT_NE(result.err.find("the eye (--eye 0,0,0) and the target"), std::string::npos) << result.err;
        EXPECT_EQ(listFiles(directory),
                  std::vector<std::string>({"named.json", "named.obj", "named.png", "unnamed.obj"}));
        EXPECT_EQ(readImage(directory / "named.png").size(), cv::Size(48, 40));
        const auto stats = nlohmann::json::parse(readText(directory / "named.json"));
        EXPECT_GT(stats["write_ms"].get<double>(), 0.0);
        EXPECT_GT(stats["total_ms"].get<double>(), stats["write_ms"].get<double>());
        EXPECT_GT(stats["peak_rss_mib"].get<double>(), 0.0);
        EXPECT_EQ(stats["draw_threads"], std::stoi(threads));
    }
}

TEST_F(Cli, AFrameNameOneModelLacksFailsThatModelAloneAndTheBatchGoesOn) {
    // --frame names a node only the first and third models have: the second fails (exit 3, its error naming the
    // name), as --expression on a model without a VRM face does, and the third is drawn.
    const std::string tetrahedron = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::ofstream(directory / "named.obj") << "o body\n" << tetrahedron;
    std::ofstream(directory / "unnamed.obj") << tetrahedron;
    std::ofstream(directory / "named2.obj") << "o body\n" << tetrahedron;
    const CliRun result = run("render named.obj unnamed.obj named2.obj -o '{name}.png' --frame body --size 48x40");
    EXPECT_EQ(result.exitCode, 3) << result.err;
    EXPECT_NE(result.err.find("[2/3] 'unnamed.obj' failed: resolveCamera(): --frame 'body': no mesh lies under"),
              std::string::npos)
        << result.err;
    EXPECT_EQ(listFiles(directory),
              std::vector<std::string>({"named.obj", "named.png", "named2.obj", "named2.png", "unnamed.obj"}));
}

TEST_F(Cli, DrawingThreadsThatBothStopTheBatchTellBothErrorsAndKeepTheStillsBeforeThem) {
    // --draw-threads 2: the second still fails on one thread and, before that thread stops the batch, the third
    // (already started on the other) fails too. Neither waits for the other for ever; the first still is committed,
    // the later error is told as an error, and the run exits with the usage error's code.
    const std::string tetrahedron = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    const std::string centred = "v -1 -1 -1\nv 1 -1 -1\nv 0 1 -1\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::ofstream(directory / "named.obj") << tetrahedron;
    std::ofstream(directory / "unnamed.obj") << centred;
    std::ofstream(directory / "unnamed2.obj") << centred;
    // With --jobs above 0 the first still is still in flight when the third starts: the third always fails too.
    const CliRun result = run("render named.obj unnamed.obj unnamed2.obj -o '{name}.png' --eye 0,0,0 --size 48x40 "
                              "--draw-threads 2 --jobs 2");
    EXPECT_EQ(result.exitCode, 2) << result.err;
    EXPECT_NE(result.err.find("[1/3] 'named.obj' -> 'named.png'"), std::string::npos) << result.err;
    // Each error names the still it stopped at (the target is the model's centre).
    EXPECT_TRUE(std::regex_search(
        result.err,
        std::regex(R"(inkgraph: error: \[[23]/3\] 'unnamed2?\.obj': resolveCamera\(\): the eye \(--eye 0,0,0\))")))
        << result.err;
    EXPECT_EQ(listFiles(directory),
              std::vector<std::string>({"named.obj", "named.png", "unnamed.obj", "unnamed2.obj"}));
}

TEST_F(Cli, DrawingThreadsUnderATightMemoryLimitNeverWaitForEachOtherForEver) {
    // A thread whose oldest still waits for its turn behind another thread's earlier still, which waits for memory
    // that only the first thread's texture pool and loaded-ahead model keep, hung both for ever: 3 of 8 runs of this
    // list (app/Render.cpp, RenderSession::finishOldest()). timeout turns a hang into exit 124.
    const fs::path models = fs::path(INKGRAPH_SOURCE_ROOT) / "models";
    std::ofstream(directory / "six.txt") << (models / "armadillo_cgal_52k.obj").string() << "\n"
                                         << (models / "characters" / "box-textured.glb").string() << "\n"
                                         << (models / "bunny_c3d_70k.obj").string() << "\n"
                                         << (models / "cow_c3d.obj").string() << "\n"
                                         << (models / "characters" / "duck.glb").string() << "\n"
                                         << (models / "characters" / "expressions-binary-overridden.vrm").string()
                                         << "\n";
    const CliRun alone = run("render --list six.txt -o 'alone-{index}.png' --size 256x256 -q");
    ASSERT_EQ(alone.exitCode, 0) << alone.err;
    for (int attempt = 0; attempt < 4; ++attempt) {
        const CliRun result = run("render --list six.txt -o 'threads-{index}.png' --size 256x256 --memory-limit 257 "
                                  "--draw-threads 3 --jobs 3 -q",
                                  "timeout 120");
        ASSERT_EQ(result.exitCode, 0) << "attempt " << attempt << ": " << result.err;
        for (int still = 1; still <= 6; ++still)
            EXPECT_TRUE(sameImage(directory / ("alone-" + std::to_string(still) + ".png"),
                                  directory / ("threads-" + std::to_string(still) + ".png")))
                << still;
    }
}

TEST_F(Cli, DrawingThreadsWhoseContextsAlonePassTheMemoryLimitAreRefused) {
    // Sixteen threads under --memory-limit 115: the process and fifteen more GL contexts need about 288 MiB before any
    // still, so no still could keep to the limit (they peaked at 227 MiB, each still let in "as one that fits alone").
    const std::string spot = model("spot_c3d.obj");
    const CliRun refused =
        run("render " + spot + " " + spot + " -o 'x-{index}.png' --size 64x64 --draw-threads 16 --memory-limit 115 -q");
    EXPECT_EQ(refused.exitCode, 2) << refused.err;
    EXPECT_NE(
        refused.err.find("--draw-threads 16: the process (about 108 MiB) and 1 more GL context (about 12 MiB each)"),
        std::string::npos)
        << "two stills: two threads" << refused.err;
    EXPECT_NE(refused.err.find("draw on at most 1 thread, or raise the limit"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(directory / "x-1.png"));
    const CliRun fits =
        run("render " + spot + " " + spot + " -o 'x-{index}.png' --size 64x64 --draw-threads 2 --memory-limit 150 -q");
    EXPECT_EQ(fits.exitCode, 0) << fits.err;
}

/** The bytes of every file under `folder` but the dumps' manifests (they hold timings), by relative path. */
std::map<std::string, std::string> filesUnder(const fs::path& folder) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(folder))
        if (entry.is_regular_file() && entry.path().filename() != "manifest.json")
            files[fs::relative(entry.path(), folder).string()] = readText(entry.path());
    return files;
}

/** `log` with every number of milliseconds ("123 ms", "in 1.5 s") replaced by "#". */
std::string withoutTimes(const std::string& log) {
    return std::regex_replace(std::regex_replace(log, std::regex("[0-9]+ ms"), "# ms"), std::regex("in [0-9.]+ s"),
                              "in # s");
}

TEST_F(Cli, AnyNumberOfJobsOrDrawingThreadsWritesTheSameBytesAndTellsTheSameLinesInOrder) {
    // The pipelined batch (app/Render.h): stills in their post stage on workers while the next draws, and with
    // --draw-threads several threads drawing at once, each in a GL context of its own (app/BatchRun.cpp). A bad model
    // in the middle is told in its place; every file, dumps included (read back after the next still drew), is the
    // same.
    std::ofstream(directory / "broken.obj") << "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n";
    // A model with a warning: told with its own still, before its progress line, whatever loaded meanwhile.
    std::ofstream(directory / "warns.obj") << "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                           << "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::ofstream list(directory / "models.txt");
    for (const char* name :
         {"spot_c3d.obj", "warns.obj", "broken.obj", "suzanne_npm_4k.obj", "fandisk_c3d.obj", "teapot_c3d.obj"}) {
        const bool bundled = std::string(name).find('_') != std::string::npos;
        list << (bundled ? fs::path(INKGRAPH_SOURCE_ROOT) / "models" / name : fs::path(name)).string() << "\n";
    }
    list.close();
    std::map<std::string, std::string> firstFiles;
    std::string firstLog;
    const std::pair<const char*, const char*> runs[] = {{"0", "--jobs 0"},
                                                        {"1", "--jobs 1"},
                                                        {"3", "--jobs 3"},
                                                        {"4", "--jobs 3 --draw-threads 2"},
                                                        {"5", "--jobs 0 --draw-threads 2"},
                                                        {"6", "--jobs 1 --draw-threads 4"}};
    for (const auto& [folder, flags] : runs) {
        const std::string jobs = flags;
        const std::string out = std::string("jobs") + folder;
        fs::create_directories(directory / out);
        const CliRun result = run("render --list models.txt -o '" + out + "/{index}.png' --dump '" + out +
                                  "/dump-{index}' --svg '" + out + "/{index}.svg' " + jobs + kLook);
        ASSERT_EQ(result.exitCode, 3) << result.err;
        const std::size_t first = result.err.find("[1/6]");
        const std::size_t warning = result.err.find("warning: 'warns.obj': mtllib 'missing.mtl'");
        const std::size_t second = result.err.find("[2/6]");
        const std::size_t broken = result.err.find("[3/6] 'broken.obj' failed");
        EXPECT_LT(first, warning) << result.err;
        EXPECT_LT(warning, second) << result.err;
        const std::size_t fourth = result.err.find("[4/6]");
        ASSERT_NE(broken, std::string::npos) << result.err;
        EXPECT_LT(second, broken) << result.err;
        EXPECT_LT(broken, fourth) << result.err;
        const std::map<std::string, std::string> files = filesUnder(directory / out);
        for (const char* picture : {"1.png", "2.png", "4.png", "5.png", "6.png"}) EXPECT_EQ(files.count(picture), 1u);
        EXPECT_EQ(files.count("3.png"), 0u);
        if (firstLog.empty()) {
            firstFiles = files;
            firstLog = withoutTimes(result.err);
            EXPECT_GT(files.size(), 20u) << "pictures, SVGs and dumps";
            continue;
        }
        EXPECT_EQ(files, firstFiles) << jobs;
        std::string log = withoutTimes(result.err);
        // The outputs' folders differ by name only.
        log = std::regex_replace(log, std::regex("jobs[0-9]"), "jobsN");
        EXPECT_EQ(log, std::regex_replace(firstLog, std::regex("jobs[0-9]"), "jobsN")) << jobs;
    }
}

TEST_F(Cli, ABatchThatRendersNothingStillTellsEachStillsWarnings) {
    // --print-plan alone: no still draws, and each still's buffered warnings are told before its line.
    std::ofstream(directory / "warns.obj") << "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const CliRun result = run("render warns.obj " + model("spot_c3d.obj") + " --print-plan");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const std::size_t warning = result.err.find("warning: 'warns.obj': mtllib 'missing.mtl'");
    ASSERT_NE(warning, std::string::npos) << result.err;
    EXPECT_LT(warning, result.err.find("[1/2] 'warns.obj'")) << result.err;
}

TEST_F(Cli, KernelsOnTheGpuStayOnTheContextsThreadInAPipelinedBatch) {
    // --post-stage gpu: the contour's compute shader needs the context, so its pass is no part of the host tail the
    // workers run (a worker without the context would fail or crash); the composite on the GPU leaves no tail at all.
    const std::string models = model("spot_c3d.obj") + " " + model("cow_c3d.obj") + " " + model("teapot_c3d.obj");
    for (const char* jobs : {"0", "2"}) {
        const CliRun result = run("render " + models + " -o 'gpu" + std::string(jobs) +
                                  "-{index}.png' --post-stage gpu --lines contour,depth-edge,suggestive -q --jobs " +
                                  jobs + kLook.substr(0, kLook.find(" --lines")));
        ASSERT_EQ(result.exitCode, 0) << result.err;
    }
    for (const char* index : {"1", "2", "3"})
        EXPECT_EQ(readText(directory / ("gpu0-" + std::string(index) + ".png")),
                  readText(directory / ("gpu2-" + std::string(index) + ".png")))
            << index;
}

TEST_F(Cli, ShardsOfAListRenderDisjointSharesThatMakeTheWhole) {
    std::ofstream list(directory / "models.txt");
    for (const char* name : {"spot_c3d", "cow_c3d", "teapot_c3d", "suzanne_npm_4k", "torusknot_open3d"})
        list << (fs::path(INKGRAPH_SOURCE_ROOT) / "models" / (std::string(name) + ".obj")).string() << "\n";
    list.close();
    for (int shard = 0; shard < 2; ++shard) {
        fs::create_directories(directory / ("shard" + std::to_string(shard)));
        const CliRun result = run("render --list models.txt --shard " + std::to_string(shard) + "/2 -o 'shard" +
                                  std::to_string(shard) + "/{index}-{name}.png' --size 32x32 -q");
        ASSERT_EQ(result.exitCode, 0) << result.err;
    }
    EXPECT_EQ(listFiles(directory / "shard0"),
              std::vector<std::string>({"1-spot_c3d.png", "3-teapot_c3d.png", "5-torusknot_open3d.png"}));
    EXPECT_EQ(listFiles(directory / "shard1"), std::vector<std::string>({"2-cow_c3d.png", "4-suzanne_npm_4k.png"}));
}

TEST_F(Cli, APictureTheWorkerCannotWriteStopsTheBatchAndLeavesNoFile) {
    // A pipelined batch writes each picture beside its place on the worker that encoded it (app/Render.cpp); with a
    // 2 KiB file-size limit that write fails there. It is the still's failure, told as a failed write is (exit 5), and
    // neither a picture nor a temporary file is left, whatever the other stills in flight had written.
    std::ofstream list(directory / "models.txt");
    for (const char* name : {"spot_c3d.obj", "suzanne_npm_4k.obj", "teapot_c3d.obj"})
        list << (fs::path(INKGRAPH_SOURCE_ROOT) / "models" / name).string() << "\n";
    list.close();
    for (const char* threads : {"1", "3"}) {
        SCOPED_TRACE(std::string("--draw-threads ") + threads);
        const CliRun result = run("render --list models.txt -o '{index}.png' --size 256x256 --jobs 2 --shading cel "
                                  "--draw-threads " +
                                      std::string(threads),
                                  "sh -c 'ulimit -f 4; exec \"$0\" \"$@\"'");
        EXPECT_EQ(result.exitCode, 5) << result.err;
        EXPECT_NE(result.err.find("File too large"), std::string::npos) << result.err;
        EXPECT_EQ(listFiles(directory), std::vector<std::string>{"models.txt"});
        // Every still in flight fails. The first in the list is the error (the run's last line); the second, which
        // the first's failure found in flight, is told as an error of its own, never in the first one's place.
        const std::size_t lastLine = result.err.rfind('\n', result.err.size() - 2);
        const std::string last = result.err.substr(lastLine == std::string::npos ? 0 : lastLine + 1);
        EXPECT_NE(last.find("cannot write '1.png': File too large"), std::string::npos) << result.err;
        EXPECT_NE(result.err.find("inkgraph: error: writeFile(): cannot write '2.png': File too large\n"),
                  std::string::npos)
            << result.err;
    }
}

TEST_F(Cli, ABatchWhoseOutputsCollideWritesNothing) {
    const CliRun result = run("render " + model("spot_c3d.obj") + " " + model("cow_c3d.obj") +
                              " -o '{name}.png' --stats stats.json --size 32x32");
    EXPECT_EQ(result.exitCode, 2) << result.err;
    EXPECT_NE(result.err.find("--stats 'stats.json' would be the same file for all 2 models"), std::string::npos)
        << result.err;
    EXPECT_EQ(listFiles(directory), std::vector<std::string>());
}

} // namespace
} // namespace inkgraph
