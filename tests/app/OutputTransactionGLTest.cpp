// The output transaction (app/OutputFiles.h, app/DumpFolder.h) through the real executable: outputs are regular files
// or new names, never a file the run reads; -o, --stats and --dump are committed together or not at all, at every
// step of the commit (test hooks INKGRAPH_TEST_COMMIT_FAIL / _KILL); a crash at any step leaves each output whole, old
// or new, and the next run recovers; a dump folder in use is refused; a planted manifest never deletes anything.
#include "CliTestSupport.h"
#include "render/TemporaryFiles.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <linux/fs.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace inkgraph {
namespace {

using test::Cli;
using test::CliRun;
using test::readText;
namespace fs = std::filesystem;

using Snapshot = std::map<std::string, std::string>;

/** Width and height from a PNG's header (IHDR), or 0x0 when the bytes are not a whole PNG's start. */
std::pair<std::uint32_t, std::uint32_t> pngSize(const std::string& bytes) {
    if (bytes.size() < 24 || bytes.compare(1, 3, "PNG") != 0) return {0, 0};
    const auto bigEndian = [&](std::size_t at) {
        std::uint32_t value = 0;
        for (std::size_t i = 0; i < 4; ++i) value = value << 8 | std::uint8_t(bytes[at + i]);
        return value;
    };
    return {bigEndian(16), bigEndian(20)};
}

class OutputTransaction : public Cli {
protected:
    /** Renders the bundled cow into `folder` at `side`² with -o, --stats and --dump. */
    CliRun renderInto(const fs::path& folder, int side, const std::string& environment = "") {
        const std::string size = std::to_string(side) + "x" + std::to_string(side);
        return run("render " + model("spot_c3d.obj") + " --lines none --size " + size + " -o '" +
                       (folder / "out.png").string() + "' --stats '" + (folder / "s.json").string() + "' --dump '" +
                       (folder / "d").string() + "'",
                   environment);
    }

    /** An earlier run's outputs (32²) in `old/`, kept as the state each hooked run starts from. */
    void makeEarlierOutputs() {
        fs::create_directories(directory / "old");
        const CliRun earlier = renderInto(directory / "old", 32);
        ASSERT_EQ(earlier.exitCode, 0) << earlier.err;
        oldState = snapshot(directory / "old");
    }

    /** work/ as old/ left it. */
    void resetWork() {
        fs::remove_all(directory / "work");
        fs::copy(directory / "old", directory / "work", fs::copy_options::recursive);
        ASSERT_EQ(snapshot(directory / "work"), oldState);
    }

    Snapshot oldState;
};

/** A pid that is surely gone: a child that has exited and been reaped (-1 when fork fails). */
pid_t goneProcess() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    if (child > 0) ::waitpid(child, nullptr, 0);
    return child;
}

/** Each test runs on this file system's RENAME_EXCHANGE and on the two renames of file systems without it (NFS). */
const char* const kSwapModes[] = {"", "INKGRAPH_TEST_NO_RENAME_EXCHANGE=1 "};

TEST_F(OutputTransaction, AFailureAtAnyCommitStepChangesNothing) {
    makeEarlierOutputs();
    for (const std::string mode : kSwapModes) {
        int steps = 0;
        for (int step = 1; step < 30; ++step) {
            SCOPED_TRACE(mode + "failed after step " + std::to_string(step));
            resetWork();
            const CliRun result =
                renderInto(directory / "work", 48, mode + "INKGRAPH_TEST_COMMIT_FAIL=" + std::to_string(step));
            if (result.exitCode == 0) break; // past the commit point: nothing left to fail
            ++steps;
            EXPECT_EQ(result.exitCode, 5) << result.err;
            EXPECT_NE(result.err.find("test hook: failed after commit step " + std::to_string(step)), std::string::npos)
                << result.err;
            // Every file as it was, byte for byte, and nothing beside them: not a temporary, not a staging folder.
            EXPECT_EQ(snapshot(directory / "work"), oldState);
        }
        // staged, earlier dump marked, earlier -o and --stats kept, dump swapped in, -o and --stats moved.
        EXPECT_EQ(steps, 7);
    }
}

