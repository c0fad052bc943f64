#pragma once
/** @file Running the library's work without the GIL, safely at interpreter exit. */

#include <Python.h>

#include <exception>
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

} // namespace inkgraph::python
