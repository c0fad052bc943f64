// libFuzzer target: the Python module's argument conversion. This program embeds Debian's Python with the
// extension's bindings compiled in (python/Bindings.h; an instrumented extension cannot load into the uninstrumented
// python3, but an instrumented program can embed it), imports the package from python/inkgraph/, and calls its entry
// points with Python values the fuzz bytes build: None, bools, ints (up to 512 bits), floats (nan, inf, 1e308, ...),
// str (any code point: NUL, lone surrogates), bytes, paths, NumPy arrays, Looks, and nested lists, tuples and dicts of
// them. The calls: make_look(), make_frame(), Look() with its typed fields and Look.set(), Look.from_arguments(),
// Look.from_style_file(), Frame() and its typed fields, Frame.from_arguments(), buffer_names(), Scene.from_arrays(),
// and render() with every argument, drawing a loaded tetrahedron
// with a renderer that checks what it is handed and stops before GL (the C++ Renderer::render() takes the GL context;
// its flag checks are the command line's, fuzzed by `style`).
//
// The contract: a call ends normally or raises inkgraph.Error (any kind), TypeError or ValueError. Any other exception
// (a RuntimeError from a C++ exception the bindings do not translate, SystemError, OverflowError, MemoryError, ...), a
// crash, a sanitizer report or a leak fails. Python allocates through malloc (PYMEM_ALLOCATOR_MALLOC) so that
// AddressSanitizer sees every object and LeakSanitizer can tell a lost one from a reachable one.
#include "python/Bindings.h"
#include "tests/fuzz/FuzzBytes.h"

#include <pybind11/embed.h>
#include <pybind11/pybind11.h>
// AddressSanitizer's macro: gcc's, or clang's feature test (clang 14 does not define gcc's).
#if defined(__SANITIZE_ADDRESS__)
#define FUZZ_PYTHON_ARGS_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FUZZ_PYTHON_ARGS_ASAN 1
#endif
#endif
#if defined(FUZZ_PYTHON_ARGS_ASAN)
#include <sanitizer/lsan_interface.h>
#endif

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace py = pybind11;
using namespace pybind11::literals;

