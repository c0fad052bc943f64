/** @file decodeDracoMesh() (DracoMesh.h) through libdraco's decoder; every index Draco hands back is checked before it
 *  is used. */

#include "scene/DracoMesh.h"

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <draco/mesh/mesh.h>

#include <memory>

namespace inkgraph::detail {

DracoMesh decodeDracoMesh(const unsigned char* data, std::size_t size,
                          const std::function<void(std::size_t, std::size_t)>& admit) {
    DracoMesh result;
    draco::DecoderBuffer input;
    input.Init(reinterpret_cast<const char*>(data), size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&input);
    if (!decoded.ok()) {
        result.error = decoded.status().error_msg_string();
        return result;
    }
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (!mesh) {
        result.error = "no mesh decoded";
        return result;
    }
    result.pointCount = mesh->num_points();
    admit(result.pointCount, mesh->num_faces());

    result.indices.reserve(std::size_t(mesh->num_faces()) * 3);
    for (draco::FaceIndex face(0); face < mesh->num_faces(); ++face) {
        for (int corner = 0; corner < 3; ++corner) {
            const std::uint32_t index = mesh->face(face)[corner].value();
            if (index >= result.pointCount) {
                result.error = "face " + std::to_string(face.value()) + " names point " + std::to_string(index) +
                               " of " + std::to_string(result.pointCount);
                return result;
            }
            result.indices.push_back(index);
        }
    }
    for (int a = 0; a < mesh->num_attributes(); ++a) {
        const draco::PointAttribute* source = mesh->attribute(a);
        if (source == nullptr || source->num_components() == 0) continue;
        DracoMesh::Attribute attribute;
        attribute.components = source->num_components();
        attribute.normalized = source->normalized();
        attribute.values.resize(result.pointCount * std::size_t(attribute.components));
        for (draco::PointIndex point(0); point < result.pointCount; ++point) {
            const draco::AttributeValueIndex entry = source->mapped_index(point);
            float* out = attribute.values.data() + std::size_t(point.value()) * std::size_t(attribute.components);
            if (entry.value() >= source->size() || !source->ConvertValue<float>(entry, source->num_components(), out)) {
                result.error = "attribute " + std::to_string(source->unique_id()) + ": cannot read point " +
                               std::to_string(point.value());
                return result;
            }
        }
        result.attributes.emplace(source->unique_id(), std::move(attribute));
    }
    return result;
}

} // namespace inkgraph::detail