TEST_F(OutputTransaction, ABatchRerunLeavesItsNewPicturesAndNoSecondNames) {
    // A rerun replaces each picture; the commit keeps the old one under a second name until it is in place, and a
    // pipelined batch removes those names on another thread (app/Render.cpp): when the run ends they are all gone.
    const fs::path models = fs::path(INKGRAPH_SOURCE_ROOT) / "models";
    std::ofstream(directory / "models.txt") << (models / "spot_c3d.obj").string() << "\n"
                                            << (models / "cow_c3d.obj").string() << "\n"
                                            << (models / "fandisk_c3d.obj").string() << "\n";
    for (const char* jobs : {"2", "0"}) {
        SCOPED_TRACE(std::string("--jobs ") + jobs);
        const fs::path folder = directory / (std::string("jobs") + jobs);
        fs::create_directories(folder);
        for (const int side : {32, 48}) {
            const std::string size = std::to_string(side) + "x" + std::to_string(side);
            const CliRun batch = run("render --list models.txt --lines none --size " + size + " -q --jobs " + jobs +
                                     " -o '" + (folder / "{index}.png").string() + "'");
            ASSERT_EQ(batch.exitCode, 0) << batch.err;
        }
        const Snapshot files = snapshot(folder);
        ASSERT_EQ(files.size(), 3u) << "only the three pictures: no second name left";
        for (const auto& [name, entry] : files) {
            EXPECT_TRUE(name == "1.png" || name == "2.png" || name == "3.png") << name;
            ASSERT_EQ(entry.rfind("file: ", 0), 0u) << name;
            EXPECT_EQ(pngSize(entry.substr(6)), std::make_pair(std::uint32_t(48), std::uint32_t(48))) << name;
        }
    }
}

TEST_F(OutputTransaction, ACrashAtAnyCommitStepLeavesEachOutputWholeAndTheNextRunRecovers) {
    makeEarlierOutputs();
    for (const std::string mode : kSwapModes) {
        int crashes = 0;
        for (int step = 1; step < 30; ++step) {
            SCOPED_TRACE(mode + "killed after step " + std::to_string(step));
            resetWork();
            const fs::path work = directory / "work";
            const CliRun result = renderInto(work, 48, mode + "INKGRAPH_TEST_COMMIT_KILL=" + std::to_string(step));
            if (result.exitCode == 0) break; // the hook's step lies past the last one
            ++crashes;
            EXPECT_NE(result.err.find("test hook: killed after commit step " + std::to_string(step)), std::string::npos)
                << result.err;
            const Snapshot after = snapshot(work);

            // -o and --stats: each the old file or the new one, whole.
            const std::string picture = readText(work / "out.png");
            EXPECT_TRUE(picture == readText(directory / "old" / "out.png") ||
                        pngSize(picture) == std::make_pair(48u, 48u));
            const auto stats = nlohmann::json::parse(readText(work / "s.json"));
            EXPECT_TRUE(stats["size"] == nlohmann::json::array({32, 32}) ||
                        stats["size"] == nlohmann::json::array({48, 48}));

            // The dump: the earlier one, byte for byte, or the new one, whole (the staging marker may be left in it).
            std::set<std::string> dumpFiles;
            for (const auto& entry : fs::directory_iterator(work / "d"))
                if (entry.path().filename() != ".inkgraph-staging") dumpFiles.insert(entry.path().filename().string());
            const auto manifest = nlohmann::json::parse(readText(work / "d" / "manifest.json"));
            if (manifest["size"] == nlohmann::json::array({32, 32})) {
                for (const std::string& name : dumpFiles)
                    EXPECT_EQ(after.at("d/" + name), oldState.at("d/" + name)) << name;
                std::set<std::string> oldFiles;
                for (const auto& entry : fs::directory_iterator(directory / "old" / "d"))
                    oldFiles.insert(entry.path().filename().string());
                EXPECT_EQ(dumpFiles, oldFiles);
            } else {
                EXPECT_EQ(manifest["size"], nlohmann::json::array({48, 48}));
                EXPECT_EQ(dumpFiles, (std::set<std::string>{"final.png", "manifest.json", "shading.png"}));
                EXPECT_EQ(pngSize(readText(work / "d" / "final.png")), std::make_pair(48u, 48u));
            }

            // The next run succeeds and sweeps whatever the crash left (the process that left it is gone).
            const CliRun next = renderInto(work, 48);
            ASSERT_EQ(next.exitCode, 0) << next.err;
            EXPECT_EQ(listFiles(work), (std::vector<std::string>{"d", "out.png", "s.json"}));
            EXPECT_EQ(listFiles(work / "d"), (std::vector<std::string>{"final.png", "manifest.json", "shading.png"}));
        }
        // The 7 steps that can fail, then the dump's tidying.
        EXPECT_EQ(crashes, 8);
    }
}

