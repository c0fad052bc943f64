#pragma once
/** @file Running the library's work without the GIL, safely at interpreter exit. */

#include <Python.h>

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <optional>
#include <type_traits>
#include <utility>

#include <unistd.h>

namespace inkgraph::python {

/** Takes the GIL back after withoutGil()'s work. A thread that comes back while the interpreter is finalizing (a
 *  daemon thread still inside a render at exit) waits for the process to end, as Python 3.14 makes such threads
 *  do: Python 3.11 ends it with pthread_exit as it takes the GIL, whose forced unwind through pybind11's
 *  gil_scoped_release, a noexcept destructor, called std::terminate and aborted the process at exit. Finalizing
 *  that begins only after the check still ends the thread so, but the unwind then runs through plain frames that
 *  let it pass (pybind11's dispatcher rethrows it). */
inline void retakeGil(PyThreadState* state) {
    if (_Py_IsFinalizing())
        for (;;) pause();
    PyEval_RestoreThread(state);
}

/** Runs `work` (C++ only: it must not touch Python objects) without the GIL and returns its result or rethrows its
 *  exception once the GIL is back. In place of py::gil_scoped_release (retakeGil() says why). */
template <typename Work>
auto withoutGil(Work&& work) {
    using Result = decltype(std::forward<Work>(work)());
    PyThreadState* const state = PyEval_SaveThread();
    std::exception_ptr failure;
    if constexpr (std::is_void_v<Result>) {
        try {
            std::forward<Work>(work)();
        } catch (...) {
            failure = std::current_exception();
        }
        retakeGil(state);
        if (failure) std::rethrow_exception(failure);
    } else {
        std::optional<Result> result;
        try {
            result.emplace(std::forward<Work>(work)());
        } catch (...) {
            failure = std::current_exception();
        }
        retakeGil(state);
        if (failure) std::rethrow_exception(failure);
        return std::move(*result);
    }
}

/** The calls that drive the renderer, the loaders and the writers (not close()), counted, so that the interpreter's
 *  exit can wait for those in flight and keep new ones from starting: a daemon thread rendering while exit() ran the
 *  library's and the GL driver's static destructors crashed the process (SIGSEGV). stopCallsForExit() runs from an
 *  atexit handler (inkgraph/_front.py), before the default renderer is closed; a call another thread starts after it
 *  waits for the process to end (the exiting thread's own, from atexit handlers that run later, still run). */
class CallsAtExit {
public:
    /** Runs `work` as withoutGil() does, counted; blocks for good once the exit has begun. */
    template <typename Work>
    static auto run(Work&& work) {
        return withoutGil([&] {
            enter();
            struct Leave {
                ~Leave() { leave(); }
            } leave;
            return std::forward<Work>(work)();
        });
    }

    /** Keeps new calls from starting and waits (without the GIL) for those in flight. */
    static void stopCallsForExit() {
        withoutGil([] {
            std::unique_lock lock(state().mutex);
            state().exiting = true;
            state().exitingThread = std::this_thread::get_id();
            state().idle.wait(lock, [] { return state().inFlight == 0; });
        });
    }

private:
    struct State {
        const pid_t process = getpid();
        std::mutex mutex;
        std::condition_variable idle;
        std::size_t inFlight = 0;
        bool exiting = false;
        std::thread::id exitingThread; ///< the thread that runs the exit, whose later calls (atexit handlers) still run
    };
    /** Never destroyed: threads may still wait on it at exit. A child forked while a thread of the parent was in a
     *  call takes a fresh one: the parent's count (and maybe its lock) speak of threads the child lacks, and its exit
     *  waited for them for ever. */
    static State& state() {
        static std::atomic<State*> shared{new State()};
        State* current = shared.load();
        if (current->process == getpid()) return *current;
        State* const fresh = new State();
        if (shared.compare_exchange_strong(current, fresh)) return *fresh;
        delete fresh; // another thread of the child made it first
        return *current;
    }
    static void enter() {
        std::unique_lock lock(state().mutex);
        if (state().exiting && std::this_thread::get_id() != state().exitingThread) {
            lock.unlock();
            for (;;) pause();
        }
        ++state().inFlight;
    }
    static void leave() {
        const std::lock_guard lock(state().mutex);
        if (--state().inFlight == 0) state().idle.notify_all();
    }
};

} // namespace inkgraph::python
