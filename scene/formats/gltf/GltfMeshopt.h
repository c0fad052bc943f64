#pragma once
/** @file EXT_meshopt_compression (gltfpack's output): buffer views compressed by meshoptimizer's codecs, decoded
 *  through Debian's libmeshoptimizer into plain bytes before any accessor is read, so accessors, sparse data,
 *  animations and images read them as they read any buffer view. Every size, offset and count the extension declares
 *  is checked against the buffers before the library sees it. Internal to the scene layer. */

#include "scene/formats/FormatReaders.h"

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace inkgraph::detail {

/** The extension's name, as files write it in extensionsUsed/Required, on buffer views and on fallback buffers. */
inline constexpr const char* kMeshoptExtension = "EXT_meshopt_compression";

/** Gives every placeholder buffer of `document` (a glTF's JSON) one byte of data in place of none: a buffer the
 *  extension marks `fallback`, or one without a URI that is not a GLB's binary chunk (index 0 of a GLB). Such a buffer
 *  declares the size of the uncompressed data but holds none, and tinygltf refuses it ("invalid GLB: byteLength" or a
 *  missing URI); only compressed views may use it, and they are decoded into buffers of their own. Returns the
 *  placeholders' indices (none when the file does not use the extension). */
std::vector<std::size_t> stubMeshoptPlaceholders(nlohmann::json& document, bool binary);

/** Decodes every buffer view carrying the extension into a buffer of its own appended to `model.buffers`, and points
 *  the view at it; the decoded bytes are charged to `budget` first. Throws SceneError through
 *  throwLoadError(path, "buffer view <n>: EXT_meshopt_compression: ...") for a malformed extension object, sizes that
 *  disagree or leave their buffer, an unknown mode or filter, data the library cannot decode, and for an uncompressed
 *  view of a placeholder buffer (`placeholders`, stubMeshoptPlaceholders()). */
void decodeMeshoptBufferViews(const std::string& path, tinygltf::Model& model,
                              const std::vector<std::size_t>& placeholders, MeshBudget& budget);

} // namespace inkgraph::detail