TEST_F(OutputTransaction, AFolderMovedAwayDuringTheCommitGetsItsFilesBackAndNoTemporaries) {
    // A user moving the output folder during a batch: the commit's next step by name fails, and what it had done is
    // undone in the folder where it now is (through the folders it was made in, held open), temporaries and the
    // dump's staging folder included. Before, they and the new files were left in the moved folder (temporaries in
    // 14 of 100 such batches; -o, --stats and --dump a mix of the two runs).
    makeEarlierOutputs();
    for (const std::string mode : kSwapModes)
        for (const bool withEarlierFiles : {true, false}) {
            int failures = 0;
            for (int step = 1; step < 30; ++step) {
                SCOPED_TRACE(mode + (withEarlierFiles ? "over earlier files" : "into an empty folder") +
                             ", moved after step " + std::to_string(step));
                const fs::path work = directory / "work", moved = directory / "work.moved";
                fs::remove_all(work);
                fs::remove_all(moved);
                if (withEarlierFiles)
                    fs::copy(directory / "old", work, fs::copy_options::recursive);
                else
                    fs::create_directories(work);
                const Snapshot before = snapshot(work);
                const CliRun result = renderInto(work, 48, mode + "INKGRAPH_TEST_COMMIT_MOVE=" + std::to_string(step));
                ASSERT_TRUE(fs::exists(moved)) << "the hook moved nothing";
                if (result.exitCode == 0) {
                    // Moved after the last step: committed, as a move after the run; nothing but the outputs.
                    EXPECT_EQ(listFiles(moved), (std::vector<std::string>{"d", "out.png", "s.json"}));
                    EXPECT_EQ(listFiles(moved / "d"),
                              (std::vector<std::string>{"final.png", "manifest.json", "shading.png"}));
                    break;
                }
                ++failures;
                EXPECT_EQ(result.exitCode, 5) << result.err;
                EXPECT_EQ(snapshot(moved), before) << "every file as it was, and nothing beside them";
            }
            // Moved before each later step by name: after staging, the earlier dump's mark (a step with no earlier
            // dump too), each earlier file kept (none in an empty folder), the dump's swap and -o's move.
            EXPECT_EQ(failures, withEarlierFiles ? 6 : 4);
        }
}

TEST_F(OutputTransaction, ADumpFolderRenamedDuringTheCommitKeepsNoMarker) {
    // The dump folder itself renamed by the user during the commit: its mark goes into the earlier dump and comes out
    // of it through the folder held open, wherever it is; by name, the mark stayed in the renamed dump.
    makeEarlierOutputs();
    const Snapshot earlierDump = snapshot(directory / "old" / "d");
    for (const std::string mode : kSwapModes) {
        int failures = 0;
        for (int step = 1; step < 30; ++step) {
            SCOPED_TRACE(mode + "renamed after step " + std::to_string(step));
            const fs::path work = directory / "work";
            fs::remove_all(work);
            fs::create_directories(work);
            fs::copy(directory / "old" / "d", work / "d", fs::copy_options::recursive);
            const CliRun result = run("render " + model("spot_c3d.obj") + " --lines none --size 48x48 --dump '" +
                                          (work / "d").string() + "'",
                                      mode + "INKGRAPH_TEST_COMMIT_MOVE=" + std::to_string(step));
            ASSERT_TRUE(fs::exists(work / "d.moved")) << "the hook renamed nothing";
            if (result.exitCode == 0) {
                // Renamed after the swap: the new dump, tidied, and the earlier one gone.
                EXPECT_EQ(listFiles(work), (std::vector<std::string>{"d.moved"}));
                EXPECT_EQ(listFiles(work / "d.moved"),
                          (std::vector<std::string>{"final.png", "manifest.json", "shading.png"}));
                break;
            }
            ++failures;
            EXPECT_EQ(result.exitCode, 5) << result.err;
            EXPECT_EQ(listFiles(work), (std::vector<std::string>{"d.moved"})) << "a staging folder was left";
            EXPECT_EQ(snapshot(work / "d.moved"), earlierDump) << "the renamed earlier dump changed";
        }
        EXPECT_EQ(failures, 2); // renamed after staging and after the mark: the swap by name finds no folder
    }
}

