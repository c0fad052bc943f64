// app/Batch: which models a run renders, how output paths expand, and which batches are refused before any work.
// No GL: the rendering of a batch is tests/app/BatchGLTest.cpp.
#include "app/Batch.h"
#include "flags/StyleFile.h"

#include "tests/support/TestFolder.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>

namespace inkgraph {
namespace {

namespace fs = std::filesystem;

RenderOptions withModels(std::vector<std::string> models) {
    RenderOptions options;
    options.modelPaths = std::move(models);
    if (!options.modelPaths.empty()) options.modelPath = options.modelPaths.front();
    options.outputPath = "out/{name}.png";
    return options;
}

std::vector<std::string> pathsOf(const BatchList& list) {
    std::vector<std::string> paths;
    for (const BatchModel& model : list.models) paths.push_back(model.path);
    return paths;
}

std::string usageMessage(const RenderOptions& options, const BatchList& list) {
    try {
        checkBatchOutputs(options, list);
    } catch (const UsageError& error) {
        return error.what();
    }
    return "";
}

class BatchListFile : public test::TestFolder {
protected:
    std::string write(const std::string& name, const std::string& text) {
        std::ofstream(directory / name, std::ios::binary) << text;
        return (directory / name).string();
    }
};

TEST(BatchList, OneModelIsNoBatchAndSeveralAre) {
    std::istringstream none;
    const BatchList one = batchList(withModels({"a.obj"}), none);
    EXPECT_FALSE(one.isBatch);
    EXPECT_EQ(one.total, 1u);
    EXPECT_EQ(pathsOf(one), std::vector<std::string>({"a.obj"}));
    const BatchList two = batchList(withModels({"a.obj", "b.glb"}), none);
    EXPECT_TRUE(two.isBatch);
    EXPECT_EQ(pathsOf(two), std::vector<std::string>({"a.obj", "b.glb"}));
    EXPECT_EQ(two.models[1].position, 1u);
}

TEST_F(BatchListFile, ListLinesFollowTheArgumentsSkippingCommentsAndBlanks) {
    RenderOptions options = withModels({"first.obj"});
    options.listPath = write("list.txt", "# models\n  b.obj  \n\n\tc.stl\r\n#d.obj\nsub dir/e f.glb\n");
    std::istringstream none;
    const BatchList list = batchList(options, none);
    EXPECT_TRUE(list.isBatch);
    EXPECT_EQ(list.total, 4u);
    EXPECT_EQ(pathsOf(list), std::vector<std::string>({"first.obj", "b.obj", "c.stl", "sub dir/e f.glb"}));
}

TEST_F(BatchListFile, AByteOrderMarkBeforeAPathIsSkipped) {
    RenderOptions options;
    options.listPath = write("bom.txt", "\xEF\xBB\xBF"
                                        "a.obj\r\nb.obj\r\n");
    std::istringstream none;
    EXPECT_EQ(pathsOf(batchList(options, none)), std::vector<std::string>({"a.obj", "b.obj"}));
    options.listPath = write("bom-comment.txt", "\xEF\xBB\xBF# models\na.obj\n");
    EXPECT_EQ(pathsOf(batchList(options, none)), std::vector<std::string>({"a.obj"}));
    options.listPath = write("joined.txt", "\xEF\xBB\xBF"
                                           "a.obj\n"
                                           "\xEF\xBB\xBF"
                                           "b.obj\n"); // two lists joined with cat
    EXPECT_EQ(pathsOf(batchList(options, none)), std::vector<std::string>({"a.obj", "b.obj"}));
    std::istringstream piped("\xEF\xBB\xBF"
                             "c.obj\n");
    options.listPath = "-";
    EXPECT_EQ(pathsOf(batchList(options, piped)), std::vector<std::string>({"c.obj"}));
}

TEST_F(BatchListFile, AListFromAPipeIsReadAsStandardInputIs) {
    // The shell's `--list <(find models -name '*.obj')` names a pipe (/dev/fd/63), not a regular file.
    const fs::path pipe = directory / "list.fifo";
    ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
    std::thread writer([&pipe] { std::ofstream(pipe) << "# found\na.obj\nb.glb\n"; });
    RenderOptions options;
    options.listPath = pipe.string();
    std::istringstream none;
    const BatchList list = batchList(options, none);
    writer.join();
    EXPECT_EQ(pathsOf(list), std::vector<std::string>({"a.obj", "b.glb"}));
}

TEST_F(BatchListFile, AListOfOneModelIsStillABatch) {
    RenderOptions options;
    options.listPath = write("one.txt", "a.obj\n");
    std::istringstream none;
    const BatchList list = batchList(options, none);
    EXPECT_TRUE(list.isBatch); // a progress line, as for every list
    EXPECT_EQ(pathsOf(list), std::vector<std::string>({"a.obj"}));
}

TEST(BatchList, DashReadsTheListFromStandardInput) {
    RenderOptions options;
    options.listPath = "-";
    std::istringstream input("x.obj\ny.obj");
    EXPECT_EQ(pathsOf(batchList(options, input)), std::vector<std::string>({"x.obj", "y.obj"}));
}

TEST(BatchList, ShardsTakeEveryNthModelAndTogetherTheWholeList) {
    std::vector<std::string> models;
    for (int i = 0; i < 10; ++i) models.push_back("m" + std::to_string(i) + ".obj");
    std::vector<std::string> union_;
    for (int k = 0; k < 3; ++k) {
        RenderOptions options = withModels(models);
        options.shard = Shard{k, 3};
        std::istringstream none;
        const BatchList list = batchList(options, none);
        EXPECT_EQ(list.total, 10u);
        for (const BatchModel& model : list.models) {
            EXPECT_EQ(int(model.position % 3), k) << model.path;
            EXPECT_EQ(model.path, models[model.position]);
            union_.push_back(model.path);
        }
        EXPECT_EQ(list.models.size(), k == 0 ? 4u : 3u);
    }
    std::sort(union_.begin(), union_.end());
    std::sort(models.begin(), models.end());
    EXPECT_EQ(union_, models);
}

TEST_F(BatchListFile, BadListsAreRefusedNamingTheFile) {
    std::istringstream none;
    RenderOptions options;
    options.listPath = write("empty.txt", "# nothing\n\n");
    try {
        batchList(options, none);
        FAIL() << "an empty list was accepted";
    } catch (const UsageError& error) {
        EXPECT_NE(std::string(error.what()).find("--list '" + options.listPath + "': no models"), std::string::npos)
            << error.what();
    }
    options.listPath = write("binary.txt", std::string("a.obj\nb\0c.obj\n", 14));
    try {
        batchList(options, none);
        FAIL() << "a list with a NUL byte was accepted";
    } catch (const UsageError& error) {
        EXPECT_NE(std::string(error.what()).find("line 2: binary data"), std::string::npos) << error.what();
    }
    options.listPath = (directory / "missing.txt").string();
    try {
        batchList(options, none);
        FAIL() << "a missing list was accepted";
    } catch (const UsageError& error) {
        EXPECT_NE(std::string(error.what()).find("missing.txt"), std::string::npos) << error.what();
        EXPECT_EQ(std::string(error.what()).rfind("--list", 0), 0u) << error.what();
    }
}

TEST(BatchOutputs, PlaceholdersExpandToTheModelNameAndPaddedPosition) {
    const BatchModel model{"models/dir.v2/bunny.obj", 2};
    EXPECT_EQ(expandOutputPattern("out/{name}.png", model, 3), "out/bunny.png");
    EXPECT_EQ(expandOutputPattern("{index}-{name}-{index}.png", model, 12), "03-bunny-03.png");
    EXPECT_EQ(expandOutputPattern("{index}.png", model, 1000), "0003.png");
    EXPECT_EQ(expandOutputPattern("plain.png", model, 3), "plain.png");
    EXPECT_EQ(expandOutputPattern("{nam}{index", model, 3), "{nam}{index"); // only the two placeholders
}

TEST(BatchOutputs, EveryOutputOfAStillIsExpanded) {
    RenderOptions options = withModels({"a.obj", "b.obj"});
    options.dumpDirectory = "d/{name}";
    options.statsPath = "s/{name}.json";
    options.graphvizPath = "g/{index}.dot";
    options.contactSheetPath = "c/{name}.png";
    options.svgPath = "v/{name}.svg";
    const RenderOptions still = stillOptions(options, BatchStill{{"x/b.obj", 1}}, 2);
    EXPECT_EQ(still.modelPath, "x/b.obj");
    EXPECT_EQ(still.outputPath, "out/b.png");
    EXPECT_EQ(still.dumpDirectory, "d/b");
    EXPECT_EQ(still.statsPath, "s/b.json");
    EXPECT_EQ(still.graphvizPath, "g/2.dot");
    EXPECT_EQ(still.contactSheetPath, "c/b.png");
    EXPECT_EQ(still.svgPath, "v/b.svg");
}

TEST(BatchOutputs, SeveralModelsNeedAPlaceholderInEveryOutput) {
    std::istringstream none;
    RenderOptions options = withModels({"a.obj", "b.obj"});
    options.statsPath = "stats.json";
    const std::string message = usageMessage(options, batchList(options, none));
    EXPECT_NE(message.find("--stats 'stats.json' would be the same file for all 2 models"), std::string::npos)
        << message;
    EXPECT_NE(message.find("'out/{name}.json'"), std::string::npos) << message;
    options.statsPath = "{index}.json";
    EXPECT_EQ(usageMessage(options, batchList(options, none)), "");
    RenderOptions single = withModels({"a.obj"});
    single.outputPath = "a.png";
    EXPECT_EQ(usageMessage(single, batchList(single, none)), ""); // one model needs none
}

TEST(BatchOutputs, ModelsOfOneNameCollideUnlessIndexed) {
    std::istringstream none;
    RenderOptions options = withModels({"x/spot.obj", "y/spot.obj"});
    const std::string message = usageMessage(options, batchList(options, none));
    EXPECT_NE(message.find("-o 'out/spot.png' is written for both 'x/spot.obj'"), std::string::npos) << message;
    EXPECT_NE(message.find("{index}"), std::string::npos) << message;
    options.outputPath = "out/{index}-{name}.png";
    EXPECT_EQ(usageMessage(options, batchList(options, none)), "");
    // The same model twice is two stills: with {name} alone they would overwrite each other.
    RenderOptions twice = withModels({"a.obj", "a.obj"});
    EXPECT_NE(usageMessage(twice, batchList(twice, none)).find("is written for both"), std::string::npos);
}

TEST(BatchOutputs, AShareMayNotWriteWhatAnotherShareWrites) {
    // Array tasks write into one folder: 'x/spot.obj' (shard 0/2) and 'y/spot.obj' (shard 1/2) would both write
    // out/spot.png, each task alone seeing no collision in its own share. Either task refuses, naming both.
    std::istringstream none;
    for (int k = 0; k < 2; ++k) {
        RenderOptions options = withModels({"x/spot.obj", "y/spot.obj", "z/cow.obj"});
        options.shard = Shard{k, 2};
        const BatchList list = batchList(options, none);
        ASSERT_EQ(list.models.size(), k == 0 ? 2u : 1u);
        const std::string message = usageMessage(options, list);
        EXPECT_NE(message.find("is written for both 'x/spot.obj' (list position 1, shard 0/2) and 'y/spot.obj' "
                               "(position 2, shard 1/2)"),
                  std::string::npos)
            << message;
        options.outputPath = "out/{index}-{name}.png";
        EXPECT_EQ(usageMessage(options, batchList(options, none)), "");
    }
    // Shares that never meet (another folder per model) pass.
    RenderOptions apart = withModels({"x/spot.obj", "y/cow.obj"});
    apart.shard = Shard{1, 2};
    EXPECT_EQ(usageMessage(apart, batchList(apart, none)), "");
}

TEST(BatchList, MoreStillsThanOneProcessRendersAreRefusedPointingToShard) {
    std::istringstream none;
    RenderOptions options = withModels(std::vector<std::string>(11, "a.obj"));
    options.outputPath = "out/{index}-{view}.png";
    options.viewsGiven = true;
    options.viewSampling.count = 100000;
    try {
        batchList(options, none);
        ADD_FAILURE() << "11 models x 100000 views were accepted";
    } catch (const UsageError& error) {
        EXPECT_NE(std::string(error.what()).find("--shard K/N (e.g. --shard 0/2)"), std::string::npos) << error.what();
    }
    options.shard = Shard{0, 2}; // 6 models x 100000: within the limit
    EXPECT_EQ(batchList(options, none).models.size(), 6u);
}

TEST_F(BatchListFile, TheFilesEveryStillReadsBesidesItsModelAreJudgedOnceBeforeTheRun) {
    const std::string good = write("good.json", "{\"head\": [0, 0.1, 0, 1]}");
    const std::string bad = write("bad.json", "{\"tail\": [0, 0, 0, 1]}");
    const std::string notPng = write("map.png", "not a PNG");
    RenderOptions options = withModels({"a.vrm", "b.vrm"});
    EXPECT_NO_THROW(checkBatchInputs(options));
    options.pose = "a-pose";
    options.viewSampling.poseChoices = {"rest", "a-pose", good};
    EXPECT_NO_THROW(checkBatchInputs(options));
    const auto message = [&](const RenderOptions& checked) {
        try {
            checkBatchInputs(checked);
        } catch (const std::exception& error) {
            return std::string(error.what());
        }
        return std::string();
    };
    options.viewSampling.poseChoices = {"rest", good, bad};
    EXPECT_EQ(message(options).rfind("--poses: '" + bad + "': unknown humanoid bone 'tail' (VRM's humanoid bones: ", 0),
              0u)
        << message(options);
    options.viewSampling.poseChoices.clear();
    options.pose = bad + ".missing";
    EXPECT_EQ(message(options), "--pose: '" + bad + ".missing': the pose file cannot be found");
    options.pose.clear();
    options.look.shading = ShadingModel::Cel;
    options.look.shadeMapPath = notPng;
    EXPECT_EQ(message(options).rfind("--shademap: '" + notPng + "'", 0), 0u) << message(options);
    // A style file's map is named by the style's line, as its other settings are.
    const std::string style = write("look.style", "shading = cel\nshademap = map.png\n");
    const SourcedArguments expanded = expandStyleFile({"a.obj", "--style", style, "-o", "o.png"});
    const RenderOptions styled = parseRenderOptions(expanded.arguments, expanded.origins);
    EXPECT_EQ(message(styled).rfind("--style '" + style + "' line 2: --shademap: '", 0), 0u) << message(styled);
    options.shadeMapOrigin.clear();
    EXPECT_EQ(parseRenderOptions({"a.obj", "-o", "o.png", "--shading", "cel", "--shademap", notPng}).shadeMapOrigin,
              "");
}

TEST(BatchOutputs, NoStillMayOverwriteAModelOfTheList) {
    std::istringstream none;
    RenderOptions options = withModels({"m/2.obj", "m/a.obj"});
    options.outputPath = "m/{index}.obj"; // the second still would write 'm/2.obj', the first model
    const std::string message = usageMessage(options, batchList(options, none));
    EXPECT_NE(message.find("-o 'm/2.obj' (for 'm/a.obj') would overwrite the model 'm/2.obj'"), std::string::npos)
        << message;
}

TEST_F(BatchListFile, NoStillMayWriteItsOwnModelOrAFileEveryStillReads) {
    // Found before any work, as for the stills before it: each still alone would find it only at its turn, after
    // the stills before it had written their files.
    for (const char* name : {"a.obj", "b.obj", "3.obj", "3.txt", "3.style", "3.png"})
        write(name, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string models[] = {(directory / "a.obj").string(), (directory / "b.obj").string(),
                                  (directory / "3.obj").string()};
    std::istringstream none;
    const auto messageFor = [&](const std::string& statsExtension, const std::function<void(RenderOptions&)>& set) {
        RenderOptions options = withModels({models[0], models[1], models[2]});
        options.outputPath = (directory / "out-{index}.png").string();
        options.statsPath = (directory / ("{index}" + statsExtension)).string();
        set(options);
        return usageMessage(options, batchList(options, none));
    };
    const std::string stats = "--stats '" + (directory / "3").string();
    EXPECT_EQ(messageFor(".obj", [](RenderOptions&) {}), stats + ".obj' is the model itself; choose another file");
    EXPECT_EQ(messageFor(".txt", [&](RenderOptions& options) { options.listPath = (directory / "3.txt").string(); }),
              stats + ".txt' is the --list file; choose another file");
    EXPECT_EQ(
        messageFor(".style", [&](RenderOptions& options) { options.stylePath = (directory / "3.style").string(); }),
        stats + ".style' is the --style file; choose another file");
    EXPECT_EQ(messageFor(".png",
                         [&](RenderOptions& options) {
                             options.look.shadeMapPath = (directory / "sub" / ".." / "3.png").string();
                         }),
              stats + ".png' is the --shademap itself; choose another file");
    EXPECT_EQ(messageFor(".json", [&](RenderOptions& options) { options.listPath = "-"; }), "");
}

TEST(BatchOutputs, AHardLinkOfAModelIsThatModel) {
    // Another name, the same inode: writing '1.png' for the first still would change the second model.
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() / ("inkgraph-batch-link-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    std::ofstream(folder / "b.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(folder / "a.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::filesystem::create_hard_link(folder / "b.obj", folder / "1.png");
    std::istringstream none;
    RenderOptions options = withModels({(folder / "a.obj").string(), (folder / "b.obj").string()});
    options.outputPath = (folder / "{index}.png").string();
    const std::string message = usageMessage(options, batchList(options, none));
    std::filesystem::remove_all(folder);
    EXPECT_NE(message.find("1.png' (for '" + (folder / "a.obj").string() + "') would overwrite the model '" +
                           (folder / "b.obj").string() + "'"),
              std::string::npos)
        << message;
}

TEST(BatchOutputs, NoStillMayReplaceAFileAnotherModelReads) {
    // One model's output over another model's glTF buffer or material shade map, or an OBJ's material library: the
    // batch is refused before any work, though each still alone only checks its own inputs.
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() / ("inkgraph-batch-named-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    std::ofstream(folder / "scene.gltf")
        << R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36,"uri":"geometry.bin"}],)"
           R"("images":[{"uri":"skin%20tone.png"}],"materials":[{"extras":{"inkgraph":{"shademap":"maps/ink.png"}}}]})";
    std::ofstream(folder / "geometry.bin") << std::string(36, '\0');
    std::ofstream(folder / "skin tone.png") << "png";
    std::filesystem::create_directories(folder / "maps");
    std::ofstream(folder / "maps" / "ink.png") << "png";
    std::ofstream(folder / "cube.obj") << "mtllib cube.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(folder / "cube.mtl") << "newmtl red\n";
    for (const char* name : {"geometry", "skin tone", "ink"})
        std::ofstream(folder / (std::string(name) + ".obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::istringstream none;
    const auto messageFor = [&](const std::string& model, const std::string& flag, const std::string& pattern) {
        RenderOptions options =
            withModels({(folder / "scene.gltf").string(), (folder / "cube.obj").string(), (folder / model).string()});
        options.outputPath = (folder / "{index}.png").string();
        (options.*(flag == "--stats" ? &RenderOptions::statsPath : &RenderOptions::svgPath)) = pattern;
        return usageMessage(options, batchList(options, none));
    };
    EXPECT_NE(messageFor("geometry.obj", "--stats", (folder / "{name}.bin").string())
                  .find("geometry.bin' (for '" + (folder / "geometry.obj").string() + "') would overwrite '" +
                        (folder / "geometry.bin").string() + "', which the model '" + (folder / "scene.gltf").string() +
                        "' reads"),
              std::string::npos);
    EXPECT_NE(messageFor("skin tone.obj", "--stats", (folder / "{name}.png").string()).find("which the model"),
              std::string::npos);
    EXPECT_NE(messageFor("ink.obj", "--svg", (folder / "maps" / "{name}.png").string()).find("maps/ink.png"),
              std::string::npos);
    const std::string library = messageFor("ink.obj", "--stats", (folder / "{name}.mtl").string());
    EXPECT_NE(library.find("cube.mtl', which the model"), std::string::npos) << library;
    EXPECT_EQ(messageFor("ink.obj", "--stats", (folder / "{name}.json").string()), "");
    std::filesystem::remove_all(folder);
}

} // namespace
} // namespace inkgraph
