#pragma once
/** @file The contents of the extension `inkgraph._inkgraph` in one place, for the two hosts that load them: the
 *  extension module Debian's python3 imports (Module.cpp) and the fuzz target that embeds Python with its bindings
 *  compiled in (tests/fuzz/FuzzPythonArgs.cpp: an instrumented extension cannot load into an uninstrumented
 *  interpreter, but an instrumented program can embed one). */

#include <pybind11/pybind11.h>

namespace inkgraph::python {

/** Defines every class, function and the error translation of `inkgraph._inkgraph` on `m`. */
void defineModule(pybind11::module_& m);

} // namespace inkgraph::python
