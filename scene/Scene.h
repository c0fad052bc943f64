#pragma once
/** @file Plain scene data shared by every layer: meshes in world space, an optional camera and light.
 *  No GL here; passes upload what they need. */

#include "scene/Material.h"
#include "scene/Warning.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
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

/** One triangle mesh (node transforms already applied); positions are relative to Scene::origin. */
struct Mesh {
    std::string name;                  ///< node/mesh/object name, or the file stem
    std::vector<glm::vec3> positions;  ///< welded, finite; relative to Scene::origin (world = origin + position)
    std::vector<glm::vec3> normals;    ///< one unit normal per position (from the file, else area-weighted smooth)
    std::vector<glm::uvec3> triangles; ///< counter-clockwise seen from the front (outward normals), none degenerate
    /** Texture coordinates TEXCOORD_0 and TEXCOORD_1, one per position, or empty when the file has none (glTF's
     *  convention: (0, 0) is the image's top-left corner). */
    std::vector<glm::vec2> texcoords[2];
    std::vector<glm::vec4> colors; ///< linear RGBA vertex colours (glTF COLOR_0, OBJ `v x y z r g b`), or empty
    Material material;             ///< what the surface looks like (scene/Material.h)
    /** The names of the nodes from the scene's root down to the one holding this mesh (glTF node names, "" for an
     *  unnamed node; an OBJ's `o` name), or empty when the format has no nodes (STL). --frame selects meshes by it. */
    std::vector<std::string> nodePath;
    /** Which instance of its node path this mesh belongs to, where the path alone cannot tell (two unnamed sibling
     *  glTF nodes have equal paths): the glTF node's index, 0 for formats without nodes. Meshes with equal nodePath and
     *  nodeInstance are one object (scene/ObjectIds.h: the G-buffer's objectId, the object-boundary lines). */
    std::size_t nodeInstance = 0;
    /** What the loader knows about its weld, so data derived later need not weld again (MeshOps weldMeshPositions()):
     *  set when it welded by position alone (no file normals, texture coordinates or colours kept copies of a point
     *  apart), then a position weld (weldVertices() without normals or classes) at this distance or less merges
     *  nothing. Empty when not known. Code that moves positions must reset it. */
    std::optional<double> positionsWeldedAt;
    /** Whether `normals` are exactly computeSmoothNormals(positions, triangles), as the loader computes them for a
     *  file without normals (and without texture seams or colour borders to smooth across), so the inflated hull's
     *  normals are these (GpuScene::hullNormals()). Code that changes positions or triangles must reset it. */
    bool normalsAreSmooth = false;
    /** Drawn from its front only though its material is two-sided: every triangle lies back to back with another
     *  sheet's that covers its back (cullBackToBackSheets(): a card printed on both sides). The material stays as the
     *  file gives it, so material ids and the manifest do not change. */
    bool backCulled = false;
    /** Where the loader dropped some of the triangles the file gave this mesh (zero-area or collapsed by the weld, a
     *  two-sided material's back-to-back twins: finalizeMesh()), each kept triangle's index among the file's (after
     *  polygons and strips are cut into triangles), ascending; empty when it dropped none, so triangle t is the
     *  file's t. Triangle ids count the file's triangles (scene/MeshLabels.h), so that they name the same triangle
     *  as the file does. */
    std::vector<std::uint32_t> fileTriangles;
    /** How many triangles the file gave it, the dropped ones included; 0 (a mesh made in code) reads as
     *  triangles.size(). */
    std::size_t fileTriangleCount = 0;
    /** Per triangle, 1 where its 2nd and 3rd corners are the file's 3rd and 2nd (the loader swapped them to keep the
     *  front outward: a glTF node's mirroring transform, a closed surface wound inside out); empty when none is. The
     *  G-buffer's barycentric weights swap them back, so they are the file's corners' weights. */
    std::vector<std::uint8_t> cornersSwapped;

