/** @file KHR_draco_mesh_compression decoding (GltfDraco.h). The extension object names a buffer view holding a Draco
 *  mesh and, per glTF attribute, the Draco attribute's unique id; the primitive's accessors keep their type, component
 *  type and normalization but have no data of their own. */

#include "scene/formats/gltf/GltfDraco.h"

#include "scene/formats/gltf/DracoMesh.h"
#include "scene/formats/gltf/GltfAccessors.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>

namespace inkgraph::detail {

namespace {

/** glTF's rule for a normalized integer component (as GltfAccessors.cpp applies it), for values Draco hands back as
 *  plain integers. */
float normalizedValue(float value, int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return std::max(value / 127.0f, -1.0f);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return value / 255.0f;
    case TINYGLTF_COMPONENT_TYPE_SHORT: return std::max(value / 32767.0f, -1.0f);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return value / 65535.0f;
    default: return value;
    }
}

} // namespace

bool hasDracoCompression(const tinygltf::Primitive& primitive) {
    return primitive.extensions.count(kDracoExtension) > 0;
}

DracoPrimitive decodeDracoPrimitive(const std::string& path, const tinygltf::Model& model,
                                    const tinygltf::Primitive& primitive, const std::string& label,
                                    MeshBudget& budget) {
    const std::string where = label + ": " + kDracoExtension;
    const auto fail = [&](const std::string& problem) { throwLoadError(path, where + ": " + problem); };
    const tinygltf::Value& extension = primitive.extensions.at(kDracoExtension);
    if (!extension.IsObject() || !extension.Has("bufferView") || !extension.Get("bufferView").IsInt() ||
        !extension.Has("attributes") || !extension.Get("attributes").IsObject()) {
        fail("needs an integer 'bufferView' and an 'attributes' object");
    }
    const int viewIndex = extension.Get("bufferView").GetNumberAsInt();
    if (viewIndex < 0 || std::size_t(viewIndex) >= model.bufferViews.size()) {
        fail("buffer view " + std::to_string(viewIndex) + " out of range (file has " +
             std::to_string(model.bufferViews.size()) + " buffer views)");
    }
    const tinygltf::BufferView& view = model.bufferViews[std::size_t(viewIndex)];
    if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size()) {
        fail("buffer view " + std::to_string(viewIndex) + " has an out-of-range buffer");
    }
    const std::vector<unsigned char>& buffer = model.buffers[std::size_t(view.buffer)].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
        fail("buffer view " + std::to_string(viewIndex) + " (offset " + std::to_string(view.byteOffset) + ", length " +
             std::to_string(view.byteLength) + ") exceeds its buffer of " + std::to_string(buffer.size()) + " bytes");
    }

    const DracoMesh decoded =
        decodeDracoMesh(buffer.data() + view.byteOffset, view.byteLength,
                        [&](std::size_t points, std::size_t faces) { budget.charge(points, faces); });
    if (!decoded.error.empty()) {
        fail("Draco cannot decode buffer view " + std::to_string(viewIndex) + " (" + excerptForMessage(decoded.error) +
             ")");
    }

    DracoPrimitive result;
    result.vertexCount = decoded.pointCount;
    result.indices = decoded.indices;
    for (const auto& [name, idValue] : extension.Get("attributes").Get<tinygltf::Value::Object>()) {
        const std::string attribute = excerptForMessage(name);
        const auto accessorEntry = primitive.attributes.find(name);
        if (accessorEntry == primitive.attributes.end()) {
            fail("attribute '" + attribute + "' is compressed but not among the primitive's attributes");
        }
        if (!idValue.IsInt()) {
            fail("attribute '" + attribute + "' must map to an integer Draco attribute id");
        }
        const int accessorIndex = accessorEntry->second;
        if (accessorIndex < 0 || std::size_t(accessorIndex) >= model.accessors.size()) {
            fail("attribute '" + attribute + "': accessor index " + std::to_string(accessorIndex) + " out of range");
        }
        const tinygltf::Accessor& accessor = model.accessors[std::size_t(accessorIndex)];
        const int components = componentsOf(accessor.type);
        const int id = idValue.GetNumberAsInt();
        const auto source = id < 0 ? decoded.attributes.end() : decoded.attributes.find(std::uint32_t(id));
        if (source == decoded.attributes.end()) {
            fail("attribute '" + attribute + "': the Draco data has no attribute with id " + std::to_string(id));
        }
        if (components == 0 || source->second.components != components) {
            fail("attribute '" + attribute + "' has " + std::to_string(source->second.components) +
                 " components in the Draco data but " + std::to_string(components) + " in accessor " +
                 std::to_string(accessorIndex));
        }
        // Draco converts its own normalized integers; integers it stores plain take glTF's rule when the accessor
        // says they are normalized.
        const bool normalizeHere = accessor.normalized && !source->second.normalized;
        std::vector<float> values = source->second.values;
        for (std::size_t i = 0; i < values.size(); ++i) {
            if (normalizeHere) values[i] = normalizedValue(values[i], accessor.componentType);
            if (!std::isfinite(values[i])) {
                fail("attribute '" + attribute + "' point " + std::to_string(i / std::size_t(components)) +
                     ": non-finite value");
            }
        }
        result.attributes.emplace(name, std::move(values));
    }
    if (result.attributes.count("POSITION") == 0) {
        fail("POSITION is not among the compressed attributes");
    }
    return result;
}

} // namespace inkgraph::detail
