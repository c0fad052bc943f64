// What a signal leaves behind (render/TemporaryFiles.h): every temporary registered is removed, and a file that is
// being created when the signal comes is waited for and removed too, never left unregistered. Each case runs in a
// process of its own (a death test re-executes this binary), since the handling is installed once per process.
#include "render/TemporaryFiles.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <iterator>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace inkgraph {
namespace {

namespace fs = std::filesystem;

/** Creates `file` under a TemporaryCreation that the signal arrives during (sent by this thread, landing on the
 *  signal thread), then writes `finished` (not registered) once the creation is over, and waits to be ended. */
[[noreturn]] void createWhileASignalComes(const fs::path& file, const fs::path& finished) {
    removeTemporariesOnSignals();
    {
        const TemporaryCreation creating;
        ::kill(::getpid(), SIGINT);
        // Long enough that a removal which did not wait would have ended the process by now.
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        const int descriptor = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
        if (descriptor >= 0) ::close(descriptor);
        registerTemporary(file);
        std::ofstream(finished) << "created\n";
    }
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1)); // the signal ends the process here
}

TEST(TemporaryFilesOnSignals, ASignalWaitsForAFileBeingCreatedThenRemovesIt) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    // The threadsafe style runs this function again in the child it starts, up to the statement: the folder is named
    // by the test's own process, which is the child's parent.
    const bool inChild = !GTEST_FLAG_GET(internal_run_death_test).empty();
    const fs::path folder =
        fs::temp_directory_path() / ("inkgraph-temporaries-" + std::to_string(inChild ? ::getppid() : ::getpid()));
    if (!inChild) {
        fs::remove_all(folder);
        fs::create_directories(folder);
    }
    const fs::path file = folder / ".inkgraph-test.tmp";
    const fs::path finished = folder / "finished.txt";
    EXPECT_EXIT(createWhileASignalComes(file, finished), ::testing::KilledBySignal(SIGINT), "");
    EXPECT_TRUE(fs::exists(finished)) << "the process ended while a temporary was half made";
    EXPECT_FALSE(fs::exists(file)) << "the temporary made before the removal was left behind";
    fs::remove_all(folder);
}

std::string contents(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/** A folder of this test's own, named by the test process (the parent, in a death test's child). */
fs::path testFolder(const std::string& what) {
    const bool inChild = !GTEST_FLAG_GET(internal_run_death_test).empty();
    return fs::temp_directory_path() / ("inkgraph-" + what + "-" + std::to_string(inChild ? ::getppid() : ::getpid()));
}

/** Makes `file` (registered), moves its folder to `moved`, then stops the process with SIGTERM. */
[[noreturn]] void moveTheFolderThenStop(const fs::path& file, const fs::path& moved) {
    removeTemporariesOnSignals();
    const int descriptor = createTemporaryFile(file, 0644);
    if (descriptor >= 0) ::close(descriptor);
    ::rename(file.parent_path().c_str(), moved.c_str());
    ::kill(::getpid(), SIGTERM);
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1)); // the signal ends the process here
}

TEST(TemporaryFilesOnSignals, ATemporaryIsRemovedFromItsFolderMovedAway) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const fs::path root = testFolder("moved-on-signal");
    const bool inChild = !GTEST_FLAG_GET(internal_run_death_test).empty();
    if (!inChild) {
        fs::remove_all(root);
        fs::create_directories(root / "out");
    }
    EXPECT_EXIT(moveTheFolderThenStop(root / "out" / ".inkgraph-test.tmp", root / "moved"),
                ::testing::KilledBySignal(SIGTERM), "");
    EXPECT_TRUE(fs::exists(root / "moved")) << "the folder was not moved";
    EXPECT_TRUE(fs::is_empty(root / "moved")) << "the temporary was left in the moved folder";
    fs::remove_all(root);
}

/** Registers `file` and then its folder (so the folder lies in the later entry, as when a batch's stills reuse the
 *  entries another still's commit freed), then stops the process with SIGINT. */
[[noreturn]] void registerAFolderAfterItsFileThenStop(const fs::path& file) {
    removeTemporariesOnSignals();
    {
        const TemporaryCreation creating;
        fs::create_directories(file.parent_path());
        registerTemporary(file);
        registerTemporary(file.parent_path());
        std::ofstream(file) << "staged\n";
    }
    ::kill(::getpid(), SIGINT);
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1)); // the signal ends the process here
}

