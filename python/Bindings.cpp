/** @file The bindings of `inkgraph._inkgraph` (Bindings.h): the public C++ API (api/include/inkgraph/inkgraph.h) for
 *  Python, one class per API class under its own name, members in Python's spelling (Look.from_arguments,
 *  Still.buffer_names, Frame.frame_nodes), enum members in Python's constant spelling (Shading.CEL,
 *  LineType.NORMAL_EDGE), each also named by its command-line word (LineType.from_name("normal-edge"), .cli_name),
 *  and that word accepted wherever the enum is. The Pythonic front (inkgraph.render(), looks as dicts, the default
 *  renderer) is python/inkgraph/__init__.py; the exception classes are python/inkgraph/_errors.py, and every
 *  inkgraph::api::Error reaches Python as the one of its kind; a warning record is an inkgraph.InkgraphWarning
 *  (python/inkgraph/_warnings.py), issued through Python's warnings module when a load or a render makes it.
 *
 *  The small value types (Vec3, Color, Orbit, Clip, LineStyle, StrokeSettings) are immutable in Python: a Look's and a
 *  Frame's getters return copies, so `frame.eye.x = 1` on a mutable copy would change nothing and say nothing;
 *  `replace()` gives a changed copy to assign back.
 *
 *  Images reach Python without a copy: a buffer's array points into the Still's pixels and keeps the Still alive as
 *  its base object; the arrays are read-only, since a Still's images are shared and never change. Scene.from_arrays()
 *  hands the C++ call copies of its own (converted to float32 and uint32 in C order, or copied as they are), since it
 *  reads them without the GIL while other threads may change the caller's. */

#include "Bindings.h"
#include "ArgumentRefusals.h"
#include "CheckedArguments.h"
#include "WithoutGil.h"

#include <inkgraph/inkgraph.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <mutex>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

namespace py = pybind11;
namespace ig = inkgraph::api;
using namespace pybind11::literals;
using inkgraph::python::CallsAtExit;
using inkgraph::python::checked;
using inkgraph::python::commaSeparated;
using inkgraph::python::escapedUtf8;
using inkgraph::python::reprText;
using inkgraph::python::withoutGil;

namespace {

/** Text a caller gives (a flag's value, which may be a path; a name) as the bytes it stands for. A str from
 *  os.listdir() or os.fsdecode() carries each byte that is not UTF-8 as a lone surrogate (U+DC80-U+DCFF): those become
 *  the bytes again, as os.fsencode() makes them, so a shade map or pose file of such a name is found. pybind11's
 *  std::string refused the whole call with TypeError. */
struct OsText {
    std::string bytes;
};

} // namespace

namespace pybind11::detail {

template <>
struct type_caster<OsText> {
    PYBIND11_TYPE_CASTER(OsText, const_name("str"));

    bool load(handle source, bool) {
        if (!PyUnicode_Check(source.ptr())) return false;
        // Any other lone surrogate names no file: escaped (\udXXX), it is a name like any other, and refused as
        // unknown by the library.
        for (const char* errors : {"surrogateescape", "backslashreplace"}) {
            PyObject* encoded = PyUnicode_AsEncodedString(source.ptr(), "utf-8", errors);
            if (encoded == nullptr) {
                PyErr_Clear();
                continue;
            }
            value.bytes.assign(PyBytes_AS_STRING(encoded), std::size_t(PyBytes_GET_SIZE(encoded)));
            Py_DECREF(encoded);
            // The library takes C strings for paths: "a.png\0junk" would read a.png, and a message would end at the
            // NUL. Refused as Python refuses it in a path (open(): "embedded null character").
            if (const auto nul = value.bytes.find('\0'); nul != std::string::npos)
                throw ig::Error(ig::Error::Kind::Usage, "inkgraph: a str argument holds a NUL character (at offset " +
                                                            std::to_string(nul) +
                                                            "); no flag value, name or path holds one");
            return true;
        }
        return false;
    }

    /** Back to a str as os.fsdecode() makes it (the default values in the signatures). */
    static handle cast(const OsText& text, return_value_policy, handle) {
        return PyUnicode_DecodeUTF8(text.bytes.data(), Py_ssize_t(text.bytes.size()), "surrogateescape");
    }
};

} // namespace pybind11::detail

namespace {

/** The class of python/inkgraph/_errors.py that stands for `kind`. */
const char* errorClassName(ig::Error::Kind kind) {
    switch (kind) {
    case ig::Error::Kind::Usage: return "UsageError";
    case ig::Error::Kind::Input: return "InputError";
    case ig::Error::Kind::Context: return "ContextError";
    case ig::Error::Kind::Output: return "OutputError";
    case ig::Error::Kind::Render: return "RenderError";
    }
    return "RenderError";
}

/** Text the library made (a message, a name read from a model file) as a str. Bytes that are not UTF-8 (a Latin-1 or
 *  Shift-JIS name in an older tool's OBJ or MTL, a path's) are escaped as \xNN instead of refused: pybind11's own
 *  conversion raised UnicodeDecodeError for the whole call. */
py::str textOf(const std::string& text) {
    PyObject* decoded = PyUnicode_DecodeUTF8(text.data(), Py_ssize_t(text.size()), "backslashreplace");
    if (decoded == nullptr) throw py::error_already_set();
    return py::reinterpret_steal<py::str>(decoded);
}

/** Each of `texts` as textOf() makes it. */
py::list textOf(const std::vector<std::string>& texts) {
    py::list list;
    for (const std::string& text : texts) list.append(textOf(text));
    return list;
}

/** A file's path as os.fsdecode() makes it: bytes that are not UTF-8 become lone surrogates, which os.fsencode()
 *  turns back into the same bytes, so the str names the same file. */
py::str pathTextOf(const std::string& path) {
    PyObject* decoded = PyUnicode_DecodeUTF8(path.data(), Py_ssize_t(path.size()), "surrogateescape");
    if (decoded == nullptr) throw py::error_already_set();
    return py::reinterpret_steal<py::str>(decoded);
}

/** Sets the Python error for `error`: its class by kind, the message as the library wrote it (textOf()), the exit
 *  code `inkgraph render` would give. Looked up when raised, since _errors.py is imported by the package that
 *  imports this module. */
void raisePythonError(const ig::Error& error) {
    const py::object type = py::module_::import("inkgraph._errors").attr(errorClassName(error.kind()));
    const py::object value = type(textOf(error.what()), "exit_code"_a = error.exitCode());
    PyErr_SetObject(type.ptr(), value.ptr());
}

[[noreturn]] void failUsage(const std::string& message) { throw ig::Error(ig::Error::Kind::Usage, message); }
[[noreturn]] void failInput(const std::string& message) { throw ig::Error(ig::Error::Kind::Input, message); }

/** Text a caller gave back as a list of str, as os.fsdecode() makes them: a value set from a name that is not UTF-8
 *  reads back as the str it was set from (pybind11's own conversion raised UnicodeDecodeError). */
py::list osTextsOf(const std::vector<std::string>& texts) {
    py::list list;
    for (const std::string& text : texts) list.append(pathTextOf(text));
    return list;
}

std::vector<std::string> bytesOf(const std::vector<OsText>& texts) {
    std::vector<std::string> bytes;
    bytes.reserve(texts.size());
    for (const OsText& text : texts) bytes.push_back(text.bytes);
    return bytes;
}

// ---- Warnings ------------------------------------------------------------------------------------------------------

/** The records as inkgraph.InkgraphWarning objects: a Warning category of its own, so that Python's warnings filters
 *  can select them, with the record's fields as attributes. */
py::list warningObjects(const std::vector<ig::Warning>& warnings) {
    const py::object type = py::module_::import("inkgraph._warnings").attr("InkgraphWarning");
    py::list objects;
    for (const ig::Warning& warning : warnings)
        objects.append(type(textOf(warning.message), "code"_a = warning.code, "file"_a = pathTextOf(warning.file),
                            "item"_a = textOf(warning.item)));
    return objects;
}

/** Issues each record through warnings.warn(), attributed to the first caller outside the package (_warnings.py
 *  finds it). Under an "error" filter the first raises, and so does the call that made them. */
void issueWarnings(const py::list& objects) {
    if (!objects.empty()) py::module_::import("inkgraph._warnings").attr("issue")(objects);
}

// ---- Enums ---------------------------------------------------------------------------------------------------------

std::string cliName(ig::Shading value) { return ig::nameOf(value); }
std::string cliName(ig::LineType value) { return ig::nameOf(value); }
std::string cliName(ig::ViewVector value) { return ig::nameOf(value); }
std::string cliName(ig::FaceOrientation value) { return ig::nameOf(value); }
std::string cliName(ig::Precision value) { return ig::nameOf(value); }
// The API names these three nowhere: the words of --camera and --egl-platform, and CameraSource's members lowercased
// (it has no flag).
std::string cliName(ig::CameraPlacement value) { return value == ig::CameraPlacement::Auto ? "auto" : "file"; }
std::string cliName(ig::CameraSource value) {
    switch (value) {
    case ig::CameraSource::File: return "file";
    case ig::CameraSource::Auto: return "auto";
    case ig::CameraSource::Orbit: return "orbit";
    case ig::CameraSource::Eye: return "eye";
    }
    return "auto";
}
std::string cliName(ig::Renderer::Platform value) {
    switch (value) {
    case ig::Renderer::Platform::Auto: return "auto";
    case ig::Renderer::Platform::Device: return "device";
    case ig::Renderer::Platform::Surfaceless: return "surfaceless";
    }
    return "auto";
}

/** Every member of an enum as Python has it, in declaration order, and what the enum is called in messages. */
template <typename Enum>
struct EnumMembers {
    static inline std::vector<Enum> values;
    static inline std::string className;
    static inline std::string what; ///< "shading", "line type"
};

template <typename Enum>
std::string availableNames() {
    std::string names;
    for (const Enum value : EnumMembers<Enum>::values) names += (names.empty() ? "" : ", ") + cliName(value);
    return names;
}

template <typename Enum>
Enum enumNamed(const std::string& name, const std::string& where) {
    for (const Enum value : EnumMembers<Enum>::values)
        if (cliName(value) == name) return value;
    failUsage(where + ": unknown " + EnumMembers<Enum>::what + " '" + name + "' (available: " + availableNames<Enum>() +
              ")");
}

/** `value` as the enum: a member, or its command-line word ("normal-edge"). */
template <typename Enum>
Enum enumArgument(py::handle value, const std::string& where) {
    if (py::isinstance<Enum>(value)) return value.cast<Enum>();
    if (py::isinstance<py::str>(value)) return enumNamed<Enum>(escapedUtf8(value), where);
    throw py::type_error(where + ": expected a " + EnumMembers<Enum>::className + " or its name (" +
                         availableNames<Enum>() + "), got " + reprText(value));
}

template <typename Enum, typename Scope>
py::enum_<Enum> defineEnum(Scope& scope, const char* className, const char* what, const char* doc,
                           std::initializer_list<std::pair<const char*, Enum>> members) {
    py::enum_<Enum> type(scope, className, doc);
    // "Renderer.Platform" for one nested in a class, as its refusals name it.
    const std::string qualifiedName = type.attr("__qualname__").template cast<std::string>();
    EnumMembers<Enum>::className = className;
    EnumMembers<Enum>::what = what;
    for (const auto& [name, value] : members) {
        type.value(name, value);
        EnumMembers<Enum>::values.push_back(value);
    }
    type.def(
        py::init(checked(qualifiedName + "(): ", {"name"},
                         [](const OsText& name) { return enumNamed<Enum>(name.bytes, EnumMembers<Enum>::className); })),
        "name"_a, "The member named by its command-line word, as from_name().");
    type.def_static(
        "from_name",
        checked(qualifiedName + ".from_name(): ", {"name"},
                [](const OsText& name) { return enumNamed<Enum>(name.bytes, EnumMembers<Enum>::className); }),
        "name"_a, "The member named by its command-line word; UsageError naming the words there are.");
    type.def_property_readonly(
        "cli_name", [](Enum value) { return cliName(value); }, "The command line's word for this member.");
    // Pickled as the member of its value, by every protocol: pybind11's own pickling of protocols 0 and 1 went through
    // copyreg to pybind11's base class, whose allocation throws through C (the interpreter aborted).
    type.def("__reduce__", [](Enum self) {
        return py::make_tuple(py::type::of<Enum>(), py::make_tuple(static_cast<std::int64_t>(self)));
    });
    return type;
}

// ---- Numbers and the small value types -----------------------------------------------------------------------------

/** A real number (an int, a float, a NumPy scalar; not a str, not a bool), else TypeError naming `where`. */
double realNumber(py::handle value, const std::string& where) {
    if (!PyNumber_Check(value.ptr()) || PyBool_Check(value.ptr()) || PyComplex_Check(value.ptr()))
        throw py::type_error(where + ": expected a number, got " + reprText(value));
    const double number = PyFloat_AsDouble(value.ptr());
    if (number == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        throw py::value_error(where + ": " + reprText(value) + " is not a number a double holds");
    }
    return number;
}

/** The numbers of a tuple, list or 1-D array of `counts` numbers, else TypeError naming `where` and `expected`. */
std::vector<double> realNumbers(py::handle value, std::initializer_list<std::size_t> counts, const std::string& where,
                                const std::string& expected) {
    const auto fail = [&] { throw py::type_error(where + ": expected " + expected + ", got " + reprText(value)); };
    if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value))
        fail();
    const auto sequence = py::reinterpret_borrow<py::sequence>(value);
    const std::size_t count = py::len(sequence);
    bool countFits = false;
    for (const std::size_t allowed : counts) countFits = countFits || count == allowed;
    if (!countFits) fail();
    std::vector<double> numbers;
    // Each item held as an object: a sequence's items may be made on access (a NumPy array's scalars), and a handle
    // would outlive them.
    for (const py::object item : sequence) numbers.push_back(realNumber(item, where));
    return numbers;
}

