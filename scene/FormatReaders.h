#pragma once
/** @file The per-format readers behind loadScene() and the error helpers they share. Internal to the scene layer:
 *  readers produce raw (unwelded) meshes; loadScene() cleans them up with finalizeMesh(). */

#include "scene/MeshOps.h"
#include "scene/Scene.h"

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace inkgraph::detail {

/** Everything a reader found in one file, before welding. */
struct RawScene {
    std::string format; ///< as in LoadReport::format
    std::vector<RawMesh> meshes;
    std::optional<SceneCamera> camera;
    std::optional<DirectionalLight> light;
    std::vector<std::string> warnings;
};

/** The memory bound of one load (LoadOptions::memoryLimitBytes), checked before anything of a counted size is
 *  allocated. The estimate is the file's own bytes plus a fixed cost per vertex and per triangle that covers the
 *  reader's copy, welding, the finished mesh and its GPU upload (scene/README.md gives the measured peak). */
class MeshBudget {
public:
    static constexpr std::size_t kBytesPerVertex = 96;
    static constexpr std::size_t kBytesPerTriangle = 64;

    MeshBudget(const std::string& path, std::size_t limitBytes) : mPath(path), mLimitBytes(limitBytes) {}

    /** A file's bytes, held in memory while it is read (called once per file: glTF's external buffers add theirs).
     *  Throws SceneError naming the file above the limit. */
    void chargeFile(std::size_t bytes);
    /** Throws SceneError naming the file when what is charged so far plus these counts exceeds the limit. */
    void check(std::size_t vertices, std::size_t triangles) const;
    /** check(), then counts them for good (one glTF mesh may be instanced by many nodes). */
    void charge(std::size_t vertices, std::size_t triangles);

    std::size_t limitBytes() const { return mLimitBytes; }

private:
    std::size_t estimate(std::size_t vertices, std::size_t triangles) const;

    std::string mPath;
    std::size_t mLimitBytes;
    std::size_t mFileBytes = 0;
    std::size_t mVertices = 0;
    std::size_t mTriangles = 0;
};

/** Throws SceneError("loadScene(): '<path>': <problem>"). */
[[noreturn]] void throwLoadError(const std::string& path, std::string_view problem);

/** Throws SceneError("loadScene(): '<path>' line <line>: <problem>"). */
[[noreturn]] void throwLoadErrorAtLine(const std::string& path, std::size_t line, std::string_view problem);

/** Wavefront OBJ from the whole file's text. */
RawScene readObj(const std::string& path, std::string_view content, MeshBudget& budget);

/** STL, binary or ASCII (decided from the content), from the whole file's bytes. */
RawScene readStl(const std::string& path, std::string_view content, MeshBudget& budget);

/** glTF 2.0 or GLB (the content starts with the "glTF" magic) through tinygltf, from the whole file's bytes;
 *  external buffers are resolved next to `path`. */
RawScene readGltf(const std::string& path, std::string_view content, MeshBudget& budget);

} // namespace inkgraph::detail