    std::size_t triangleCount() const { return triangles.size(); }
    /** How many triangle ids the mesh's triangles take: the file's triangles, the dropped ones included. */
    std::size_t numberedTriangleCount() const { return std::max(fileTriangleCount, triangles.size()); }
    /** Triangle `triangle`'s index among the file's triangles (Mesh::fileTriangles). */
    std::size_t fileTriangleOf(std::size_t triangle) const {
        return fileTriangles.empty() ? triangle : fileTriangles[triangle];
    }
    /** Whether its back faces are drawn: a two-sided material's, unless backCulled. */
    bool drawsBackFaces() const { return material.doubleSided && !backCulled; }
};

/** The first perspective camera of a glTF file, in the scene's frame: `eye` is relative to Scene::origin like the
 *  positions (world eye = origin + eye); directions are the same in both frames. */
struct SceneCamera {
    glm::dvec3 eye{0.0};
    glm::dvec3 forward{0.0, 0.0, -1.0}; ///< unit; the camera looks down its local -Z
    glm::dvec3 up{0.0, 1.0, 0.0};       ///< unit; the camera's local +Y
    double fovYDegrees = 35.0;
    std::optional<double> aspectRatio; ///< width / height when the file gives one
    std::string name;                  ///< for messages: "camera 0 'main'", or "camera 0" for an unnamed one
};

/** A KHR_lights_punctual directional light. */
struct DirectionalLight {
    glm::dvec3 towardLight{0.0, 0.0, 1.0}; ///< unit world direction from the surface toward the light
    glm::dvec3 color{1.0};
    double intensity = 1.0;
};

/** LoadOptions::weldTolerance's default: positions within a millionth of the model's size are one. */
inline constexpr double kDefaultWeldTolerance = 1e-6;

/** What the loader did, for --stats and the manifest. */
struct LoadReport {
    /** "obj", "stl-binary", "stl-ascii", "ply-ascii", "ply-binary", "gltf", "glb"; "arrays" for sceneFromArrays() */
    std::string format;
    std::size_t trianglesRead = 0;     ///< after triangulating polygons, strips and fans
    std::size_t degenerateDropped = 0; ///< zero-area or repeated-index triangles removed
    /** triangles removed as a repeat of another on the same corners, wound the same way (repeatedTriangles()) */
    std::size_t repeatedDropped = 0;
    /** triangles of two-sided materials removed as the back-to-back twin of another (backToBackTwins()) */
    std::size_t backToBackDropped = 0;
    /** triangles of two-sided materials drawn one-sided, each sheet from its own side: back to back with another that
     *  carries attributes or a material of its own (cullBackToBackSheets()) */
    std::size_t backToBackOneSided = 0;
    std::size_t verticesBeforeWeld = 0;
    std::size_t verticesAfterWeld = 0;
    bool normalsComputed = false;        ///< true when some mesh had no normals in the file
    std::vector<Warning> warnings;       ///< e.g. skipped POINTS primitives, ignored orthographic cameras
    std::vector<std::string> inputFiles; ///< every file this load read: the model, glTF external buffers and images
                                         ///< (paths as opened, resolved against the model's folder)
    /** Texture files a material names that the load already found missing (an OBJ's maps, warned with their library
     *  and line), by name as written and resolved path; the materials are drawn without them. A glTF's images are
     *  found or not when drawn (SceneMaterials), so they are never here. */
    std::vector<SceneImage> missingImages;
    /** LoadOptions::weldTolerance of this load: what is derived from the scene later (SceneDerivedData's position
     *  welds for the hull and the edges) welds as the load did. */
    double weldTolerance = kDefaultWeldTolerance;
};

/** A skin joint or VRM humanoid bone node, for --frame: the part of a skinned character it moves. */
struct SceneJoint {
    std::string node; ///< the node's name ("" for an unnamed one)
    std::string bone; ///< its VRM humanoid bone name (VRM 1.0's), or ""
    /** The bounding box of the posed vertices this joint and its descendant joints weight (weight > 0), in the
     *  scene's local frame like the positions; empty (lower above upper) when they weight none. */
    glm::dvec3 lower{std::numeric_limits<double>::max()};
    glm::dvec3 upper{std::numeric_limits<double>::lowest()};
};

