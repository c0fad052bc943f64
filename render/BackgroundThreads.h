#pragma once
/** @file The threads that inkgraph's libraries run for it in the background, ended and joined at a defined point.
 *
 *  Two kinds start on their own: OpenCV runs its parallel loops on oneTBB's worker pool (Debian's build), which
 *  starts workers lazily and asynchronously and, at exit, lets them finish on their own time; and the OpenImageIO
 *  module is loaded on a thread of ours (render/ImageIoModule.h), whose dlopen starts yet more pools (log4cplus's, by
 *  way of OpenVDB). A process that ends while one of these threads is being created or torn down breaks
 *  LeakSanitizer's check at exit, which stops every thread and reads its stack and thread-local storage ("Tracer
 *  caught signal 11"). So every inkgraph process ends the same way: the executable's main (app/main.cpp) and every
 *  test binary's (tests/support/TestMain.cpp) join these threads, then, in sanitized builds, run the leak check
 *  before any library's static teardown begins (docs/robustness.md, "How a process ends"). */

namespace inkgraph {

/** Ends OpenCV's parallel workers and waits until each has exited; OpenCV keeps its thread setting, so a later
 *  parallel loop starts new workers. Throws std::runtime_error naming the pool when the workers cannot be joined
 *  (another user of oneTBB still holds it). */
void stopParallelWorkers();

/** Marks work that may run OpenCV's parallel loops on oneTBB's workers (a library render) for its life: a fork() while
 *  one lives leaves the workers alone (stopParallelWorkersAtEachFork()). */
class ParallelWork {
public:
    ParallelWork();
    ~ParallelWork();
    ParallelWork(const ParallelWork&) = delete;
    ParallelWork& operator=(const ParallelWork&) = delete;
};

/** From its first call on, every fork() of the process first joins oneTBB's workers (stopParallelWorkers()) unless a
 *  ParallelWork lives. A child inherits no thread but the one that forked, yet oneTBB's state still names the parent's
 *  workers, and its exit handler detaches them in the child: SIGSEGV when the child exits. Joined before the fork,
 *  the parent and the child each start new workers when a parallel loop needs them. For the library (api/), whose
 *  users fork (Python's multiprocessing); the command line never forks. */
void stopParallelWorkersAtEachFork();

/** OpenCV's parallel loops on `threads` threads for the object's life (1: in the calling thread), then on as many as
 *  before. */
class ParallelLoopThreads {
public:
    explicit ParallelLoopThreads(int threads);
    ~ParallelLoopThreads();
    ParallelLoopThreads(const ParallelLoopThreads&) = delete;
    ParallelLoopThreads& operator=(const ParallelLoopThreads&) = delete;

private:
    int mThreadsBefore;
};

/** Waits for the OpenImageIO module's loader if it was started (render/ImageFiles.h), then stopParallelWorkers():
 *  afterwards no thread that inkgraph started is being created or torn down, and none of ours is left running. */
void joinBackgroundThreads();

/** The end of every inkgraph process: joinBackgroundThreads(), then, in builds with AddressSanitizer, LeakSanitizer's
 *  check at this point (a leak ends the process with LeakSanitizer's exit code, and the check at exit is skipped);
 *  the process may then run static destructors or _Exit. */
void finishProcess();

} // namespace inkgraph
