#pragma once
/** @file inkgraph's public C++ API: load a scene (a file, or arrays in memory), describe a look and a frame with typed
 *  fields, render, get the picture, named buffers, the camera it was drawn with and its warnings. This header is the
 *  whole contract: it includes only the standard library, so a program that links `inkgraph::inkgraph`
 *  (find_package(inkgraph)) needs none of inkgraph's dependencies' headers.
 *
 *      #include <inkgraph/inkgraph.h>
 *      namespace ig = inkgraph::api;
 *
 *      ig::Renderer renderer;                                  // one GL context, kept for every render
 *      const ig::Scene bunny = ig::Scene::load("bunny.obj");
 *      ig::Look look;                                          // the command line's default look
 *      look.setShading(ig::Shading::Cel).setLines({ig::LineType::Silhouette, ig::LineType::Contour});
 *      ig::Frame frame;
 *      frame.width = frame.height = 512;
 *      frame.orbit = ig::Orbit{30.0, 10.0};
 *      const ig::Still still = renderer.render(bunny, look, frame, {"depth", "lines.contour"});
 *      still.write("bunny.png");                                // the picture, format from the extension
 *      const ig::StillCamera& camera = still.camera();          // K, [R|t], view, projection
 *
 *  Every typed field is checked by the same rules, with the same messages, as `inkgraph render`'s flag that sets it
 *  (`inkgraph help render`); Look::fromArguments() and Frame::fromArguments() take those flags as strings, so style
 *  files and command lines carry over. Errors are ig::Error, whose message starts with the API's function and quotes
 *  the names. docs/api.md describes it all, and its "Versions and ABI" section what a version promises. */

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

/** The library's version, as the header knows it; version() gives the library's own at run time. */
#define INKGRAPH_VERSION_MAJOR 0
#define INKGRAPH_VERSION_MINOR 2
#define INKGRAPH_VERSION_PATCH 0

/** The ABI's namespace: one per 0.x minor (the soname is libinkgraph.so.0.MINOR), so a program built against another
 *  minor fails to link instead of calling into a changed layout. */
#define INKGRAPH_ABI_NAMESPACE v0_2

/** What the shared library exports: this header's classes and functions, nothing else (api/CMakeLists.txt). */
#if defined(__GNUC__)
#define INKGRAPH_API __attribute__((visibility("default")))
#else
#define INKGRAPH_API
#endif