/** A mesh of the file whose triangles were all degenerate, so the loader skipped it (a pose that scales a part to 0, a
 *  file's own sliver): what it would have been, kept so that the meshes, objects, materials and triangles after it
 *  keep their ids in every pose (scene/MeshNumbering.h). */
struct SkippedMesh {
    /** Where it stood: the index in Scene::meshes of the first drawn mesh after it (Scene::meshes.size() when none). */
    std::size_t before = 0;
    /** Its name, node path and instance, material and Mesh::fileTriangleCount; no vertices or triangles. */
    Mesh mesh;
};

struct Scene {
    /** World = origin + stored position. Positions are computed in double while loading and stored in float relative
     *  to this point (the centre of the model's bounding box), so a model far from the world origin (georeferenced
     *  exports at 1e7 units) keeps its detail. Everything positional the scene carries (the glTF camera's eye) is in
     *  the same local frame; resolveCamera() takes world coordinates from the user and subtracts this. */
    glm::dvec3 origin{0.0};
    std::vector<Mesh> meshes; ///< the meshes drawn, in the file's order
    /** The file's meshes the loader skipped, in the file's order (SkippedMesh::before ascending): they draw nothing
     *  but keep their numbers (scene/MeshNumbering.h). */
    std::vector<SkippedMesh> skippedMeshes;
    std::optional<SceneCamera> camera;
    std::optional<DirectionalLight> light;
    /** The direction the model faces when its file says so (unit, world): a VRM 0.x character faces -Z, a VRM 1.0
     *  one +Z (their specifications). Auto-framing looks at this side; empty, it looks from +Z. */
    std::optional<glm::dvec3> front;
    std::vector<SceneImage> images; ///< what the materials' TextureRef::image indexes, still encoded
    /** Every skin joint and VRM humanoid bone node of a glTF model, in node order (--frame by joint or bone). */
    std::vector<SceneJoint> joints;
    LoadReport report;

    std::size_t triangleCount() const;
    std::size_t vertexCount() const;
};

struct BoundingSphere {
    glm::dvec3 center{0.0};
    double radius = 0.0;
};

/** The largest model extent (bounding-box diagonal, in the file's units) a load accepts. The renderer works in float
 *  relative to the model's centre and squares distances (eye to surface, about 3x the extent when auto-framed): far
 *  below float's 3.4e38 even squared, with room for the depth range and the derivative kernels. */
inline constexpr double kMaxModelExtent = 1e15;
/** The smallest non-zero model extent a load accepts: curvature derivatives scale as 1/extent^3, which in double
 *  stays far from overflow at 1e-12 (1e36), as do the squared areas (1e-24) the clean-up thresholds compare. */
inline constexpr double kMinModelExtent = 1e-12;

/** The glTF extensions the reader implements; a file that lists any other in `extensionsRequired` is refused (the
 *  glTF 2.0 specification requires it), one that merely uses another is loaded without it. */
const std::vector<std::string>& supportedGltfExtensions();

/** 8 GiB: a 60-million-triangle mesh. */
inline constexpr std::size_t kDefaultLoadMemoryLimit = std::size_t(8) << 30;

/** One VRM expression at a weight (--expression NAME=WEIGHT). */
struct ExpressionWeight {
    std::string name;    ///< as the file names it, case-sensitive: a VRM 1.0 preset or custom name, or a 0.x group
    double weight = 0.0; ///< in [0, 1]
    bool operator==(const ExpressionWeight&) const = default;
};

