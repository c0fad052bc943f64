#pragma once
/** @file inkgraph's public C++ API: load a scene, describe a look and a frame, render, get named buffers as images,
 *  write outputs. This header is the whole contract: it includes only the standard library, so a program that links
 *  `inkgraph::inkgraph` (find_package(inkgraph)) needs none of inkgraph's dependencies' headers.
 *
 *      #include <inkgraph/inkgraph.h>
 *      namespace ig = inkgraph::api;
 *
 *      ig::Renderer renderer;                                  // one GL context, kept for every render
 *      const ig::Scene bunny = ig::Scene::load("bunny.obj");
 *      ig::Look look = ig::Look::fromArguments({"--shading", "cel", "--lines", "silhouette,contour"});
 *      ig::Frame frame;
 *      frame.width = frame.height = 512;
 *      const ig::Still still = renderer.render(bunny, look, frame, {"gbuffer.normal", "lines.contour"});
 *      still.write("bunny.png");                                // the picture, format from the extension
 *      const ig::Image& normal = still.buffer("gbuffer.normal"); // 512 x 512 x 4 float32
 *
 *  The look and the frame are described with the names and values of `inkgraph render`'s flags (`inkgraph help
 *  render`), checked by the same code, so every look the command line can draw the library can too, and their
 *  errors read the same. Errors are ig::Error, whose message is the command line's (a flag's with the API's function
 *  in front) and quotes the names. docs/api.md describes it all. */

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

/** What the shared library exports: this header's classes and functions, nothing else (api/CMakeLists.txt). */
#if defined(__GNUC__)
#define INKGRAPH_API __attribute__((visibility("default")))
#else
#define INKGRAPH_API
#endif

namespace inkgraph::api {

/** "0.1.0". */
INKGRAPH_API std::string version();
/** The git commit the library was built from ("unknown" outside a git checkout). */
INKGRAPH_API std::string gitCommit();

/** Every failure of the API. The message is the command line's own (the function or flag first, names quoted). */
class INKGRAPH_API Error : public std::runtime_error {
public:
    enum class Kind {
        /** A bad flag, value, buffer name, camera or image; too little memory for the request; a Renderer used while
         *  another holds the process's GL context, or made before the fork of the process it is used in; a still
         *  written over a file its render read. */
        Usage,
        Input,   ///< an unreadable or invalid model, shade map or texture
        Context, ///< no OpenGL 4.5 core context through EGL, or the shaders are missing or do not compile
        Output,  ///< a file could not be written, or its place is not a regular file or a new name
        Render,  ///< the render itself failed: an internal error
    };
    Error(Kind kind, const std::string& message) : std::runtime_error(message), mKind(kind) {}
    Kind kind() const noexcept { return mKind; }
    /** The exit code `inkgraph render` gives for this kind (2 usage, 3 input, 4 context, 5 output, 1 render). */
    int exitCode() const noexcept;

private:
    Kind mKind;
};

/** An image: rows top first, tightly packed, channels interleaved (R, G, B, A order). */
struct INKGRAPH_API Image {
    enum class Type { UInt8, Float32 };
    int width = 0;
    int height = 0;
    int channels = 0; ///< 1 or 4
    Type type = Type::UInt8;
    std::vector<std::uint8_t> bytes; ///< width * height * channels * bytesPerChannel()

    std::size_t bytesPerChannel() const { return type == Type::Float32 ? 4 : 1; }
    /** The pixels as floats; throws Error(Usage) unless type is Float32. */
    const float* floats() const;
    /** Writes the image; the format follows the extension (PNG in the process; EXR, TIFF, JPEG through
     *  OpenImageIO). Float32 is kept by EXR and TIFF. Written under a temporary name beside `path` and renamed over
     *  it, so `path` must be a regular file or a new name, as the command line's outputs: a device, a FIFO, a socket
     *  or a folder (also through a link) is refused, never replaced. Throws Error(Output) naming the file. */
    void write(const std::string& path) const;
};

/** What Scene::load() takes besides the path (the command line's --animation, --time, --memory-limit). */
struct SceneOptions {
    std::string animation; ///< a glTF animation's name or index; empty: the rest pose
    double time = 0.0;     ///< seconds into `animation`
    /** The load refuses files that would need more, and so does each render of the scene (its buffers at the
     *  frame's size); 0: the command line's default, half this machine's memory but at least 1 GiB. */
    std::size_t memoryLimitBytes = 0;
};

/** A model loaded once (OBJ with MTL, glTF/GLB, VRM, STL, PLY): render it with any number of looks and frames.
 *  Copies share the loaded data. */
class INKGRAPH_API Scene {
public:
    /** Throws Error(Input) naming the file and the problem. */
    static Scene load(const std::string& path, const SceneOptions& options = {});
    const std::string& path() const;
    std::size_t triangleCount() const;
    std::size_t vertexCount() const;
    std::size_t meshCount() const;
    /** The loader's warnings (a texture it could not read, a skipped primitive, ...). */
    std::vector<std::string> warnings() const;

