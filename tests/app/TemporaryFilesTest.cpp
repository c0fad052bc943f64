// What a signal leaves behind (render/TemporaryFiles.h): every temporary registered is removed, and a file that is
// being created when the signal comes is waited for and removed too, never left unregistered. Each case runs in a
// process of its own (a death test re-executes this binary), since the handling is installed once per process.
#include "render/TemporaryFiles.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

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

} // namespace
} // namespace inkgraph
