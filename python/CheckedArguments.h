#pragma once
/** @file Arguments converted by the binding itself, so that a value of the wrong type is a TypeError naming the
 *  function, the argument and the type it takes ("Frame(): width: expected an int from -2147483648 to 2147483647, got
 *  2147483648"). pybind11's own refusal ("incompatible function arguments", the signatures and every value given)
 *  named no argument. `checked(where, names, f)` wraps a function whose parameters are typed: pybind11 passes each
 *  argument through as it is (Loose<T>, named in the signature as T is, so help() and the stubs read as before), and
 *  the wrapper converts each with T's own caster in turn, refusing the first that does not convert. Parameters that
 *  take any object already (py::handle, py::object, py::args, py::kwargs) are passed as they are. Only the types of
 *  the arguments given are checked here: a missing or unknown keyword, or too many values, is named by
 *  ArgumentRefusals.h. */

#include <pybind11/pybind11.h>

#include <cstddef>
#include <limits>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace inkgraph::python {

/** An argument as the caller gave it, for checked() to convert to T. */
template <typename T>
struct Loose {
    pybind11::object object;
};

} // namespace inkgraph::python

namespace pybind11::detail {

template <typename T>
struct type_caster<inkgraph::python::Loose<T>> {
    PYBIND11_TYPE_CASTER(inkgraph::python::Loose<T>, make_caster<T>::name);

    bool load(handle source, bool) {
        value.object = reinterpret_borrow<object>(source);
        return true;
    }
    static handle cast(const inkgraph::python::Loose<T>& loose, return_value_policy, handle) {
        return loose.object.inc_ref();
    }
};

} // namespace pybind11::detail

namespace inkgraph::python {

/** Whether pybind11 passes a parameter of type T as the object itself (nothing to check). */
template <typename T>
constexpr bool takesAnyObject =
    std::is_same_v<std::decay_t<T>, pybind11::handle> || std::is_same_v<std::decay_t<T>, pybind11::object> ||
    std::is_same_v<std::decay_t<T>, pybind11::args> || std::is_same_v<std::decay_t<T>, pybind11::kwargs>;

/** The type a wrapper's parameter has for a wrapped parameter of type T. */
template <typename T>
using Passed = std::conditional_t<takesAnyObject<T>, T, Loose<T>>;

/** What T is called in a refusal: its caster's name, a registered class by its Python name ("Look", "Optional[Frame]",
 *  "List[str]"); an integer with its range, which pybind11's name leaves out. */
template <typename T>
std::string expectedText() {
    using Plain = std::decay_t<T>;
    if constexpr (std::is_integral_v<Plain> && !std::is_same_v<Plain, bool>) {
        return "an int from " + std::to_string(std::numeric_limits<Plain>::min()) + " to " +
               std::to_string(std::numeric_limits<Plain>::max());
    } else {
        constexpr auto name = pybind11::detail::make_caster<T>::name;
        const auto types = name.types();
        std::string text;
        std::size_t type = 0;
        for (const char* c = name.text; *c != '\0'; ++c) {
            if (*c != '%') {
                text += *c;
                continue;
            }
            const std::type_info* info = types[type++];
            const pybind11::detail::type_info* registered =
                info != nullptr ? pybind11::detail::get_type_info(*info) : nullptr;
            std::string typeName = registered != nullptr ? registered->type->tp_name : "object";
            if (const auto dot = typeName.rfind('.'); dot != std::string::npos) typeName.erase(0, dot + 1);
            text += typeName;
        }
        if (text == "os.PathLike") return "a path (str or os.PathLike)";
        return text;
    }
}

/** A str as UTF-8, lone surrogates (as os.fsdecode leaves undecodable bytes) escaped (\udcff) rather than refused. */
inline std::string escapedUtf8(pybind11::handle text) {
    return pybind11::reinterpret_borrow<pybind11::str>(text)
        .attr("encode")("utf-8", "backslashreplace")
        .cast<std::string>();
}

/** "a, b, c": names as Python's messages list them. */
inline std::string commaSeparated(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) {
        if (!text.empty()) text += ", ";
        text += name;
    }
    return text;
}

/** repr(value) as UTF-8, lone surrogates escaped; for a value whose __repr__ raises an Exception, its type's name
 *  (the refusal stays a TypeError). An interrupt or SystemExit there is raised as it is. */
inline std::string reprText(pybind11::handle value) {
    try {
        return escapedUtf8(pybind11::repr(value));
    } catch (pybind11::error_already_set& error) {
        if (!error.matches(PyExc_Exception)) throw;
        return std::string("<") + Py_TYPE(value.ptr())->tp_name + " object whose repr() raised>";
    }
}

/** A function `f` whose arguments are converted by its own parameters' casters, each refused by name. */
template <typename Function, typename Return, typename... Parameters>
class Checked {
public:
    Checked(std::string where, std::vector<std::string> names, Function function)
        : mWhere(std::move(where)), mNames(std::move(names)), mFunction(std::move(function)) {}

    Return operator()(Passed<Parameters>... arguments) const {
        return call(std::index_sequence_for<Parameters...>(), arguments...);
    }

private:
    /** The caster of a parameter that checked() converts, an empty slot for one passed as it is. */
    struct Nothing {};
    template <typename T>
    using Slot = std::conditional_t<takesAnyObject<T>, Nothing, pybind11::detail::make_caster<T>>;

    template <std::size_t... Index>
    Return call(std::index_sequence<Index...>, Passed<Parameters>&... arguments) const {
        std::tuple<Slot<Parameters>...> slots;
        (load<Index, Parameters>(std::get<Index>(slots), arguments), ...);
        return mFunction(take<Parameters>(std::get<Index>(slots), arguments)...);
    }

    template <std::size_t Index, typename T>
    void load(Slot<T>& slot, Passed<T>& argument) const {
        if constexpr (!takesAnyObject<T>) {
            // A class's caster takes None as a null pointer, which pybind11 refuses before it when it converts.
            constexpr bool aClass = std::is_base_of_v<pybind11::detail::type_caster_generic, Slot<T>>;
            if (!(aClass && argument.object.is_none()) && slot.load(argument.object, true)) return;
            const std::string name = Index < mNames.size() ? mNames[Index] : "argument " + std::to_string(Index + 1);
            throw pybind11::type_error(mWhere + (name.empty() ? "" : name + ": ") + "expected " + expectedText<T>() +
                                       ", got " + reprText(argument.object));
        }
    }

    template <typename T>
    static decltype(auto) take(Slot<T>& slot, Passed<T>& argument) {
        if constexpr (takesAnyObject<T>) {
            return static_cast<T>(argument);
        } else {
            return pybind11::detail::cast_op<T>(std::move(slot));
        }
    }

    std::string mWhere;
    std::vector<std::string> mNames;
    Function mFunction;
};

template <typename Function, typename Method>
struct CheckedOf;
template <typename Function, typename Class, typename Return, typename... Parameters>
struct CheckedOf<Function, Return (Class::*)(Parameters...) const> {
    using Type = Checked<Function, Return, Parameters...>;
};

/** `function` (a lambda) with its arguments checked: `where` starts each refusal ("Look.set(): ", or "Look.bands: "
 *  for a setter), then the parameter's name in `names` (one per parameter, "" for none: a setter's value). */
template <typename Function>
auto checked(std::string where, std::vector<std::string> names, Function function) {
    using Type = typename CheckedOf<Function, decltype(&Function::operator())>::Type;
    return Type(std::move(where), std::move(names), std::move(function));
}

} // namespace inkgraph::python
