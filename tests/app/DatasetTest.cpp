// app/Dataset and app/DatasetCheck without GL: the checksum, the settings digest (flag order does not matter, what
// decides a still's files does), the refusals of --dataset, the journal's torn line, and check-dataset on hand-made
// data sets. The rendering and the kills are tests/app/dataset-kill-test.sh.
#include "app/Dataset.h"
#include "app/DatasetCheck.h"
#include "flags/StyleFile.h"

#include "render/ImageFiles.h"
#include "render/TemporaryFiles.h"
#include "tests/support/TestFolder.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace inkgraph {
namespace {

namespace fs = std::filesystem;

TEST(DatasetChecksum, IsFnv1a64) {
    // The published FNV-1a 64-bit test values.
    EXPECT_EQ(hexDigits(fnv1a64("", 0)), "cbf29ce484222325");
    EXPECT_EQ(hexDigits(fnv1a64("a", 1)), "af63dc4c8601ec8c");
    EXPECT_EQ(hexDigits(fnv1a64("foobar", 6)), "85944171f73967e8");
    // Continued over pieces, the same as at once.
    EXPECT_EQ(fnv1a64("bar", 3, fnv1a64("foo", 3)), fnv1a64("foobar", 6));
}

TEST(DatasetChecksum, ShellWordsQuoteOnlyWhatNeedsIt) {
    EXPECT_EQ(shellWord("--size"), "--size");
    EXPECT_EQ(shellWord("out/a-1.png"), "out/a-1.png");
    EXPECT_EQ(shellWord("{name}.png"), "'{name}.png'");
    EXPECT_EQ(shellWord("a b"), "'a b'");
    EXPECT_EQ(shellWord("it's"), "'it'\\''s'");
    EXPECT_EQ(shellWord(""), "''");
}

TEST(DatasetTemporaryTag, IsThisHostAndThisProcessEvenAfterAFork) {
    const std::string tag = temporaryTag();
    const std::size_t dash = tag.find('-');
    ASSERT_EQ(dash, 8u) << tag;
    EXPECT_EQ(tag.substr(dash + 1), std::to_string(::getpid()));
    int ends[2];
    ASSERT_EQ(::pipe(ends), 0);
    const pid_t child = ::fork();
    if (child == 0) {
        const std::string childTag = temporaryTag();
        (void)!::write(ends[1], childTag.data(), childTag.size());
        ::_exit(0);
    }
    ASSERT_GT(child, 0);
    ::close(ends[1]);
    char text[64] = {};
    const ssize_t count = ::read(ends[0], text, sizeof text - 1);
    ::close(ends[0]);
    ::waitpid(child, nullptr, 0);
    EXPECT_EQ(std::string(text, std::size_t(std::max<ssize_t>(count, 0))),
              tag.substr(0, dash + 1) + std::to_string(child))
        << "a forked child (Python's multiprocessing) numbers its temporaries by its own pid";
}

class Dataset : public test::TestFolder {
protected:
    /** A run's options and list from `arguments` (after "render"), and its DatasetRun. */
    std::unique_ptr<DatasetRun> runOf(const std::vector<std::string>& arguments) {
        // As app/Cli.cpp runs it: the digest reads the arguments as the parser takes them.
        const SourcedArguments expanded = expandStyleFile(arguments);
        options = parseRenderOptions(expanded.arguments, expanded.origins);
        std::istringstream none;
        list = batchList(options, none);
        stills = batchStills(options, list);
        return std::make_unique<DatasetRun>(options, list, stills, arguments, expanded.arguments);
    }
    std::string digestOf(const std::vector<std::string>& arguments) {
        auto run = runOf(arguments);
        const BatchStill& first = stills.front();
        return run->settingsDigest({first.model.path, first.model.position, first.viewIndex},
                                   stillOptions(options, first, list.total));
    }
    std::string usageError(const std::vector<std::string>& arguments) {
        try {
            runOf(arguments);
        } catch (const UsageError& error) {
            return error.what();
        }
        return "";
    }
    std::string write(const fs::path& path, const std::string& text) {
        fs::create_directories(path.parent_path());
        std::ofstream(path, std::ios::binary) << text;
        return path.string();
    }
    void SetUp() override {
        TestFolder::SetUp();
        model = write(directory / "cube.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        set = (directory / "set").string();
    }

    RenderOptions options;
    BatchList list;
    std::vector<BatchStill> stills;
    std::string model;
    std::string set;
};

TEST_F(Dataset, TheDigestIgnoresFlagOrderAndRunFlagsButNotTheSettings) {
    const std::vector<std::string> base = {model,       "--size", "64x64", "--lines",          "contour",
                                           "--dataset", set,      "-o",    set + "/{name}.png"};
    const std::string digest = digestOf(base);
    EXPECT_EQ(digest.size(), 16u);
    EXPECT_EQ(digestOf({"--lines", "contour", "-o", set + "/{name}.png", model, "--dataset", set, "--size", "64x64"}),
              digest)
        << "flag order";
    EXPECT_EQ(
        digestOf({model, "--output", set + "/{name}.png", "--size", "64x64", "--lines", "contour", "--dataset", set}),
        digest)
        << "-o and --output are one flag";
    EXPECT_EQ(digestOf({model, "--size=64x64", "--lines=contour", "--dataset=" + set, "-o", set + "/{name}.png"}),
              digest)
        << "--size=64x64 is --size 64x64";
    std::vector<std::string> quiet = base;
    quiet.insert(quiet.end(), {"-q", "--memory-limit", "2048", "--egl-platform", "surfaceless", "--jobs", "3",
                               "--draw-threads", "2"});
    EXPECT_EQ(digestOf(quiet), digest) << "flags that change how the run goes, not what it writes";
    std::vector<std::string> larger = base;
    larger[2] = "65x64";
    EXPECT_NE(digestOf(larger), digest) << "--size";
    std::vector<std::string> renamed = base;
    renamed.back() = set + "/{name}-2.png";
    EXPECT_NE(digestOf(renamed), digest) << "the output path";
    // A model changed in place (its size and modification time) renders again.
    write(model, "v 0 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_NE(digestOf(base), digest) << "the model file";
}

TEST_F(Dataset, TheDigestHoldsTheViewAndItsSeed) {
    const std::vector<std::string> base = {
        model, "--views", "2", "--seed", "3", "--dataset", set, "-o", set + "/{name}-{view}.png"};
    auto run = runOf(base);
    ASSERT_EQ(stills.size(), 2u);
    const auto digestOfView = [&](std::size_t view) {
        const BatchStill& still = stills[view];
        return run->settingsDigest({still.model.path, still.model.position, still.viewIndex},
                                   stillOptions(options, still, list.total));
    };
    const std::string first = digestOfView(0), second = digestOfView(1);
    EXPECT_NE(first, second) << "each view is its own still";
    run.reset(); // one run of a split at a time
    std::vector<std::string> otherSeed = base;
    otherSeed[4] = "4";
    EXPECT_NE(digestOf(otherSeed), first) << "--seed";
    EXPECT_EQ(digestOf(base), first) << "the same seed, the same digest";
}

TEST_F(Dataset, OutputsOutsideTheFolderAndItsOwnFilesAreRefused) {
    EXPECT_NE(usageError({model, "--dataset", set, "-o", (directory / "x.png").string()})
                  .find("-o '" + (directory / "x.png").string() + "' lies outside --dataset '" + set + "'"),
              std::string::npos);
    EXPECT_NE(usageError({model, "--dataset", set, "-o", set + "/a.png", "--stats", set + "/../s.json"})
                  .find("--stats '" + set + "/../s.json' lies outside"),
              std::string::npos);
    EXPECT_NE(usageError({model, "--dataset", set, "-o", set + "/.inkgraph/a.png"})
                  .find("is a file of the data set itself (.inkgraph)"),
              std::string::npos);
    EXPECT_NE(usageError({model, "--dataset", set, "-o", set + "/a.png", "--stats", set + "/index.jsonl"})
                  .find("--stats '" + set + "/index.jsonl' is a file of the data set itself (index.jsonl)"),
              std::string::npos);
    EXPECT_EQ(usageError({model, "--dataset", set, "-o", set + "/a.png"}), "");
    EXPECT_TRUE(fs::is_directory(set)) << "a new DIR is made";
    // An output inside DIR that is a link leading out of it is named as the link it is.
    fs::create_symlink("/dev/zero", fs::path(set) / "zero.json");
    EXPECT_NE(usageError({model, "--dataset", set, "-o", set + "/a.png", "--stats", set + "/zero.json"})
                  .find("--stats '" + set + "/zero.json' is a link to '/dev/zero', outside --dataset '" + set +
                        "'; every output of a data set is a file inside it: remove the link"),
              std::string::npos);
}

TEST_F(Dataset, ANameThatIsNotUtf8IsRefusedBeforeAnythingIsMade) {
    // The index and the card are JSON: such a name was recorded with U+FFFD in place of its bytes, so check-dataset
    // missed the file and --resume rendered it again on every run.
    const std::string model8 = write(directory / "bad\xff.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(usageError({model8, "--dataset", set, "-o", set + "/{name}.png"}),
              "--dataset '" + set + "': the model '" + model8 +
                  "' is not UTF-8, and the data set's index and card (JSON) hold UTF-8 text only: rename it");
    EXPECT_EQ(usageError({model, "--dataset", set, "-o", set + "/a\xfe.png"}),
              "--dataset '" + set + "': -o '" + set +
                  "/a\xfe.png' is not UTF-8, and the data set's index and card (JSON) hold UTF-8 text only: rename it");
    EXPECT_NE(usageError({model, "--dataset", set, "-o", set + "/a.png", "--frame", "x\xc3"})
                  .find("the argument 'x\xc3' is not UTF-8"),
              std::string::npos);
    EXPECT_FALSE(fs::exists(set)) << "a refused run makes no DIR";
    // UTF-8 beyond ASCII is a name like any other.
    EXPECT_EQ(usageError({model, "--dataset", set, "-o", set + "/\xc3\xa9t\xc3\xa9.png"}), "");
}

TEST_F(Dataset, AnExistingDataSetNeedsResume) {
    for (const std::string name : {"index.jsonl", "README.md", ".inkgraph/journal.jsonl"}) {
        fs::remove_all(set);
        write(fs::path(set) / name, "");
        EXPECT_NE(usageError({model, "--dataset", set, "-o", set + "/a.png"})
                      .find("already holds a data set ('" + name + "'); add --resume"),
                  std::string::npos)
            << name;
        EXPECT_EQ(usageError({model, "--dataset", set, "-o", set + "/a.png", "--resume"}), "") << name;
    }
    // A sharded run into an unsharded data set, resumed or not: one layout per folder.
    fs::remove_all(set);
    write(fs::path(set) / "index.jsonl", "");
    EXPECT_NE(usageError({model, "--dataset", set, "-o", set + "/a.png", "--shard", "0/2", "--resume"})
                  .find("made without --shard ('index.jsonl'), this run is with --shard K/2"),
              std::string::npos);
    // Another shard's files are that shard's: this one starts afresh beside them.
    fs::remove_all(set);
    write(fs::path(set) / "index-1-of-2.jsonl", "");
    EXPECT_EQ(usageError({model, "--dataset", set, "-o", set + "/a.png", "--shard", "0/2"}), "");
}

TEST_F(Dataset, AnotherSplitIsRefusedResumedOrNotNamingTheFile) {
    const struct {
        std::string file;
        std::vector<std::string> shard; // this run's
        std::string message;            // empty: accepted
    } cases[] = {
        {"index-1-of-2.jsonl",
         {"--shard", "0/3"},
         "made with --shard K/2 ('index-1-of-2.jsonl'), this run is with "
         "--shard K/3"},
        {"README-1-of-2.md", {"--shard", "0/3"}, "made with --shard K/2 ('README-1-of-2.md')"},
        {".inkgraph/journal-1-of-2.jsonl", {"--shard", "0/3"}, "('.inkgraph/journal-1-of-2.jsonl')"},
        {"README-1-of-2.md", {}, "made with --shard K/2 ('README-1-of-2.md'), this run is without --shard"},
        {".inkgraph/journal-0-of-2.jsonl", {}, "made with --shard K/2 ('.inkgraph/journal-0-of-2.jsonl')"},
        {".inkgraph/journal.jsonl", {"--shard", "1/2"}, "made without --shard ('.inkgraph/journal.jsonl')"},
        {"index-old.jsonl", {}, "made by another run ('-old') ('index-old.jsonl')"},
        {".inkgraph/journal-1-of-2.jsonl", {"--shard", "0/2"}, ""}, // the same split: another shard's own
        {"README-notes.md", {}, ""},                                // not a card of any split
    };
    for (const auto& test : cases)
        for (const bool resume : {false, true}) {
            fs::remove_all(set);
            write(fs::path(set) / test.file, "");
            std::vector<std::string> arguments = {model, "--dataset", set, "-o", set + "/a.png"};
            arguments.insert(arguments.end(), test.shard.begin(), test.shard.end());
            if (resume) arguments.push_back("--resume");
            const std::string error = usageError(arguments);
            if (test.message.empty())
                EXPECT_EQ(error, "") << test.file;
            else
                EXPECT_NE(error.find(test.message), std::string::npos) << test.file << ": " << error;
        }
}

TEST_F(Dataset, ASecondRunOfTheSameSplitIsRefusedWhileTheFirstRuns) {
    // Two runs of one split at once (a requeued array task beside the one it replaces) interleaved their journals and
    // left a set check-dataset rejected: the second is refused now, and the first finishes alone.
    const std::vector<std::string> arguments = {model, "--dataset", set, "-o", set + "/a.png", "--resume"};
    auto first = runOf(arguments);
    const fs::path lock = fs::path(set) / ".inkgraph" / "lock";
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(lock)));
    std::string refusal;
    try {
        runOf(arguments);
    } catch (const FileError& error) {
        refusal = error.what();
    }
    EXPECT_NE(refusal.find("DatasetRun: --dataset '" + set +
                           "' is being written by another inkgraph run; wait until it has finished, then --resume"),
              std::string::npos)
        << refusal;
    const std::vector<std::string> during = checkDataset(set).errors;
    EXPECT_NE(
        std::find(during.begin(), during.end(),
                  "'.inkgraph/lock': an inkgraph run is writing this data set now; check it when it has finished"),
        during.end())
        << ::testing::PrintToString(during);
    // The shards of one split run at once by design: each has a lock of its own.
    const std::string shards = (directory / "shards").string();
    auto shard0 = runOf({model, "--dataset", shards, "-o", shards + "/a.png", "--shard", "0/2"});
    auto shard1 = runOf({model, "--dataset", shards, "-o", shards + "/b.png", "--shard", "1/2"});
    EXPECT_THROW(runOf({model, "--dataset", shards, "-o", shards + "/a.png", "--shard", "0/2", "--resume"}), FileError);