namespace {

/** Words the flag parser knows, so that values reach past "unknown flag": flags with and without dashes (dict keys
 *  drop them), values of the right shape and of the wrong one, buffer names. */
const char* const kTokens[] = {
    "--shading",
    "shading",
    "cel",
    "comic",
    "flat",
    "--lines",
    "lines",
    "silhouette",
    "contour",
    "outline,contour",
    "suggestive",
    "none",
    "--silhouette-width",
    "silhouette-width",
    "silhouette_width",
    "--line-weight",
    "3",
    "0",
    "-1",
    "0.5",
    "1e308",
    "nan",
    "inf",
    "--background",
    "background",
    "1,0.9,0.8",
    "--orbit",
    "orbit",
    "30,10",
    "--fov",
    "fov",
    "40",
    "--eye",
    "--target",
    "--up",
    "0,1,0",
    "--camera",
    "--frame",
    "--size",
    "512x512",
    "--style",
    "--egl-platform",
    "--memory-limit",
    "1G",
    "--bands",
    "--shininess",
    "--shademap",
    "--light",
    "--supersample",
    "--dump",
    "-o",
    "--output",
    "--",
    "-",
    "",
    "normal",
    "depth",
    "lines.contour",
    "gbuffer.*",
    "picture",
    "shade.color",
    "materialId",
    "coverage",
    "view",
    "--animation",
    "--time",
    "--face-orientation",
    "--front-rule",
    "--gbuffer-precision",
    "--min-stroke-length",
    "--overlapping-lines",
    "--clip",
    "--view-vector",
};

/** Python set up once: the interpreter, the package, a loaded scene and the renderer stand-in. */
struct Harness {
    py::module_ inkgraph;
    py::object scene;
    py::object stopBeforeGl;
    py::object reachedRenderer;
    py::object allowed; ///< the tuple of exception classes the contract allows
    py::object pathClass;
    py::object numpyArray;
    py::object look;
    py::object frame;
};

void startPython() {
    PyPreConfig preconfig;
    PyPreConfig_InitPythonConfig(&preconfig);
    preconfig.allocator = PYMEM_ALLOCATOR_MALLOC;
    if (PyStatus status = Py_PreInitialize(&preconfig); PyStatus_Exception(status)) Py_ExitStatusException(status);
    PyConfig config;
    PyConfig_InitPythonConfig(&config);
    config.install_signal_handlers = 0; // libFuzzer's own handlers stay
    config.write_bytecode = 0;          // no __pycache__ in the source tree
    config.parse_argv = 0;
    config.user_site_directory = 0;
    const PyStatus status = Py_InitializeFromConfig(&config);
    PyConfig_Clear(&config);
    if (PyStatus_Exception(status)) Py_ExitStatusException(status);
}

Harness& harness() {
    static Harness* const made = [] {
#if defined(FUZZ_PYTHON_ARGS_ASAN)
        // What the start-up allocates is not checked for leaks: importing Debian's NumPy leaves some 5.7 KB of
        // numpy.random's (Cython) code objects and tuples that LeakSanitizer cannot reach from what it scans (they
        // are reported after the import alone, and no longer once a call has run). Every input's allocations are.
        const __lsan::ScopedDisabler startUpIsNotChecked;
#endif
        startPython();
        auto* h = new Harness; // never destroyed: the interpreter is never finalised, its objects stay reachable
        // The bindings as the module `inkgraph._inkgraph`, before the package that imports it.
        static PyModuleDef definition{};
        py::module_ extension = py::module_::create_extension_module("inkgraph._inkgraph", nullptr, &definition);
        inkgraph::python::defineModule(extension);
        py::module_::import("sys").attr("modules")["inkgraph._inkgraph"] = extension;
        py::module_::import("sys").attr("path").attr("insert")(0, INKGRAPH_PYTHON_SOURCE_DIR);
        h->inkgraph = py::module_::import("inkgraph");

        // Work in a folder of our own: style files and models are named relative to it.
        char folder[] = "/tmp/inkgraph-fuzz-python-XXXXXX";
        if (::mkdtemp(folder) == nullptr) throw std::runtime_error("FuzzPythonArgs: cannot create a folder in /tmp");
        std::filesystem::current_path(folder);
        std::ofstream("tetrahedron.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
        h->scene = h->inkgraph.attr("Scene").attr("load")("tetrahedron.obj");

        py::dict globals;
        globals["__name__"] = "fuzz_python_args";
        globals["inkgraph"] = h->inkgraph;
        py::exec(R"(
class ReachedRenderer(Exception):
    """render() handed its arguments to the renderer: the conversion is done."""

class StopBeforeGl:
    """A renderer for render(): checks what render() hands it, as Renderer.render() takes it, and stops."""
    def render(self, scene, look, frame, buffers):
        if not (isinstance(scene, inkgraph.Scene) and isinstance(look, inkgraph.Look)
                and isinstance(frame, inkgraph.Frame) and isinstance(buffers, list)
                and all(isinstance(name, str) for name in buffers)):
            raise AssertionError(f"render() handed the renderer {scene!r}, {look!r}, {frame!r}, {buffers!r}")
        inkgraph.Look.from_arguments(look.arguments)  # the look it made is one the library accepts again
        raise ReachedRenderer()
)",
                 globals);
        h->stopBeforeGl = globals["StopBeforeGl"]();
        h->reachedRenderer = globals["ReachedRenderer"];
        const py::module_ builtins = py::module_::import("builtins");
        h->allowed = py::make_tuple(h->inkgraph.attr("Error"), builtins.attr("TypeError"), builtins.attr("ValueError"));
        h->pathClass = py::module_::import("pathlib").attr("PurePosixPath");
        h->numpyArray = py::module_::import("numpy").attr("array");
        h->look = h->inkgraph.attr("Look");
        h->frame = h->inkgraph.attr("Frame");
        return h;
    }();
    return *made;
}

py::object token(inkgraph::fuzz::FuzzBytes& in) { return py::str(in.pick(kTokens)); }

/** A str of any code points, lone surrogates and NUL included. */
py::object anyString(inkgraph::fuzz::FuzzBytes& in) {
    std::vector<Py_UCS4> points(std::size_t(in.integer(0, 12)));
    for (Py_UCS4& point : points) point = Py_UCS4(in.boolean() ? in.integer(0, 0x7f) : in.integer(0, 0x10ffff));
    return py::reinterpret_steal<py::object>(
        PyUnicode_FromKindAndData(PyUnicode_4BYTE_KIND, points.data(), py::ssize_t(points.size())));
}

py::object value(inkgraph::fuzz::FuzzBytes& in, int depth);

py::list values(inkgraph::fuzz::FuzzBytes& in, int depth) {
    py::list list;
    for (std::size_t n = in.integer(0, 4); n > 0; --n) list.append(value(in, depth - 1));
    return list;
}

py::object value(inkgraph::fuzz::FuzzBytes& in, int depth) {
    Harness& h = harness();
    switch (in.below(depth > 0 ? 17 : 11)) {
    case 0: return py::none();
    case 1: return py::bool_(in.boolean());
    case 2: return py::int_(in.signed64());
    case 3: { // up to 512 bits, either sign
        const std::string bytes = in.bytes(64);
        return py::module_::import("builtins")
            .attr("int")
            .attr("from_bytes")(py::bytes(bytes), "little", "signed"_a = true);
    }
    case 4: {
        const double special[] = {NAN, INFINITY, -INFINITY, 1e308, -1e308, 5e-324, -0.0, 0.5, 3.0, 1e-300};
        return py::float_(in.boolean() ? in.pick(special) : in.real());
    }
    case 5:
    case 6: return token(in);
    case 7: return anyString(in);
    case 8: { // bytes as text, invalid UTF-8 as lone surrogates (surrogateescape, as os.fsdecode gives them)
        const std::string bytes = in.bytes(24);
        return py::reinterpret_steal<py::object>(
            PyUnicode_DecodeUTF8(bytes.data(), py::ssize_t(bytes.size()), "surrogateescape"));
    }
    case 9: return py::bytes(in.bytes(24));
    case 10: return h.pathClass(token(in));
    case 11: return values(in, depth);
    case 12: return py::tuple(values(in, depth));
    case 13: {
        py::dict dict;
        for (std::size_t n = in.integer(0, 4); n > 0; --n) {
            const py::object key = in.below(8) == 0 ? value(in, 0) : token(in);
            if (PyObject_Hash(key.ptr()) == -1) { // an unhashable key (a list) cannot be in a dict
                PyErr_Clear();
                continue;
            }
            dict[key] = value(in, depth - 1);
        }
        return dict;
    }
    case 14: { // a NumPy array of numbers (render()'s look values take them)
        py::list numbers;
        for (std::size_t n = in.integer(0, 4); n > 0; --n)
            numbers.append(in.boolean() ? py::object(py::int_(std::int32_t(in.signed64())))
                                        : py::object(py::float_(in.real())));
        return h.numpyArray(numbers);
    }
    case 15: return h.look();
    default: return h.pathClass(anyString(in));
    }
}

/** Keyword arguments among `names`, each present or not, with fuzzed values. */
py::dict keywords(inkgraph::fuzz::FuzzBytes& in, std::initializer_list<const char*> names) {
    py::dict kwargs;
    for (const char* name : names)
        if (in.boolean()) kwargs[name] = value(in, 2);
    return kwargs;
}

void call(inkgraph::fuzz::FuzzBytes& in) {
    Harness& h = harness();
    const char* const lookFields[] = {"shading",           "shininess",  "bands",  "shade_map", "view_vector",
                                      "face_orientation",  "front_rule", "light",  "paper",     "supersample",
                                      "gbuffer_precision", "lines",      "strokes"};
    const char* const frameFields[] = {"width", "height", "eye",       "orbit",       "target",    "up",
                                       "fov",   "clip",   "placement", "frame_nodes", "animation", "time"};
    switch (in.below(11)) {
    case 0: h.inkgraph.attr("make_look")(value(in, 3), **keywords(in, {"shading", "lines"})); break;
    case 1: h.inkgraph.attr("make_frame")(**keywords(in, {"size", "camera"})); break;
    case 2: {
        py::object look = h.look();
        for (std::size_t n = in.integer(1, 3); n > 0; --n) {
            switch (in.below(3)) {
            case 0: look.attr("set")(value(in, 1)); break;
            case 1: look.attr("set")(value(in, 1), value(in, 1)); break;
            default: py::setattr(look, in.pick(lookFields), value(in, 2)); break;
            }
        }
        py::repr(look);
        break;
    }
    case 3: py::repr(h.look.attr("from_arguments")(value(in, 2))); break;
    case 4: h.look.attr("from_style_file")(value(in, 1)); break;
    case 5: {
        py::object frame = h.frame(**keywords(in, {"width", "height", "eye", "orbit", "fov", "clip", "placement"}));
        if (in.boolean()) py::setattr(frame, in.pick(frameFields), value(in, 2));
        py::repr(frame);
        break;
    }
    case 6: h.inkgraph.attr("buffer_names")(in.boolean() ? h.look() : value(in, 1)); break;
    case 7: py::repr(h.frame.attr("from_arguments")(value(in, 2))); break;
    case 8: h.inkgraph.attr("Scene").attr("from_arrays")(value(in, 2), value(in, 2)); break;
    default: {
        py::dict kwargs = keywords(in, {"look", "size", "lines", "buffers", "camera", "shading"});
        kwargs["renderer"] = h.stopBeforeGl;
        // Mostly the loaded scene; sometimes a value for the model, which render() loads (a path that does not exist).
        h.inkgraph.attr("render")(in.below(8) == 0 ? value(in, 1) : h.scene, **kwargs);
        break;
    }
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Harness& h = harness();
    inkgraph::fuzz::FuzzBytes in(data, size);
    for (int calls = 0; calls < 8 && in.remaining() > 0; ++calls) {
        try {
            call(in);
        } catch (py::error_already_set& error) {
            if (error.matches(h.reachedRenderer) || error.matches(h.allowed)) continue;
            std::fprintf(stderr, "FuzzPythonArgs: an exception the contract does not allow:\n");
            error.restore();
            PyErr_Print();
            std::abort();
        }
    }
    return 0;
}
