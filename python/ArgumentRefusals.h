#pragma once
/** @file A call whose arguments fit no parameter list refused by name. pybind11 refuses such a call (a missing
 *  argument, an unknown keyword, too many values) with "incompatible function arguments", the signatures and every
 *  value given, and names no argument. After the module is defined, nameArgumentRefusals() puts a step in front of
 *  each of its functions: when pybind11 refuses a call to a function with one parameter list, the step compares the
 *  call with that list as pybind11 matched it and replaces the refusal with a TypeError that starts with the function
 *  and quotes the argument ("Scene.load(): missing required argument 'path'", "Orbit(): unexpected keyword argument
 *  'bogus'; it takes 'azimuth', 'elevation', 'distance', 'distance_scale'"). A call that fits the list is never
 *  touched: its errors are the function's own (checked() names a value of the wrong type, CheckedArguments.h).
 *  Overloaded functions keep pybind11's message, which lists each overload. The functions, their docstrings and
 *  help() are unchanged. */

#include <pybind11/pybind11.h>

namespace inkgraph::python {

/** Installs the refusal by name on every pybind11 function of `m`: its functions, and the methods, static methods
 *  and constructors of its classes. Call it once, after everything is defined. */
void nameArgumentRefusals(pybind11::module_& m);

} // namespace inkgraph::python