ig::Vec3 vec3Argument(py::handle value, const std::string& where) {
    if (py::isinstance<ig::Vec3>(value)) return value.cast<ig::Vec3>();
    const std::vector<double> xyz = realNumbers(value, {3}, where, "a Vec3 or (x, y, z)");
    return ig::Vec3{xyz[0], xyz[1], xyz[2]};
}

ig::Color colorArgument(py::handle value, const std::string& where) {
    if (py::isinstance<ig::Color>(value)) return value.cast<ig::Color>();
    const std::vector<double> rgba = realNumbers(value, {3, 4}, where, "a Color, (r, g, b) or (r, g, b, a)");
    return ig::Color{rgba[0], rgba[1], rgba[2], rgba.size() == 4 ? rgba[3] : 1.0};
}

ig::Orbit orbitArgument(py::handle value, const std::string& where) {
    if (py::isinstance<ig::Orbit>(value)) return value.cast<ig::Orbit>();
    const std::vector<double> numbers =
        realNumbers(value, {2, 3}, where, "an Orbit, (azimuth, elevation) or (azimuth, elevation, distance)");
    ig::Orbit orbit{numbers[0], numbers[1], std::nullopt};
    if (numbers.size() == 3) orbit.distance = numbers[2];
    return orbit;
}

ig::Clip clipArgument(py::handle value, const std::string& where) {
    if (py::isinstance<ig::Clip>(value)) return value.cast<ig::Clip>();
    const std::vector<double> numbers = realNumbers(value, {2}, where, "a Clip or (near, far)");
    return ig::Clip{numbers[0], numbers[1]};
}

template <typename Value>
std::optional<Value> optionalArgument(py::handle value, Value (*convert)(py::handle, const std::string&),
                                      const std::string& where) {
    if (value.is_none()) return std::nullopt;
    return convert(value, where);
}

/** What every small value type has: equality and a hash by its fields, a repr that constructs it again, and
 *  replace(**changes), a copy with some fields changed. */
template <typename Class>
void addValueProtocol(Class& type, std::vector<std::string> fields) {
    const auto fieldTuple = [fields](py::handle self) {
        py::list values;
        for (const std::string& field : fields) values.append(self.attr(field.c_str()));
        return py::tuple(values);
    };
    type.def("__eq__", [fieldTuple](py::handle self, py::handle other) -> py::object {
        if (!py::type::of(self).is(py::type::of(other))) return py::reinterpret_borrow<py::object>(Py_NotImplemented);
        return py::bool_(fieldTuple(self).equal(fieldTuple(other)));
    });
    type.def("__hash__", [fieldTuple](py::handle self) { return py::hash(fieldTuple(self)); });
    // Pickled (and copied) as the constructor called with the fields, which it takes in this order.
    type.def("__reduce__",
             [fieldTuple](py::handle self) { return py::make_tuple(py::type::of(self), fieldTuple(self)); });
    type.def("__repr__", [fields](py::handle self) {
        std::string text = py::type::of(self).attr("__name__").cast<std::string>() + "(";
        for (std::size_t i = 0; i < fields.size(); ++i)
            text += (i == 0 ? "" : ", ") + fields[i] + "=" + reprText(self.attr(fields[i].c_str()));
        return text + ")";
    });
    type.def(
        "replace",
        [fields](py::handle self, const py::kwargs& changes) {
            using Value = typename Class::type;
            const std::string typeName = py::str(py::type::of<Value>().attr("__name__"));
            const std::string where = typeName + ".replace(): ";
            if (!py::isinstance<Value>(self))
                throw py::type_error(where + "self: expected " + typeName + ", got " + reprText(self));
            py::dict values;
            for (const std::string& field : fields) values[field.c_str()] = self.attr(field.c_str());
            for (const auto& [name, value] : changes) {
                if (!values.contains(name))
                    throw py::type_error(where + reprText(name) + " is not a field (fields: " + commaSeparated(fields) +
                                         ")");
                values[name] = value;
            }
            return py::type::of(self)(**values);
        },
        "A copy with the fields given changed.");
}

/** The fields of tuple-like value types unpack: `x, y, z = frame.eye`. */
template <typename Class>
void addIteration(Class& type, std::vector<std::string> fields) {
    type.def("__iter__", [fields](py::handle self) {
        py::list values;
        for (const std::string& field : fields) values.append(self.attr(field.c_str()));
        return py::iter(values);
    });
    type.def("__len__", [size = fields.size()](py::handle) { return size; });
}

// ---- Images --------------------------------------------------------------------------------------------------------

/** `image` as a NumPy array over its own pixels (height x width, and x channels unless 1, rows rowBytes() apart),
 *  read-only, keeping `owner` (the Python Still that holds the image, and the array it was drawn into) alive. */
py::array imageArray(const ig::Image& image, py::handle owner) {
    const auto itemSize = static_cast<py::ssize_t>(image.bytesPerChannel());
    const py::ssize_t channels = image.channels();
    std::vector<py::ssize_t> shape{image.height(), image.width()};
    std::vector<py::ssize_t> strides{static_cast<py::ssize_t>(image.rowBytes()), channels * itemSize};
    if (channels != 1) {
        shape.push_back(channels);
        strides.push_back(itemSize);
    }
    const py::dtype dtype =
        image.type() == ig::Image::Type::Float32 ? py::dtype::of<float>() : py::dtype::of<std::uint8_t>();
    py::array array(dtype, shape, strides, image.data(), owner);
    array.attr("flags").attr("writeable") = false;
    return array;
}

/** Python's MemoryError naming what could not be laid out: pybind11's ensure() clears NumPy's own error when a
 *  conversion fails, and with the dtype checked first only memory can make it fail. */
[[noreturn]] void failMemory(const std::string& message) {
    PyErr_SetString(PyExc_MemoryError, message.c_str());
    throw py::error_already_set();
}

/** The pixels of `array`, in C order whatever its strides, as bytes. */
template <typename Channel>
std::vector<std::uint8_t> pixelBytes(const py::array& array) {
    const auto contiguous = py::array_t<Channel, py::array::c_style | py::array::forcecast>::ensure(array);
    if (!contiguous)
        failMemory("write_image(): no memory to lay out the " + std::to_string(array.size()) + " values of the image");
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(contiguous.nbytes()));
    if (!bytes.empty()) std::memcpy(bytes.data(), contiguous.data(), bytes.size());
    return bytes;
}

/** A copy of `array` as an ig::Image: uint8 or float32, height x width or height x width x 1 or 4. */
ig::Image imageFromArray(const py::array& array) {
    const auto fail = [](const std::string& problem) { failUsage("write_image(): " + problem); };
    const py::ssize_t dimensions = array.ndim();
    if (dimensions != 2 && dimensions != 3)
        fail("expected a height x width [x channels] array, got " + std::to_string(dimensions) + " dimensions");
    const py::ssize_t channels = dimensions == 3 ? array.shape(2) : 1;
    if (channels != 1 && channels != 4) fail("expected 1 or 4 channels, got " + std::to_string(channels));
    // Checked before narrowing: a side of 3e9 read as int would be told as a negative size.
    for (const py::ssize_t side : {array.shape(0), array.shape(1)})
        if (side > py::ssize_t(std::numeric_limits<int>::max()))
            fail("an image of " + std::to_string(array.shape(1)) + "x" + std::to_string(array.shape(0)) +
                 " pixels is larger than an image can be (at most " + std::to_string(std::numeric_limits<int>::max()) +
                 " a side)");
    const auto height = static_cast<int>(array.shape(0));
    const auto width = static_cast<int>(array.shape(1));
    if (py::isinstance<py::array_t<std::uint8_t>>(array))
        return ig::Image(width, height, int(channels), ig::Image::Type::UInt8, pixelBytes<std::uint8_t>(array));
    if (py::isinstance<py::array_t<float>>(array))
        return ig::Image(width, height, int(channels), ig::Image::Type::Float32, pixelBytes<float>(array));
    fail("expected a uint8 or float32 array, got " + py::str(array.dtype()).cast<std::string>());
    return {};
}

