// render/BackgroundThreads: the threads that OpenCV's parallel loops and the OpenImageIO module's loader run are joined
// when asked, so no process ends while one of them is being created or torn down (docs/robustness.md).
#include "render/BackgroundThreads.h"

#include "render/ImageFiles.h"

#include <gtest/gtest.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/task_arena.h>
#include <opencv2/core/utility.hpp>

#include <dlfcn.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <mutex>
#include <set>
#include <string>
#include <thread>

namespace inkgraph {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/** The kernel's ids of this process's threads. */
std::set<std::string> threadIds() {
    std::set<std::string> ids;
    for (const auto& entry : fs::directory_iterator("/proc/self/task")) ids.insert(entry.path().filename().string());
    return ids;
}

/** The threads of this process that were not in `before`. */
std::set<std::string> threadsStartedSince(const std::set<std::string>& before) {
    std::set<std::string> started;
    for (const std::string& id : threadIds())
        if (before.count(id) == 0) started.insert(id);
    return started;
}

/** Runs a parallel loop whose stripes wait (up to 10 s) until two threads have entered it, so that at least one of
 *  oneTBB's workers is started and used; returns how many threads ran stripes. */
std::size_t loopOnTwoThreads() {
    std::mutex mutex;
    std::set<std::thread::id> seen;
    std::atomic<bool> twoSeen{false};
    const auto deadline = Clock::now() + std::chrono::seconds(10);
    cv::parallel_for_(
        cv::Range(0, 64),
        [&](const cv::Range&) {
            {
                const std::lock_guard<std::mutex> lock(mutex);
                seen.insert(std::this_thread::get_id());
                if (seen.size() >= 2) twoSeen = true;
            }
            while (!twoSeen && Clock::now() < deadline) std::this_thread::yield();
        },
        64);
    return seen.size();
}

/** Waits up to 5 s for none of `ids` to be a thread of this process any more. A joined thread can still be listed for
 *  a moment: the kernel wakes the joiner before it removes the task. */
bool allGoneWithin5s(const std::set<std::string>& ids) {
    const auto deadline = Clock::now() + std::chrono::seconds(5);
    for (;;) {
        const std::set<std::string> now = threadIds();
        bool anyLeft = false;
        for (const std::string& id : ids) anyLeft = anyLeft || now.count(id) != 0;
        if (!anyLeft) return true;
        if (Clock::now() > deadline) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
}

TEST(BackgroundThreads, StopParallelWorkersJoinsEveryWorkerAndLaterLoopsStartNewOnes) {
    // Allows oneTBB a worker even on a one-core machine.
    const oneapi::tbb::global_control twoThreads(oneapi::tbb::global_control::max_allowed_parallelism, 2);
    const int threadSetting = cv::getNumThreads();
    const std::set<std::string> before = threadIds();
    ASSERT_GE(loopOnTwoThreads(), 2u) << "no worker of OpenCV's pool took part in the loop";
    const std::set<std::string> workers = threadsStartedSince(before);
    ASSERT_FALSE(workers.empty());

    stopParallelWorkers();
    EXPECT_TRUE(allGoneWithin5s(workers)) << workers.size() << " worker(s) still running after stopParallelWorkers()";
    EXPECT_EQ(cv::getNumThreads(), threadSetting) << "OpenCV's thread setting must be kept";

    // The pool comes back on demand, and stopping twice in a row is harmless.
    const std::set<std::string> beforeAgain = threadIds();
    EXPECT_GE(loopOnTwoThreads(), 2u);
    const std::set<std::string> newWorkers = threadsStartedSince(beforeAgain);
    EXPECT_FALSE(newWorkers.empty());
    stopParallelWorkers();
    EXPECT_NO_THROW(stopParallelWorkers());
    EXPECT_TRUE(allGoneWithin5s(newWorkers));
}

TEST(BackgroundThreads, StopParallelWorkersNamesThePoolWhenItIsStillHeld) {
    // An initialised task_arena outside OpenCV holds oneTBB's pool: no join, and the error says why.
    oneapi::tbb::task_arena held(2);
    held.initialize();
    loopOnTwoThreads();
    try {
        stopParallelWorkers();
        FAIL() << "expected std::runtime_error";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("stopParallelWorkers(): oneTBB's worker pool"), std::string::npos)
            << error.what();
    }
    held.terminate();
    EXPECT_NO_THROW(stopParallelWorkers()) << "once the arena is gone the pool can be joined";
}

TEST(BackgroundThreads, ParallelLoopThreadsRunsLoopsInTheCallerOnlyWhileItLives) {
    // A pipelined batch's post stages take one thread each (app/BatchRun.cpp): OpenCV's loops then run in the worker
    // that calls them, and afterwards on as many threads as before.
    const oneapi::tbb::global_control twoThreads(oneapi::tbb::global_control::max_allowed_parallelism, 2);
    const int threadSetting = cv::getNumThreads();
    {
        const ParallelLoopThreads oneEach(1);
        EXPECT_EQ(cv::getNumThreads(), 1);
        std::set<std::thread::id> seen;
        cv::parallel_for_(
            cv::Range(0, 64), [&](const cv::Range&) { seen.insert(std::this_thread::get_id()); }, 64);
        EXPECT_EQ(seen, std::set<std::thread::id>{std::this_thread::get_id()});
    }
    EXPECT_EQ(cv::getNumThreads(), threadSetting);
    EXPECT_GE(loopOnTwoThreads(), 2u) << "the loops are parallel again";
    stopParallelWorkers();
}

TEST(BackgroundThreads, JoinWaitsForTheImageModuleLoadThatWasStarted) {
    const fs::path module = fs::path(INKGRAPH_BINARY_ROOT) / "libinkgraph_imageio.so";
    ASSERT_TRUE(fs::exists(module)) << module;
    preloadImageIo();
    joinBackgroundThreads();
    // The loader's dlopen has returned: the module is in the process.
    void* loaded = dlopen(module.c_str(), RTLD_NOW | RTLD_NOLOAD);
    EXPECT_NE(loaded, nullptr) << "the module is not loaded after joinBackgroundThreads()";
    if (loaded != nullptr) dlclose(loaded); // only drops the reference RTLD_NOLOAD took
}

} // namespace
} // namespace inkgraph
