// --views by the real `inkgraph` executable: the stills of each model's sampled views, their records, and the
// determinism docs/datasets.md promises (the same command twice, any --shard split, and --orbit/--light with the
// recorded numbers all give the same bytes). Needs a GL context (llvmpipe in CI); the stills are small (64x64 and
// 40x40) and few.
#include "scene/ViewSampling.h"
#include "CliTestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <set>

namespace inkgraph::views_gl_test {
namespace {

using test::Cli;
using test::CliRun;
using test::readText;
namespace fs = std::filesystem;

const std::string kLook = " --shading comic --lines outline,contour,crease";

/** A JSON number as text that reads back as the same double (JSON writes the shortest such text). */
std::string numberText(const nlohmann::json& number) { return number.dump(); }

TEST_F(Cli, ViewsAreSampledRecordedAndReproducedByTheirNumbers) {
    fs::copy_file(fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "suzanne_npm_4k.obj", directory / "m.obj");
    const std::string views = "render m.obj --views 3 --seed 7 --view-distance-jitter 0.2 --light 0.2,1,0.5 "
                              "--light-jitter 30 --size 64x64" +
                              kLook;
    fs::create_directories(directory / "a");
    fs::create_directories(directory / "b");
    const CliRun first = run(views + " -o 'a/v-{view}.png' --stats 'a/v-{view}.json'");
    ASSERT_EQ(first.exitCode, 0) << first.err;
    EXPECT_NE(first.err.find("inkgraph: [2/3] 'm.obj' view 1 -> 'a/v-1.png': "), std::string::npos) << first.err;
    EXPECT_NE(first.err.find("inkgraph: rendered 3 of 3 stills (1 model x 3 views) in"), std::string::npos)
        << first.err;

    ViewSampling sampling;
    sampling.count = 3;
    sampling.seed = 7;
    sampling.distanceJitter = 0.2;
    sampling.lightJitterDegrees = 30.0;
    sampling.light = glm::dvec3(0.2, 1.0, 0.5);
    std::set<double> azimuths;
    std::vector<nlohmann::json> records;
    for (int view = 0; view < 3; ++view) {
        const auto stats = nlohmann::json::parse(readText(directory / "a" / ("v-" + std::to_string(view) + ".json")));
        const nlohmann::json& record = stats["view"];
        const ViewSample expected = sampleView(sampling, "m.obj", std::size_t(view));
        EXPECT_EQ(record["index"].get<int>(), view);
        EXPECT_EQ(record["count"].get<int>(), 3);
        EXPECT_EQ(record["seed"].get<int>(), 7);
        EXPECT_EQ(record["azimuth"].get<double>(), expected.azimuthDegrees) << view;
        EXPECT_EQ(record["elevation"].get<double>(), expected.elevationDegrees) << view;
        EXPECT_EQ(record["distance_scale"].get<double>(), expected.distanceScale) << view;
        ASSERT_TRUE(record["light"].is_array());
        for (int axis = 0; axis < 3; ++axis)
            EXPECT_EQ(record["light"][axis].get<double>(), (*expected.towardLight)[axis]) << view;
        EXPECT_TRUE(record["expression"].is_null());
        EXPECT_TRUE(record["pose"].is_null());
        EXPECT_EQ(stats["camera_source"], "orbit");
        azimuths.insert(record["azimuth"].get<double>());
        records.push_back(record);
    }
    EXPECT_EQ(azimuths.size(), 3u) << "three different views";
    EXPECT_NE(readText(directory / "a" / "v-0.png"), readText(directory / "a" / "v-1.png"));
    EXPECT_NE(readText(directory / "a" / "v-1.png"), readText(directory / "a" / "v-2.png"));

    // The same command again: the same bytes.
    const CliRun second = run(views + " -o 'b/v-{view}.png' -q");
    ASSERT_EQ(second.exitCode, 0) << second.err;
    for (int view = 0; view < 3; ++view) {
        const std::string name = "v-" + std::to_string(view) + ".png";
        EXPECT_EQ(readText(directory / "a" / name), readText(directory / "b" / name)) << name;
    }

    // View 1 by its recorded numbers, without --views: the same picture.
    const nlohmann::json& record = records[1];
    const std::string light =
        numberText(record["light"][0]) + "," + numberText(record["light"][1]) + "," + numberText(record["light"][2]);
    const CliRun again = run("render m.obj --orbit " + record["orbit"].get<std::string>() + " --camera auto --light " +
                             light + " --size 64x64 -o again.png -q" + kLook);
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_EQ(readText(directory / "again.png"), readText(directory / "a" / "v-1.png"));
}

TEST_F(Cli, ViewsChooseExpressionsAndPosesThatTheirRecordReproduces) {
    // Godette (3439 triangles) has VRM expressions. Copied, so the views' key is "g.vrm" wherever the checkout is:
    // seed 1 gives view 0 no expression in the A-pose and view 1 happy=1 in the rest pose.
    fs::copy_file(fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "characters" / "godette.vrm", directory / "g.vrm");
    const std::string godette = "g.vrm";
    const CliRun result = run("render " + godette +
                              " --views 2 --seed 1 --expressions 'happy=1;none' --poses rest,a-pose --size 64x64 -q"
                              " -o 'v-{view}.png' --stats 'v-{view}.json' --dump 'd-{view}'" +
                              kLook);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    std::set<std::string> expressions, poses;
    for (int view = 0; view < 2; ++view) {
        const std::string name = "v-" + std::to_string(view);
        const nlohmann::json record = nlohmann::json::parse(readText(directory / (name + ".json")))["view"];
        const nlohmann::json manifest =
            nlohmann::json::parse(readText(directory / ("d-" + std::to_string(view)) / "manifest.json"));
        EXPECT_EQ(manifest["view"], record) << "the manifest records the view as --stats does";
        expressions.insert(record["expression"].get<std::string>());
        poses.insert(record["pose"].get<std::string>());
        const std::string expression =
            record["expression"] == "none" ? "" : " --expression " + record["expression"].get<std::string>();
        const std::string pose = record["pose"] == "rest" ? "" : " --pose " + record["pose"].get<std::string>();
        const CliRun again = run("render " + godette + " --orbit " + record["orbit"].get<std::string>() + expression +
                                 pose + " --size 64x64 -q -o again.png" + kLook);
        ASSERT_EQ(again.exitCode, 0) << again.err;
        EXPECT_EQ(readText(directory / "again.png"), readText(directory / (name + ".png"))) << name;
    }
    EXPECT_EQ(expressions, std::set<std::string>({"happy=1", "none"}));
    EXPECT_EQ(poses, std::set<std::string>({"a-pose", "rest"}));
}

TEST_F(Cli, ViewsOfAShardedListAreTheUnshardedRunsBytes) {
    for (const char* name : {"suzanne_npm_4k", "cow_c3d", "spot_c3d"})
        fs::copy_file(fs::path(INKGRAPH_SOURCE_ROOT) / "models" / (std::string(name) + ".obj"),
                      directory / (std::string(name) + ".obj"));
    const std::string models = "suzanne_npm_4k.obj cow_c3d.obj spot_c3d.obj";
    const std::string views = " --views 2 --seed 3 --view-elevation 20,15 --size 40x40 -q" + kLook;
    fs::create_directories(directory / "whole");
    fs::create_directories(directory / "shards");
    const CliRun whole = run("render " + models + views + " -o 'whole/{index}-{name}-{view}.png'");
    ASSERT_EQ(whole.exitCode, 0) << whole.err;
    for (const char* shard : {"0/2", "1/2"}) {
        const CliRun part =
            run("render " + models + views + " --shard " + shard + " -o 'shards/{index}-{name}-{view}.png'");
        ASSERT_EQ(part.exitCode, 0) << part.err;
    }
    const std::vector<std::string> names = listFiles(directory / "whole");
    EXPECT_EQ(names, std::vector<std::string>({"1-suzanne_npm_4k-0.png", "1-suzanne_npm_4k-1.png", "2-cow_c3d-0.png",
                                               "2-cow_c3d-1.png", "3-spot_c3d-0.png", "3-spot_c3d-1.png"}));
    EXPECT_EQ(listFiles(directory / "shards"), names);
    for (const std::string& name : names)
        EXPECT_EQ(readText(directory / "whole" / name), readText(directory / "shards" / name)) << name;
}

TEST_F(Cli, ViewsWithoutTheViewPlaceholderWriteNothing) {
    const CliRun result = run("render " + model("spot_c3d.obj") + " --views 4 -o out.png --size 32x32");
    EXPECT_EQ(result.exitCode, 2) << result.err;
    EXPECT_NE(result.err.find("-o 'out.png' would be the same file for all 4 views of --views; put {view} in it"),
              std::string::npos)
        << result.err;
    EXPECT_EQ(listFiles(directory), std::vector<std::string>());
}

TEST_F(Cli, ABadPoseOrShadeMapFailsTheRunBeforeItsFirstStill) {
    // Each still read them as it loaded: a bad --poses file failed only the views drawing it, found as the run
    // reached them (views 0 and 2 of 4 here, after views 1 and 3 were written), a missing --shademap every still.
    std::ofstream(directory / "bad.json") << "{\"head\": [0, 0, 0, 0]}";
    const CliRun poses = run("render " + model("spot_c3d.obj") + " " + model("cow_c3d.obj") +
                             " --views 4 --poses rest,bad.json -o '{name}-{view}.png' --size 32x32");
    EXPECT_EQ(poses.exitCode, 3) << poses.err;
    EXPECT_NE(poses.err.find("inkgraph: --poses: 'bad.json': 'head': the quaternion must be finite and of non-zero "
                             "length"),
              std::string::npos)
        << poses.err;
    EXPECT_EQ(poses.err.find("[1/8]"), std::string::npos) << "no still began: " << poses.err;
    const CliRun shadeMap = run("render " + model("spot_c3d.obj") + " " + model("cow_c3d.obj") +
                                " --shading cel --shademap missing.png -o '{name}.png' --size 32x32");
    EXPECT_EQ(shadeMap.exitCode, 3) << shadeMap.err;
    EXPECT_NE(shadeMap.err.find("inkgraph: --shademap: 'missing.png': file not found"), std::string::npos)
        << shadeMap.err;
    EXPECT_EQ(shadeMap.err.find("[1/2]"), std::string::npos) << "no still began: " << shadeMap.err;
    EXPECT_EQ(listFiles(directory), std::vector<std::string>({"bad.json"}));
}

} // namespace
} // namespace inkgraph::views_gl_test