/** A row-major C++ matrix as a float64 NumPy array of its own. */
template <std::size_t Rows, std::size_t Columns>
py::array_t<double> matrixArray(const std::array<std::array<double, Columns>, Rows>& matrix) {
    py::array_t<double> array({py::ssize_t(Rows), py::ssize_t(Columns)});
    auto cells = array.template mutable_unchecked<2>();
    for (std::size_t row = 0; row < Rows; ++row)
        for (std::size_t column = 0; column < Columns; ++column)
            cells(py::ssize_t(row), py::ssize_t(column)) = matrix[row][column];
    return array;
}

py::object vec3List(const ig::Vec3& v) { return py::cast(std::vector<double>{v.x, v.y, v.z}); }

// ---- Mesh arrays ---------------------------------------------------------------------------------------------------

std::string shapeText(const py::array& array) {
    std::string text = "(";
    for (py::ssize_t axis = 0; axis < array.ndim(); ++axis)
        text += (axis == 0 ? "" : ", ") + std::to_string(array.shape(axis));
    return text + (array.ndim() == 1 ? ",)" : ")");
}

/** Mesh arrays as the C++ call reads them: C order, converted to the element type when they are not. */
using FloatRows = py::array_t<float, py::array::c_style | py::array::forcecast>;
using FaceRows = py::array_t<std::uint32_t, py::array::c_style | py::array::forcecast>;

/** numpy.asarray(value); a sequence NumPy cannot make an array of (rows of different lengths) is the caller's
 *  InputError like any other bad array, not NumPy's ValueError. */
py::array arrayOf(py::handle value, const std::string& where, const std::string& expected) {
    try {
        return py::module_::import("numpy").attr("asarray")(value);
    } catch (py::error_already_set& error) {
        if (!error.matches(PyExc_ValueError)) throw;
        failInput(where + expected + ", got a sequence NumPy cannot make an array of (" +
                  escapedUtf8(py::str(error.value())) + ")");
    }
}

/** `converted` (Rows::ensure() of `array`, numpy.asarray() of the caller's `value`), or a copy of it when it is still
 *  the caller's memory: the library reads the arrays without the GIL, more than once (its checks, then the mesh), and
 *  another Python thread may change them in between (an index made out of range after its check read out of bounds).
 *  A conversion there is no memory for is Python's MemoryError, not a wrong array. */
template <typename Rows>
Rows ownedRows(Rows converted, const py::array& array, py::handle value, const std::string& where, const char* type) {
    if (!converted)
        failMemory(where + "cannot be converted to " + type + ": no memory for its " + std::to_string(array.size()) +
                   " values");
    const bool callersMemory = array.ptr() == value.ptr() || !array.owndata();
    if (callersMemory && converted.data() == array.data()) {
        Rows owned = Rows::ensure(py::module_::import("numpy").attr("array")(converted, "copy"_a = true));
        if (!owned) failMemory(where + "no memory for a copy of its " + std::to_string(array.size()) + " values");
        return owned;
    }
    return converted;
}

/** A 2-D array of `columns` (one of them) numbers a row, as a float32 array in C order of the binding's own. `rows`,
 * when given, is the count it must have (one per vertex). */
FloatRows floatRows(py::handle value, const std::string& name, std::initializer_list<py::ssize_t> columns,
                    std::optional<py::ssize_t> rows) {
    const std::string where = "Scene.from_arrays(): " + name + ": ";
    std::string expected = "expected an (N, ";
    for (const py::ssize_t count : columns)
        expected += (expected.back() == ' ' ? "" : " or (N, ") + std::to_string(count) + ")";
    expected += " array of numbers";
    const py::array array = arrayOf(value, where, expected);
    const char kind = array.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
        failInput(where + expected + ", got dtype " + py::str(array.dtype()).cast<std::string>());
    bool columnsFit = false;
    for (const py::ssize_t count : columns) columnsFit = columnsFit || (array.ndim() == 2 && array.shape(1) == count);
    if (!columnsFit) failInput(where + expected + ", got shape " + shapeText(array));
    if (rows && array.shape(0) != *rows)
        failInput(where + "expected " + std::to_string(*rows) + " rows (one per vertex), got " +
                  std::to_string(array.shape(0)));
    return ownedRows(FloatRows::ensure(array), array, value, where, "float32");
}

/** The faces as a uint32 array in C order of the binding's own; other integers are converted after checking that every
 * index fits (a negative one would wrap to a large valid-looking one). */
FaceRows faceRows(py::handle value) {
    const std::string where = "Scene.from_arrays(): faces: ";
    const std::string expected = "expected an (M, 3) array of integer vertex indices";
    const py::array array = arrayOf(value, where, expected);
    const char kind = array.dtype().kind();
    if (kind != 'i' && kind != 'u')
        failInput(where + expected + ", got dtype " + py::str(array.dtype()).cast<std::string>());
    if (array.ndim() != 2 || array.shape(1) != 3) failInput(where + expected + ", got shape " + shapeText(array));
    if (!py::isinstance<py::array_t<std::uint32_t>>(array) && array.size() > 0) {
        const py::int_ smallest = array.attr("min")();
        const py::int_ largest = array.attr("max")();
        if (smallest < py::int_(0)) failInput(where + "index " + reprText(smallest) + " is negative");
        if (largest > py::int_(std::uint32_t(-1)))
            failInput(where + "index " + reprText(largest) + " does not fit in 32 bits");
    }
    return ownedRows(FaceRows::ensure(array), array, value, where, "uint32");
}

// ---- Stills and the renderer ---------------------------------------------------------------------------------------

/** A still for Python: the C++ still and, when it was rendered into an array of the caller's (render(out=...)), that
 *  array, which the still's picture views and so must outlive it (the picture's arrays keep the still alive). */
struct PythonStill {
    ig::Still still;
    py::object out;
};

/** Scene.objects' and Still.objects' dicts. */
py::list objectDicts(const std::vector<ig::SceneObject>& found) {
    py::list objects;
    for (const ig::SceneObject& object : found)
        objects.append(py::dict("id"_a = object.id, "name"_a = textOf(object.name),
                                "node_path"_a = textOf(object.nodePath), "meshes"_a = textOf(object.meshes)));
    return objects;
}

/** Scene.meshes' and Still.meshes' dicts, with the --dump manifest's keys. */
py::list meshDicts(const std::vector<ig::SceneMesh>& found) {
    py::list meshes;
    for (const ig::SceneMesh& mesh : found)
        meshes.append(py::dict("id"_a = mesh.id, "drawn"_a = mesh.drawn, "name"_a = textOf(mesh.name),
                               "node_path"_a = textOf(mesh.nodePath), "object_id"_a = mesh.objectId,
                               "material_id"_a = mesh.materialId, "material"_a = textOf(mesh.material),
                               "first_triangle"_a = mesh.firstTriangle, "triangle_count"_a = mesh.triangleCount));
    return meshes;
}

/** One ig::Renderer for Python: its calls run without the GIL, one at a time (the C++ renderer is not
 *  thread-safe, and Python threads may share the object), and close() ends its GL context at once. */
class PythonRenderer {
public:
    explicit PythonRenderer(ig::Renderer::Platform platform) : mRenderer(std::in_place, platform) {}

    // The look and the frame by value: the render runs without the GIL, while another Python thread may change the
    // objects it was given.
    ig::Still render(const ig::Scene& scene, const ig::Look& look, const ig::Frame& frame,
                     const std::vector<std::string>& buffers, std::uint8_t* out, std::size_t rowBytes) {
        const std::unique_lock lock = oneAtATime();
        ig::Renderer& renderer = open("Renderer.render()");
        return out ? renderer.renderInto(out, rowBytes, scene, look, frame, buffers)
                   : renderer.render(scene, look, frame, buffers);
    }
    std::string glDescription() {
        const std::unique_lock lock = oneAtATime();
        return mRenderer ? mRenderer->glDescription() : "";
    }
    void close() {
        const std::unique_lock lock = oneAtATime();
        mRenderer.reset();
        mClosed = true;
    }
    /** Without the lock: whether it is closed needs no wait for a render another thread is in. */
    bool closed() const { return mClosed; }

private:
    /** The lock of this renderer's calls; none in a process forked from the one that made it, which has only the
     *  thread that forked: the lock may be held by a thread of the parent's that it lacks (a render then refuses, as
     *  the library refuses a forked context). */
    std::unique_lock<std::mutex> oneAtATime() {
        return int(getpid()) == mMadeInProcess ? std::unique_lock(mMutex) : std::unique_lock<std::mutex>();
    }

    ig::Renderer& open(const std::string& function) {
        if (!mRenderer) failUsage(function + ": the renderer is closed");
        return *mRenderer;
    }

    std::mutex mMutex;
    const int mMadeInProcess = int(getpid());
    std::optional<ig::Renderer> mRenderer;
    std::atomic<bool> mClosed{false};
};

/** `out` checked as the picture of `frame`: a writable uint8 (height, width, 4) array whose pixels are packed (4
 *  bytes apart, channels 1 apart) and whose rows lie at least width * 4 bytes apart. */
std::size_t pictureRowBytes(const py::handle& out, const ig::Frame& frame) {
    const std::string where = "Renderer.render(): out: ";
    const std::string expected = "expected a writable uint8 array of shape (" + std::to_string(frame.height) + ", " +
                                 std::to_string(frame.width) + ", 4), the frame's height x width x RGBA";
    if (!py::isinstance<py::array>(out)) throw py::type_error(where + expected + ", got " + reprText(out));
    const auto array = py::reinterpret_borrow<py::array>(out);
    if (!py::isinstance<py::array_t<std::uint8_t>>(array))
        failUsage(where + expected + ", got dtype " + py::str(array.dtype()).cast<std::string>());
    if (array.ndim() != 3 || array.shape(0) != frame.height || array.shape(1) != frame.width || array.shape(2) != 4)
        failUsage(where + expected + ", got shape " + shapeText(array));
    if (!array.writeable()) failUsage(where + expected + ", got a read-only array");
    if (array.strides(2) != 1 || array.strides(1) != 4 || array.strides(0) < py::ssize_t(frame.width) * 4)
        failUsage(where +
                  "the pixels of a row must be packed (strides (row, 4, 1) with row >= width * 4), got strides (" +
                  std::to_string(array.strides(0)) + ", " + std::to_string(array.strides(1)) + ", " +
                  std::to_string(array.strides(2)) + ")");
    return std::size_t(array.strides(0));
}

} // namespace