TEST_F(OutputTransaction, ACtrlCDuringTheCommitLandsAfterIt) {
    // The signal goes to the process; whichever thread takes it (the libraries' threads block none), the commit ends
    // first: every output new, then the process ends as SIGINT would have it, with nothing left behind.
    makeEarlierOutputs();
    for (int step = 1; step <= 8; ++step) {
        SCOPED_TRACE("interrupted after step " + std::to_string(step));
        resetWork();
        const fs::path work = directory / "work";
        const CliRun result = renderInto(work, 48, "INKGRAPH_TEST_COMMIT_INTERRUPT=" + std::to_string(step));
        // Ended by the signal (the shell that ran it reports 128 + SIGINT).
        EXPECT_TRUE(result.exitCode == 130 || result.exitCode == -1) << result.exitCode << ": " << result.err;
        EXPECT_EQ(pngSize(readText(work / "out.png")), std::make_pair(48u, 48u));
        EXPECT_EQ(nlohmann::json::parse(readText(work / "s.json"))["size"], nlohmann::json::array({48, 48}));
        EXPECT_EQ(pngSize(readText(work / "d" / "final.png")), std::make_pair(48u, 48u));
        EXPECT_EQ(listFiles(work), (std::vector<std::string>{"d", "out.png", "s.json"}));
        EXPECT_EQ(listFiles(work / "d"), (std::vector<std::string>{"final.png", "manifest.json", "shading.png"}));
    }
}

TEST_F(OutputTransaction, AMarkerThatIsNotAFileIsRefused) {
    // A link planted as the staging marker would have the commit create (or, for a FIFO, block on) a file elsewhere.
    ASSERT_EQ(run("render " + model("spot_c3d.obj") + " --size 16x16 --dump d").exitCode, 0);
    fs::create_directories(directory / "elsewhere");
    fs::create_symlink(directory / "elsewhere" / "made-by-the-commit", directory / "d" / ".inkgraph-staging");
    const Snapshot before = snapshot(directory);
    const CliRun result = run("render " + model("spot_c3d.obj") + " --size 16x16 --dump d");
    EXPECT_EQ(result.exitCode, 5);
    EXPECT_NE(result.err.find("its .inkgraph-staging is not a file inkgraph wrote"), std::string::npos) << result.err;
    EXPECT_EQ(snapshot(directory), before);
}

TEST_F(OutputTransaction, ADumpFolderInUseIsRefusedAtOnce) {
    makeEarlierOutputs();
    resetWork();
    // Another run holds the folder's lock, as a run does from its check until its commit ends.
    const int held = ::open((directory / "work" / "d").c_str(), O_RDONLY | O_DIRECTORY);
    ASSERT_GE(held, 0);
    ASSERT_EQ(::flock(held, LOCK_EX), 0);
    const CliRun result = renderInto(directory / "work", 48);
    ::close(held);
    EXPECT_EQ(result.exitCode, 5);
    EXPECT_NE(result.err.find("is being written by another inkgraph run"), std::string::npos) << result.err;
    EXPECT_EQ(snapshot(directory / "work"), oldState);
    EXPECT_EQ(renderInto(directory / "work", 48).exitCode, 0) << "once the lock is gone, the folder is usable";
}

TEST_F(OutputTransaction, DevicesFifosAndLinksToThemAreNeverReplaced) {
    fs::create_symlink("/dev/null", directory / "null.json");
    ASSERT_EQ(::mkfifo((directory / "pipe.svg").c_str(), 0644), 0);
    const Snapshot before = snapshot(directory);
    const CliRun device = run("render " + model("spot_c3d.obj") + " -o out.png --size 16x16 --stats null.json");
    EXPECT_EQ(device.exitCode, 5);
    EXPECT_NE(device.err.find("--stats 'null.json' is a character device"), std::string::npos) << device.err;
    const CliRun fifo =
        run("render " + model("spot_c3d.obj") + " -o out.png --size 16x16 --lines contour --svg pipe.svg");
    EXPECT_EQ(fifo.exitCode, 5);
    EXPECT_NE(fifo.err.find("--svg 'pipe.svg' is a FIFO"), std::string::npos) << fifo.err;
    EXPECT_EQ(snapshot(directory), before);
    struct stat status {};
    ASSERT_EQ(::stat("/dev/null", &status), 0);
    EXPECT_TRUE(S_ISCHR(status.st_mode));
}

