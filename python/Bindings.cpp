/** @file The bindings of `inkgraph._inkgraph` (Bindings.h): the public C++ API (api/include/inkgraph/inkgraph.h) for
 *  Python, one class per API class under its own name, members in Python's spelling (Look.from_arguments,
 *  Still.buffer_names). The Pythonic front (inkgraph.render(), looks as dicts, the default renderer) is
 *  python/inkgraph/__init__.py; the exception classes are python/inkgraph/_errors.py, and every inkgraph::api::Error
 *  reaches Python as the one of its kind.
 *
 *  Images reach Python without a copy: a buffer's array points into the Still's pixels and keeps the Still alive as
 *  its base object; the arrays are read-only, since a Still's images are shared and never change. */

#include "Bindings.h"

#include <inkgraph/inkgraph.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace py = pybind11;
namespace ig = inkgraph::api;
using namespace pybind11::literals;

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

/** Sets the Python error for `error`: its class by kind, the message exactly as the library wrote it, the exit
 *  code `inkgraph render` would give. Looked up when raised, since _errors.py is imported by the package that
 *  imports this module. */
void raisePythonError(const ig::Error& error) {
    const py::object type = py::module_::import("inkgraph._errors").attr(errorClassName(error.kind()));
    const py::object value = type(error.what(), "exit_code"_a = error.exitCode());
    PyErr_SetObject(type.ptr(), value.ptr());
}

/** `image` as a NumPy array over its own pixels (height x width, and x channels unless 1), read-only, keeping
 *  `owner` (the Python Still that holds the image) alive. */
py::array imageArray(const ig::Image& image, py::handle owner) {
    const auto itemSize = static_cast<py::ssize_t>(image.bytesPerChannel());
    const py::ssize_t channels = image.channels;
    std::vector<py::ssize_t> shape{image.height, image.width};
    std::vector<py::ssize_t> strides{image.width * channels * itemSize, channels * itemSize};
    if (channels != 1) {
        shape.push_back(channels);
        strides.push_back(itemSize);
    }
    const py::dtype dtype =
        image.type == ig::Image::Type::Float32 ? py::dtype::of<float>() : py::dtype::of<std::uint8_t>();
    py::array array(dtype, shape, strides, image.bytes.data(), owner);
    array.attr("flags").attr("writeable") = false;
    return array;
}

/** The pixels of `array`, in C order whatever its strides, as bytes. */
template <typename Channel>
std::vector<std::uint8_t> pixelBytes(const py::array& array) {
    const auto contiguous = py::array_t<Channel, py::array::c_style | py::array::forcecast>::ensure(array);
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(contiguous.nbytes()));
    if (!bytes.empty()) std::memcpy(bytes.data(), contiguous.data(), bytes.size());
    return bytes;
}

/** A copy of `array` as an ig::Image: uint8 or float32, height x width or height x width x 1 or 4. */
ig::Image imageFromArray(const py::array& array) {
    const auto fail = [](const std::string& problem) {
        throw ig::Error(ig::Error::Kind::Usage, "write_image(): " + problem);
    };
    const py::ssize_t dimensions = array.ndim();
    if (dimensions != 2 && dimensions != 3)
        fail("expected a height x width [x channels] array, got " + std::to_string(dimensions) + " dimensions");
    const py::ssize_t channels = dimensions == 3 ? array.shape(2) : 1;
    if (channels != 1 && channels != 4) fail("expected 1 or 4 channels, got " + std::to_string(channels));
    ig::Image image;
    image.height = static_cast<int>(array.shape(0));
    image.width = static_cast<int>(array.shape(1));
    image.channels = static_cast<int>(channels);
    if (py::isinstance<py::array_t<std::uint8_t>>(array)) {
        image.type = ig::Image::Type::UInt8;
        image.bytes = pixelBytes<std::uint8_t>(array);
    } else if (py::isinstance<py::array_t<float>>(array)) {
        image.type = ig::Image::Type::Float32;
        image.bytes = pixelBytes<float>(array);
    } else {
        fail("expected a uint8 or float32 array, got " + py::str(array.dtype()).cast<std::string>());
    }
    return image;
}

/** One ig::Renderer for Python: its calls run without the GIL, one at a time (the C++ renderer is not
 *  thread-safe, and Python threads may share the object), and close() gives the GL context back at once. */
class PythonRenderer {
public:
    explicit PythonRenderer(const std::string& eglPlatform) : mRenderer(std::in_place, eglPlatform) {}

