#pragma once
/** @file Plain scene data shared by every layer: meshes in world space, an optional camera and light.
 *  No GL here; passes upload what they need. */

#include <glm/glm.hpp>

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace inkgraph {

/** Thrown for any input problem while reading a model. The message starts with the function, names
 *  the file in single quotes and says what is wrong, e.g.
 *  `loadScene(): 'bunny.obj' line 12: vertex index 900 out of range (file has 512 vertices)`. */
class SceneError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/** One triangle mesh in world space (node transforms already applied). */
struct Mesh {
    std::string name;                  ///< node/mesh/object name, or the file stem
    std::vector<glm::vec3> positions;  ///< welded, finite
    std::vector<glm::vec3> normals;    ///< one unit normal per position (from the file, else area-weighted smooth)
    std::vector<glm::uvec3> triangles; ///< counter-clockwise seen from the front (outward normals), none degenerate
    glm::vec4 baseColor{0.8f, 0.8f, 0.8f, 1.0f}; ///< linear RGBA; glTF baseColorFactor or the default grey
    /** The shade map this mesh asks for (glTF material extras {"inkgraph": {"shademap": "..."}}), a path resolved
     *  against the glTF file's folder and lexically normalised; empty: the run's map. Read by the app, not here. */
    std::string shadeMapPath;
    std::string materialName; ///< the glTF material's name, for messages; empty without one or for other formats

    std::size_t triangleCount() const { return triangles.size(); }
};

/** The first perspective camera of a glTF file, in world space. */
struct SceneCamera {
    glm::dvec3 eye{0.0};
    glm::dvec3 forward{0.0, 0.0, -1.0}; ///< unit; the camera looks down its local -Z
    glm::dvec3 up{0.0, 1.0, 0.0};       ///< unit; the camera's local +Y
    double fovYDegrees = 35.0;
    std::optional<double> aspectRatio; ///< width / height when the file gives one
};

/** A KHR_lights_punctual directional light. */
struct DirectionalLight {
    glm::dvec3 towardLight{0.0, 0.0, 1.0}; ///< unit world direction from the surface toward the light
    glm::dvec3 color{1.0};
    double intensity = 1.0;
};

/** What the loader did, for --stats and the manifest. */
struct LoadReport {
    std::string format;                ///< "obj", "stl-binary", "stl-ascii", "gltf", "glb"
    std::size_t trianglesRead = 0;     ///< after triangulating polygons, strips and fans
    std::size_t degenerateDropped = 0; ///< zero-area or repeated-index triangles removed
    std::size_t verticesBeforeWeld = 0;
    std::size_t verticesAfterWeld = 0;
    bool normalsComputed = false;      ///< true when some mesh had no normals in the file
    std::vector<std::string> warnings; ///< e.g. skipped POINTS primitives, ignored orthographic cameras
};

struct Scene {
    std::vector<Mesh> meshes;
    std::optional<SceneCamera> camera;
    std::optional<DirectionalLight> light;
    LoadReport report;

    std::size_t triangleCount() const;
    std::size_t vertexCount() const;
};

struct BoundingSphere {
    glm::dvec3 center{0.0};
    double radius = 0.0;
};

/** 8 GiB: a 60-million-triangle mesh. */
inline constexpr std::size_t kDefaultLoadMemoryLimit = std::size_t(8) << 30;

/** Options of loadScene(). */
struct LoadOptions {
    /** Positions closer than weldTolerance x (bounding-box diagonal) are merged. Relative, so the result does
     *  not depend on the model's units. */
    double weldTolerance = 1e-6;
    /** The most memory one load may take, estimated before allocating from the file size and the vertex and
     *  triangle counts the file declares or has reached (detail::MeshBudget); above it loading stops with a
     *  SceneError naming the file. The CLI sets it from --memory-limit. */
    std::size_t memoryLimitBytes = kDefaultLoadMemoryLimit;
};

/** Reads .gltf, .glb, .obj or .stl (binary or ASCII), chosen by content and extension.
 *  Throws SceneError for a missing or unreadable file, corrupt or truncated content, non-finite
 *  coordinates, out-of-range indices, or a file with no triangles. */
Scene loadScene(const std::string& path, const LoadOptions& options = {});

/** loadScene() on a file's bytes already in memory (the fuzz targets' entry): `path` names the file in messages,
 *  its extension picks the reader, and glTF's external buffers are resolved next to it. */
Scene loadSceneFromMemory(const std::string& path, std::string_view content, const LoadOptions& options = {});

/** A bounding sphere of every mesh (centre of the bounding box, radius to the farthest vertex).
 *  Throws SceneError on an empty scene. */
BoundingSphere computeBoundingSphere(const Scene& scene);

} // namespace inkgraph
