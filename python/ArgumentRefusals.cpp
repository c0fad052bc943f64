#include "ArgumentRefusals.h"

#include "CheckedArguments.h"

#include <algorithm>
#include <cstddef>
#include <map>
#include <new>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph::python {

namespace {

namespace py = pybind11;
using FunctionRecord = py::detail::function_record;

/** pybind11's dispatcher, which every function of the module calls through its PyMethodDef (the same one for all). */
PyCFunctionWithKeywords pybindDispatcher = nullptr;

/** The attribute a class gives each of its functions, by record, and whether it is a property's (a getter, setter or
 *  deleter, which pybind11 names ""). pybind11's own names can differ: an enum's __str__ is named "name". */
struct Attribute {
    std::string name;
    bool accessor = false;
};
std::map<const FunctionRecord*, Attribute> attributes;

/** "Scene.load(): ", "Orbit(): " for a constructor, "sample_views(): " for a function of the module; a nested class
 *  by its qualified name ("Renderer.Platform(): "); a property's accessor as a field ("Vec3.x: "). */
std::string whereOf(const FunctionRecord& function) {
    std::string name = function.name;
    if (!function.scope || !PyType_Check(function.scope.ptr())) return name + "(): ";
    const std::string type = py::str(function.scope.attr("__qualname__"));
    if (name == "__init__") return type + "(): ";
    if (const auto attribute = attributes.find(&function); attribute != attributes.end()) {
        if (attribute->second.accessor) return type + "." + attribute->second.name + ": ";
        name = attribute->second.name;
    }
    return type + "." + name + "(): ";
}

std::string quotedName(const std::string& name) { return "'" + name + "'"; }

std::string quotedNames(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + quotedName(name);
    return text;
}

std::string countOf(std::size_t count, const char* noun) {
    return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

/** Why a call does not fit a parameter list: the reason ("missing required argument 'path'") and what the list
 *  takes, for a reason that names a keyword it does not (" (arguments: azimuth, elevation)"). */
struct Misfit {
    std::string reason;
    std::string takes;
};

/** Why pybind11 found no way to fit the call (`arguments`, `keywords`; a method's self first, by position or, where
 *  the method names its parameters, by keyword) to `function`'s parameter list, in the order it tries: positions,
 *  then keywords and defaults. Nothing when the call fits, so that the refusal came from the function itself. Every
 *  keyword is a str (not a subclass, whose equality need not be its spelling's). */
std::optional<Misfit> misfit(const FunctionRecord& function, PyObject* arguments, PyObject* keywords) {
    const std::size_t self = function.is_method ? 1 : 0;
    const auto given = std::size_t(PyTuple_GET_SIZE(arguments));
    const std::size_t positional = function.nargs_pos;
    const std::size_t needed = function.nargs - std::size_t(function.has_args) - std::size_t(function.has_kwargs);
    // The parameters as the caller knows them: self is not counted or listed.
    std::vector<std::string> names;
    for (std::size_t index = self; index < function.args.size(); ++index) {
        const char* name = function.args[index].name;
        names.emplace_back(name != nullptr ? name : "");
    }
    const std::string got = ", got " + std::to_string(given > self ? given - self : 0);

    if (!function.has_args && given > positional) {
        const std::size_t most = positional - self;
        if (needed == self && !function.has_kwargs) return Misfit{"takes no arguments" + got, ""};
        if (most == 0)
            return Misfit{names.empty() ? "takes keyword arguments only" + got
                                        : "takes its arguments by keyword only (" + quotedNames(names) + ")" + got,
                          ""};
        const std::vector<std::string> first(names.begin(),
                                             names.begin() + std::ptrdiff_t(std::min(most, names.size())));
        return Misfit{"takes at most " + countOf(most, "positional argument") +
                          (first.empty() ? "" : " (" + quotedNames(first) + ")") + got,
                      ""};
    }

    if (keywords != nullptr) {
        PyObject* key = nullptr;
        PyObject* value = nullptr;
        Py_ssize_t position = 0;
        while (PyDict_Next(keywords, &position, &key, &value)) {
            const std::string keyword = escapedUtf8(py::str(key));
            std::size_t index = 0;
            while (index < function.args.size() &&
                   (function.args[index].name == nullptr || keyword != function.args[index].name))
                ++index;
            if (index >= function.args.size()) {
                if (function.has_kwargs) continue;
                return Misfit{"unexpected keyword argument " + reprText(key),
                              names.empty() ? " (it takes no keyword arguments)"
                                            : " (arguments: " + commaSeparated(names) + ")"};
            }
            if (index < std::min(given, positional))
                return Misfit{"argument " + quotedName(keyword) + " given twice, by position and by keyword", ""};
            if (index < function.nargs_pos_only)
                return Misfit{"argument " + quotedName(keyword) + " is positional only, given by keyword", ""};
        }
    }

    // The positions given fill the parameters before them; the rest come from keywords or defaults.
    std::vector<std::string> missing;
    for (std::size_t index = std::min(given, positional); index < needed; ++index) {
        if (index >= function.args.size()) {
            if (index < self) return Misfit{"missing required argument 'self'", ""};
            return Misfit{"takes " + countOf(needed - self, "argument") + got, ""};
        }
        const py::detail::argument_record& parameter = function.args[index];
        const bool byKeyword = keywords != nullptr && parameter.name != nullptr && index >= function.nargs_pos_only &&
                               PyDict_GetItemString(keywords, parameter.name) != nullptr;
        if (!byKeyword && !parameter.value) missing.emplace_back(parameter.name != nullptr ? parameter.name : "?");
    }
    if (missing.size() == 1) return Misfit{"missing required argument " + quotedName(missing.front()), ""};
    if (!missing.empty()) return Misfit{"missing required arguments " + quotedNames(missing), ""};
    return std::nullopt;
}

/** Whether every keyword of a call is a str itself, which misfit() can judge by its spelling. */
bool keywordsAreStrings(PyObject* keywords) {
    PyObject* key = nullptr;
    PyObject* value = nullptr;
    Py_ssize_t position = 0;
    while (keywords != nullptr && PyDict_Next(keywords, &position, &key, &value))
        if (!PyUnicode_CheckExact(key)) return false;
    return true;
}

/** The refusal of a call to `function` (the head of its overload chain): misfit()'s, for an overloaded function the
 *  reason all its overloads share (a keyword none takes). Nothing when one fits or their reasons differ: pybind11's
 *  refusal, which lists every overload, says more. */
std::optional<std::string> refusal(const FunctionRecord& function, PyObject* arguments, PyObject* keywords) {
    if (!keywordsAreStrings(keywords)) return std::nullopt;
    // pybind11 refuses a constructor called on an object of another class before it matches any argument.
    if (function.is_constructor &&
        (PyTuple_GET_SIZE(arguments) == 0 ||
         !PyObject_TypeCheck(PyTuple_GET_ITEM(arguments, 0), reinterpret_cast<PyTypeObject*>(function.scope.ptr()))))
        return std::nullopt;
    if (function.next == nullptr) {
        const std::optional<Misfit> only = misfit(function, arguments, keywords);
        if (!only) return std::nullopt;
        return whereOf(function) + only->reason + only->takes;
    }
    std::optional<std::string> shared;
    for (const FunctionRecord* overload = &function; overload != nullptr; overload = overload->next) {
        const std::optional<Misfit> reason = misfit(*overload, arguments, keywords);
        if (!reason || (shared && *shared != reason->reason)) return std::nullopt;
        shared = reason->reason;
    }
    return whereOf(function) + *shared;
}

/** repr() of the first of `keywords` that UTF-8 cannot encode (a lone surrogate). */
std::string unencodableKeyword(PyObject* keywords) {
    PyObject* key = nullptr;
    PyObject* value = nullptr;
    Py_ssize_t position = 0;
    while (keywords != nullptr && PyDict_Next(keywords, &position, &key, &value)) {
        if (PyUnicode_AsUTF8AndSize(key, nullptr) != nullptr) continue;
        PyErr_Clear();
        return reprText(key);
    }
    throw std::logic_error("unencodableKeyword(): every keyword encodes");
}

/** The function record `capsule` holds (install() checked that it holds one). */
const FunctionRecord* recordOf(PyObject* capsule) {
    return static_cast<const FunctionRecord*>(PyCapsule_GetPointer(capsule, PyCapsule_GetName(capsule)));
}

/** The short name of `object`'s class ("Color"), or "None". */
std::string classNameOf(PyObject* object) {
    if (object == Py_None) return "None";
    const std::string name = Py_TYPE(object)->tp_name;
    return name.substr(name.rfind('.') + 1);
}

/** "an X whose constructor has not run" when `argument` is an object of one of pybind11's classes made by
 *  `cls.__new__(cls)` without `__init__`: its value is uninitialized memory. pybind11 registers every instance whose
 *  value it holds, made by a constructor or handed over from C++ (owned or not); the value's pointer says nothing, as
 *  pybind11 allocates it when first asked for and never constructs it then. Any other object (an int, a str) is
 *  passed over by one subtype test, without pybind11's type lookup, which would cache every type it is asked about. */
std::optional<std::string> unconstructed(PyObject* argument) {
    const auto* base = reinterpret_cast<PyTypeObject*>(py::detail::get_internals().instance_base);
    if (!PyObject_TypeCheck(argument, const_cast<PyTypeObject*>(base))) return std::nullopt;
    // Each of its pybind11 classes' values (a Python class may derive from several).
    for (const py::detail::value_and_holder& value :
         py::detail::values_and_holders(reinterpret_cast<py::detail::instance*>(argument))) {
        if (value.instance_registered()) continue;
        const std::string name =
            py::handle(reinterpret_cast<PyObject*>(value.type->type)).attr("__qualname__").cast<std::string>();
        return "a " + name + " whose constructor has not run (" + name + ".__new__() without __init__())";
    }
    return std::nullopt;
}

/** What is wrong with an argument that pybind11 would let through unusable: a method's self that is not of its class
 *  (None, which a method bound as a C++ member function takes as a null pointer: a crash; any object, where self is
 *  taken as a plain object), and any argument, by position or keyword, whose constructor has not run
 *  (`Renderer.__new__(Renderer)`: garbage values, a MemoryError, a hang on a mutex). A constructor's own self is
 *  the object it is making. */
std::optional<std::string> argumentProblem(const FunctionRecord& function, PyObject* arguments, PyObject* keywords) {
    const auto given = std::size_t(PyTuple_GET_SIZE(arguments));
    const std::size_t self = function.is_method ? 1 : 0;
    if (function.is_method && !function.is_constructor && PyType_Check(function.scope.ptr())) {
        // Self by position, or by keyword where the method names its parameters.
        PyObject* object = given > 0             ? PyTuple_GET_ITEM(arguments, 0)
                           : keywords != nullptr ? PyDict_GetItemString(keywords, "self")
                                                 : nullptr;
        if (object != nullptr && !PyObject_TypeCheck(object, reinterpret_cast<PyTypeObject*>(function.scope.ptr())))
            return "self: expected " + py::str(function.scope.attr("__qualname__")).cast<std::string>() + ", got " +
                   classNameOf(object);
    }
    for (std::size_t index = function.is_constructor ? 1 : 0; index < given; ++index) {
        if (const auto problem = unconstructed(PyTuple_GET_ITEM(arguments, Py_ssize_t(index)))) {
            const char* name = index < function.args.size() ? function.args[index].name : nullptr;
            const std::string label = name != nullptr && name[0] != '\0' ? std::string(name)
                                      : index < self                     ? "self"
                                                     : "argument " + std::to_string(index + 1 - self);
            return label + ": " + *problem;
        }
    }
    PyObject* key = nullptr;
    PyObject* value = nullptr;
    Py_ssize_t position = 0;
    while (keywords != nullptr && PyDict_Next(keywords, &position, &key, &value))
        if (const auto problem = unconstructed(value))
            return py::str(key).attr("encode")("utf-8", "backslashreplace").cast<std::string>() + ": " + *problem;
    return std::nullopt;
}

/** Calls pybind11's dispatcher; a TypeError for a call that does not fit the function's parameter list is replaced by
 *  misfit()'s. An argument that pybind11 would let through unusable is refused first (argumentProblem()). Every
 *  other result and error passes through as it is. */
PyObject* dispatchNamingMisfits(PyObject* capsule, PyObject* arguments, PyObject* keywords) {
    const FunctionRecord* function = recordOf(capsule);
    if (function == nullptr) return nullptr;
    try {
        if (const std::optional<std::string> problem = argumentProblem(*function, arguments, keywords)) {
            PyErr_SetString(PyExc_TypeError, (whereOf(*function) + *problem).c_str());
            return nullptr;
        }
    } catch (py::error_already_set& error) {
        error.restore();
        return nullptr;
    } catch (const std::bad_alloc&) {
        return PyErr_NoMemory();
    } catch (const std::exception& error) {
        // Nothing may leave a C function as a C++ exception (std::terminate).
        PyErr_SetString(PyExc_RuntimeError, error.what());
        return nullptr;
    }
    PyObject* result = nullptr;
    bool refused = false;
    bool escaped = false;
    try {
        result = pybindDispatcher(capsule, arguments, keywords);
        refused = result == nullptr && PyErr_ExceptionMatches(PyExc_TypeError);
    } catch (py::error_already_set& error) {
        // pybind11 writes its refusal outside its own try: a keyword that is a lone surrogate fails to encode there,
        // and the exception would leave a C function (std::terminate). Another error there (a keyword's __format__
        // that raises, an interrupt) is raised as it is.
        const bool unencodable = error.matches(PyExc_UnicodeError);
        error.restore();
        if (!unencodable) return nullptr;
        refused = escaped = true;
    } catch (const std::bad_alloc&) {
        return PyErr_NoMemory();
    }
    if (!refused) return result;
    PyObject* type = nullptr;
    PyObject* value = nullptr;
    PyObject* traceback = nullptr;
    PyErr_Fetch(&type, &value, &traceback);
    std::optional<std::string> message;
    try {
        message = refusal(*function, arguments, keywords);
        // A call pybind11 refused for another reason, with such a keyword among its arguments.
        if (!message && escaped)
            message = whereOf(*function) + "no parameter list fits the arguments (keyword " +
                      unencodableKeyword(keywords) + " among them)";
    } catch (const py::error_already_set&) {
        message.reset();
    } catch (const std::exception&) {
        message.reset();
    }
    if (!message) {
        PyErr_Restore(type, value, traceback);
        return nullptr;
    }
    Py_XDECREF(type);
    Py_XDECREF(value);
    Py_XDECREF(traceback);
    PyErr_SetString(PyExc_TypeError, message->c_str());
    return nullptr;
}

/** The record of `object` when it is a pybind11 function or a method of one, else null. */
const FunctionRecord* recordOfFunction(py::handle object) {
    const py::handle function = py::detail::get_function(object);
    if (!function || !PyCFunction_Check(function.ptr())) return nullptr;
    PyObject* self = PyCFunction_GET_SELF(function.ptr());
    if (self == nullptr || !PyCapsule_CheckExact(self) ||
        !py::detail::is_function_record_capsule(py::reinterpret_borrow<py::capsule>(self)))
        return nullptr;
    return recordOf(self);
}

PyCFunctionWithKeywords asFunctionWithKeywords(PyCFunction function) {
    return reinterpret_cast<PyCFunctionWithKeywords>(reinterpret_cast<void (*)()>(function));
}

/** Routes `object`'s calls through dispatchNamingMisfits() if it is a pybind11 function (or a method of one), and
 *  those of a property's getter, setter and deleter; `attribute` is the name the class gives it. */
void install(py::handle object, const std::string& attribute, bool accessor = false) {
    if (PyObject_TypeCheck(object.ptr(), &PyProperty_Type)) {
        for (const char* function : {"fget", "fset", "fdel"}) install(object.attr(function), attribute, true);
        return;
    }
    // The function a static method holds (the class's staticmethod keeps it alive).
    if (PyObject_TypeCheck(object.ptr(), &PyStaticMethod_Type)) object = object.attr("__func__");
    const FunctionRecord* record = recordOfFunction(object);
    if (record == nullptr) return;
    attributes[record] = Attribute{attribute, accessor};
    const py::handle function = py::detail::get_function(object);
    PyMethodDef* definition = reinterpret_cast<PyCFunctionObject*>(function.ptr())->m_ml;
    const PyCFunctionWithKeywords current = asFunctionWithKeywords(definition->ml_meth);
    if (current == &dispatchNamingMisfits) return;
    if (pybindDispatcher == nullptr) pybindDispatcher = current;
    // Only pybind11's own dispatcher is known to refuse as misfit() reads the record.
    if (current != pybindDispatcher) return;
    definition->ml_meth = reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&dispatchNamingMisfits));
}

