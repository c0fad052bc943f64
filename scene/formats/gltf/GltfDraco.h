#pragma once
/** @file KHR_draco_mesh_compression: a glTF primitive's Draco-compressed geometry decoded through Debian's libdraco,
 *  checked as every other glTF read is (tinygltf's own Draco path trusts the file's indices and offsets, so it is not
 *  compiled in). Internal to the scene layer. */

#include "scene/formats/FormatReaders.h"

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
struct Primitive;
} // namespace tinygltf

namespace inkgraph::detail {

/** The extension's name, as files write it in extensionsUsed/Required and on primitives. */
inline constexpr const char* kDracoExtension = "KHR_draco_mesh_compression";

/** One primitive's decoded geometry: what its accessors would have held. */
struct DracoPrimitive {
    std::size_t vertexCount = 0;
    std::vector<std::uint32_t> indices; ///< three per triangle, each below vertexCount
    /** Per glTF attribute name the extension maps ("POSITION", "TEXCOORD_0", ...): componentsOf(accessor type) floats
     *  per vertex, normalized integers converted by glTF's rule as readAccessorFloats() does. */
    std::map<std::string, std::vector<float>> attributes;
};

/** Whether `primitive` carries the extension. */
bool hasDracoCompression(const tinygltf::Primitive& primitive);

/** Decodes the primitive's Draco buffer view. The decoded counts are charged to `budget` before the geometry is
 *  copied out. Throws SceneError through throwLoadError(path, "<label>: KHR_draco_mesh_compression: ...") for a
 *  malformed extension object, a buffer view out of range, data Draco cannot decode, a missing attribute or one whose
 *  component count differs from its accessor's. */
DracoPrimitive decodeDracoPrimitive(const std::string& path, const tinygltf::Model& model,
                                    const tinygltf::Primitive& primitive, const std::string& label, MeshBudget& budget);

} // namespace inkgraph::detail