TEST(TemporaryFilesOnSignals, AFolderRegisteredAfterItsFilesIsRemovedWithThem) {
    // The sweep went from the newest entry to the oldest, taking a later entry for a newer path: a staging folder
    // that reused a later entry than its files failed to go (not empty yet), 8 of 73 interrupted --jobs 2 batches.
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const fs::path root = testFolder("folder-after-files");
    const bool inChild = !GTEST_FLAG_GET(internal_run_death_test).empty();
    if (!inChild) {
        fs::remove_all(root);
        fs::create_directories(root);
    }
    EXPECT_EXIT(registerAFolderAfterItsFileThenStop(root / "staging" / "final.png"), ::testing::KilledBySignal(SIGINT),
                "");
    EXPECT_TRUE(fs::is_empty(root)) << "the staging folder or its file was left";
    fs::remove_all(root);
}

/** Creates `count` registered temporaries in `folder`, then stops the process with SIGTERM. */
[[noreturn]] void createManyThenStop(const fs::path& folder, int count) {
    removeTemporariesOnSignals();
    for (int i = 0; i < count; ++i) {
        const int descriptor = createTemporaryFile(folder / (".inkgraph-many-" + std::to_string(i) + ".tmp"), 0644);
        if (descriptor < 0) ::_exit(3); // reported as the wrong ending
        ::close(descriptor);
    }
    ::kill(::getpid(), SIGTERM);
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1)); // the signal ends the process here
}

TEST(TemporaryFilesOnSignals, MoreTemporariesThanTheFirstChunkHoldsAreAllRemoved) {
    // The table held 256 paths: a --jobs 64 batch with --dump (about 1,400 temporaries at once) registered no more,
    // and a signal left the rest (2 of 8 runs). 1,000 fill four chunks.
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const fs::path root = testFolder("many-on-signal");
    const bool inChild = !GTEST_FLAG_GET(internal_run_death_test).empty();
    if (!inChild) {
        fs::remove_all(root);
        fs::create_directories(root);
    }
    EXPECT_EXIT(createManyThenStop(root, 1000), ::testing::KilledBySignal(SIGTERM), "");
    const auto left = std::distance(fs::directory_iterator(root), fs::directory_iterator());
    EXPECT_EQ(left, 0) << "temporaries were left";
    fs::remove_all(root);
}

TEST(TemporaryFiles, ThoseBeyondTheFirstChunkAreFoundByTheirFolderAfterAMove) {
    const fs::path root = testFolder("many-moved");
    fs::remove_all(root);
    fs::create_directories(root / "out");
    std::vector<fs::path> files;
    for (int i = 0; i < 600; ++i) {
        files.push_back(root / "out" / (".inkgraph-many-" + std::to_string(i) + ".tmp"));
        const int descriptor = createTemporaryFile(files.back(), 0644);
        ASSERT_GE(descriptor, 0) << std::strerror(errno);
        ::close(descriptor);
    }
    fs::rename(root / "out", root / "moved");
    for (const fs::path& file : files) EXPECT_TRUE(removeTemporary(file)) << file << ": " << std::strerror(errno);
    EXPECT_TRUE(fs::is_empty(root / "moved"));
    fs::remove_all(root);
}

class TemporaryFilesInAMovedFolder : public ::testing::Test {
protected:
    void SetUp() override {
        fs::remove_all(root);
        fs::create_directories(root / "out");
    }
    void TearDown() override { fs::remove_all(root); }

    /** Creates `name` in out/ as a registered temporary holding `text`. */
    fs::path makeTemporary(const std::string& name, const std::string& text) {
        const fs::path file = root / "out" / name;
        const int descriptor = createTemporaryFile(file, 0644);
        EXPECT_GE(descriptor, 0) << std::strerror(errno);
        if (descriptor >= 0) {
            EXPECT_EQ(::write(descriptor, text.data(), text.size()), ssize_t(text.size()));
            ::close(descriptor);
        }
        return file;
    }
    void moveAway() { fs::rename(root / "out", root / "moved"); }

    const fs::path root = testFolder("moved-folder");
};