namespace inkgraph::python {

namespace {

void defineValueTypes(py::module_& m) {
    py::class_<ig::Vec3> vec3(m, "Vec3",
                              "A direction or a point, in the model's world units. Immutable; a tuple "
                              "(x, y, z) is taken wherever a Vec3 is.");
    vec3.def(py::init(checked("Vec3(): ", {"x", "y", "z"},
                              [](double x, double y, double z) {
                                  return ig::Vec3{x, y, z};
                              })),
             "x"_a = 0.0, "y"_a = 0.0, "z"_a = 0.0)
        .def_readonly("x", &ig::Vec3::x)
        .def_readonly("y", &ig::Vec3::y)
        .def_readonly("z", &ig::Vec3::z);
    addValueProtocol(vec3, {"x", "y", "z"});
    addIteration(vec3, {"x", "y", "z"});

    py::class_<ig::Color> color(m, "Color",
                                "A colour, display RGBA, channels in [0, 1]. Immutable; a tuple (r, g, b) "
                                "or (r, g, b, a) is taken wherever a Color is.");
    color
        .def(py::init(checked("Color(): ", {"r", "g", "b", "a"},
                              [](double r, double g, double b, double a) {
                                  return ig::Color{r, g, b, a};
                              })),
             "r"_a = 0.0, "g"_a = 0.0, "b"_a = 0.0, "a"_a = 1.0)
        .def_readonly("r", &ig::Color::r)
        .def_readonly("g", &ig::Color::g)
        .def_readonly("b", &ig::Color::b)
        .def_readonly("a", &ig::Color::a);
    addValueProtocol(color, {"r", "g", "b", "a"});
    addIteration(color, {"r", "g", "b", "a"});

    py::class_<ig::Orbit> orbit(m, "Orbit",
                                "--orbit: the eye on a sphere around the target, angles in degrees from the model's "
                                "front; distance None is the auto-framing distance. Immutable; a tuple (azimuth, "
                                "elevation[, distance]) is taken wherever an Orbit is.");
    orbit
        .def(py::init(
                 checked("Orbit(): ", {"azimuth", "elevation", "distance", "distance_scale"},
                         [](double azimuth, double elevation, std::optional<double> distance, double distanceScale) {
                             return ig::Orbit{azimuth, elevation, distance, distanceScale};
                         })),
             "azimuth"_a = 0.0, "elevation"_a = 0.0, "distance"_a = py::none(), "distance_scale"_a = 1.0)
        .def_readonly("azimuth", &ig::Orbit::azimuth)
        .def_readonly("elevation", &ig::Orbit::elevation)
        .def_readonly("distance", &ig::Orbit::distance)
        .def_readonly("distance_scale", &ig::Orbit::distanceScale,
                      "With distance None: the eye at this multiple of the auto-framing distance (--orbit AZ,EL,xS).");
    addValueProtocol(orbit, {"azimuth", "elevation", "distance", "distance_scale"});
    // Unpacks as the tuple an Orbit is taken as; the scale is a field only.
    addIteration(orbit, {"azimuth", "elevation", "distance"});

    py::class_<ig::ViewSample> viewSample(
        m, "ViewSample",
        "One view of --views, as sample_views() draws it and the command line's --stats records it (\"view\"). "
        "Immutable; orbit() is the Orbit that places it in a Frame, light the direction to give Look.light.");
    viewSample
        .def(py::init(checked(
                 "ViewSample(): ", {"index", "azimuth", "elevation", "distance_scale", "light", "expression", "pose"},
                 [](std::size_t index, double azimuth, double elevation, double distanceScale, const py::object& light,
                    const std::optional<OsText>& expression, const std::optional<OsText>& pose) {
                     // As the getters give them back (a pose's path as os.fsdecode() makes it), so a view copies and
                     // pickles as itself: bytes were taken and could not be read back.
                     const auto bytesOfText = [](const std::optional<OsText>& text) {
                         return text ? std::optional<std::string>(text->bytes) : std::nullopt;
                     };
                     return ig::ViewSample{index,
                                           azimuth,
                                           elevation,
                                           distanceScale,
                                           optionalArgument(light, vec3Argument, "ViewSample.light"),
                                           bytesOfText(expression),
                                           bytesOfText(pose)};
                 })),
             "index"_a = 0, "azimuth"_a = 0.0, "elevation"_a = 0.0, "distance_scale"_a = 1.0, "light"_a = py::none(),
             "expression"_a = py::none(), "pose"_a = py::none())
        .def_readonly("index", &ig::ViewSample::index)
        .def_readonly("azimuth", &ig::ViewSample::azimuth)
        .def_readonly("elevation", &ig::ViewSample::elevation)
        .def_readonly("distance_scale", &ig::ViewSample::distanceScale)
        .def_readonly("light", &ig::ViewSample::light)
        .def_property_readonly("expression",
                               [](const ig::ViewSample& self) -> py::object {
                                   if (!self.expression) return py::none();
                                   return textOf(*self.expression);
                               })
        .def_property_readonly("pose",
                               [](const ig::ViewSample& self) -> py::object {
                                   if (!self.pose) return py::none();
                                   return pathTextOf(*self.pose);
                               })
        .def("orbit", &ig::ViewSample::orbit, "The Orbit of this view, for Frame.orbit: distance None, its scale.");
    addValueProtocol(viewSample, {"index", "azimuth", "elevation", "distance_scale", "light", "expression", "pose"});

    py::class_<ig::Clip> clip(m, "Clip",
                              "--clip NEAR,FAR. Immutable; a tuple (near, far) is taken wherever a Clip is.");
    clip.def(py::init(checked("Clip(): ", {"near", "far"},
                              [](double nearPlane, double farPlane) {
                                  return ig::Clip{nearPlane, farPlane};
                              })),
             "near"_a, "far"_a)
        .def_readonly("near", &ig::Clip::near)
        .def_readonly("far", &ig::Clip::far);
    addValueProtocol(clip, {"near", "far"});
    addIteration(clip, {"near", "far"});

    py::class_<ig::LineStyle> lineStyle(m, "LineStyle",
                                        "How one line type is drawn (--TYPE-width in pixels, --TYPE-color). Immutable; "
                                        "replace() gives a changed copy.");
    lineStyle
        .def(py::init(checked("LineStyle(): ", {"width", "color"},
                              [](double width, py::handle lineColor) {
                                  return ig::LineStyle{width, colorArgument(lineColor, "LineStyle.color")};
                              })),
             "width"_a = ig::LineStyle{}.width, "color"_a = ig::Color{})
        .def_readonly("width", &ig::LineStyle::width)
        .def_readonly("color", &ig::LineStyle::color);
    addValueProtocol(lineStyle, {"width", "color"});

    py::class_<ig::StrokeSettings> strokes(m, "StrokeSettings",
                                           "How line pixels become strokes, for every type (docs/strokes.md): "
                                           "--min-stroke-length, --line-weight depth/strength/taper, "
                                           "--overlapping-lines merge. Immutable; replace() gives a changed copy.");
    const ig::StrokeSettings defaults;
    strokes
        .def(py::init(checked(
                 "StrokeSettings(): ",
                 {"min_length", "weight_by_depth", "weight_by_strength", "taper_ends", "merge_overlaps"},
                 [](double minLength, bool weightByDepth, bool weightByStrength, bool taperEnds, bool mergeOverlaps) {
                     return ig::StrokeSettings{minLength, weightByDepth, weightByStrength, taperEnds, mergeOverlaps};
                 })),
             "min_length"_a = defaults.minLength, "weight_by_depth"_a = defaults.weightByDepth,
             "weight_by_strength"_a = defaults.weightByStrength, "taper_ends"_a = defaults.taperEnds,
             "merge_overlaps"_a = defaults.mergeOverlaps)
        .def_readonly("min_length", &ig::StrokeSettings::minLength)
        .def_readonly("weight_by_depth", &ig::StrokeSettings::weightByDepth)
        .def_readonly("weight_by_strength", &ig::StrokeSettings::weightByStrength)
        .def_readonly("taper_ends", &ig::StrokeSettings::taperEnds)
        .def_readonly("merge_overlaps", &ig::StrokeSettings::mergeOverlaps);
    addValueProtocol(strokes, {"min_length", "weight_by_depth", "weight_by_strength", "taper_ends", "merge_overlaps"});
}

void defineEnums(py::module_& m) {
    using S = ig::Shading;
    defineEnum<S>(m, "Shading", "shading", "--shading: how surfaces are shaded (docs/shading.md).",
                  {{"NONE", S::None},
                   {"FLAT", S::Flat},
                   {"GOURAUD", S::Gouraud},
                   {"LAMBERT", S::Lambert},
                   {"PHONG", S::Phong},
                   {"CEL", S::Cel},
                   {"COMIC", S::Comic},
                   {"MTOON", S::MToon},
                   {"AUTO", S::Auto}});
    using L = ig::LineType;
    defineEnum<L>(m, "LineType", "line type",
                  "The line types, in the order the composite draws them (--lines; docs/lines.md).",
                  {{"HIDDEN_MESH_SILHOUETTE", L::HiddenMeshSilhouette},
                   {"HIDDEN_CREASE", L::HiddenCrease},
                   {"HIDDEN_BORDER", L::HiddenBorder},
                   {"HIDDEN_INTERSECTION", L::HiddenIntersection},
                   {"HIDDEN_SUGGESTIVE_OBJECT", L::HiddenSuggestiveObject},
                   {"OUTLINE", L::Outline},
                   {"SILHOUETTE", L::Silhouette},
                   {"NORMAL_EDGE", L::NormalEdge},
                   {"DEPTH_EDGE", L::DepthEdge},
                   {"CREASE", L::Crease},
                   {"BORDER", L::Border},
                   {"INTERSECTION", L::Intersection},
                   {"MATERIAL_BOUNDARY", L::MaterialBoundary},
                   {"OBJECT_BOUNDARY", L::ObjectBoundary},
                   {"SUGGESTIVE", L::Suggestive},
                   {"SUGGESTIVE_OBJECT", L::SuggestiveObject},
                   {"CONTOUR", L::Contour},
                   {"MESH_SILHOUETTE", L::MeshSilhouette}});
    defineEnum<ig::ViewVector>(m, "ViewVector", "view vector", "--view-vector (comic).",
                               {{"EXACT", ig::ViewVector::Exact}, {"CONSTANT", ig::ViewVector::Constant}});
    using F = ig::FaceOrientation;
    defineEnum<F>(m, "FaceOrientation", "face orientation", "--face-orientation (comic).",
                  {{"STANDARD", F::Standard},
                   {"DURING_TRIANGLES", F::DuringTriangles},
                   {"DURING_VERTICES", F::DuringVertices},
                   {"AFTER_VERTICES", F::AfterVertices}});
    defineEnum<ig::Precision>(m, "Precision", "precision", "--gbuffer-precision.",
                              {{"FLOAT32", ig::Precision::Float32}, {"FLOAT16", ig::Precision::Float16}});
    defineEnum<ig::CameraPlacement>(
        m, "CameraPlacement", "camera placement",
        "Where the view comes from when eye, orbit and frame_nodes leave it open: the "
        "file's camera when it has one, or always auto-framing (--camera auto).",
        {{"FILE_OR_AUTO", ig::CameraPlacement::FileOrAuto}, {"AUTO", ig::CameraPlacement::Auto}});
    using C = ig::CameraSource;
    defineEnum<C>(m, "CameraSource", "camera source", "Where a still's view came from.",
                  {{"FILE", C::File}, {"AUTO", C::Auto}, {"ORBIT", C::Orbit}, {"EYE", C::Eye}});
}

/** The names Look(**fields) and Frame(**fields) take: the settable properties. */
const std::vector<std::string> kLookFields{
    "shading", "shininess",        "bands", "shade_map",   "view_vector", "face_orientation",  "front_rule",
    "light",   "ambient",          "paper", "supersample", "msaa",        "gbuffer_precision", "lines",
    "strokes", "outline_width_map"};
const std::vector<std::string> kFrameFields{"eye",  "orbit",       "target",      "up",        "fov",
                                            "clip", "placement",   "frame_nodes", "animation", "time",
                                            "pose", "expressions", "look_at"};

/** Sets the keyword arguments of a constructor as the properties they name, refusing other names. */
void setFields(py::handle object, const py::kwargs& fields, const std::vector<std::string>& allowed,
               const std::string& className) {
    for (const auto& [name, value] : fields) {
        const std::string key = escapedUtf8(name);
        if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
            std::string names;
            for (const std::string& field : allowed) names += (names.empty() ? "" : ", ") + field;
            throw py::type_error(className + "(): unexpected keyword argument '" + key + "' (fields: " + names + ")");
        }
        py::setattr(object, name, value);
    }
}

void defineLook(py::module_& m) {
    py::class_<ig::Look> look(m, "Look",
                              "The look: shading and its settings, the line types with their styles and parameters, "
                              "strokes, paper, light and supersampling. Look() is the command line's default look; "
                              "each field may be given as a keyword (Look(shading='comic', lines=['outline'])). Every "
                              "setter checks its value as the flag it stands for does (UsageError with its message).");
    look.def(py::init([](const py::kwargs& fields) {
                 py::object made = py::cast(ig::Look());
                 setFields(made, fields, kLookFields, "Look");
                 return made.cast<ig::Look>();
             }),
             "Look(**fields): the command line's default look, with the fields given set in turn.")
        .def_static(
            "from_arguments",
            checked("Look.from_arguments(): ", {"arguments"},
                    [](const std::vector<OsText>& arguments) { return ig::Look::fromArguments(bytesOf(arguments)); }),
            "arguments"_a,
            "Flags and values as on the command line: ['--shading', 'comic', '--lines', 'outline,contour']. "
            "Raises UsageError with the command line's message for a bad flag or value.")
        .def_static("from_style_file",
                    checked("Look.from_style_file(): ", {"path"},
                            [](const std::filesystem::path& path) { return ig::Look::fromStyleFile(path.string()); }),
                    "path"_a,
                    "A style file (`inkgraph render --style FILE`). Raises UsageError naming the file and line.")
        .def("set",
             checked("Look.set(): ", {"self", "flag", "value"},
                     [](py::object self, const OsText& flag, const OsText& value) {
                         self.cast<ig::Look&>().set(flag.bytes, value.bytes);
                         return self;
                     }),
             "flag"_a, "value"_a = "",
             "Sets one flag, checked at once: look.set('--silhouette-width', '3'). Returns the look.")
        .def_property_readonly(
            "arguments", [](const ig::Look& self) { return osTextsOf(self.arguments()); },
            "The flags that give this look, in the order they were set: "
            "Look.from_arguments(look.arguments) is the same look.")
        .def("__copy__", [](const ig::Look& self) { return ig::Look(self); })
        .def(
            "__deepcopy__", [](const ig::Look& self, py::handle) { return ig::Look(self); }, "memo"_a)
        .def("__repr__", [](const ig::Look& self) {
            return "inkgraph.Look.from_arguments(" + reprText(osTextsOf(self.arguments())) + ")";
        });

    look.def_property(
            "shading", &ig::Look::shading,
            [](ig::Look& self, py::handle value) { self.setShading(enumArgument<ig::Shading>(value, "Look.shading")); },
            "Shading (or its name): --shading.")
        .def_property(
            "shininess", &ig::Look::shininess,
            [](ig::Look& self, py::handle value) { self.setShininess(realNumber(value, "Look.shininess")); },
            "--shininess (phong and comic).")
        .def_property("bands", &ig::Look::bands,
                      checked("Look.bands: ", {"self", ""}, [](ig::Look& self, int bands) { self.setBands(bands); }),
                      "--bands (cel); None: Qu, Chen & Zwicker's five uneven bands.")
        .def_property(
            "shade_map", [](const ig::Look& self) { return pathTextOf(self.shadeMap()); },
            checked("Look.shade_map: ", {"self", ""},
                    [](ig::Look& self, const std::filesystem::path& path) { self.setShadeMap(path.string()); }),
            "--shademap (cel, comic): a PNG; '' is the built-in map.")
        .def_property(
            "outline_width_map", [](const ig::Look& self) { return pathTextOf(self.outlineWidthMap()); },
            checked("Look.outline_width_map: ", {"self", ""},
                    [](ig::Look& self, const OsText& source) { self.setOutlineWidthMap(source.bytes); }),
            "--outline-width-map: 'none', 'color:R' or 'texture:FILE:G' (outline, silhouette and MToon outline widths "
            "scaled per vertex).")
        .def_property(
            "view_vector", &ig::Look::viewVector,
            [](ig::Look& self, py::handle value) {
                self.setViewVector(enumArgument<ig::ViewVector>(value, "Look.view_vector"));
            },
            "--view-vector (comic).")
        .def_property(
            "face_orientation", &ig::Look::faceOrientation,
            [](ig::Look& self, py::handle value) {
                self.setFaceOrientation(enumArgument<ig::FaceOrientation>(value, "Look.face_orientation"));
            },
            "--face-orientation (comic).")
        .def_property(
            "front_rule", &ig::Look::frontRule,
            checked("Look.front_rule: ", {"self", ""}, [](ig::Look& self, int rule) { self.setFrontRule(rule); }),
            "--front-rule (comic with during-vertices or after-vertices): 1, 2 or 3.")
        .def_property(
            "light", &ig::Look::light,
            [](ig::Look& self, py::handle value) { self.setLight(vec3Argument(value, "Look.light")); },
            "--light: the world direction toward the light (a Vec3 or (x, y, z)); None: the file's, else a key light.")
        .def_property(
            "ambient", &ig::Look::ambient,
            [](ig::Look& self, py::handle value) { self.setAmbient(colorArgument(value, "Look.ambient")); },
            "--ambient: the uniform ambient light, linear (a Color or (r, g, b)); None: the shading model's default.")
        .def_property(
            "paper", &ig::Look::paper,
            [](ig::Look& self, py::handle value) { self.setPaper(colorArgument(value, "Look.paper")); },
            "--background: the paper's colour (a Color or (r, g, b)).")
        .def_property("supersample", &ig::Look::supersample,
                      checked("Look.supersample: ", {"self", ""},
                              [](ig::Look& self, int factor) { self.setSupersample(factor); }),
                      "--supersample: 1 to 8.")
        .def_property("msaa", &ig::Look::msaa,
                      checked("Look.msaa: ", {"self", ""}, [](ig::Look& self, int samples) { self.setMsaa(samples); }),
                      "--msaa: samples per pixel of the shading and MToon's outline shells, 1 (off), 2, 4 or 8.")
        .def_property(
            "gbuffer_precision", &ig::Look::gbufferPrecision,
            [](ig::Look& self, py::handle value) {
                self.setGbufferPrecision(enumArgument<ig::Precision>(value, "Look.gbuffer_precision"));
            },
            "--gbuffer-precision.")
        .def_property(
            "lines", &ig::Look::lines,
            [](ig::Look& self, py::handle value) {
                if (py::isinstance<py::str>(value) || !py::isinstance<py::iterable>(value))
                    throw py::type_error("Look.lines: expected a list of LineType or their names, got " +
                                         reprText(value));
                std::vector<ig::LineType> types;
                for (const py::handle item : value) types.push_back(enumArgument<ig::LineType>(item, "Look.lines"));
                self.setLines(types);
            },
            "The line types drawn (--lines), in composite order: a list of LineType or their names; [] draws none.")
        .def_property("strokes", &ig::Look::strokes,
                      checked("Look.strokes: ", {"self", ""},
                              [](ig::Look& self, const ig::StrokeSettings& strokes) { self.setStrokes(strokes); }),
                      "StrokeSettings for every line type.")
        .def(
            "line_style",
            [](const ig::Look& self, py::handle type) {
                return self.lineStyle(enumArgument<ig::LineType>(type, "Look.line_style()"));
            },
            "type"_a, "How `type` is drawn: its LineStyle (--TYPE-width, --TYPE-color).")
        .def("set_line_style",
             checked("Look.set_line_style(): ", {"self", "type", "style"},
                     [](py::object self, py::handle type, const ig::LineStyle& style) {
                         self.cast<ig::Look&>().setLineStyle(enumArgument<ig::LineType>(type, "Look.set_line_style()"),
                                                             style);
                         return self;
                     }),
             "type"_a, "style"_a, "Sets how `type` is drawn. Returns the look.")
        .def_static(
            "line_parameter_names",
            [](py::handle type) {
                return ig::Look::lineParameterNames(enumArgument<ig::LineType>(type, "Look.line_parameter_names()"));
            },
            "type"_a,
            "The parameters `type` takes besides width and colour ('depth-jump', 'crease-angle'); one parameter may "
            "serve several types, and is then one value for all of them.")
        .def("line_parameter",
             checked("Look.line_parameter(): ", {"self", "name"},
                     [](const ig::Look& self, const OsText& name) { return self.lineParameter(name.bytes); }),
             "name"_a, "A number parameter's value (given or default).")
        .def("line_choice",
             checked("Look.line_choice(): ", {"self", "name"},
                     [](const ig::Look& self, const OsText& name) { return pathTextOf(self.lineChoice(name.bytes)); }),
             "name"_a, "A choice parameter's value ('5' of suggestive-stencil).")
        .def("set_line_parameter",
             checked("Look.set_line_parameter(): ", {"self", "name", "value"},
                     [](py::object self, const OsText& name, py::handle value) {
                         self.cast<ig::Look&>().setLineParameter(name.bytes,
                                                                 realNumber(value, "Look.set_line_parameter()"));
                         return self;
                     }),
             "name"_a, "value"_a, "Sets a number parameter ('crease-angle'). Returns the look.")
        .def("set_line_choice",
             checked("Look.set_line_choice(): ", {"self", "name", "value"},
                     [](py::object self, const OsText& name, const OsText& value) {
                         self.cast<ig::Look&>().setLineChoice(name.bytes, value.bytes);
                         return self;
                     }),
             "name"_a, "value"_a, "Sets a choice parameter. Returns the look.");
}

void defineFrame(py::module_& m) {
    py::class_<ig::Frame> frame(m, "Frame",
                                "The frame: size and camera. Unset fields (None) take the command line's defaults (the "
                                "file's camera, else framed to fit the model at 35 degrees from the front). Checked "
                                "when it renders, by the rules of the flag each field stands for.");
    frame
        .def(py::init(checked("Frame(): ", {"width", "height", ""},
                              [](int width, int height, const py::kwargs& fields) {
                                  ig::Frame made;
                                  made.width = width;
                                  made.height = height;
                                  py::object object = py::cast(made);
                                  setFields(object, fields, kFrameFields, "Frame");
                                  return object.cast<ig::Frame>();
                              })),
             "width"_a = ig::Frame{}.width, "height"_a = ig::Frame{}.height,
             "Frame(width=1024, height=1024, **fields): fields as keywords (orbit=(30, 10), fov=40).")
        .def_static(
            "from_arguments",
            checked("Frame.from_arguments(): ", {"arguments"},
                    [](const std::vector<OsText>& arguments) { return ig::Frame::fromArguments(bytesOf(arguments)); }),
            "arguments"_a,
            "The command line's camera flags: ['--orbit', '30,10', '--fov', '40', '--size', '640x480']. "
            "Raises UsageError with the command line's message for a flag that is not the frame's or a bad "
            "value.")
        .def_property(
            "width", [](const ig::Frame& self) { return self.width; },
            checked("Frame.width: ", {"self", ""}, [](ig::Frame& self, int width) { self.width = width; }),
            "--size: pixels, 1 to 16384.")
        .def_property(
            "height", [](const ig::Frame& self) { return self.height; },
            checked("Frame.height: ", {"self", ""}, [](ig::Frame& self, int height) { self.height = height; }))
        .def_property(
            "eye", [](const ig::Frame& self) { return self.eye; },
            [](ig::Frame& self, py::handle value) { self.eye = optionalArgument(value, vec3Argument, "Frame.eye"); },
            "--eye: the eye in world coordinates (a Vec3 or (x, y, z)), or None.")
        .def_property(
            "orbit", [](const ig::Frame& self) { return self.orbit; },
            [](ig::Frame& self, py::handle value) {
                self.orbit = optionalArgument(value, orbitArgument, "Frame.orbit");
            },
            "--orbit: an Orbit or (azimuth, elevation[, distance]), or None.")
        .def_property(
            "target", [](const ig::Frame& self) { return self.target; },
            [](ig::Frame& self, py::handle value) {
                self.target = optionalArgument(value, vec3Argument, "Frame.target");
            },
            "--target (world), or None.")
        .def_property(
            "up", [](const ig::Frame& self) { return self.up; },
            [](ig::Frame& self, py::handle value) { self.up = optionalArgument(value, vec3Argument, "Frame.up"); },
            "--up, or None.")
        .def_property(
            "fov", [](const ig::Frame& self) { return self.fov; },
            checked("Frame.fov: ", {"self", ""}, [](ig::Frame& self, std::optional<double> fov) { self.fov = fov; }),
            "--fov: vertical degrees, 0.01 to 179, or None.")
        .def_property(
            "clip", [](const ig::Frame& self) { return self.clip; },
            [](ig::Frame& self, py::handle value) { self.clip = optionalArgument(value, clipArgument, "Frame.clip"); },
            "--clip: a Clip or (near, far), or None (fitted to the model).")
        .def_property(
            "placement", [](const ig::Frame& self) { return self.placement; },
            [](ig::Frame& self, py::handle value) {
                self.placement = enumArgument<ig::CameraPlacement>(value, "Frame.placement");
            },
            "CameraPlacement (--camera auto is AUTO).")
        .def_property(
            "frame_nodes", [](const ig::Frame& self) { return osTextsOf(self.frameNodes); },
            checked("Frame.frame_nodes: ", {"self", ""},
                    [](ig::Frame& self, const std::vector<OsText>& nodes) { self.frameNodes = bytesOf(nodes); }),
            "--frame: fit the view to the meshes under these nodes (assign a whole list; a copy is "
            "returned).")
        .def_property(
            "animation", [](const ig::Frame& self) { return pathTextOf(self.animation); },
            checked("Frame.animation: ", {"self", ""},
                    [](ig::Frame& self, const OsText& animation) { self.animation = animation.bytes; }),
            "A glTF animation (name or index) to pose the scene in for this render; '' with time None: the "
            "scene as loaded.")
        .def_property(
            "time", [](const ig::Frame& self) { return self.time; },
            checked("Frame.time: ", {"self", ""},
                    [](ig::Frame& self, std::optional<double> time) { self.time = time; }),
            "Seconds into the animation, or None.")
        .def_property(
            "pose", [](const ig::Frame& self) { return pathTextOf(self.pose); },
            checked("Frame.pose: ", {"self", ""}, [](ig::Frame& self, const OsText& pose) { self.pose = pose.bytes; }),
            "A VRM humanoid pose for this render, as --pose: 'a-pose' or a pose file's path; '': the "
            "scene's.")
        .def_property(
            "expressions", [](const ig::Frame& self) { return self.expressions; },
            checked("Frame.expressions: ", {"self", ""},
                    [](ig::Frame& self, const std::map<std::string, double>& expressions) {
                        self.expressions = expressions;
                    }),
            "--expression: VRM expressions {name: weight in [0, 1]} for this render (assign a whole dict; a "
            "copy is returned); {}: the scene's.")
        .def_property(
            "look_at", [](const ig::Frame& self) { return self.lookAt; },
            [](ig::Frame& self, py::handle value) {
                self.lookAt = optionalArgument(value, vec3Argument, "Frame.look_at");
            },
            "--look-at: the point (world) a VRM character looks at for this render, or None (the scene's).")
        .def("__copy__", [](const ig::Frame& self) { return self; })
        .def(
            "__deepcopy__", [](const ig::Frame& self, py::handle) { return self; }, "memo"_a)
        .def("__repr__", [](py::handle self) {
            const auto& value = self.cast<const ig::Frame&>();
            std::string text = "inkgraph.Frame(" + std::to_string(value.width) + ", " + std::to_string(value.height);
            const ig::Frame defaults;
            for (const std::string& field : kFrameFields) {
                const py::object fieldValue = self.attr(field.c_str());
                const py::object defaultValue = py::cast(defaults).attr(field.c_str());
                if (!fieldValue.equal(defaultValue)) text += ", " + field + "=" + reprText(fieldValue);
            }
            return text + ")";
        });
}

/** Still.strokes(): the strokes as the --strokes file's "strokes" list holds them (docs/datasets.md). */
py::list strokeDicts(const std::vector<ig::StillStroke>& strokes) {
    py::list list;
    for (const ig::StillStroke& stroke : strokes) {
        py::list points;
        for (const ig::StillStrokePoint& point : stroke.points) {
            py::dict entry;
            entry["x"] = point.x;
            entry["y"] = point.y;
            entry["world"] = point.world
                                 ? py::object(py::list(py::make_tuple(point.world->x, point.world->y, point.world->z)))
                                 : py::object(py::none());
            entry["mesh"] = point.mesh > 0 ? py::object(py::int_(point.mesh)) : py::object(py::none());
            entry["triangle"] = point.triangle >= 0 ? py::object(py::int_(point.triangle)) : py::object(py::none());
            points.append(entry);
        }
        py::dict entry;
        entry["type"] = stroke.type;
        entry["visible"] = stroke.visible;
        entry["closed"] = stroke.closed;
        entry["points"] = points;
        list.append(entry);
    }
    return list;
}

void defineStill(py::module_& m) {
    py::class_<ig::StillCamera>(m, "StillCamera",
                                "The camera a still was drawn with, in world coordinates. The matrices are float64 "
                                "NumPy arrays of their own, row-major.")
        .def_property_readonly(
            "intrinsics", [](const ig::StillCamera& c) { return matrixArray(c.intrinsics); },
            "OpenCV's K (3 x 3): fx = fy = (height / 2) / tan(fov_y / 2), cx = width / 2 - 0.5, cy = height / 2 - 0.5 "
            "(x right, y down, the centre of pixel (0, 0) at (0, 0)), for the picture's size.")
        .def_property_readonly(
            "extrinsics", [](const ig::StillCamera& c) { return matrixArray(c.extrinsics); },
            "OpenCV's [R|t] (3 x 4): world points to the OpenCV camera frame (x right, y down, z forward). With the "
            "depth buffer: X_cam = depth * K^-1 [u v 1], X_world = R^T (X_cam - t).")
        .def_property_readonly(
            "view", [](const ig::StillCamera& c) { return matrixArray(c.view); },
            "OpenGL's view matrix (4 x 4): world points to view space (x right, y up, looking down -z).")
        .def_property_readonly(
            "projection", [](const ig::StillCamera& c) { return matrixArray(c.projection); },
            "OpenGL's projection matrix (4 x 4, clip space z in [-w, w]).")
        .def_readonly("eye", &ig::StillCamera::eye)
        .def_readonly("target", &ig::StillCamera::target)
        .def_readonly("up", &ig::StillCamera::up)
        .def_readonly("fov_y", &ig::StillCamera::fovY, "Vertical field of view, degrees.")
        .def_readonly("near", &ig::StillCamera::near)
        .def_readonly("far", &ig::StillCamera::far)
        .def_readonly("clip_given", &ig::StillCamera::clipGiven,
                      "near and far were Frame.clip; else fitted to the model's bounding sphere.")
        .def_readonly("width", &ig::StillCamera::width)
        .def_readonly("height", &ig::StillCamera::height)
        .def_readonly("source", &ig::StillCamera::source)
        .def(
            "as_dict",
            [](const ig::StillCamera& c) {
                py::dict d;
                d["width"] = c.width;
                d["height"] = c.height;
                d["source"] = cliName(c.source);
                d["intrinsics"] = matrixArray(c.intrinsics).attr("tolist")();
                d["extrinsics"] = matrixArray(c.extrinsics).attr("tolist")();
                d["view"] = matrixArray(c.view).attr("tolist")();
                d["projection"] = matrixArray(c.projection).attr("tolist")();
                d["eye"] = vec3List(c.eye);
                d["target"] = vec3List(c.target);
                d["up"] = vec3List(c.up);
                d["fov_y"] = c.fovY;
                d["near"] = c.near;
                d["far"] = c.far;
                d["clip_given"] = c.clipGiven;
                return d;
            },
            "The camera as plain lists and numbers (for JSON): the matrices as lists of rows, source by its name.")
        .def("__repr__", [](const ig::StillCamera& c) {
            return "<inkgraph.StillCamera " + std::to_string(c.width) + "x" + std::to_string(c.height) + ", " +
                   cliName(c.source) + ", fov_y " + reprText(py::float_(c.fovY)) + ">";
        });

    py::class_<PythonStill>(m, "Still",
                            "One rendered still: the picture and the buffers asked for, as read-only NumPy arrays "
                            "that share the still's pixels (copy one to change it), the camera and the warnings.")
        .def_property_readonly(
            "picture",
            [](const py::object& self) { return imageArray(self.cast<const PythonStill&>().still.picture(), self); },
            "The final picture: height x width x 4 uint8 (RGBA); with render(out=...), a read-only view of out's "
            "pixels.")
        .def("buffer",
             checked("Still.buffer(): ", {"self", "name"},
                     [](const py::object& self, const OsText& name) {
                         return imageArray(self.cast<const PythonStill&>().still.buffer(name.bytes), self);
                     }),
             "name"_a,
             "A buffer asked for in render(), by a name it was asked with: float32 or uint8, height x width (one "
             "channel) or height x width x 4. Raises UsageError naming the buffers there are.")
        .def_property_readonly(
            "buffer_names", [](const PythonStill& self) { return self.still.bufferNames(); },
            "The buffers, each by the first name it was asked with, in that order ('gbuffer.*' and 'lines.*' give "
            "each buffer's own name).")
        .def_property_readonly(
            "camera", [](const PythonStill& self) { return self.still.camera(); }, "The StillCamera it was drawn with.")
        .def_property_readonly(
            "meshes", [](const PythonStill& self) { return meshDicts(self.still.meshes()); },
            "The meshes of the scene it drew, as Scene.meshes gives them: what its 'meshId', 'triangleId' and "
            "'barycentric' values and its strokes' meshes name. Scene.meshes unless the frame posed the scene again "
            "(animation, time, pose, expressions, look_at): a mesh the pose collapses (a prop scaled to 0) draws "
            "nothing and is 'drawn': False here; every mesh keeps its id.")
        .def_property_readonly(
            "objects", [](const PythonStill& self) { return objectDicts(self.still.objects()); },
            "Its objects, as Scene.objects gives them: what its 'objectId' values name (likewise the frame's pose's).")
        .def(
            "strokes", [](const PythonStill& self) { return strokeDicts(self.still.strokes()); },
            "Every kept stroke of every drawn line type, when render() was asked for 'strokes' (else UsageError): a "
            "list of dicts {'type', 'visible', 'closed', 'points'}, each point {'x', 'y', 'world' ([X, Y, Z] or "
            "None), 'mesh' (id or None), 'triangle' (global index or None)}: the 'strokes' list of the command "
            "line's --strokes file, value for value.")
        .def_property_readonly(
            "warnings", [](const PythonStill& self) { return warningObjects(self.still.warnings()); },
            "What the load (for a still that posed its scene) and the render warned about, as InkgraphWarning "
            "records (render() has issued them through the warnings module).")
        .def("write",
             checked("Still.write(): ", {"self", "path"},
                     [](const PythonStill& self, const std::filesystem::path& path) {
                         CallsAtExit::run([&] { self.still.write(path.string()); });
                     }),
             "path"_a,
             "Writes the picture; the format follows the extension. Raises OutputError naming the file (also for a "
             "FIFO or a device), UsageError for a file the render read (the model, a shade map, ...).")
        .def_property_readonly(
            "milliseconds", [](const PythonStill& self) { return self.still.milliseconds(); },
            "Milliseconds the render took (without loading the scene).")
        .def("__repr__", [](const PythonStill& self) {
            const ig::StillCamera& camera = self.still.camera();
            return "<inkgraph.Still " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                   ", buffers " + reprText(py::cast(self.still.bufferNames())) + ">";
        });
}

void defineScene(py::module_& m) {
    py::class_<ig::Scene>(m, "Scene",
                          "A model loaded once (OBJ with MTL, glTF/GLB, VRM, STL, PLY) or made from arrays; render it "
                          "with any number of looks and frames.")
        .def_static(
            "load",
            checked("Scene.load(): ",
                    {"path", "animation", "time", "memory_limit", "strict", "pose", "expressions", "look_at",
                     "weld_distance"},
                    [](const std::filesystem::path& path, const OsText& animation, double time, std::size_t memoryLimit,
                       bool strict, const OsText& pose, const std::map<std::string, double>& expressions,
                       py::handle lookAt, double weldDistance) {
                        ig::SceneOptions options;
                        options.animation = animation.bytes;
                        options.time = time;
                        options.pose = pose.bytes;
                        options.expressions = expressions;
                        options.lookAt = optionalArgument(lookAt, vec3Argument, "Scene.load(look_at)");
                        options.memoryLimitBytes = memoryLimit;
                        options.strict = strict;
                        options.weldDistance = weldDistance;
                        std::optional<ig::Scene> scene;
                        CallsAtExit::run([&] { scene.emplace(ig::Scene::load(path.string(), options)); });
                        issueWarnings(warningObjects(scene->warnings()));
                        return *scene;
                    }),
            "path"_a, "animation"_a = OsText{}, "time"_a = 0.0, "memory_limit"_a = ig::SceneOptions{}.memoryLimitBytes,
            "strict"_a = false, "pose"_a = OsText{}, "expressions"_a = std::map<std::string, double>{},
            "look_at"_a = py::none(), "weld_distance"_a = ig::SceneOptions{}.weldDistance,
            "Loads a model; `animation` (a glTF animation's name or index) and `time` (seconds) pose it, as "
            "--animation and --time, and `pose` ('a-pose' or a pose file) a VRM's humanoid, as --pose; "
            "`expressions` ({name: weight}) and `look_at` ((x, y, z) or None) set a VRM character's face, as "
            "--expression and --look-at; `memory_limit` (bytes) bounds the load and each render of the scene as "
            "--memory-limit (0: the command line's default); `strict` makes every warning of the load and of each "
            "render an InputError, as --strict; vertices closer than `weld_distance` x the model's size are merged "
            "(0 to 0.01), as --weld-distance. Issues the loader's warnings (InkgraphWarning). Raises "
            "InputError naming the file and the problem.")
        .def_static(
            "from_arrays",
            checked("Scene.from_arrays(): ",
                    {"vertices", "faces", "normals", "uvs", "colors", "name", "memory_limit", "weld_distance"},
                    [](py::handle vertices, py::handle faces, py::handle normals, py::handle uvs, py::handle colors,
                       const OsText& name, std::size_t memoryLimit, double weldDistance) {
                        const auto vertexArray = floatRows(vertices, "vertices", {3}, std::nullopt);
                        const py::ssize_t vertexCount = vertexArray.shape(0);
                        const auto faceArray = faceRows(faces);
                        std::optional<FloatRows> normalArray, uvArray, colorArray;
                        if (!normals.is_none()) normalArray = floatRows(normals, "normals", {3}, vertexCount);
                        if (!uvs.is_none()) uvArray = floatRows(uvs, "uvs", {2}, vertexCount);
                        if (!colors.is_none()) colorArray = floatRows(colors, "colors", {3, 4}, vertexCount);
                        ig::MeshArrays arrays;
                        arrays.vertices = vertexArray.data();
                        arrays.vertexCount = std::size_t(vertexCount);
                        arrays.faces = faceArray.data();
                        arrays.faceCount = std::size_t(faceArray.shape(0));
                        if (normalArray) arrays.normals = normalArray->data();
                        if (uvArray) arrays.uvs = uvArray->data();
                        if (colorArray) {
                            arrays.colors = colorArray->data();
                            arrays.colorChannels = int(colorArray->shape(1));
                        }
                        ig::SceneOptions options;
                        options.memoryLimitBytes = memoryLimit;
                        options.weldDistance = weldDistance;
                        std::optional<ig::Scene> scene;
                        // The library checks the values (finite, indices in range, the limits) and names its arrays as
                        // the arguments are named; only the function is spelt Python's way.
                        try {
                            CallsAtExit::run(
                                [&] { scene.emplace(ig::Scene::fromArrays(arrays, name.bytes, options)); });
                        } catch (const ig::Error& error) {
                            const std::string cpp = "Scene::fromArrays()";
                            std::string message = error.what();
                            if (message.rfind(cpp, 0) == 0)
                                message = "Scene.from_arrays()" + message.substr(cpp.size());
                            throw ig::Error(error.kind(), message);
                        }
                        issueWarnings(warningObjects(scene->warnings()));
                        return *scene;
                    }),
            "vertices"_a, "faces"_a, "normals"_a = py::none(), "uvs"_a = py::none(), "colors"_a = py::none(),
            "name"_a = OsText{"arrays"}, "memory_limit"_a = ig::SceneOptions{}.memoryLimitBytes,
            "weld_distance"_a = ig::SceneOptions{}.weldDistance,
            "A scene of one mesh from NumPy arrays (or anything numpy.asarray takes): vertices (N, 3), faces (M, 3) "
            "vertex indices counter-clockwise seen from the front, and optionally normals (N, 3), uvs (N, 2) and "
            "colors (N, 3) or (N, 4) in [0, 1]. float32 C-contiguous arrays (uint32 faces) are read where they are; "
            "others are converted (integer faces after checking every index fits in uint32). Renders as an OBJ with "
            "the same vertices and faces does (welded as Scene.load's weld_distance says). Raises InputError naming "
            "the argument and the problem (a shape, a dtype, a value that is not finite, an index out of range).")
        .def_property_readonly(
            "path", [](const ig::Scene& self) { return pathTextOf(self.path()); }, "The file, or '' for arrays.")
        .def_property_readonly("triangle_count", &ig::Scene::triangleCount)
        .def_property_readonly("vertex_count", &ig::Scene::vertexCount)
        .def_property_readonly("mesh_count", &ig::Scene::meshCount)
        .def_property_readonly(
            "objects", [](const ig::Scene& self) { return objectDicts(self.objects()); },
            "Its objects (node instances), as dicts {'id', 'name', 'node_path', 'meshes'}: 'id' is the object's "
            "value in the 'objectId' buffer (0 there is the background).")
        .def_property_readonly(
            "meshes", [](const ig::Scene& self) { return meshDicts(self.meshes()); },
            "Its meshes, as dicts {'id', 'drawn', 'name', 'node_path', 'object_id', 'material_id', 'material', "
            "'first_triangle', 'triangle_count'}, as the --dump manifest's 'meshes': 'id' is the mesh's value in the "
            "'meshId' buffer, and its triangles have the 'triangleId' values first_triangle + 1 ... first_triangle + "
            "triangle_count (0 there is the background), numbered as its file gives them: a triangle the loader "
            "dropped (zero-area, a back-to-back twin) keeps its number, which appears nowhere, and a mesh whose "
            "triangles are all degenerate ('drawn': False) keeps its id and numbers, so the ids are the same in every "
            "pose. A still whose frame poses the scene again names its own: Still.meshes.")
        .def_property_readonly(
            "warnings", [](const ig::Scene& self) { return warningObjects(self.warnings()); },
            "The loader's warnings, as InkgraphWarning records.")
        .def("__repr__", [](const ig::Scene& scene) {
            const std::string counts = "  # " + std::to_string(scene.triangleCount()) + " triangles";
            if (scene.path().empty()) return "<inkgraph.Scene from arrays>" + counts;
            return "inkgraph.Scene.load(" + reprText(pathTextOf(scene.path())) + ")" + counts;
        });
}

void defineRenderer(py::module_& m) {
    py::class_<PythonRenderer> renderer(m, "Renderer",
                                        "Renders stills. The first render makes one GL context (EGL, no display), kept "
                                        "with every compiled program until close() or the renderer's end: a batch pays "
                                        "start-up once. Each renderer has a context of its own, so renderers on "
                                        "several threads render at once (render() releases the GIL); a renderer's "
                                        "own calls run one at a time, from any thread.");
    defineEnum<ig::Renderer::Platform>(renderer, "Platform", "EGL platform",
                                       "How the GL context is reached: --egl-platform.",
                                       {{"AUTO", ig::Renderer::Platform::Auto},
                                        {"DEVICE", ig::Renderer::Platform::Device},
                                        {"SURFACELESS", ig::Renderer::Platform::Surfaceless}});
    renderer
        .def(py::init([](py::handle platform) {
                 return std::make_unique<PythonRenderer>(
                     enumArgument<ig::Renderer::Platform>(platform, "Renderer(): platform"));
             }),
             "platform"_a = ig::Renderer::Platform::Auto,
             "`platform`: Renderer.Platform or its name ('auto', 'device', 'surfaceless'), as --egl-platform. Makes "
             "nothing yet.")
        .def(
            "render",
            checked(
                "Renderer.render(): ", {"self", "scene", "look", "frame", "buffers", "out"},
                [](PythonRenderer& self, const ig::Scene& scene, const std::optional<ig::Look>& look,
                   const std::optional<ig::Frame>& frame, const std::vector<OsText>& buffers, const py::object& out) {
                    const ig::Look lookValue = look.value_or(ig::Look());
                    const ig::Frame frameValue = frame.value_or(ig::Frame());
                    std::uint8_t* pixels = nullptr;
                    std::size_t rowBytes = 0;
                    if (!out.is_none()) {
                        rowBytes = pictureRowBytes(out, frameValue);
                        pixels = static_cast<std::uint8_t*>(py::reinterpret_borrow<py::array>(out).mutable_data());
                    }
                    std::optional<ig::Still> still;
                    CallsAtExit::run([&] {
                        still.emplace(self.render(scene, lookValue, frameValue, bytesOf(buffers), pixels, rowBytes));
                    });
                    issueWarnings(warningObjects(still->warnings()));
                    return PythonStill{std::move(*still), out};
                }),
            "scene"_a, "look"_a = py::none(), "frame"_a = py::none(), "buffers"_a = std::vector<OsText>{},
            "out"_a = py::none(),
            "Renders `scene` with `look` in `frame` (None: the defaults), keeping `buffers` (buffer_names(look); "
            "'gbuffer.*' and 'lines.*' expand). With `out`, a writable uint8 (height, width, 4) array whose pixel rows "
            "are packed (a row stride of its own is fine), the picture is drawn into it and the still's picture views "
            "it. Runs without the GIL; issues the still's warnings (InkgraphWarning). Raises an inkgraph.Error.")
        // Each waits for a render another thread is in, so without the GIL: holding it, every Python thread waited
        // (closed no longer waits at all).
        .def_property_readonly(
            "gl_description", [](PythonRenderer& self) { return withoutGil([&] { return self.glDescription(); }); },
            "The GL renderer, version and EGL platform in use, or '' before the first render.")
        .def(
            "close", [](PythonRenderer& self) { withoutGil([&] { self.close(); }); },
            "Gives the GL context back now; render() then raises UsageError.")
        .def_property_readonly("closed", &PythonRenderer::closed)
        .def("__enter__", [](const py::object& self) { return self; })
        .def("__exit__", [](PythonRenderer& self, const py::args&) { withoutGil([&] { self.close(); }); });
}

} // namespace