namespace inkgraph::api {
inline namespace INKGRAPH_ABI_NAMESPACE {

/** "0.2.0": the library's version (INKGRAPH_VERSION_* are the header's). */
INKGRAPH_API std::string version();
/** The git commit the library was built from ("unknown" outside a git checkout). */
INKGRAPH_API std::string gitCommit();

/** Every failure of the API. The message is the command line's own (the function or flag first, names quoted). */
class INKGRAPH_API Error : public std::runtime_error {
public:
    enum class Kind {
        /** A bad value, buffer name, camera or image; too little memory for the request; a Renderer used while
         *  another holds the process's GL context, or made before the fork of the process it is used in; a still
         *  written over a file its render read. */
        Usage,
        Input,   ///< an unreadable or invalid model, mesh arrays, shade map or texture
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

/** Something a load or a render warns about, as a record: a texture it could not read, a camera that sees none of the
 *  model, a shade map this shading does not use. docs/robustness.md ("Warning codes") lists every code. */
struct Warning {
    std::string code;    ///< stable, kebab-case: "texture-missing"
    std::string message; ///< as the command line prints it after "inkgraph: warning: "
    std::string file;    ///< the file it concerns (a texture, a shade map, the model), or ""
    std::string item;    ///< the thing in the model it concerns (a material, mesh, texture or node), or ""
};

/** An image: rows top first, rowBytes() apart (tightly packed but in a caller's buffer: Renderer::renderInto()),
 *  channels interleaved (R, G, B, A order). A rendered image views the render's own pixels (no copy); copies of an
 *  Image share them, and the library never changes them (a picture drawn into a caller's buffer changes when the
 *  caller writes there, or renders into it again). */
class INKGRAPH_API Image {
public:
    enum class Type { UInt8, Float32 };
    Image() = default;
    /** An image of your own pixels (to write() it): `bytes` holds width * height * channels * bytesPerChannel()
     *  bytes. Throws Error(Usage) for fields that do not agree (a side below 1, channels not 1 or 4, a type not
     *  of Type, a byte count that does not fit). */
    Image(int width, int height, int channels, Type type, std::vector<std::uint8_t> bytes);

    int width() const { return mWidth; }
    int height() const { return mHeight; }
    int channels() const { return mChannels; } ///< 1 or 4
    Type type() const { return mType; }
    std::size_t bytesPerChannel() const { return mType == Type::Float32 ? 4 : 1; }
    /** Bytes from one row's start to the next's: width * channels * bytesPerChannel() unless the pixels are a
     *  caller's (renderInto()). */
    std::size_t rowBytes() const { return mRowBytes; }
    /** Bytes from the first pixel to the end of the last row. */
    std::size_t byteCount() const { return mHeight < 1 ? 0 : mRowBytes * std::size_t(mHeight - 1) + packedRowBytes(); }
    std::size_t packedRowBytes() const { return std::size_t(mWidth) * std::size_t(mChannels) * bytesPerChannel(); }
    /** The pixels, byteCount() bytes; null for an empty Image. */
    const std::uint8_t* data() const { return mData; }
    /** The pixels as floats, rows rowBytes() apart; throws Error(Usage) unless type() is Float32. */
    const float* floats() const;
    /** Writes the image; the format follows the extension (PNG in the process; EXR, TIFF, JPEG through
     *  OpenImageIO). Float32 is kept by EXR and TIFF. Written under a temporary name beside `path` and renamed over
     *  it, so `path` must be a regular file or a new name: a device, a FIFO, a socket or a folder (also through a
     *  link) is refused, never replaced. Throws Error(Output) naming the file. */
    void write(const std::string& path) const;

private:
    friend struct ImageAccess;
    /** An image over pixels that `owner` keeps alive (null: the caller's, kept by the caller). */
    Image(int width, int height, int channels, Type type, const std::uint8_t* data, std::size_t rowBytes,
          std::shared_ptr<const void> owner);

    int mWidth = 0;
    int mHeight = 0;
    int mChannels = 0;
    Type mType = Type::UInt8;
    std::size_t mRowBytes = 0;
    const std::uint8_t* mData = nullptr;
    std::shared_ptr<const void> mOwner;
};

/** A direction or a point, in the model's world units. */
struct Vec3 {
    double x = 0.0;
    double y = 0.0;
    double z = 0.0;
};

/** What Scene::load() and Scene::fromArrays() take besides the model. */
struct SceneOptions {
    std::string animation; ///< a glTF animation's name or index; empty: the rest pose (files only)
    double time = 0.0;     ///< seconds into `animation`, >= 0
    /** A VRM humanoid pose after `animation` (--pose): "a-pose" or a pose file's path (docs/posing.md); empty: none
     *  (files only). */
    std::string pose;
    /** VRM expressions by name (case-sensitive) at weights in [0, 1], as --expression (docs/vrm.md); empty: the
     *  file's own face (files only). */
    std::map<std::string, double> expressions;
    std::optional<Vec3> lookAt; ///< a point (world) a VRM character looks at, as --look-at (files only)
    /** The load refuses models that would need more, and so does each render of the scene (its buffers at the
     *  frame's size); 0: the command line's default, half this machine's memory but at least 1 GiB. */
    std::size_t memoryLimitBytes = 0;
    /** Vertices closer than this x the model's size (its bounding box's diagonal) are merged when loading, 0 to 0.01
     *  (--weld-distance): lower for details under a millionth of the model, higher to join faces written apart. */
    double weldDistance = 1e-6;
    /** --strict: every warning fails: the load's with Error(Input) from Scene::load(), and each render's (a
     *  missing or undecodable texture, the model outside the view) with Error(Input) from Renderer::render(). */
    bool strict = false;
};

/** A mesh in memory, for Scene::fromArrays(): rows tightly packed, the pointers borrowed only for the call. */
struct MeshArrays {
    const float* vertices = nullptr; ///< vertexCount x 3: x, y, z
    std::size_t vertexCount = 0;
    const std::uint32_t* faces = nullptr; ///< faceCount x 3 vertex indices, counter-clockwise seen from the front
    std::size_t faceCount = 0;
    const float* normals = nullptr; ///< vertexCount x 3, or null: computed as for an OBJ without normals
    const float* uvs = nullptr;     ///< vertexCount x 2, or null
    const float* colors = nullptr;  ///< vertexCount x colorChannels in [0, 1], or null
    int colorChannels = 0;          ///< 3 or 4 when `colors` is given
};

struct SceneAccess;
struct LookAccess;
struct ImageAccess;

/** One object of a scene: a node instance (every mesh one glTF node holds; a file without nodes is one object). */
struct SceneObject {
    std::uint32_t id = 0;              ///< its value in the "objectId" buffer (0 there is the background)
    std::string name;                  ///< the node's name, or for an unnamed node its first mesh's name
    std::vector<std::string> nodePath; ///< the node names from the root down to it ("" for an unnamed node)
    std::vector<std::string> meshes;   ///< the names of its meshes, the skipped ones (SceneMesh::drawn) included
};

/** One mesh (primitive) of a scene, with the values it has in the id buffers: what names a pixel of "meshId",
 *  "triangleId", "objectId" and "materialId". */
struct SceneMesh {
    /** Its value in the "meshId" buffer (0 there is the background): its index + 1 among the file's meshes, the same
     *  in every pose and frame. */
    std::uint32_t id = 0;
    /** False for a mesh whose triangles are all degenerate (a pose that scales a prop to 0): it draws nothing, and
     *  keeps its id, object, material and triangle numbers so that the other meshes keep theirs (mesh-degenerate). */
    bool drawn = true;
    std::string name;                  ///< the glTF mesh's name ("mesh N" unnamed), the OBJ object's, or the file stem
    std::vector<std::string> nodePath; ///< the node names from the root down to its node (empty without nodes)
    std::uint32_t objectId = 0;        ///< its object's value in the "objectId" buffer (Scene::objects())
    std::uint32_t materialId = 0;      ///< its material's value in the "materialId" buffer
    std::string material;              ///< its material's name ("" for an unnamed one)
    std::uint64_t firstTriangle = 0;   ///< how many triangles the files give the meshes before it
    /** Its triangles are "triangleId" firstTriangle + 1 ... firstTriangle + count: as many as its file gives it, the
     *  ones the loader dropped (zero-area, back-to-back twins) included, whose ids appear nowhere. */
    std::uint64_t triangleCount = 0;
};

/** A model loaded once (OBJ with MTL, glTF/GLB, VRM, STL, PLY, or arrays): render it with any number of looks and
 *  frames. Copies share the loaded data. */
class INKGRAPH_API Scene {
public:
    /** Throws Error(Input) naming the file and the problem. */
    static Scene load(const std::string& path, const SceneOptions& options = {});
    /** A scene of one mesh given as arrays, checked as the file readers check theirs (indices in range, finite values,
     *  the same size limits) and prepared as an OBJ with the same vertices and faces is, so it renders the same.
     *  Throws Error(Input) naming the array and the problem. `name` names the mesh in messages. */
    static Scene fromArrays(const MeshArrays& arrays, const std::string& name = "arrays",
                            const SceneOptions& options = {});
    /** The file, or "" for arrays. */
    const std::string& path() const;
    std::size_t triangleCount() const;
    std::size_t vertexCount() const;
    /** The meshes it draws: meshes() less those whose triangles are all degenerate (SceneMesh::drawn false). */
    std::size_t meshCount() const;
    /** The loader's warnings (a texture it could not read, a skipped primitive, ...). */
    std::vector<Warning> warnings() const;
    /** Its objects, by id from 1: what the "objectId" buffer's values (and the object-boundary lines) tell apart. */
    std::vector<SceneObject> objects() const;
    /** Its meshes, by id from 1 (the "meshId" buffer's values), each with its range of "triangleId" values: triangles
     *  are numbered over the meshes in this order, each mesh's as its file gives them, from 1. Every mesh of the file,
     *  one whose triangles are all degenerate too (SceneMesh::drawn false), so the ids are the same in every pose. A
     *  still whose frame poses the scene again names its own: Still::meshes(). */
    std::vector<SceneMesh> meshes() const;

    /** A scene is a shared, unchanging handle. Only copying is declared, so a move copies too and leaves the source a
     *  whole scene (a move that emptied it made every later call on it crash). */
    Scene(const Scene&) = default;
    Scene& operator=(const Scene&) = default;

    struct Impl; ///< opaque: the library's own

private:
    friend struct SceneAccess;
    explicit Scene(std::shared_ptr<const Impl> impl) : mImpl(std::move(impl)) {}
    std::shared_ptr<const Impl> mImpl;
};

/** A colour, display RGBA, channels in [0, 1]. */
struct Color {
    double r = 0.0;
    double g = 0.0;
    double b = 0.0;
    double a = 1.0;
};

/** `--shading`: how surfaces are shaded (docs/shading.md). Auto (the default): each material its own model, MToon
 *  where it has one, cel elsewhere. */
enum class Shading { None, Flat, Gouraud, Lambert, Phong, Cel, Comic, MToon, Auto };
/** The line types, in the order the composite draws them (`--lines`; docs/lines.md): the hidden-line types first,
 *  under every visible line. */
enum class LineType {
    HiddenMeshSilhouette,   ///< the parts of MeshSilhouette the model hides, dashed (StrokeSettings::hiddenDashOn/Off)
    HiddenCrease,           ///< the parts of Crease the model hides, dashed
    HiddenBorder,           ///< the parts of Border the model hides, dashed
    HiddenIntersection,     ///< the parts of Intersection the model hides, dashed
    HiddenSuggestiveObject, ///< the parts of SuggestiveObject the model hides, dashed
    Outline,
    Silhouette,
    NormalEdge,
    DepthEdge,
    Crease,
    Border,
    Intersection,
    MaterialBoundary,
    ObjectBoundary,
    Suggestive,
    SuggestiveObject,
    Contour,
    MeshSilhouette,
};
/** `--view-vector` (comic). */
enum class ViewVector { Exact, Constant };
/** `--face-orientation` (comic). */
enum class FaceOrientation { Standard, DuringTriangles, DuringVertices, AfterVertices };
/** `--gbuffer-precision`. */
enum class Precision { Float32, Float16 };

/** The command line's name of each: "mtoon", "normal-edge", "during-vertices", "half". */
INKGRAPH_API std::string nameOf(Shading shading);
INKGRAPH_API std::string nameOf(LineType type);
INKGRAPH_API std::string nameOf(ViewVector mode);
INKGRAPH_API std::string nameOf(FaceOrientation method);
INKGRAPH_API std::string nameOf(Precision precision);
/** The line type named `name`; Error(Usage) naming the types there are. */
INKGRAPH_API LineType lineTypeNamed(const std::string& name);

/** How one line type is drawn (`--TYPE-width`, `--TYPE-color`). */
struct LineStyle {
    double width = 2.0; ///< pixels, 0.001 to 256
    Color color;
};

/** How line pixels become strokes, for every type (docs/strokes.md). */
struct StrokeSettings {
    double minLength = 0.01;       ///< --min-stroke-length: a share of the picture's height, 0 to 1
    bool weightByDepth = false;    ///< --line-weight depth
    bool weightByStrength = false; ///< --line-weight strength
    bool taperEnds = false;        ///< --line-weight taper
    bool mergeOverlaps = false;    ///< --overlapping-lines merge
    double hiddenDashOn = 6.0;     ///< --hidden-dash ON,OFF: the hidden-lines types' dashes, 1 to 4096 output pixels
    double hiddenDashOff = 4.0;    ///< and their gaps, 0 (solid) or 1 to 4096
};

/** The look: shading and its settings, the line types with their styles and parameters, strokes, paper, light and
 *  supersampling. Look() is the command line's default (auto shading: MToon where a material has it, else cel;
 *  silhouette and contour). Each setter checks
 *  its value at once, as the flag it stands for does, and throws Error(Usage) with that flag's message after the
 *  setter's name ("Look::setBands(): --bands: ..."); what depends on the other settings (a setting that has no
 *  effect with the rest, such as bands with Phong shading) is checked when the look renders. */
class INKGRAPH_API Look {
public:
    Look();
    ~Look();
    Look(const Look&);
    Look& operator=(const Look&);
    Look(Look&&) noexcept;
    Look& operator=(Look&&) noexcept;

    /** The adapter from the command line's words: {"--shading", "comic", "--lines", "outline,contour"}, as
     *  `inkgraph render` takes them (the Look and Lines sections of `inkgraph help render`, --style included). Throws
     *  Error(Usage) for a flag that is not a look flag (a camera, an output) or a bad value, with the CLI's message. */
    static Look fromArguments(const std::vector<std::string>& arguments);
    /** A style file (`inkgraph render --style FILE`). Throws Error(Usage) naming the file (and the line) as the
     *  command line does, also for a setting that is not the look's (size, fov: the Frame's). */
    static Look fromStyleFile(const std::string& path);
    /** One flag as a string: set("--silhouette-width", "3"); a flag without a value takes "". */
    Look& set(const std::string& flag, const std::string& value = "");
    /** The flags that give this look, in the order they were set (a setter replaces its flag's earlier value):
     *  fromArguments(look.arguments()) is the same look. */
    std::vector<std::string> arguments() const;

    Shading shading() const;
    Look& setShading(Shading shading);
    double shininess() const; ///< phong and comic
    Look& setShininess(double exponent);
    std::optional<int> bands() const; ///< cel and auto; unset: Qu, Chen & Zwicker's five uneven bands
    Look& setBands(int bands);
    std::string shadeMap() const; ///< cel, comic or auto: a PNG; "" is the built-in map
    Look& setShadeMap(const std::string& path);
    /** --outline-width-map: "none", "color:R" or "texture:FILE:G" (the outline, silhouette and MToon outline widths
     *  scaled per vertex by a vertex colour or texture channel). */
    std::string outlineWidthMap() const;
    Look& setOutlineWidthMap(const std::string& source);
    ViewVector viewVector() const;
    Look& setViewVector(ViewVector mode);
    FaceOrientation faceOrientation() const;
    Look& setFaceOrientation(FaceOrientation method);
    int frontRule() const; ///< comic with during-vertices or after-vertices: 1, 2 or 3
    Look& setFrontRule(int rule);
    std::optional<Vec3> light() const; ///< world direction toward the light; unset: the file's, else a key light
    Look& setLight(const Vec3& towardLight);
    /** --ambient: the uniform ambient light, linear RGB (alpha 1); unset: the shading model's default (0.15 for
     *  flat to phong, 0.05 for mtoon and auto). */
    std::optional<Color> ambient() const;
    Look& setAmbient(const Color& linearRgb);
    Color paper() const; ///< --background (alpha is 1)
    Look& setPaper(const Color& color);
    int supersample() const; ///< 1 to 8
    Look& setSupersample(int factor);
    int msaa() const; ///< --msaa: samples per pixel of the shading and MToon's outline shells, 1 (off), 2, 4 or 8
    Look& setMsaa(int samples);
    Precision gbufferPrecision() const;
    Look& setGbufferPrecision(Precision precision);

    /** The line types drawn, in the order they were given (the composite draws them in LineType's order); empty:
     *  none. */
    std::vector<LineType> lines() const;
    Look& setLines(const std::vector<LineType>& types);
    LineStyle lineStyle(LineType type) const;
    Look& setLineStyle(LineType type, const LineStyle& style);
    /** The names of the parameters `type` takes besides width and colour ("depth-jump", "crease-angle"); a parameter
     *  may serve several types, and is then one value for all of them. */
    static std::vector<std::string> lineParameterNames(LineType type);
    /** A number parameter's value (given or default); Error(Usage) for a name no line type takes, a choice, or a
     *  parameter with no default that was not set. */
    double lineParameter(const std::string& name) const;
    /** A choice parameter's value ("5" of --suggestive-stencil). */
    std::string lineChoice(const std::string& name) const;
    Look& setLineParameter(const std::string& name, double value);
    Look& setLineChoice(const std::string& name, const std::string& value);
    StrokeSettings strokes() const;
    Look& setStrokes(const StrokeSettings& strokes);

    struct Impl;

private:
    friend struct LookAccess;
    std::unique_ptr<Impl> mImpl;
};

/** --orbit: the eye on a sphere around the target, angles from the model's front. */
struct Orbit {
    double azimuth = 0.0;           ///< degrees about up, [-360, 360]; 90 looks from the front view's right
    double elevation = 0.0;         ///< degrees above the horizontal, [-89.9, 89.9]
    std::optional<double> distance; ///< world units; unset: the auto-framing distance
    /** With distance unset: the eye at this multiple of the auto-framing distance, (0, 1000] (--orbit AZ,EL,xS). */
    double distanceScale = 1.0;
};

/** --views' settings besides the count and the seed (docs/datasets.md#views-and-variations): what sampleViews()
 *  draws each view from. Checked by the flags' rules, with their messages. */
struct ViewSampling {
    double elevationMean = 10.0;      ///< --view-elevation MEAN,SD,LOW,HIGH: degrees
    double elevationDeviation = 10.0; ///< the normal's standard deviation, [0, 180]
    double elevationLow = -30.0;      ///< the clamp, within [-89.9, 89.9]
    double elevationHigh = 60.0;
    double distanceJitter = 0.0; ///< --view-distance-jitter J, [0, 0.9]
    double lightJitter = 0.0;    ///< --light-jitter DEG, [0, 180]; needs `light`
    std::optional<Vec3> light;   ///< --light: the direction the jitter turns
    /** --expressions' alternatives, each in --expression's syntax ("angry=1,blink=0.5") or "none". */
    std::vector<std::string> expressions;
    std::vector<std::string> poses; ///< --poses' alternatives: "rest", "a-pose" or a pose file
};

/** One view, as the command line's --views draws it and records it in --stats ("view"). */
struct ViewSample {
    std::size_t index = 0;
    double azimuth = 0.0;                  ///< degrees, [0, 360)
    double elevation = 0.0;                ///< degrees
    double distanceScale = 1.0;            ///< times the auto-framing distance
    std::optional<Vec3> light;             ///< with a light jitter: Look::setLight() with it
    std::optional<std::string> expression; ///< with expressions: the alternative, "none" or as --expression writes it
    std::optional<std::string> pose;       ///< with poses: "rest", "a-pose" or the file

    /** The view's orbit, for Frame::orbit: the command line's view exactly. */
    Orbit orbit() const { return Orbit{azimuth, elevation, std::nullopt, distanceScale}; }
};

/** The `count` views (1 to 100000) of the model `modelKey` (its path as the command line lists it) for `seed`, exactly
 *  the command line's `--views count --seed seed` with `sampling`'s flags. Throws Error(Usage) with the flag's message
 *  for a setting out of range. */
INKGRAPH_API std::vector<ViewSample> sampleViews(std::size_t count, std::uint64_t seed, const std::string& modelKey,
                                                 const ViewSampling& sampling = {});

/** --clip NEAR,FAR. */
struct Clip {
    double near = 0.0;
    double far = 0.0;
};

/** Where the view comes from when eye, orbit and frameNodes leave it open: the file's camera when it has one, or
 *  always auto-framing (--camera auto). */
enum class CameraPlacement { FileOrAuto, Auto };

/** The frame: size, camera and pose. Unset fields take the command line's defaults (the file's camera, else framed to
 *  fit the model at 35 degrees from the front, slightly above). Checked when it renders, by the rules of the flag
 *  each field stands for, with its message after the field's name ("Frame::fov: --fov: ..."). */
struct INKGRAPH_API Frame {
    int width = 1024; ///< --size, 1 to 16384
    int height = 1024;
    std::optional<Vec3> eye; ///< --eye (world)
    std::optional<Orbit> orbit;
    std::optional<Vec3> target; ///< --target (world)
    std::optional<Vec3> up;     ///< --up
    std::optional<double> fov;  ///< --fov: vertical degrees, 0.01 to 179
    std::optional<Clip> clip;
    CameraPlacement placement = CameraPlacement::FileOrAuto;
    std::vector<std::string> frameNodes; ///< --frame: fit the view to the meshes under these nodes
    /** A pose other than the scene's own (SceneOptions), for this render: the scene's file is loaded again in that
     *  pose (a scene made from arrays has none). Empty with time unset: the scene as loaded. */
    std::string animation;
    /** Seconds into `animation`; also the clock of MToon's UV animation (--time). Unset: the scene's
     *  SceneOptions::time. Given without `animation`, it moves the scene's own animation (SceneOptions::animation)
     *  to this time, the file loaded again; a scene loaded without one it poses nothing (warning time-unused when
     *  no material has a UV animation). */
    std::optional<double> time;
    /** A VRM humanoid pose other than the scene's own (SceneOptions::pose), for this render (--pose): the scene's
     *  file is loaded again in it. Empty: the scene's pose. */
    std::string pose;
    /** A face other than the scene's own (SceneOptions::expressions, lookAt), for this render: the scene's file is
     *  loaded again with these (each replacing the scene's when given) in the scene's pose at the frame's time. */
    std::map<std::string, double> expressions;
    std::optional<Vec3> lookAt;

    /** The adapter from the command line's Camera flags: {"--orbit", "30,10", "--fov", "40", "--size", "640x480"}.
     *  Throws Error(Usage) for a flag that is not the frame's, or a bad value, with the CLI's message. */
    static Frame fromArguments(const std::vector<std::string>& arguments);
};

/** Where a still's view came from. */
enum class CameraSource {
    File,  ///< the model's own camera (glTF)
    Auto,  ///< auto-framed (Frame::frameNodes included)
    Orbit, ///< Frame::orbit
    Eye,   ///< Frame::eye
};

/** The camera a still was drawn with, in world coordinates. Matrices are row-major: m[row][column]. */
struct StillCamera {
    /** OpenGL's view matrix: world points to view space (x right, y up, looking down -z). */
    std::array<std::array<double, 4>, 4> view{};
    /** OpenGL's projection matrix (perspective, clip space with z in [-w, w]). */
    std::array<std::array<double, 4>, 4> projection{};
    /** OpenCV's camera matrix K: fx = fy = (height / 2) / tan(fovY / 2), cx = width / 2 - 0.5, cy = height / 2 - 0.5
     *  (x right, y down, the centre of pixel (0, 0) at (0, 0)), for the picture's size. A buffer at S x the size
     *  (supersampling) scales fx, fy by S and has its centre at S x width / 2 - 0.5. */
    std::array<std::array<double, 3>, 3> intrinsics{};
    /** OpenCV's [R|t]: world points to the OpenCV camera frame (x right, y down, z forward). With the `depth` buffer
     *  (view depth, 0 off the model): X_cam = depth * K^-1 [u v 1]^T, X_world = R^T (X_cam - t). */
    std::array<std::array<double, 4>, 3> extrinsics{};
    Vec3 eye;
    Vec3 target;
    Vec3 up;
    double fovY = 0.0; ///< degrees
    double near = 0.0;
    double far = 0.0;
    bool clipGiven = false; ///< near and far were Frame::clip; else fitted to the model's bounding sphere
    int width = 0;
    int height = 0;
    CameraSource source = CameraSource::Auto;
};

/** One point of a StillStroke (docs/datasets.md, "Strokes with their 3-D points"). */
struct StillStrokePoint {
    double x = 0.0, y = 0.0;    ///< output pixels: x right, y down, the centre of pixel (0, 0) at (0, 0) (as K's)
    std::optional<Vec3> world;  ///< the world point it came from; unset where no surface lies under the point
    int mesh = 0;               ///< the Scene's mesh index + 1; 0 when not known
    std::int64_t triangle = -1; ///< global triangle index over the scene's meshes in order; -1 when not known
};

/** A kept stroke of one drawn line type, as the command line's --strokes writes it. */
struct StillStroke {
    std::string type;    ///< "contour", "hidden-crease", ...
    bool visible = true; ///< false for the hidden-lines types
    bool closed = false;
    std::vector<StillStrokePoint> points; ///< in order along the stroke
};

/** One rendered still: the picture, every buffer asked for, the camera and the warnings. */
class INKGRAPH_API Still {
public:
    /** The final picture, RGBA8 (the command line's -o). */
    const Image& picture() const;
    /** A buffer asked for in render(), by the name it was asked with; throws Error(Usage) naming the buffers there
     *  are. */
    const Image& buffer(const std::string& name) const;
    /** The buffers, each by the first name it was asked with, in that order ("gbuffer.*" gives each field's short
     *  name, "lines.*" each line type's "lines.<type>"); buffer() also answers any name of the same buffer. */
    std::vector<std::string> bufferNames() const;
    /** The camera it was drawn with. */
    const StillCamera& camera() const;
    /** The meshes of the scene it drew, as Scene::meshes() gives them: what its "meshId", "triangleId" and
     *  "barycentric" values and its strokes' meshes name. Scene::meshes() unless the frame posed the scene again
     *  (Frame::animation, time, pose, expressions, lookAt): the same ids, and a mesh the pose collapses to nothing (a
     *  prop's node scaled to 0) has SceneMesh::drawn false. */
    const std::vector<SceneMesh>& meshes() const;
    /** Its objects, as Scene::objects() gives them: what its "objectId" values name (likewise the frame's pose's). */
    const std::vector<SceneObject>& objects() const;
    /** Every kept stroke of every drawn line type with its points' world points, mesh and triangle, in the order
     *  --strokes writes them (values rounded alike: x, y to 1e-4 pixels, world to 7 digits), when render() was asked
     *  for "strokes"; throws Error(Usage) otherwise. */
    const std::vector<StillStroke>& strokes() const;
    /** What the load (for a still that posed its scene) and the render warned about. */
    const std::vector<Warning>& warnings() const;
    /** Writes the picture as Image::write() does, but never over a file the render read (the model, its buffers
     *  and images, the shade maps, the look's style file), compared as the command line compares its outputs
     *  with its inputs (links and hard links too): that is Error(Usage), naming the file and what it is. */
    void write(const std::string& path) const;
    /** Milliseconds the render took: without loading the scene, but with loading it again for a frame's own pose. */
    double milliseconds() const;

    /** A shared, unchanging handle, as a Scene is: a move copies and leaves the source a whole still too. */
    Still(const Still&) = default;
    Still& operator=(const Still&) = default;

    struct Impl;

private:
    friend class Renderer;
    explicit Still(std::shared_ptr<const Impl> impl) : mImpl(std::move(impl)) {}
    std::shared_ptr<const Impl> mImpl;
};

/** The buffers render() can return (it takes "strokes" too, which asks for Still::strokes() and is no image, so not
 * listed here): "normal", "view",
 * "wVec", "nDotV", "depth", "coverage", "baseColor", "radial", "materialId", "objectId", "meshId", "triangleId" (the
 * G-buffer's fields: float32 exact integers, 0 for the background; Scene::objects() and Scene::meshes() name the ids),
 * "barycentric" (4 x float32: the visible point's weights in its triangle's corners, alpha the id of their triangle, as
 * "triangleId"), "gbuffer.*" (every field, the labels included), "lines.<type>" (the drawn layer of a line type, its
 * coverage from 0 off the line to 255 on it), "lines.*" (every drawn type; only for a look that draws lines),
 * "picture". render() also takes the graph's own name of any image it computes (`inkgraph render --print-plan`:
 * "shade.color", "gbuffer.zBuffer"); a name that is neither is refused (Error(Usage), naming the buffers the look has).
 */
INKGRAPH_API std::vector<std::string> bufferNames(const Look& look);

/** Renders stills. One GL context (EGL, no display) is made by the first render and kept, with every compiled
 *  program, for the renderer's life: a batch pays start-up once. Each renderer has a context of its own, so several
 *  renderers render at once, each on its own thread. Any thread may render with a renderer or destroy it, one render
 *  at a time (each render makes the context current on its thread and releases it at its end; a GL context of the
 *  caller's own that was current there, and the bound EGL client API, are current again after the render and after
 *  the renderer's end). A process forked after a render can render neither with it nor with a new one (the driver's
 *  threads stay in the parent): Error(Usage) and Error(Context) say so. Scenes and looks may be shared across threads
 *  (they are read only). Call nothing of the library from static destructors or atexit handlers: its own statics
 *  (the format readers, the flag table) and the GL driver may be gone by then. */
class INKGRAPH_API Renderer {
public:
    /** How the GL context is reached: `--egl-platform`. */
    enum class Platform { Auto, Device, Surfaceless };
    /** Nothing is made yet. */
    explicit Renderer(Platform platform = Platform::Auto);
    ~Renderer();
    Renderer(Renderer&&) noexcept;
    Renderer& operator=(Renderer&&) noexcept;
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /** Renders `scene` with `look` in `frame`, keeping `buffers` (bufferNames()). Only the passes the picture and those
     *  buffers need run. Buffers come as the graph holds them: G-buffer fields at the look's supersample times the
     *  frame's size, line layers at the frame's size. Throws Error; an unknown buffer name is Error(Usage) naming the
     *  buffers this look has. */
    Still render(const Scene& scene, const Look& look, const Frame& frame,
                 const std::vector<std::string>& buffers = {});
    /** The same, with the picture written into `picture` (frame.height rows of frame.width RGBA8 pixels, `rowBytes`
     *  apart, at least width * 4) instead of memory of the still's own; the still's picture() then views it, so
     *  `picture` must outlive the still's use of it. */
    Still renderInto(std::uint8_t* picture, std::size_t rowBytes, const Scene& scene, const Look& look,
                     const Frame& frame, const std::vector<std::string>& buffers = {});
    /** The GL renderer, version and vendor in use and the EGL platform ("llvmpipe (LLVM 15.0.6, 256 bits) / 4.5 (Core
     *  Profile) Mesa 22.3.6 (Mesa/X.org) via EGL device platform"), or "" before the first render. */
    std::string glDescription() const;

    struct Impl;

private:
    std::unique_ptr<Impl> mImpl;
};

} // namespace INKGRAPH_ABI_NAMESPACE
} // namespace inkgraph::api