TEST_F(OutputTransaction, OutputsThatAreInputsByAnyNameAreRefused) {
    // A hard link has its own name but the model's inode.
    fs::copy_file(fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "spot_c3d.obj", directory / "m.obj");
    fs::create_hard_link(directory / "m.obj", directory / "m-link.png");
    const Snapshot before = snapshot(directory);
    const CliRun link = run("render m.obj -o m-link.png --size 16x16");
    EXPECT_EQ(link.exitCode, 2);
    EXPECT_NE(link.err.find("-o 'm-link.png' is the model itself"), std::string::npos) << link.err;
    EXPECT_EQ(snapshot(directory), before);

    // A file in the dump folder the commit would replace, read by this run as its shade map.
    ASSERT_EQ(run("render m.obj --size 16x16 --dump d").exitCode, 0);
    const Snapshot dumped = snapshot(directory);
    const CliRun map = run("render m.obj --size 16x16 --dump d --shading cel --shademap d/final.png");
    EXPECT_EQ(map.exitCode, 2);
    EXPECT_NE(map.err.find("--dump 'd' holds 'final.png', which is the --shademap itself"), std::string::npos)
        << map.err;
    EXPECT_EQ(snapshot(directory), dumped);
}

TEST_F(OutputTransaction, APlantedManifestNeverDeletesAnything) {
    fs::create_directories(directory / "d");
    std::ofstream(directory / "victim.txt") << "precious";
    fs::create_symlink(directory / "victim.txt", directory / "d" / "link.png");
    const std::string absolute = (directory / "victim.txt").string();
    for (const std::string& name :
         {std::string("../victim.txt"), absolute, std::string("link.png"), std::string("."), std::string("")}) {
        SCOPED_TRACE(name);
        std::ofstream(directory / "d" / "manifest.json")
            << nlohmann::json({{"inkgraph", "0"}, {"files", {{{"file", name}}}}}).dump();
        const Snapshot before = snapshot(directory);
        const CliRun result = run("render " + model("spot_c3d.obj") + " -o out.png --size 16x16 --dump d");
        EXPECT_EQ(result.exitCode, 5);
        EXPECT_NE(result.err.find("holds files that are not an inkgraph dump"), std::string::npos) << result.err;
        EXPECT_EQ(snapshot(directory), before);
    }
}

TEST_F(OutputTransaction, StagingFoldersAreSweptOnlyByTheirMarker) {
    const pid_t child = goneProcess();
    ASSERT_GT(child, 0);
    // This machine's tag: the run below is on the same host; a name of another host's tag is never this run's to sweep.
    const std::string host = temporaryTag().substr(0, temporaryTag().find('-'));
    const std::string otherHost = host == "00000000" ? "00000001" : "00000000";
    const std::string dead = host + "-" + std::to_string(child);
    const std::string stale = ".inkgraph-dump-" + dead + "-0";
    const std::string otherHosts = ".inkgraph-dump-" + otherHost + "-" + std::to_string(child) + "-0";
    // Named like a staging folder of a dead run, but without the marker: someone else's, never touched.
    fs::create_directories(directory / (stale + "x"));
    std::ofstream(directory / (stale + "x") / "notes.txt") << "precious";
    // Without the marker but empty (killed between its mkdir and its marker): removed; unmarked with a file: kept.
    const std::string emptyStale = ".inkgraph-dump-" + dead + "-1";
    const std::string unmarked = ".inkgraph-dump-" + dead + "-2";
    fs::create_directories(directory / emptyStale);
    fs::create_directories(directory / unmarked);
    std::ofstream(directory / unmarked / "notes.txt") << "precious";
    // With the marker: a crashed run's staging folder, removed by the next run dumping beside it.
    fs::create_directories(directory / stale);
    std::ofstream(directory / stale / ".inkgraph-staging");
    std::ofstream(directory / stale / "final.png") << "half";
    // With the marker, but made on another machine (a shared folder): its pid means nothing here; kept.
    fs::create_directories(directory / otherHosts);
    std::ofstream(directory / otherHosts / ".inkgraph-staging");
    std::ofstream(directory / otherHosts / "final.png") << "live";
    // Temporary files: exactly ".inkgraph-<host>-<dead pid>-<n>.tmp" is a killed run's; anything else of that look,
    // or another host's, is not.
    const std::string otherTemporary = ".inkgraph-" + otherHost + "-" + std::to_string(child) + "-3.tmp";
    std::ofstream(directory / (".inkgraph-" + dead + "-3.tmp")) << "half";
    std::ofstream(directory / (".inkgraph-" + dead + "-notes.txt")) << "precious";
    std::ofstream(directory / otherTemporary) << "live";
    const CliRun result = run("render " + model("spot_c3d.obj") + " --size 16x16 --dump d -o out.png");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_FALSE(fs::exists(directory / stale));
    EXPECT_FALSE(fs::exists(directory / emptyStale));
    EXPECT_EQ(readText(directory / unmarked / "notes.txt"), "precious");
    EXPECT_FALSE(fs::exists(directory / (".inkgraph-" + dead + "-3.tmp")));
    EXPECT_EQ(readText(directory / (stale + "x") / "notes.txt"), "precious");
    EXPECT_EQ(readText(directory / (".inkgraph-" + dead + "-notes.txt")), "precious");
    EXPECT_EQ(readText(directory / otherHosts / "final.png"), "live");
    EXPECT_EQ(readText(directory / otherTemporary), "live");
}