/** Options of loadScene(). */
struct LoadOptions {
    /** Positions closer than weldTolerance x (bounding-box diagonal) are merged. Relative, so the result does
     *  not depend on the model's units. The CLI sets it from --weld-distance. */
    double weldTolerance = kDefaultWeldTolerance;
    /** The most memory one load may take, estimated before allocating from the file size and the vertex and
     *  triangle counts the file declares or has reached (detail::MeshBudget); above it loading stops with a
     *  SceneError naming the file. The CLI sets it from --memory-limit. */
    std::size_t memoryLimitBytes = kDefaultLoadMemoryLimit;
    /** A glTF animation to pose the model by: its name, or its index as text when no animation has that name; empty
     *  for the rest pose (the nodes' own transforms and morph weights). A name the file does not have is a SceneError
     *  listing the animations it has. A path ending in ".vrma" that names an existing file is a VRM Animation instead,
     *  retargeted onto a VRM model's humanoid bones (docs/posing.md). The CLI sets it from --animation. */
    std::string animation;
    /** Seconds into `animation` (clamped to each channel's keyframes); finite and >= 0. The CLI's --time. */
    double time = 0.0;
    /** A VRM humanoid pose, applied after `animation`: "a-pose" (both upper arms lowered 45 degrees from the rest
     *  T-pose), or the path of a pose file, {"boneName": [x, y, z, w], ...} in the VRM normalized pose convention
     *  (docs/posing.md); empty for none. A model without a VRM humanoid, a bad file or an unknown bone name is a
     *  SceneError. The CLI's --pose. */
    std::string pose;
    /** VRM expressions to show (VRM 1.0 VRMC_vrm.expressions, 0.x blendShapeMaster), applied after the animation:
     *  their morph targets, material colours and texture transforms (docs/vrm.md). A name the file does not have,
     *  or any expression for a file without them, is a SceneError listing the expressions it has. The CLI's
     *  --expression. */
    std::vector<ExpressionWeight> expressions;
    /** A point (world coordinates of the file) the VRM character looks at: its eye bones turned, or its look
     *  expressions weighted, as the file's lookAt says (docs/vrm.md). A file without VRM look-at data is a
     *  SceneError. The CLI's --look-at. */
    std::optional<glm::dvec3> lookAt;
    bool operator==(const LoadOptions&) const = default;
};

/** Reads .gltf, .glb (and .vrm, a GLB), .obj, .stl or .ply (binary or ASCII), chosen by extension (the format table)
 *  and content.
 *  Throws SceneError for a missing or unreadable file, corrupt or truncated content, non-finite
 *  coordinates, out-of-range indices, a model whose extent lies outside [kMinModelExtent, kMaxModelExtent], or a file
 *  with no triangles. */
Scene loadScene(const std::string& path, const LoadOptions& options = {});

/** loadScene() on a file's bytes already in memory (the fuzz targets' entry): `path` names the file in messages,
 *  its extension picks the reader, and glTF's external buffers are resolved next to it. */
Scene loadSceneFromMemory(const std::string& path, std::string_view content, const LoadOptions& options = {});

/** The files a model names besides itself, found without loading it: a glTF's external buffers and images and its
 *  materials' shade maps (a GLB's JSON chunk alone is read), an OBJ's material libraries and their textures. For checks
 * before any work (a batch's outputs must not replace a file another model reads). Best effort: a file that cannot be
 * read names none, and loading it reports why. */
std::vector<std::string> referencedFiles(const std::string& path);

/** Reads and judges a LoadOptions::pose as loadScene() does, without a model: "" and "a-pose" pass; a pose file that
 *  cannot be read, or that every model would refuse (not JSON, a bone outside VRM's humanoid bones, a bone given
 *  twice, a quaternion that is not four finite numbers of non-zero length), throws SceneError naming the file and
 *  starting with `speaker` (a flag, for the command line). Whether the model is a VRM is judged when it loads. A run
 *  of many stills calls this before the first, where each still drawing the pose would fail alike. */
void checkPoseFile(const std::string& pose, std::size_t memoryLimitBytes = kDefaultLoadMemoryLimit,
                   std::string_view speaker = "checkPoseFile()");

/** The input formats loadScene() reads, named as the reader table names them, in its order ("glTF, GLB, VRM, OBJ,
 *  STL, PLY"): for help texts, so they list what the loader reads. */
std::string modelFormatNames();

/** Every file extension loadScene() reads, in the reader table's order (".gltf, .glb, .vrm, .obj, .stl, .ply"): for
 *  usage texts, so a format added to the table is named there too. */
std::string modelFileExtensions();

/** A bounding sphere of every mesh (centre of the bounding box, radius to the farthest vertex), in the scene's local
 *  frame like the positions (add Scene::origin for world coordinates).
 *  Throws SceneError on an empty scene. */
BoundingSphere computeBoundingSphere(const Scene& scene);

} // namespace inkgraph
