#include "ArgumentRefusals.h"

#include "CheckedArguments.h"

#include <algorithm>
#include <cstddef>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph::python {

namespace {

namespace py = pybind11;
using FunctionRecord = py::detail::function_record;

/** pybind11's dispatcher, which every function of the module calls through its PyMethodDef (the same one for all). */
PyCFunctionWithKeywords pybindDispatcher = nullptr;

/** "Scene.load(): ", "Orbit(): " for a constructor, "sample_views(): " for a function of the module. */
std::string whereOf(const FunctionRecord& function) {
    const std::string name = function.name;
    if (!function.scope || !PyType_Check(function.scope.ptr())) return name + "(): ";
    const std::string type = py::str(function.scope.attr("__name__"));
    if (name == "__init__") return type + "(): ";
    return type + "." + name + "(): ";
}

std::string quotedName(const std::string& name) { return "'" + name + "'"; }

std::string quotedNames(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + quotedName(name);
    return text;
}

/** "azimuth, elevation", as the Python-level functions list the keywords they take. */
std::string plainNames(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
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

/** Why pybind11 found no way to fit the call (`arguments`, `keywords`, self first for a method) to `function`'s
 *  parameter list, in the order it tries: positions, then keywords and defaults. Nothing when the call fits, so that
 *  the refusal came from the function itself. */
std::optional<Misfit> misfit(const FunctionRecord& function, PyObject* arguments, PyObject* keywords) {
    const std::size_t self = function.is_method ? 1 : 0;
    const auto given = std::size_t(PyTuple_GET_SIZE(arguments));
    if (given < self) return Misfit{"missing required argument 'self'", ""};
    const std::size_t positional = function.nargs_pos;
    const std::size_t needed = function.nargs - std::size_t(function.has_args) - std::size_t(function.has_kwargs);
    std::vector<std::string> names;
    for (std::size_t index = self; index < function.args.size(); ++index) {
        const char* name = function.args[index].name;
        names.emplace_back(name != nullptr ? name : "");
    }

    if (!function.has_args && given > positional) {
        const std::size_t most = positional - self;
        const std::string got = ", got " + std::to_string(given - self);
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
            const std::string keyword = py::str(key).attr("encode")("utf-8", "backslashreplace").cast<std::string>();
            std::size_t index = self;
            while (index < function.args.size() &&
                   (function.args[index].name == nullptr || keyword != function.args[index].name))
                ++index;
            if (index >= function.args.size()) {
                if (function.has_kwargs) continue;
                return Misfit{"unexpected keyword argument " + reprText(key),
                              names.empty() ? " (it takes no keyword arguments)"
                                            : " (arguments: " + plainNames(names) + ")"};
            }
            if (index < std::min(given, positional))
                return Misfit{"argument " + quotedName(keyword) + " given twice, by position and by keyword", ""};
            if (index < function.nargs_pos_only)
                return Misfit{"argument " + quotedName(keyword) + " is positional only, given by keyword", ""};
        }
    }

    // The positions given fill the parameters before them; the rest come from keywords or defaults.
    const std::size_t missingFrom = std::max(self, std::min(given, positional));
    std::vector<std::string> missing;
    for (std::size_t index = missingFrom; index < needed; ++index) {
        if (index >= function.args.size())
            return Misfit{"takes " + countOf(needed - self, "argument") + ", got " + std::to_string(given - self), ""};
        const py::detail::argument_record& parameter = function.args[index];
        const bool byKeyword = keywords != nullptr && parameter.name != nullptr && index >= function.nargs_pos_only &&
                               PyDict_GetItemString(keywords, parameter.name) != nullptr;
        if (!byKeyword && !parameter.value) missing.emplace_back(parameter.name != nullptr ? parameter.name : "?");
    }
    if (missing.size() == 1) return Misfit{"missing required argument " + quotedName(missing.front()), ""};
    if (!missing.empty()) return Misfit{"missing required arguments " + quotedNames(missing), ""};
    return std::nullopt;
}

/** The refusal of a call to `function` (the head of its overload chain): misfit()'s, for an overloaded function the
 *  reason all its overloads share (a keyword none takes). Nothing when one fits or their reasons differ: pybind11's
 *  refusal, which lists every overload, says more. */
std::optional<std::string> refusal(const FunctionRecord& function, PyObject* arguments, PyObject* keywords) {
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

/** Calls pybind11's dispatcher; a TypeError for a call that does not fit the function's one parameter list is
 *  replaced by misfit()'s. Every other result and error passes through as it is. */
PyObject* dispatchNamingMisfits(PyObject* capsule, PyObject* arguments, PyObject* keywords) {
    PyObject* result = nullptr;
    bool refused = false;
    bool escaped = false;
    try {
        result = pybindDispatcher(capsule, arguments, keywords);
        refused = result == nullptr && PyErr_ExceptionMatches(PyExc_TypeError);
    } catch (py::error_already_set& error) {
        // pybind11 writes its refusal outside its own try: a keyword that is a lone surrogate fails to encode there,
        // and the exception would leave a C function (std::terminate).
        error.restore();
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
        const auto record = py::reinterpret_borrow<py::capsule>(capsule);
        const auto* function = record.get_pointer<FunctionRecord>();
        message = refusal(*function, arguments, keywords);
        // A call pybind11 refused for another reason (None for self), with such a keyword among its arguments.
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

PyCFunctionWithKeywords asFunctionWithKeywords(PyCFunction function) {
    return reinterpret_cast<PyCFunctionWithKeywords>(reinterpret_cast<void (*)()>(function));
}

/** Routes `object`'s calls through dispatchNamingMisfits() if it is a pybind11 function (or a method of one). */
void install(py::handle object) {
    // The function a static method holds (the class's staticmethod keeps it alive).
    if (PyObject_TypeCheck(object.ptr(), &PyStaticMethod_Type)) object = object.attr("__func__");
    const py::handle function = py::detail::get_function(object);
    if (!function || !PyCFunction_Check(function.ptr())) return;
    PyObject* self = PyCFunction_GET_SELF(function.ptr());
    if (self == nullptr || !PyCapsule_CheckExact(self) ||
        !py::detail::is_function_record_capsule(py::reinterpret_borrow<py::capsule>(self)))
        return;
    PyMethodDef* definition = reinterpret_cast<PyCFunctionObject*>(function.ptr())->m_ml;
    const PyCFunctionWithKeywords current = asFunctionWithKeywords(definition->ml_meth);
    if (current == &dispatchNamingMisfits) return;
    if (pybindDispatcher == nullptr) pybindDispatcher = current;
    // Only pybind11's own dispatcher is known to refuse as misfit() reads the record.
    if (current != pybindDispatcher) return;
    definition->ml_meth = reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&dispatchNamingMisfits));
}

} // namespace

void nameArgumentRefusals(py::module_& m) {
    for (const auto item : py::reinterpret_borrow<py::dict>(m.attr("__dict__"))) {
        const py::handle value = item.second;
        if (!PyType_Check(value.ptr())) {
            install(value);
            continue;
        }
        // A class's own attributes (its __dict__, a mapping proxy): methods, static methods, __init__.
        for (const py::handle member : value.attr("__dict__").attr("values")()) install(member);
    }
}

} // namespace inkgraph::python