/** pybind11_object's own tp_new, kept by guardTheInstanceBase(). */
newfunc gInstanceBaseNew = nullptr;

/** pybind11_object's tp_new, refusing a type with no pybind11 class among its bases. pybind11 (2.10, upstream too)
 *  throws out of its C tp_new for one, which ends the interpreter with std::terminate: `pybind11_object()`, reached
 *  as `type(inkgraph.Look()).__mro__[1]()`, or a Python class derived from it alone. */
PyObject* newOfAClassWithAValue(PyTypeObject* type, PyObject* arguments, PyObject* keywords) {
    if (py::detail::all_type_info(type).empty()) {
        PyErr_Format(PyExc_TypeError, "%s(): cannot be made: it holds no value of a bound C++ class", type->tp_name);
        return nullptr;
    }
    return gInstanceBaseNew(type, arguments, keywords);
}

/** Puts newOfAClassWithAValue() in place of pybind11_object's tp_new, once: in the base and in every class that took
 *  it from the base (each pybind11 class, of this module and of any other sharing the base, and Python classes
 *  derived from them), since Python refuses `Look.__new__(Look)` as unsafe where a class's tp_new and the base's
 *  differ. Classes made later take the guard from the base. A class with a value reaches pybind11's own tp_new
 *  through it. */
