#include "render/BackgroundThreads.h"

#include "render/ImageFiles.h"

#include <oneapi/tbb/global_control.h>
#include <opencv2/core/utility.hpp>

#include <pthread.h>

#include <mutex>
#include <new>
#include <stdexcept>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

namespace inkgraph {

void stopParallelWorkers() {
    const int threads = cv::getNumThreads();
    // OpenCV's own arena holds the pool while its thread setting is above 0; 0 releases it.
    cv::setNumThreads(0);
    // A blocking finalize: returns once every worker thread has been joined.
    oneapi::tbb::task_scheduler_handle pool{oneapi::tbb::attach{}};
    const bool joined = oneapi::tbb::finalize(pool, std::nothrow);
    cv::setNumThreads(threads);
    if (!joined)
        throw std::runtime_error(
            "stopParallelWorkers(): oneTBB's worker pool, which OpenCV's parallel loops run on, is "
            "still held by another user (an initialised task_arena or a task_scheduler_handle outside "
            "OpenCV); its workers were not joined");
}

namespace {

std::mutex gParallelWorkMutex;
int gParallelWorkCount = 0; ///< ParallelWork objects alive, under gParallelWorkMutex

/** pthread_atfork()'s prepare handler: in the thread that forks, before the fork. */
void stopParallelWorkersBeforeFork() {
    // A ParallelWork being made or ended on another thread holds the mutex only for its count: such a fork leaves
    // the workers as they are, as one during a render does.
    const std::unique_lock<std::mutex> gate(gParallelWorkMutex, std::try_to_lock);
    if (!gate.owns_lock() || gParallelWorkCount > 0) return;
    try {
        stopParallelWorkers();
    } catch (...) { // another user of oneTBB holds the pool: the fork goes on as it would have
    }
}

} // namespace

ParallelWork::ParallelWork() {
    const std::lock_guard<std::mutex> lock(gParallelWorkMutex);
    ++gParallelWorkCount;
}

ParallelWork::~ParallelWork() {
    const std::lock_guard<std::mutex> lock(gParallelWorkMutex);
    --gParallelWorkCount;
}

void stopParallelWorkersAtEachFork() {
    static const int registered = pthread_atfork(stopParallelWorkersBeforeFork, nullptr, nullptr);
    (void)registered; // ENOMEM: forks then go on as before
}

ParallelLoopThreads::ParallelLoopThreads(int threads) : mThreadsBefore(cv::getNumThreads()) {
    cv::setNumThreads(threads);
}

ParallelLoopThreads::~ParallelLoopThreads() { cv::setNumThreads(mThreadsBefore); }

void joinBackgroundThreads() {
    // The loader first: a dlopen in progress may still be starting the pools of OpenImageIO's dependencies.
    finishImageIoPreload();
    stopParallelWorkers();
}

void finishProcess() {
    joinBackgroundThreads();
#if defined(__SANITIZE_ADDRESS__)
    // Before static destructors: some libraries' pools end their threads there without joining them (log4cplus's
    // workers detach themselves, oneTBB's are released from its library destructor), so the check at exit could
    // meet them half torn down.
    __lsan_do_leak_check();
#endif
}

} // namespace inkgraph