/** Gives each class of `m` that does not pickle (the renderer, a scene, a still, a look, a frame: its own __reduce__ is
 *  not there) a __reduce__ that refuses: pickle's protocols 0 and 1 went through copyreg to pybind11's base class,
 *  whose allocation throws through C, and the interpreter aborted (`pickle.dumps(Look(), 0)`). Protocols 2 and up
 *  refused already ("cannot pickle"), as now every protocol does. copy.copy() and deepcopy() of a Look or Frame use
 *  their __copy__ and __deepcopy__. */
void refusePicklingOfTheRest(py::module_& m) {
    std::vector<py::handle> classes;
    for (const auto [name, value] : py::reinterpret_borrow<py::dict>(m.attr("__dict__"))) {
        if (!PyType_Check(value.ptr())) continue;
        classes.push_back(value);
        for (const auto [nestedName, nested] : py::dict(value.attr("__dict__")))
            if (PyType_Check(nested.ptr())) classes.push_back(nested);
    }
    for (const py::handle type : classes) {
        if (py::dict(type.attr("__dict__")).contains("__reduce__") ||
            !type.attr("__module__").equal(m.attr("__name__")))
            continue;
        const std::string name = type.attr("__qualname__").cast<std::string>();
        type.attr("__reduce__") = py::cpp_function(
            [name](py::handle) -> py::object { throw py::type_error("cannot pickle '" + name + "' object"); },
            py::name("__reduce__"), py::is_method(type), py::sibling(py::getattr(type, "__reduce__", py::none())));
    }
}