void guardTheInstanceBase() {
    auto* base = reinterpret_cast<PyTypeObject*>(py::detail::get_internals().instance_base);
    if (base->tp_new == newOfAClassWithAValue) return;
    gInstanceBaseNew = base->tp_new;
    std::vector<py::handle> classes{py::handle(reinterpret_cast<PyObject*>(base))};
    std::set<PyObject*> visited;
    while (!classes.empty()) {
        const py::handle type = classes.back();
        classes.pop_back();
        if (!visited.insert(type.ptr()).second) continue; // a class derived from two of them
        auto* object = reinterpret_cast<PyTypeObject*>(type.ptr());
        if (object->tp_new == gInstanceBaseNew) object->tp_new = newOfAClassWithAValue;
        for (const py::handle subclass : type.attr("__subclasses__")()) classes.push_back(subclass);
    }
}

} // namespace

void nameArgumentRefusals(py::module_& m) {
    guardTheInstanceBase();
    // The module's functions and classes, and each class's own attributes (its __dict__, a mapping proxy): methods,
    // static methods, __init__ and the classes nested in it (Renderer.Platform). A class is one of this module's by
    // its __module__ (not a base class it refers to), and is visited once however often it is named.
    std::vector<py::handle> scopes{m};
    std::set<PyObject*> visited;
    while (!scopes.empty()) {
        const py::handle scope = scopes.back();
        scopes.pop_back();
        // A copy of a class's __dict__ (a mapping proxy) as a dict.
        const py::dict members(scope.attr("__dict__"));
        for (const auto [key, member] : members) {
            if (!PyType_Check(member.ptr())) {
                install(member, py::str(key));
            } else if (py::hasattr(member, "__module__") && member.attr("__module__").equal(m.attr("__name__")) &&
                       visited.insert(member.ptr()).second) {
                scopes.push_back(member);
            }
        }
    }
}

} // namespace inkgraph::python
