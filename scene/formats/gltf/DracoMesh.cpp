/** @file decodeDracoMesh() (DracoMesh.h) through libdraco's decoder; every index Draco hands back is checked before it
 *  is used. */

#include "scene/formats/gltf/DracoMesh.h"

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/decode.h>
#include <draco/compression/point_cloud/point_cloud_decoder.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/varint_decoding.h>
#include <draco/mesh/mesh.h>
#include <draco/metadata/geometry_metadata.h>
#include <draco/metadata/metadata_decoder.h>

#include <algorithm>
#include <memory>

namespace inkgraph::detail {
namespace {

/** A count of the connectivity header: a plain 32-bit number before bitstream 2.0 (`plainBefore`), a varint since. */
bool readCount(draco::DecoderBuffer& buffer, std::uint16_t version, std::uint16_t plainBefore, std::uint32_t& count) {
    if (version < plainBefore) return buffer.Decode(&count);
    return draco::DecodeVarint(&count, &buffer);
}

} // namespace

DracoCounts readDracoCounts(const unsigned char* data, std::size_t size) {
    // The header and connectivity counts as Draco's bitstream specification lays them out: "DRACO", version, encoder
    // type and method, flags; the metadata when flagged; then the sequential (faces, points) or Edgebreaker
    // (traversal, [new vertices before 2.2], encoded vertices, faces) counts.
    DracoCounts counts;
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data), size);
    draco::DracoHeader header;
    if (const draco::Status status = draco::PointCloudDecoder::DecodeHeader(&buffer, &header); !status.ok()) {
        counts.error = status.error_msg_string();
        return counts;
    }
    if (header.encoder_type != draco::TRIANGULAR_MESH) {
        counts.error = "the Draco data holds a point cloud, not a triangle mesh";
        return counts;
    }
    const std::uint16_t version = DRACO_BITSTREAM_VERSION(header.version_major, header.version_minor);
    buffer.set_bitstream_version(version);
    if (header.flags & METADATA_FLAG_MASK) {
        draco::MetadataDecoder metadataDecoder;
        draco::GeometryMetadata metadata;
        if (!metadataDecoder.DecodeGeometryMetadata(&buffer, &metadata)) {
            counts.error = "its metadata cannot be read";
            return counts;
        }
    }
    std::uint32_t faces = 0, points = 0;
    bool read = false;
    if (header.encoder_method == draco::MESH_SEQUENTIAL_ENCODING) {
        const std::uint16_t varintsSince = DRACO_BITSTREAM_VERSION(2, 2);
        read = readCount(buffer, version, varintsSince, faces) && readCount(buffer, version, varintsSince, points);
    } else if (header.encoder_method == draco::MESH_EDGEBREAKER_ENCODING) {
        const std::uint16_t varintsSince = DRACO_BITSTREAM_VERSION(2, 0);
        std::uint8_t traversal = 0;
        std::uint32_t newVertices = 0;
        read = buffer.Decode(&traversal) &&
               (version >= DRACO_BITSTREAM_VERSION(2, 2) || readCount(buffer, version, varintsSince, newVertices)) &&
               readCount(buffer, version, varintsSince, points) && readCount(buffer, version, varintsSince, faces);
    } else {
        counts.error = "unknown Draco encoder method " + std::to_string(int(header.encoder_method));
        return counts;
    }
    if (!read) {
        counts.error = "its connectivity header is cut short";
        return counts;
    }
    counts.points = points;
    counts.faces = faces;
    return counts;
}

DracoMesh decodeDracoMesh(const unsigned char* data, std::size_t size,
                          const std::function<void(std::size_t, std::size_t)>& admit) {
    DracoMesh result;
    // The counts are charged before Draco allocates anything of their size: a 550 KB buffer can hold 2M triangles.
    const DracoCounts declared = readDracoCounts(data, size);
    if (!declared.error.empty()) {
        result.error = declared.error;
        return result;
    }
    admit(declared.points, declared.faces);
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
    // Attribute seams split vertices into more points than the connectivity encodes: what goes beyond the header's
    // counts is charged before it is copied out.
    admit(result.pointCount - std::min<std::size_t>(result.pointCount, declared.points),
          std::size_t(mesh->num_faces()) - std::min<std::size_t>(mesh->num_faces(), declared.faces));

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