    std::ostringstream log;
    first->finish(log);
    EXPECT_FALSE(fs::exists(fs::symlink_status(fs::path(set) / ".inkgraph")))
        << "the lock file, and the emptied .inkgraph folder, go when the run finishes";
    EXPECT_NO_THROW(runOf(arguments)) << "the first run finished: --resume may continue it";
    first.reset();
    shard0.reset();
    EXPECT_TRUE(fs::is_regular_file(fs::path(shards) / ".inkgraph" / "lock-1-of-2")) << "shard 1's, still running";
    EXPECT_FALSE(fs::exists(fs::path(shards) / ".inkgraph" / "lock-0-of-2")) << "a run that ends lets go of its lock";

    // What a killed run leaves (its lock file, held by nobody) stops no one, and check-dataset does not mention it.
    fs::remove_all(set);
    write(fs::path(set) / ".inkgraph" / "lock", "");
    EXPECT_NO_THROW(runOf({model, "--dataset", set, "-o", set + "/a.png"}));
    write(fs::path(set) / ".inkgraph" / "lock", "");
    EXPECT_NO_THROW(runOf(arguments)->finish(log));
    for (const std::string& error : checkDataset(set).errors)
        EXPECT_EQ(error.find(".inkgraph"), std::string::npos) << error; // its index, of no still rendered, has others
}

TEST_F(Dataset, ARunThatFinishesJustBeforeTheLockIsTakenStopsNoOne) {
    // A finishing run removes the emptied .inkgraph folder; when it did so between another run's making it and
    // opening its lock there, that run failed with "No such file or directory" (exit 5; a shard then went missing).
    ::setenv("INKGRAPH_TEST_LOCK_FOLDER_REMOVED", "3", 1);
    std::unique_ptr<DatasetRun> run;
    EXPECT_NO_THROW(run = runOf({model, "--dataset", set, "-o", set + "/a.png", "--shard", "1/2"}));
    ::unsetenv("INKGRAPH_TEST_LOCK_FOLDER_REMOVED");
    EXPECT_TRUE(fs::is_regular_file(fs::path(set) / ".inkgraph" / "lock-1-of-2"));
    run.reset();
    EXPECT_FALSE(fs::exists(fs::path(set) / ".inkgraph")) << "made by this run, and empty: removed with its lock";
}

TEST_F(Dataset, ARunRefusedAfterTakingTheLockLeavesTheFolderAsItWas) {
    // A --resume run of a finished data set refused once its lock was taken (a memory limit too low for a still)
    // made and removed .inkgraph, nothing else, and DIR's modification time said the set had changed.
    write(fs::path(set) / "index.jsonl", "");
    write(fs::path(set) / "README.md", "");
    const std::vector<std::string> arguments = {model, "--dataset", set, "-o", set + "/a.png", "--resume"};
    const fs::file_time_type before = fs::file_time_type::clock::now() - std::chrono::hours(1);
    fs::last_write_time(set, before);
    auto refused = runOf(arguments);
    EXPECT_TRUE(fs::is_regular_file(fs::path(set) / ".inkgraph" / "lock"));
    refused.reset(); // let go of without finishing, as a refused run is
    EXPECT_FALSE(fs::exists(fs::symlink_status(fs::path(set) / ".inkgraph")));
    EXPECT_EQ(fs::last_write_time(set), before) << "DIR's modification time changed by a run that changed nothing";
    // A run that changed DIR otherwise, or made a folder of its outputs, leaves DIR's new time.
    auto writing = runOf(arguments);
    write(fs::path(set) / "a.png", "");
    writing.reset();
    EXPECT_NE(fs::last_write_time(set), before);
    fs::last_write_time(set, before);
    auto making = runOf({model, "--dataset", set, "-o", set + "/views/a.png", "--resume"});
    making->makeOutputFolders(stillOptions(options, stills.front(), list.total));
    making.reset();
    EXPECT_TRUE(fs::is_directory(fs::path(set) / "views"));
    EXPECT_NE(fs::last_write_time(set), before);
}

TEST_F(Dataset, AnEditedPoseFileOfAListRendersAgain) {
    const std::string pose = write(directory / "wave.json", R"({"leftUpperArm": [0, 0, 0, 1]})");
    const std::vector<std::string> arguments = {model,
                                                "--views",
                                                "2",
                                                "--seed",
                                                "1",
                                                "--poses",
                                                "rest," + pose,
                                                "--dataset",
                                                set,
                                                "-o",
                                                set + "/{name}-{view}.png"};
    const std::string digest = digestOf(arguments);
    EXPECT_EQ(digestOf(arguments), digest);
    write(pose, R"({"leftUpperArm": [0, 0, 0.3826834, 0.9238795]})");
    EXPECT_NE(digestOf(arguments), digest) << "a file of --poses' list";
}

TEST_F(Dataset, TheDigestHoldsTheListLength) {
    const std::string other = write(directory / "other.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string listFile = write(directory / "list.txt", model + "\n");
    const std::vector<std::string> arguments = {"--list", listFile, "--dataset", set, "-o", set + "/{name}.png"};
    const std::string digest = digestOf(arguments);
    write(listFile, model + "\n" + other + "\n");
    EXPECT_NE(digestOf(arguments), digest) << "--stats' batch.list_length of the first still changed";
}

TEST_F(Dataset, RecordsOfWrongTypesAreAbsent) {
    const std::vector<std::string> arguments = {model, "--dataset", set, "-o", set + "/{name}.png", "--resume"};
    const std::string digest = digestOf(arguments);
    write(fs::path(set) / "cube.png", "picture");
    const std::string hash = hexDigits(fnv1a64("picture", 7));
    const auto line = [&](const std::string& size, const std::string& checksum, const std::string& files) {
        return R"({"model":")" + model + R"(","position":0,"view":0,"status":"ok","settings_digest":")" + digest +
               R"(","checksums":{"cube.png":{"size":)" + size + R"(,"fnv1a64":)" + checksum + R"(}},"files":)" + files +
               "}\n";
    };
    const fs::path journal = fs::path(set) / ".inkgraph" / "journal.jsonl";
    for (const std::string& edited :
         {line("\"7\"", "\"" + hash + "\"", "{}"), line("7", "7", "{}"), line("-7", "\"" + hash + "\"", "{}"),
          line("7", "\"" + hash + "\"", R"({"--dump": 5})"), line("7", "\"" + hash + "\"", "[]")}) {
        write(journal, edited);
        std::unique_ptr<DatasetRun> run;
        ASSERT_NO_THROW(run = runOf(arguments)) << edited;
        EXPECT_FALSE(run->isComplete({model, 0, 0}, digest)) << edited;
        std::ostringstream log;
        EXPECT_NO_THROW(run->finish(log)) << edited;
        fs::remove(fs::path(set) / "index.jsonl");
        fs::remove(fs::path(set) / "README.md");
    }
    // The same line with the right types: complete.
    write(journal, line("7", "\"" + hash + "\"", "{}"));
    EXPECT_TRUE(runOf(arguments)->isComplete({model, 0, 0}, digest));
}