/** Sets or clears an attribute (FS_IMMUTABLE_FL, FS_APPEND_FL: chattr +i, +a; root only) of the open file `file`;
 *  false when it cannot (not root, or a file system without attributes). */
bool setAttribute(int file, int attribute, bool on) {
    int attributes = 0;
    if (::ioctl(file, FS_IOC_GETFLAGS, &attributes) != 0) return false;
    attributes = on ? attributes | attribute : attributes & ~attribute;
    return ::ioctl(file, FS_IOC_SETFLAGS, &attributes) == 0;
}

/** Files made immutable or append-only for a test, cleared again when it ends, whatever happens: even root cannot
 *  remove them otherwise, nor the test's folder. Held open, so the attribute is cleared wherever a run moved them. */
class KeptInPlace {
public:
    KeptInPlace() = default;
    KeptInPlace(const KeptInPlace&) = delete;
    KeptInPlace& operator=(const KeptInPlace&) = delete;
    ~KeptInPlace() { clear(); }
    bool add(const fs::path& path, int attribute) {
        const int file = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
        if (file < 0) return false;
        if (!setAttribute(file, attribute, true)) {
            ::close(file);
            return false;
        }
        mFiles.emplace_back(file, attribute);
        return true;
    }
    void clear() {
        for (const auto& [file, attribute] : mFiles) {
            setAttribute(file, attribute, false);
            ::close(file);
        }
        mFiles.clear();
    }

private:
    std::vector<std::pair<int, int>> mFiles; ///< descriptor, attribute
};

TEST_F(OutputTransaction, AnEarlierDumpsFileThatCannotBeRemovedFailsBeforeAnyChange) {
    // Before, the commit swapped the new dump in, could not remove the immutable file from the earlier one, exited 0
    // and left a hidden staging folder no later run removed.
    makeEarlierOutputs();
    const fs::path work = directory / "work";
    for (const auto& [name, attribute, words] :
         {std::tuple<std::string, int, std::string>{"final.png", FS_IMMUTABLE_FL, "immutable (chattr +i)"},
          {"manifest.json", FS_APPEND_FL, "append-only (chattr +a)"}}) {
        SCOPED_TRACE(name);
        resetWork();
        KeptInPlace kept;
        if (!kept.add(work / "d" / name, attribute)) GTEST_SKIP() << "cannot set file attributes (root on ext4 can)";
        const CliRun result = renderInto(work, 48);
        EXPECT_EQ(result.exitCode, 5) << result.err;
        EXPECT_NE(result.err.find("--dump '" + (work / "d").string() + "' holds '" + name + "', which is " + words +
                                  ", and a dump removes the earlier dump's files; clear the attribute or give another "
                                  "folder"),
                  std::string::npos)
            << result.err;
        EXPECT_EQ(result.err.find("rendered"), std::string::npos) << "refused before any work";
        EXPECT_EQ(snapshot(work), oldState) << "no file changed, no staging folder left";
        kept.clear();
        EXPECT_EQ(renderInto(work, 48).exitCode, 0) << "once the attribute is cleared, the folder is usable";
    }
    // The folder itself: it is swapped out whole.
    resetWork();
    KeptInPlace kept;
    ASSERT_TRUE(kept.add(work / "d", FS_IMMUTABLE_FL));
    const CliRun folder = renderInto(work, 48);
    EXPECT_EQ(folder.exitCode, 5) << folder.err;
    EXPECT_NE(folder.err.find("--dump '" + (work / "d").string() + "' is immutable (chattr +i)"), std::string::npos)
        << folder.err;
    EXPECT_EQ(snapshot(work), oldState);
}