    struct Impl;
    const Impl& impl() const { return *mImpl; }

private:
    explicit Scene(std::shared_ptr<const Impl> impl) : mImpl(std::move(impl)) {}
    std::shared_ptr<const Impl> mImpl;
};

/** The look: shading, shade map, lines and their widths and colours, paper, light, supersampling, ... as
 *  `inkgraph render`'s flags of those kinds (the "Look" and "Lines" sections of `inkgraph help render`, --style
 *  included). The default is the command line's default look. */
class INKGRAPH_API Look {
public:
    Look();
    /** Flags and values as on the command line: {"--shading", "comic", "--lines", "outline,contour"}. Throws
     *  Error(Usage) for a flag that is not a look flag (a camera, an output) or a bad value, with the CLI's message. */
    static Look fromArguments(const std::vector<std::string>& arguments);
    /** A style file (`inkgraph render --style FILE`): fromArguments({"--style", path}). Throws Error(Usage) naming
     *  the file (and the line) as the command line does, also for a setting that is not the look's (size, fov: the
     *  Frame's). */
    static Look fromStyleFile(const std::string& path);
    /** One flag: set("--lines", "contour,suggestive"), set("--silhouette-width", "3"); a flag without a value
     *  takes "". The flag and its value are checked at once; what depends on the other flags (a flag that has no
     *  effect with the rest, such as --bands with --shading phong) when the look renders. */
    Look& set(const std::string& flag, const std::string& value = "");
    /** Every flag given so far, in order. */
    const std::vector<std::string>& arguments() const { return mArguments; }

private:
    std::vector<std::string> mArguments;
};

/** The frame: size and camera. Unset fields take the command line's defaults (the file's camera, else framed to fit
 *  the model at 35 degrees from the front, slightly above). */
struct Frame {
    int width = 1024; ///< --size's width and height: 1 to 16384
    int height = 1024;
    /** Camera flags as on the command line: {"--orbit", "30,10"}, {"--eye", "0,1,5", "--target", "0,0,0"}, {"--fov",
     *  "40"}, {"--clip", "0.1,100"}, {"--camera", "auto"}, {"--frame", "Head"}. Not --animation and --time: they
     *  pose the scene as it loads (SceneOptions). */
    std::vector<std::string> camera;
};

/** One rendered still: the picture and every buffer asked for. */
class INKGRAPH_API Still {
public:
    /** The final picture, RGBA8 (the command line's -o). */
    const Image& picture() const;
    /** A buffer asked for in render(), by the name it was asked with; throws Error(Usage) naming the buffers there
     *  are. */
    const Image& buffer(const std::string& name) const;
    /** The buffers, each by the first name it was asked with, in that order ("gbuffer.*" gives each field's full
     *  name); buffer() also answers any name of the same resource ("normal" for "gbuffer.normal"). */
    std::vector<std::string> bufferNames() const;
    /** What the render warned about (a material's shade map that this shading does not use, ...). */
    std::vector<std::string> warnings() const;
    /** Writes the picture as Image::write() does, but never over a file the render read (the model, its buffers
     *  and images, the shade maps, the look's --style file), compared as the command line compares its outputs
     *  with its inputs (links and hard links too): that is Error(Usage), naming the file and what it is. */
    void write(const std::string& path) const;
    /** Milliseconds the render took (without loading the scene). */
    double milliseconds() const;

    struct Impl;

private:
    friend class Renderer;
    explicit Still(std::shared_ptr<const Impl> impl) : mImpl(std::move(impl)) {}
    std::shared_ptr<const Impl> mImpl;
};

/** Graph resource names of the buffers render() can return, for the short names people use: "normal", "view",
 *  "wVec", "nDotV", "depth", "coverage", "baseColor", "radial", "materialId" -> "gbuffer.<name>"; "lines.<type>" ->
 *  the drawn layer of a line type ("lines.contour" -> "strokes.contour", the line's coverage from 0 off the line to
 *  255 on it); "picture" -> "composite.final". A full resource name ("shade.color") is returned as it is. */
INKGRAPH_API std::string bufferResourceName(const std::string& name);

/** Renders stills. One GL context (EGL, no display) is made by the first render and kept, with every compiled
 *  program, for the renderer's life: a batch pays start-up once. One renderer renders at a time per process (EGL
 *  shares one display per process, which ending a renderer's context ends): render() refuses while another renderer
 *  holds the context; destroy that one first. Any thread may render or destroy it, one render at a time (each render
 *  makes the context current on its thread and releases it at its end). A process forked after a render can render
 *  neither with it nor with a new one (the driver's threads stay in the parent): Error(Usage) and Error(Context) say
 *  so. Scenes and looks may be shared across threads (they are read only). */
class INKGRAPH_API Renderer {
public:
    /** `eglPlatform`: "auto" (default), "device" or "surfaceless", as --egl-platform. Nothing is made yet. */
    explicit Renderer(const std::string& eglPlatform = "auto");
    ~Renderer();
    Renderer(Renderer&&) noexcept;
    Renderer& operator=(Renderer&&) noexcept;
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /** Renders `scene` with `look` in `frame`, keeping `buffers` (names as bufferResourceName() takes them; "gbuffer.*"
     *  and "lines.*" expand). Only the passes the picture and those buffers need run. Buffers come as the graph holds
     *  them: G-buffer fields at the look's --supersample times the frame's size, line layers at the frame's size.
     *  Throws Error; an unknown buffer name is Error(Usage) naming the buffers this look has. */
    Still render(const Scene& scene, const Look& look, const Frame& frame,
                 const std::vector<std::string>& buffers = {});
    /** The GL renderer, version and vendor in use and the EGL platform ("llvmpipe (LLVM 15.0.6, 256 bits) / 4.5 (Core
     *  Profile) Mesa 22.3.6 (Mesa/X.org) via EGL device platform"), or "" before the first render. */
    std::string glDescription() const;

    struct Impl;

private:
    std::unique_ptr<Impl> mImpl;
};

} // namespace inkgraph::api