TEST_F(Dataset, FinishSweepsOnlyThisMachinesDeadTemporaries) {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ASSERT_GT(child, 0);
    ASSERT_EQ(::waitpid(child, nullptr, 0), child);
    const std::string host = temporaryTag().substr(0, temporaryTag().find('-'));
    const std::string otherHost = host == "00000000" ? "00000001" : "00000000";
    const fs::path sub = fs::path(set) / "sub";
    const std::string dead = write(sub / (".inkgraph-" + host + "-" + std::to_string(child) + "-0.tmp"), "x");
    const std::string live = write(sub / (".inkgraph-" + temporaryTag() + "-0.tmp"), "x");
    // Another node's (an array task writing into the same DIR): its pid means nothing here, whatever runs here.
    const std::string remote = write(sub / (".inkgraph-" + otherHost + "-" + std::to_string(child) + "-0.tmp"), "x");
    const std::string oldName = write(sub / (".inkgraph-" + std::to_string(child) + "-0.tmp"), "x");
    const fs::path remoteStaging = sub / (".inkgraph-dump-" + otherHost + "-" + std::to_string(child) + "-0");
    write(remoteStaging / ".inkgraph-staging", "");
    write(remoteStaging / "final.png", "live");
    auto run = runOf({model, "--dataset", set, "-o", set + "/{name}.png"});
    std::ostringstream log;
    run->finish(log);
    EXPECT_FALSE(fs::exists(dead)) << "this machine's, of a process that is gone";
    EXPECT_TRUE(fs::exists(live)) << "this process's own";
    EXPECT_TRUE(fs::exists(remote));
    EXPECT_TRUE(fs::exists(oldName)) << "no host: nobody's to sweep";
    EXPECT_TRUE(fs::exists(remoteStaging / "final.png"));
}