    // The look and the frame by value: the render runs without the GIL, while another Python thread may change the
    // objects it was given.
    ig::Still render(const ig::Scene& scene, ig::Look look, ig::Frame frame, std::vector<std::string> buffers) {
        const std::lock_guard lock(mMutex);
        return open("Renderer.render()").render(scene, look, frame, buffers);
    }
    std::string glDescription() {
        const std::lock_guard lock(mMutex);
        return mRenderer ? mRenderer->glDescription() : "";
    }
    void close() {
        const std::lock_guard lock(mMutex);
        mRenderer.reset();
    }
    bool closed() {
        const std::lock_guard lock(mMutex);
        return !mRenderer;
    }

private:
    ig::Renderer& open(const std::string& function) {
        if (!mRenderer) throw ig::Error(ig::Error::Kind::Usage, function + ": the renderer is closed");
        return *mRenderer;
    }

    std::mutex mMutex;
    std::optional<ig::Renderer> mRenderer;
};

std::string quotedList(const std::vector<std::string>& items) {
    std::string text;
    for (const std::string& item : items) text += (text.empty() ? "'" : ", '") + item + "'";
    return "[" + text + "]";
}

} // namespace

namespace inkgraph::python {

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

    m.def("version", &ig::version, "The library's version, \"0.1.0\".");
    m.def("git_commit", &ig::gitCommit, "The git commit the library was built from (\"unknown\" outside a checkout).");
    m.def("buffer_resource_name", &ig::bufferResourceName, "name"_a,
          "The graph resource name of a buffer: \"normal\" -> \"gbuffer.normal\", \"lines.contour\" -> "
          "\"strokes.contour\", \"picture\" -> \"composite.final\"; a full resource name stays as it is.");
    m.def(
        "write_image",
        [](const std::filesystem::path& path, const py::array& array) {
            const ig::Image image = imageFromArray(array);
            const py::gil_scoped_release release;
            image.write(path.string());
        },
        "path"_a, "image"_a,
        "Writes a uint8 or float32 array (height x width, or height x width x 1 or 4 channels, RGBA) as an image "
        "file; the format follows the extension (PNG; EXR, TIFF, JPEG through OpenImageIO). Raises OutputError "
        "naming the file, also for a place that is not a regular file or a new name (a FIFO, a device).");

    py::class_<ig::Scene>(m, "Scene",
                          "A model loaded once (OBJ, glTF/GLB, VRM, STL, PLY); render it any number of times.")
        .def_static(
            "load",
            [](const std::filesystem::path& path, const std::string& animation, double time,
               std::size_t memoryLimitBytes) {
                ig::SceneOptions options;
                options.animation = animation;
                options.time = time;
                options.memoryLimitBytes = memoryLimitBytes;
                return ig::Scene::load(path.string(), options);
            },
            "path"_a, "animation"_a = "", "time"_a = 0.0, "memory_limit_bytes"_a = ig::SceneOptions{}.memoryLimitBytes,
            py::call_guard<py::gil_scoped_release>(),
            "Loads a model; `animation` (a glTF animation's name or index) and `time` (seconds) pose it, as "
            "--animation and --time; `memory_limit_bytes` bounds the load and each render of the scene as "
            "--memory-limit (0: the command line's default). Raises InputError naming the file and the problem.")
        .def_property_readonly("path", &ig::Scene::path)
        .def_property_readonly("triangle_count", &ig::Scene::triangleCount)
        .def_property_readonly("vertex_count", &ig::Scene::vertexCount)
        .def_property_readonly("mesh_count", &ig::Scene::meshCount)
        .def_property_readonly("warnings", &ig::Scene::warnings, "The loader's warnings.")
        .def("__repr__", [](const ig::Scene& scene) {
            return "inkgraph.Scene.load('" + scene.path() + "')  # " + std::to_string(scene.triangleCount()) +
                   " triangles";
        });

    py::class_<ig::Look>(m, "Look",
                         "The look as `inkgraph render`'s look and line flags (`inkgraph help render`); the default "
                         "is the command line's default look.")
        .def(py::init<>())
        .def_static("from_arguments", &ig::Look::fromArguments, "arguments"_a,
                    "Flags and values as on the command line: ['--shading', 'comic', '--lines', 'outline,contour']. "
                    "Raises UsageError with the command line's message for a bad flag or value.")
        .def_static(
            "from_style_file", [](const std::filesystem::path& path) { return ig::Look::fromStyleFile(path.string()); },
            "path"_a, "A style file (`inkgraph render --style FILE`). Raises UsageError naming the file and line.")
        .def("set", &ig::Look::set, "flag"_a, "value"_a = "", py::return_value_policy::reference_internal,
             "Sets one flag, checked at once: look.set('--silhouette-width', '3'). Returns the look.")
        .def_property_readonly("arguments", &ig::Look::arguments, "Every flag given so far, in order.")
        .def("__repr__",
             [](const ig::Look& look) { return "inkgraph.Look.from_arguments(" + quotedList(look.arguments()) + ")"; });