void defineModule(py::module_& m) {
    m.doc() = "inkgraph's public C++ API (inkgraph/inkgraph.h) for Python; use the package `inkgraph`, whose "
              "render() is the short way.";
    py::register_exception_translator([](std::exception_ptr pointer) {
        try {
            if (pointer) std::rethrow_exception(pointer);
        } catch (const ig::Error& error) {
            raisePythonError(error);
        }
    });

    m.def("version", &ig::version, "The library's version, \"0.2.0\".");
    m.def("git_commit", &ig::gitCommit, "The git commit the library was built from (\"unknown\" outside a checkout).");

    defineValueTypes(m);
    defineEnums(m);
    defineLook(m);
    defineFrame(m);
    defineStill(m);
    defineScene(m);
    defineRenderer(m);

    m.def("sample_views",
          checked("sample_views(): ",
                  {"count", "seed", "model_key", "elevation", "distance_jitter", "light_jitter", "light", "expressions",
                   "poses"},
                  [](std::size_t count, std::uint64_t seed, const py::object& modelKey, const py::object& elevation,
                     double distanceJitter, double lightJitter, const py::object& light,
                     const std::vector<OsText>& expressions, const std::vector<OsText>& poses) {
                      ig::ViewSampling sampling;
                      const std::vector<double> angles = realNumbers(elevation, {2, 4}, "sample_views(): elevation",
                                                                     "(mean, sd) or (mean, sd, low, high), degrees");
                      sampling.elevationMean = angles[0];
                      sampling.elevationDeviation = angles[1];
                      if (angles.size() == 4) {
                          sampling.elevationLow = angles[2];
                          sampling.elevationHigh = angles[3];
                      }
                      sampling.distanceJitter = distanceJitter;
                      sampling.lightJitter = lightJitter;
                      sampling.light = optionalArgument(light, vec3Argument, "sample_views(): light");
                      sampling.expressions = bytesOf(expressions);
                      sampling.poses = bytesOf(poses);
                      // The key is the model path as the command line lists it: a str, or a path as os.fspath() gives
                      // it.
                      const bool pathLike = py::isinstance<py::str>(modelKey) || py::isinstance<py::bytes>(modelKey) ||
                                            py::hasattr(modelKey, "__fspath__");
                      if (!pathLike) {
                          throw py::type_error(
                              "sample_views(): model_key: expected a path (str, bytes or os.PathLike), got " +
                              reprText(modelKey));
                      }
                      const std::string key = py::module_::import("os").attr("fspath")(modelKey).cast<std::string>();
                      return ig::sampleViews(count, seed, key, sampling);
                  }),
          "count"_a, "seed"_a, "model_key"_a, py::kw_only(), "elevation"_a = py::make_tuple(10.0, 10.0, -30.0, 60.0),
          "distance_jitter"_a = 0.0, "light_jitter"_a = 0.0, "light"_a = py::none(),
          "expressions"_a = std::vector<std::string>{}, "poses"_a = std::vector<std::string>{},
          "The views the command line's `--views count --seed seed` draws for the model listed as model_key (its path "
          "as given), with --view-elevation, --view-distance-jitter, --light-jitter, --light, --expressions (each "
          "alternative in --expression's syntax, or 'none') and --poses ('rest', 'a-pose' or a file). Raises "
          "UsageError with the flag's message for a setting out of range (docs/datasets.md).");
    m.def("buffer_names",
          checked("buffer_names(): ", {"look"}, [](const ig::Look& look) { return ig::bufferNames(look); }), "look"_a,
          "The buffers render() can return with `look`: the G-buffer's fields ('normal', 'depth', ...), "
          "'gbuffer.*', 'lines.<type>' of the look's line types, 'lines.*', 'picture'.");
    m.def("write_image",
          checked("write_image(): ", {"path", "image"},
                  [](const std::filesystem::path& path, const py::array& array) {
                      const ig::Image image = imageFromArray(array);
                      CallsAtExit::run([&] { image.write(path.string()); });
                  }),
          "path"_a, "image"_a,
          "Writes a uint8 or float32 array (height x width, or height x width x 1 or 4 channels, RGBA) as an image "
          "file; the format follows the extension (PNG; EXR, TIFF, JPEG through OpenImageIO). Raises OutputError "
          "naming the file, also for a place that is not a regular file or a new name (a FIFO, a device).");

    m.def(
        "_stop_calls_for_exit", &CallsAtExit::stopCallsForExit,
        "At interpreter exit (an atexit handler): waits for the loads, renders and writes in flight and keeps new ones "
        "from starting, so no daemon thread is inside the library when the process ends.");

    refusePicklingOfTheRest(m);
    nameArgumentRefusals(m);
}

} // namespace inkgraph::python