TEST_F(Dataset, ATornJournalLineIsIgnoredAndCutOff) {
    const std::vector<std::string> arguments = {model, "--dataset", set, "-o", set + "/{name}.png", "--resume"};
    const std::string digest = digestOf(arguments);
    write(fs::path(set) / "cube.png", "picture");
    const std::string good = R"({"model":")" + model + R"(","position":0,"view":0,"status":"ok","settings_digest":")" +
                             digest + R"(","checksums":{"cube.png":{"size":7,"fnv1a64":")" +
                             hexDigits(fnv1a64("picture", 7)) + "\"}}}\n";
    const fs::path journal = fs::path(set) / ".inkgraph" / "journal.jsonl";
    write(journal, "not json\n" + good + good.substr(0, good.size() / 2));
    auto run = runOf(arguments);
    EXPECT_EQ(fs::file_size(journal), std::string("not json\n").size() + good.size()) << "the torn tail cut off";
    EXPECT_TRUE(run->isComplete({model, 0, 0}, digest));
    EXPECT_FALSE(run->isComplete({model, 0, 0}, "0000000000000000")) << "another digest";
    EXPECT_FALSE(run->isComplete({model, 1, 0}, digest)) << "another key";
    // The file changed since: the still is not complete.
    write(fs::path(set) / "cube.png", "pictura");
    run.reset(); // one run of a split at a time
    auto again = runOf(arguments);
    EXPECT_FALSE(again->isComplete({model, 0, 0}, digest));
}

TEST_F(Dataset, CheckDatasetFindsEachKindOfProblem) {
    const fs::path folder = directory / "made";
    const std::string png =
        std::string("\x89PNG\r\n\x1a\n", 8) + "body" + std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12);
    write(folder / "a.png", png);
    const std::string line =
        R"({"model":"a.obj","position":0,"view":0,"seed":null,"status":"ok","files":{"-o":"a.png"},)"
        R"("checksums":{"a.png":{"size":)" +
        std::to_string(png.size()) + R"(,"fnv1a64":")" + hexDigits(fnv1a64(png.data(), png.size())) + "\"}}}\n";
    write(folder / "index.jsonl", line);
    write(folder / "README.md", "| models | 1 |\n| stills in the set | 1 |\n| failed | 0 |\n");
    DatasetReport report = checkDataset(folder);
    EXPECT_TRUE(report.errors.empty()) << report.errors.front();
    EXPECT_EQ(report.stills, 1u);
    EXPECT_EQ(report.files, 1u);

    write(folder / "stray.txt", "x");
    write(folder / "sub" / ".inkgraph-99999999-0.tmp", "x");
    write(folder / ".inkgraph" / "journal.jsonl", "");
    write(folder / "README.md", "| models | 1 |\n| views per model | 2 |\n| stills in the set | 2 |\n| failed | 0 |\n");
    write(folder / "a.png", png.substr(0, png.size() - 1));
    report = checkDataset(folder);
    ASSERT_EQ(report.errors.size(), 5u);
    EXPECT_EQ(report.errors[0], "'a.png' is a PNG cut short (no IEND last)");
    EXPECT_EQ(report.errors[1], "README.md says 1 models x 2 views, index.jsonl holds 1 stills");
    EXPECT_EQ(report.errors[2], "README.md says 2 stills in the set, index.jsonl holds 1");
    EXPECT_EQ(report.errors[3], "'.inkgraph/journal.jsonl': a run that did not finish; run it again with --resume");
    EXPECT_EQ(report.errors[4],
              "'sub/.inkgraph-99999999-0.tmp': a temporary file of a run that was killed or is running");
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_EQ(report.warnings[0], "'stray.txt' is not in the index");
    EXPECT_EQ(report.files, 0u) << "a file cut short is not verified";

    // Sharded: every K of N.
    const fs::path shards = directory / "shards";
    write(shards / "index-0-of-3.jsonl", "");
    write(shards / "README-0-of-3.md", "| models | 0 |\n| stills in the set | 0 |\n| failed | 0 |\n");
    write(shards / "index-2-of-3.jsonl", "{\n");
    write(shards / "README-2-of-3.md", "| models | 0 |\n| stills in the set | 0 |\n| failed | 0 |\n");
    report = checkDataset(shards);
    ASSERT_EQ(report.errors.size(), 2u);
    EXPECT_EQ(report.errors[0], "shard 1 of 3 is missing (index-1-of-3.jsonl): that task has not finished");
    EXPECT_EQ(report.errors[1], "index-2-of-3.jsonl line 1: not a JSON object");

    // Hostile names: each one error, no crash and no million errors.
    for (const std::string name :
         {"index-99999999999-of-2.jsonl", "index-0-of-999999999.jsonl", "index-0-of-1000001.jsonl",
          "index-2-of-2.jsonl", "index-0-of-0.jsonl", "index-01-of-2.jsonl"}) {
        const fs::path hostile = directory / ("hostile-" + name);
        write(hostile / name, "");
        report = checkDataset(hostile);
        ASSERT_EQ(report.errors.size(), 2u) << name;
        EXPECT_EQ(report.errors[0], "'" + name +
                                        "': not an index inkgraph writes (index-K-of-N.jsonl with 0 <= K < N <= "
                                        "1000000, as --shard takes them)");
        EXPECT_EQ(report.errors[1], "no index.jsonl (or index-K-of-N.jsonl): not a finished data set");
    }
    // Many shards missing: the first 20 by name, then one line.
    const fs::path many = directory / "many";
    write(many / "index-0-of-1000000.jsonl", "");
    write(many / "README-0-of-1000000.md", "| models | 0 |\n| stills in the set | 0 |\n| failed | 0 |\n");
    report = checkDataset(many);
    ASSERT_EQ(report.errors.size(), 21u);
    EXPECT_EQ(report.errors[0], "shard 1 of 1000000 is missing (index-1-of-1000000.jsonl): that task has not finished");
    EXPECT_EQ(report.errors[20], "and 999979 more shards of 1000000 are missing");
    // A card count too large for any integer: a mismatch, not a crash.
    write(folder / "README.md", "| models | 99999999999999999999999 |\n| stills in the set | 1 |\n| failed | 0 |\n");
    EXPECT_NO_THROW(report = checkDataset(folder));
}

