#pragma once
/** @file Calls that pybind11 refuses without naming what is wrong, or lets through to a crash, refused by name.
 *  After the module is defined, nameArgumentRefusals() puts a step in front of each of its functions (the
 *  PyMethodDef's C function, pybind11's dispatcher behind it):
 *  - A call whose arguments fit no parameter list (a missing argument, an unknown keyword, too many values, one given
 *    twice): pybind11 refuses it with "incompatible function arguments", the signatures and every value given. The
 *    step compares the call with the list as pybind11 matched it and raises a TypeError that starts with the function
 *    and quotes the argument ("Scene.load(): missing required argument 'path'", "Orbit(): unexpected keyword argument
 *    'bogus' (arguments: azimuth, elevation, distance, distance_scale)"). An overloaded function keeps pybind11's
 *    list of overloads unless all refuse for one reason. pybind11 writes its refusal outside its own try, so a
 *    keyword that is a lone surrogate, which it cannot encode, aborted the interpreter; it is refused the same way.
 *  - Arguments that pybind11 lets through unusable: a method's self of another class (None, which a method bound as a
 *    C++ member function takes as a null pointer: a crash; any object, where self is taken as a plain object), and
 *    any argument whose constructor has not run (`Vec3.__new__(Vec3)`: its fields are uninitialized memory).
 *    Properties' getters and setters included.
 *  - pybind11's own base class made directly (`type(inkgraph.Look()).__mro__[1]()`, pybind11_object), or a Python
 *    class derived from it alone: pybind11 throws out of a C function there, which aborted the interpreter. It is a
 *    TypeError ("pybind11_object(): cannot be made: it holds no value of a bound C++ class").
 *  A call that fits, with a usable self, is never touched: its errors are the function's own (checked() names a value
 *  of the wrong type, CheckedArguments.h). The functions, their docstrings and help() are unchanged. */

#include <pybind11/pybind11.h>

namespace inkgraph::python {

/** Installs the step on every pybind11 function of `m`: its functions, and the methods, static methods,
 *  constructors and property accessors of its classes, nested classes included. Call it once, after everything is
 *  defined. */
void nameArgumentRefusals(pybind11::module_& m);

} // namespace inkgraph::python