TEST_F(OutputTransaction, AStagingFolderWithAFileLeftIsSweptOnceItCanBe) {
    // A dead run's staging folder holding a file no one may remove yet: the sweep keeps its marker, so a later run
    // removes it once the file can go. Before, the sweep removed the marker alone and the folder stayed for good.
    const pid_t child = goneProcess();
    ASSERT_GT(child, 0);
    const fs::path stale = directory / (".inkgraph-dump-" + temporaryTag().substr(0, temporaryTag().find('-')) + "-" +
                                        std::to_string(child) + "-0");
    fs::create_directories(stale);
    std::ofstream(stale / ".inkgraph-staging");
    std::ofstream(stale / "final.png") << "an earlier dump's";
    std::ofstream(stale / "shading.png") << "an earlier dump's";
    KeptInPlace kept;
    if (!kept.add(stale / "final.png", FS_IMMUTABLE_FL)) GTEST_SKIP() << "cannot set file attributes (root can)";
    const std::string render = "render " + model("spot_c3d.obj") + " --size 16x16 --dump d -o out.png";
    const CliRun first = run(render);
    ASSERT_EQ(first.exitCode, 0) << first.err;
    EXPECT_EQ(listFiles(stale), (std::vector<std::string>{".inkgraph-staging", "final.png"}));
    kept.clear();
    const CliRun second = run(render);
    ASSERT_EQ(second.exitCode, 0) << second.err;
    EXPECT_FALSE(fs::exists(stale));
}

TEST_F(OutputTransaction, LongNamesFailBeforeRenderingOrNotAtAll) {
    // 255 bytes is the limit of ext4 and tmpfs; the temporary name must not grow with the final one's extension.
    const std::string longest = "s." + std::string(253, 'j');
    const CliRun fits = run("render " + model("spot_c3d.obj") + " -o out.png --size 16x16 --stats " + longest);
    EXPECT_EQ(fits.exitCode, 0) << fits.err;
    EXPECT_TRUE(fs::exists(directory / longest));
    const CliRun tooLong = run("render " + model("spot_c3d.obj") + " -o new.png --size 16x16 --stats " + longest + "j");
    EXPECT_EQ(tooLong.exitCode, 5);
    EXPECT_NE(tooLong.err.find("its file name is 256 bytes"), std::string::npos) << tooLong.err;
    EXPECT_EQ(tooLong.err.find("rendered"), std::string::npos) << "refused before any work";
    EXPECT_FALSE(fs::exists(directory / "new.png"));
}

TEST_F(OutputTransaction, EmptyShardAndUnwritableStandardOutput) {
    const CliRun empty = run("render " + model("spot_c3d.obj") + " -o out.png --size 16x16 --shard 1/2");
    EXPECT_EQ(empty.exitCode, 0) << empty.err;
    EXPECT_NE(empty.err.find("no models in this share (shard 1/2 of 1)"), std::string::npos) << empty.err;
    EXPECT_EQ(listFiles(directory), std::vector<std::string>{});

    // The plan is printed before the commit: a run whose output cannot be written puts no file in place either.
    const std::string command = "cd '" + directory.string() + "' && LP_NUM_THREADS=1 '" + INKGRAPH_EXECUTABLE +
                                "' render " + model("spot_c3d.obj") +
                                " --size 16x16 -o out.png --print-plan > /dev/full 2> err.txt";
    const int status = std::system(command.c_str());
    EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 5);
    EXPECT_NE(readText(directory / "err.txt").find("cannot write the standard output"), std::string::npos);
    EXPECT_FALSE(fs::exists(directory / "out.png"));
}

} // namespace
} // namespace inkgraph