TEST_F(Dataset, ItsOwnFilesMustBePlainFilesAndLinksLeadNowhere) {
    const std::vector<std::string> arguments = {model, "--dataset", set, "-o", set + "/{name}.png", "--resume"};
    const fs::path journalFolder = fs::path(set) / ".inkgraph";
    const fs::path journalPath = journalFolder / "journal.jsonl";
    const auto fileError = [&] {
        try {
            runOf(arguments);
        } catch (const FileError& error) {
            return std::string(error.what());
        }
        return std::string();
    };
    const auto readText = [](const std::string& path) {
        std::ostringstream text;
        text << std::ifstream(path, std::ios::binary).rdbuf();
        return text.str();
    };
    // A FIFO in the journal's or the index's place: refused at once (a read of it waited forever).
    fs::create_directories(journalPath.parent_path());
    ASSERT_EQ(::mkfifo(journalPath.c_str(), 0644), 0);
    EXPECT_NE(fileError().find("journal.jsonl' is not a plain file"), std::string::npos) << fileError();
    fs::remove(journalPath);
    const fs::path index = fs::path(set) / "index.jsonl";
    fs::create_symlink("/dev/zero", index); // read whole, it filled the memory
    EXPECT_NE(fileError().find("index.jsonl' is not a plain file"), std::string::npos) << fileError();
    fs::remove(index);
    // A FIFO as the card: refused before the run, so the index (written first at the end) is not replaced either.
    write(index, "earlier index\n");
    const fs::path card = fs::path(set) / "README.md";
    ASSERT_EQ(::mkfifo(card.c_str(), 0644), 0);
    EXPECT_NE(fileError().find("README.md' is not a plain file"), std::string::npos) << fileError();
    EXPECT_EQ(readText(index.string()), "earlier index\n");
    fs::remove(card);
    fs::remove(index);

    // A journal linked to a file outside the set: neither cut nor appended to.
    const std::string victim = write(directory / "victim.txt", "keep\nno newline at the end");
    fs::create_symlink(victim, journalPath);
    EXPECT_NE(fileError().find("not a plain file"), std::string::npos);
    EXPECT_EQ(readText(victim), "keep\nno newline at the end");
    fs::remove(journalPath);
    fs::remove(journalFolder);

    // The journal's folder linked to another folder: its journal is neither read nor removed.
    const fs::path elsewhere = directory / "elsewhere";
    const std::string theirs = write(elsewhere / "journal.jsonl", "{}\n");
    fs::create_symlink(elsewhere, journalFolder);
    EXPECT_NE(fileError().find("/.inkgraph' is a link"), std::string::npos) << fileError();
    EXPECT_EQ(readText(theirs), "{}\n");
}

