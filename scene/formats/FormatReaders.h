#pragma once
/** @file The per-format readers behind loadScene() and the error helpers they share. Internal to the scene layer:
 *  readers produce raw (unwelded) meshes; loadScene() cleans them up with finalizeScene(). sceneFromArrays()
 *  (scene/MeshArrays.h) builds its raw mesh from memory and shares the rest; it passes its own name as `function`, the
 *  name every message of these helpers starts with. */

#include "scene/MessageText.h"
#include "scene/Scene.h"
#include "scene/mesh/MeshOps.h"
#include "scene/mesh/PolygonTriangulation.h"

#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace inkgraph::detail {

/** Everything a reader found in one file, before welding. */
struct RawScene {
    std::string format; ///< as in LoadReport::format
    /** Mesh positions are stored relative to this point (world = origin + position), picked by the reader near the
     *  model (e.g. its first vertex, computed in double) so that float keeps the model's detail even when the file
     *  places it far from the world origin. loadScene() then re-centres on the bounding-box centre (Scene::origin). */
    glm::dvec3 origin{0.0};
    std::vector<RawMesh> meshes;
    std::optional<SceneCamera> camera; ///< its eye relative to `origin`, like the positions
    std::optional<DirectionalLight> light;
    std::optional<glm::dvec3> front;       ///< as Scene::front
    std::vector<SceneImage> images;        ///< as Scene::images
    std::vector<SceneImage> missingImages; ///< as LoadReport::missingImages
    std::vector<SceneJoint> joints;        ///< as Scene::joints, their boxes relative to `origin`
    std::vector<Warning> warnings;         ///< `file` empty for the model: loadScene() names it
    std::vector<std::string> inputFiles;   ///< as LoadReport::inputFiles
};

/** `bytes` for a message: "N MiB" from 1 MiB up (rounded down), else "N KiB" or "N bytes" (a limit of a few bytes,
 *  which a library caller can set, read "0 MiB"). */
std::string memoryText(std::size_t bytes);

/** The memory bound of one load (LoadOptions::memoryLimitBytes), checked before anything of a counted size is
 *  allocated. The estimate is the file's own bytes plus a fixed cost per vertex and per triangle that covers the
 *  reader's copy, welding, the finished mesh and its GPU upload (scene/README.md gives the measured peak). */
class MeshBudget {
public:
    static constexpr std::size_t kBytesPerVertex = 96;
    static constexpr std::size_t kBytesPerTriangle = 64;

    /** `function` starts the messages, `limitName` says where the limit is set. */
    MeshBudget(const std::string& path, std::size_t limitBytes, std::string_view function = "loadScene()",
               std::string_view limitName = "--memory-limit")
        : mPath(path), mLimitBytes(limitBytes), mFunction(function), mLimitName(limitName) {}

    /** A file's bytes, held in memory while it is read (called once per file: glTF's external buffers add theirs).
     *  Throws SceneError naming the file above the limit. */
    void chargeFile(std::size_t bytes);
    /** Throws SceneError naming the file when what is charged so far plus these counts exceeds the limit. */
    void check(std::size_t vertices, std::size_t triangles) const;
    /** Throws SceneError naming the file and `what` ("skin 0 inverseBindMatrices") when what is charged so far plus
     *  `bytes` a reader holds for a while (a skin's matrices, an animation's keyframes) exceeds the limit. */
    void checkBytes(std::size_t bytes, std::string_view what) const;
    /** check(), then counts them for good (one glTF mesh may be instanced by many nodes). */
    void charge(std::size_t vertices, std::size_t triangles);
    /** Other memory a reader keeps that grows with the file's declarations (`what`: each mesh's node path, decoded
     *  buffers), counted for good; throws SceneError naming the file above the limit. */
    void chargeBytes(std::size_t bytes, std::string_view what = "the meshes' node paths");

    std::size_t limitBytes() const { return mLimitBytes; }

private:
    std::size_t estimate(std::size_t vertices, std::size_t triangles) const;

    std::string mPath;
    std::size_t mLimitBytes;
    std::string mFunction;
    std::string mLimitName;
    std::size_t mFileBytes = 0;
    std::size_t mOtherBytes = 0; ///< chargeBytes()
    std::size_t mVertices = 0;
    std::size_t mTriangles = 0;
};

/** Throws SceneError naming the file when a model's extent (bounding-box diagonal) lies outside [kMinModelExtent,
 *  kMaxModelExtent]; zero passes (a model of degenerate triangles is reported as such later). */
void checkModelExtent(const std::string& path, double extent, std::string_view function = "loadScene()");

/** Float positions for coordinates read in double: rounded directly (origin 0) when the model is about as large as
 *  its distance from the world origin, where that loses nothing and keeps every float the file wrote exact (scaling
 *  such a model by a power of two scales its stored positions exactly); otherwise relative to the bounding-box centre,
 *  the difference taken in double, so a model 1e7 units out keeps its detail. Returns the origin they are relative
 *  to. Throws (checkModelExtent()) for a model too large to render. */