    py::class_<ig::Frame>(m, "Frame",
                          "The frame: size in pixels and camera flags as on the command line (['--orbit', '30,10']).")
        .def(py::init([](int width, int height, std::vector<std::string> camera) {
                 ig::Frame frame;
                 frame.width = width;
                 frame.height = height;
                 frame.camera = std::move(camera);
                 return frame;
             }),
             "width"_a = ig::Frame{}.width, "height"_a = ig::Frame{}.height, "camera"_a = std::vector<std::string>{})
        .def_readwrite("width", &ig::Frame::width)
        .def_readwrite("height", &ig::Frame::height)
        .def_readwrite("camera", &ig::Frame::camera, "Camera flags; assign a whole list (a copy is returned).")
        .def("__repr__", [](const ig::Frame& frame) {
            return "inkgraph.Frame(" + std::to_string(frame.width) + ", " + std::to_string(frame.height) + ", " +
                   quotedList(frame.camera) + ")";
        });

    py::class_<ig::Still>(m, "Still",
                          "One rendered still: the picture and the buffers asked for, as read-only NumPy arrays that "
                          "share the still's pixels (copy one to change it).")
        .def_property_readonly(
            "picture", [](const py::object& self) { return imageArray(self.cast<const ig::Still&>().picture(), self); },
            "The final picture: height x width x 4 uint8 (RGBA).")
        .def(
            "buffer",
            [](const py::object& self, const std::string& name) {
                return imageArray(self.cast<const ig::Still&>().buffer(name), self);
            },
            "name"_a,
            "A buffer asked for in render(), by the name it was asked with: float32 or uint8, height x width (one "
            "channel) or height x width x 4. Raises UsageError naming the buffers there are.")
        .def_property_readonly("buffer_names", &ig::Still::bufferNames,
                               "The names buffer() answers, in the order they were asked for.")
        .def(
            "write", [](const ig::Still& still, const std::filesystem::path& path) { still.write(path.string()); },
            "path"_a, py::call_guard<py::gil_scoped_release>(),
            "Writes the picture; the format follows the extension. Raises OutputError naming the file (also for a "
            "FIFO or a device), UsageError for a file the render read (the model, a shade map, ...).")
        .def_property_readonly("warnings", &ig::Still::warnings,
                               "What the render warned about (a material's shade map this shading does not use, ...).")
        .def_property_readonly("milliseconds", &ig::Still::milliseconds, "Milliseconds the render took.")
        .def("__repr__", [](const ig::Still& still) {
            const ig::Image& picture = still.picture();
            return "<inkgraph.Still " + std::to_string(picture.width) + "x" + std::to_string(picture.height) +
                   ", buffers " + quotedList(still.bufferNames()) + ">";
        });

    py::class_<PythonRenderer>(m, "Renderer",
                               "Renders stills. The first render makes one GL context (EGL, no display), kept with "
                               "every compiled program until close() or the renderer's end: a batch pays start-up "
                               "once. One renderer at a time holds the process's context (render() refuses others with "
                               "UsageError until that one is closed); any thread may render, one render at a time.")
        .def(py::init<const std::string&>(), "egl_platform"_a = "auto",
             "`egl_platform`: 'auto', 'device' or 'surfaceless', as --egl-platform. Makes nothing yet.")
        .def("render", &PythonRenderer::render, "scene"_a, "look"_a, "frame"_a,
             "buffers"_a = std::vector<std::string>{}, py::call_guard<py::gil_scoped_release>(),
             "Renders `scene` with `look` in `frame`, keeping `buffers` (names as buffer_resource_name() takes them; "
             "'gbuffer.*' expands). Runs without the GIL. Raises an inkgraph.Error.")
        .def_property_readonly("gl_description", &PythonRenderer::glDescription,
                               "The GL renderer and version in use, or '' before the first render.")
        .def("close", &PythonRenderer::close, py::call_guard<py::gil_scoped_release>(),
             "Gives the GL context back now; render() then raises UsageError.")
        .def_property_readonly("closed", &PythonRenderer::closed)
        .def("__enter__", [](const py::object& self) { return self; })
        .def("__exit__", [](PythonRenderer& self, const py::args&) {
            const py::gil_scoped_release release;
            self.close();
        });
}

} // namespace inkgraph::python