TEST_F(Dataset, CheckDatasetReportsFieldsOfTheWrongTypeAndFilesThatAreNotPlain) {
    const fs::path folder = directory / "typed";
    const std::string png =
        std::string("\x89PNG\r\n\x1a\n", 8) + "body" + std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12);
    write(folder / "a.png", png);
    write(folder / "README.md", "| models | 1 |\n| stills in the set | 1 |\n| failed | 0 |\n");
    // The size as a string: an uncaught type error ended check-dataset with SIGABRT.
    write(folder / "index.jsonl", R"({"model":"a.obj","position":0,"view":0,"status":"ok","files":{"-o":"a.png"},)"
                                  R"("checksums":{"a.png":{"size":"7","fnv1a64":"x"}}})"
                                  "\n");
    DatasetReport report = checkDataset(folder);
    ASSERT_FALSE(report.errors.empty());
    EXPECT_EQ(report.errors[0].rfind("index.jsonl line 1: a field of the wrong type", 0), 0u) << report.errors[0];
    write(folder / "index.jsonl", R"({"model":"a.obj","position":0,"view":0,"status":"failed","error":5})"
                                  "\n");
    EXPECT_NO_THROW(report = checkDataset(folder));

    // A FIFO in a listed file's place: named as such, not read (the read blocked).
    fs::remove(folder / "a.png");
    ASSERT_EQ(::mkfifo((folder / "a.png").c_str(), 0644), 0);
    write(folder / "index.jsonl", R"({"model":"a.obj","position":0,"view":0,"status":"ok","files":{"-o":"a.png"},)"
                                  R"("checksums":{"a.png":{"size":7,"fnv1a64":"x"}}})"
                                  "\n");
    report = checkDataset(folder);
    ASSERT_FALSE(report.errors.empty());
    EXPECT_EQ(report.errors[0].rfind("'a.png' is not a plain file", 0), 0u) << report.errors[0];
    // A FIFO in the index's place.
    fs::remove(folder / "index.jsonl");
    ASSERT_EQ(::mkfifo((folder / "index.jsonl").c_str(), 0644), 0);
    report = checkDataset(folder);
    ASSERT_FALSE(report.errors.empty());
    EXPECT_NE(report.errors[0].find("index.jsonl' is not a plain file"), std::string::npos) << report.errors[0];
    // A FIFO as a split's lock: every run of the set refuses it, so the set is not whole.
    fs::create_directories(folder / ".inkgraph");
    ASSERT_EQ(::mkfifo((folder / ".inkgraph" / "lock").c_str(), 0644), 0);
    const std::vector<std::string> errors = checkDataset(folder).errors;
    EXPECT_NE(std::find(errors.begin(), errors.end(),
                        "'.inkgraph/lock': not a plain file (a link, a FIFO, a device or a folder); every run of the "
                        "set refuses it: remove it"),
              errors.end())
        << ::testing::PrintToString(errors);
}

} // namespace
} // namespace inkgraph
