/** @file The extension `inkgraph._inkgraph` Debian's python3 imports; what it holds is defined in Bindings.cpp. */
#include "Bindings.h"

PYBIND11_MODULE(_inkgraph, m) { inkgraph::python::defineModule(m); }