TEST_F(TemporaryFilesInAMovedFolder, CreationIsExclusive) {
    std::ofstream(root / "out" / "taken") << "someone else's\n";
    EXPECT_EQ(createTemporaryFile(root / "out" / "taken", 0644), -1);
    EXPECT_EQ(errno, EEXIST);
    EXPECT_EQ(contents(root / "out" / "taken"), "someone else's\n");
    EXPECT_EQ(createTemporaryFile(root / "gone" / "x.tmp", 0644), -1);
    EXPECT_EQ(errno, ENOENT);
}

TEST_F(TemporaryFilesInAMovedFolder, ATemporaryIsRemovedWhereItsFolderNowIs) {
    const fs::path file = makeTemporary(".inkgraph-a.tmp", "a");
    moveAway();
    EXPECT_TRUE(removeTemporary(file));
    EXPECT_TRUE(fs::is_empty(root / "moved"));
    // Forgotten: a second removal finds nothing, by the path (which names nothing now either).
    EXPECT_FALSE(removeTemporary(file));
    EXPECT_EQ(errno, ENOENT);
}

TEST_F(TemporaryFilesInAMovedFolder, ATemporaryIsRenamedWhereItsFolderNowIs) {
    const fs::path backup = makeTemporary(".inkgraph-b.tmp", "old");
    const fs::path placed = makeTemporary(".inkgraph-c.tmp", "new");
    fs::rename(placed, root / "out" / "final.png"); // the commit's move into place, by path, before the folder moves
    moveAway();
    // The undo: the new file taken back beside the placed one's temporary, the old one renamed back over it.
    EXPECT_TRUE(removeBesideTemporary(placed, root / "out" / "final.png"));
    EXPECT_FALSE(fs::exists(root / "moved" / "final.png"));
    EXPECT_TRUE(renameTemporary(backup, root / "out" / "final.png"));
    EXPECT_EQ(contents(root / "moved" / "final.png"), "old");
    forgetTemporary(placed);
    EXPECT_EQ(std::distance(fs::directory_iterator(root / "moved"), fs::directory_iterator()), 1);
}

TEST_F(TemporaryFilesInAMovedFolder, TemporariesInOneFolderShareOneDescriptor) {
    // A dump's twenty files held twenty folder descriptors, so a low `ulimit -n` (16 to 28) refused a still it had
    // rendered; one folder, one descriptor, closed with the last of its temporaries.
    const auto openDescriptors = [] {
        return std::distance(fs::directory_iterator("/proc/self/fd"), fs::directory_iterator());
    };
    const auto before = openDescriptors();
    std::vector<fs::path> files;
    for (int i = 0; i < 20; ++i) files.push_back(makeTemporary(".inkgraph-" + std::to_string(i) + ".tmp", "x"));
    EXPECT_EQ(openDescriptors(), before + 1);
    moveAway();
    for (const fs::path& file : files) EXPECT_TRUE(removeTemporary(file)) << file;
    EXPECT_TRUE(fs::is_empty(root / "moved"));
    EXPECT_EQ(openDescriptors(), before);
}

TEST_F(TemporaryFilesInAMovedFolder, ATemporaryTheFullTableCannotHoldIsRemovedByItsName) {
    // The signal's table holds 4,096 paths (16 chunks of 256): a temporary made when it is full is not registered,
    // and is removed by its path (in the folder at that path: one moved away meanwhile keeps it, as before the
    // folders were held).
    std::vector<fs::path> fillers;
    for (int i = 0; i < 4096; ++i) {
        fillers.push_back(root / "out" / ("filler" + std::to_string(i)));
        registerTemporary(fillers.back());
    }
    const fs::path unregistered = makeTemporary(".inkgraph-unregistered.tmp", "x");
    const fs::path byName = makeTemporary(".inkgraph-by-name.tmp", "x");
    for (const fs::path& filler : fillers) forgetTemporary(filler);
    EXPECT_TRUE(removeTemporary(byName));
    EXPECT_FALSE(fs::exists(byName));
    const fs::path registered = makeTemporary(".inkgraph-registered.tmp", "x"); // room again
    moveAway();
    EXPECT_FALSE(removeTemporary(unregistered)) << "it was registered after all";
    EXPECT_EQ(errno, ENOENT);
    EXPECT_TRUE(removeTemporary(registered));
    EXPECT_EQ(std::distance(fs::directory_iterator(root / "moved"), fs::directory_iterator()), 1);
    EXPECT_TRUE(fs::exists(root / "moved" / ".inkgraph-unregistered.tmp"));
}

} // namespace
} // namespace inkgraph
