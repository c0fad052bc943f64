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

/** Throws SceneError("loadScene(): '<path>': <problem>"). */
[[noreturn]] void throwLoadError(const std::string& path, std::string_view problem);

/** Throws SceneError("loadScene(): '<path>' line <line>: <problem>"). */
[[noreturn]] void throwLoadErrorAtLine(const std::string& path, std::size_t line, std::string_view problem);

/** Wavefront OBJ from the whole file's text. */
RawScene readObj(const std::string& path, std::string_view content);

/** STL, binary or ASCII (decided from the content), from the whole file's bytes. */
RawScene readStl(const std::string& path, std::string_view content);

/** glTF 2.0 through tinygltf: `binary` selects the GLB container (the file starts with the "glTF" magic). */
RawScene readGltf(const std::string& path, bool binary);

} // namespace inkgraph::detail