glm::dvec3 storeNearModel(const std::string& path, std::span<const glm::dvec3> world, std::vector<glm::vec3>& stored,
                          std::string_view function = "loadScene()");

/** The warning for the polygons `triangulator` could only fan (PolygonShape::Unresolved); call when there are any. */
Warning polygonsFannedWarning(const PolygonTriangulator& triangulator);

/** Throws SceneError("<function>: '<path>': <problem>"). */
[[noreturn]] void throwLoadError(const std::string& path, std::string_view problem,
                                 std::string_view function = "loadScene()");

/** "no triangles in the file", and what the load warned that says why (a primitive skipped for lacking POSITION, a
 *  mesh whose triangles were all degenerate): the first three messages, and how many more. */
std::string noTrianglesInTheFile(const std::vector<Warning>& warnings);

/** Throws std::invalid_argument("<function>: ...") for a weld tolerance or a time that is not finite and >= 0. */
void checkLoadOptions(const LoadOptions& options, std::string_view function = "loadScene()");

/** What a reader found made into the Scene every load returns: re-centred on the model's bounding-box centre
 *  (Scene::origin; checkModelExtent()), each mesh cleaned up by finalizeMesh() against the whole model's size, meshes
 *  left without triangles skipped with a warning. Throws SceneError naming `path` when no triangle is left. */
Scene finalizeScene(const std::string& path, RawScene raw, const LoadOptions& options,
                    std::string_view function = "loadScene()");

/** Throws SceneError("loadScene(): '<path>' line <line>: <problem>"). */
[[noreturn]] void throwLoadErrorAtLine(const std::string& path, std::size_t line, std::string_view problem);

/** A regular file's bytes for a referencedFiles() entry of the format table: best effort, what could be read, nothing
 *  thrown. */
std::string wholeFileBestEffort(const std::string& path);

/** What an OBJ's material libraries define, gathered by readMtl() over every `mtllib` file of one load. */
struct ObjMaterials {
    std::map<std::string, Material> byName; ///< `newmtl` name -> material; the first definition of a name wins
    std::vector<SceneImage> images;         ///< what the materials' textures index (RawScene::images)
    std::vector<std::string> namedFiles;    ///< every texture file named (map_Kd, map_d), resolved, found or not
    std::vector<SceneImage> missingImages;  ///< the maps not found (name as written, resolved path), once per file
};

/** Reads one material library's text into `materials`: Kd, d/Tr, Ke, map_Kd (options skipped but -clamp, -s and -o)
 *  and a map_d cut-out; texture names are resolved beside `path`. Bad lines, missing textures and unsupported
 *  statements become warnings naming the library and the line; nothing is thrown. */
void readMtl(const std::string& path, std::string_view content, ObjMaterials& materials, std::vector<Warning>& warnings,
             const std::filesystem::path& modelFolder);

/** A file an OBJ or a material library names (mtllib, map_Kd, map_d), resolved beside it as exporters write names: as
 *  written (relative to `folder`, or absolute); else with Windows' '\' as '/' and without surrounding quotes; else,
 *  for a path that leads elsewhere ("C:\Users\me\tex\skin.png" of the exporting machine), the file of its last name
 *  beside it, or for a library's texture the path or the last name beside the model (`modelFolder`, when the library
 *  lies in a folder of its own); else, for a name from Windows whose case differs from the file's
 *  ("Textures/Skin.PNG"), the one file that differs in ASCII case alone (a folder's first 10,000 entries searched), in
 *  those places. The name as written (slashed when it had '\') when none of these exists, for the message
 *  (whyFileIsMissing() tells more). */
std::string fileBeside(const std::filesystem::path& folder, const std::string& name,
                       const std::optional<std::filesystem::path>& modelFolder = std::nullopt);

/** What to say of a file fileBeside() gave and no file is at, when more is known than that it is missing: a folder
 *  on its way cannot be read ("cannot be looked for: the folder '<folder>' cannot be read (Permission denied)"), or
 *  holds several names that differ from the path's in case alone, none of which fileBeside() takes ("cannot be found:
 *  the folder '<folder>' holds 'TEX.png' and 'tex.png', which differ from its name in case alone: rename the one meant
 *  to 'Tex.png'"). Nothing when the file is simply missing (or there). */
std::optional<std::string> whyFileIsMissing(const std::string& path);

/** The texture files a material library's map_Kd and map_d lines name, resolved as readMtl() resolves them. */
std::vector<std::string> mtlReferencedFiles(const std::string& path, std::string_view content,
                                            const std::filesystem::path& modelFolder);

} // namespace inkgraph::detail
