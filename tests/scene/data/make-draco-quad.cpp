/** @file Writes draco-quad.bin, the Draco mesh GltfDracoTest loads: a unit quad (corners (0,0,0), (1,0,0), (1,1,0),
 *  (0,1,0); faces 0-1-2 and 0-2-3) with TEXCOORD (x / 2, y / 4) as float and COLOR (255 x, 51 y, 0) as normalized
 *  unsigned bytes; attribute unique ids 0 (position), 1 (texture coordinates), 2 (colour). Not part of the build:
 *    g++ -std=c++20 tests/scene/data/make-draco-quad.cpp -ldraco -o /tmp/make-draco-quad &&
 *    /tmp/make-draco-quad > tests/scene/data/draco-quad.bin
 *  (Debian's libdraco-dev 1.5.5; no quantization, so the floats come back exactly.) */

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include <array>
#include <cstdint>
#include <cstdio>

int main() {
    constexpr std::array<std::array<float, 3>, 4> corners = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
    std::array<std::array<float, 2>, 4> uvs{};
    std::array<std::array<std::uint8_t, 3>, 4> colors{};
    for (std::size_t i = 0; i < 4; ++i) {
        uvs[i] = {corners[i][0] / 2, corners[i][1] / 4};
        colors[i] = {std::uint8_t(255 * corners[i][0]), std::uint8_t(51 * corners[i][1]), 0};
    }
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(2);
    const int position = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int texcoord = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    const int color = builder.AddAttribute(draco::GeometryAttribute::COLOR, 3, draco::DT_UINT8, true);
    constexpr std::array<std::array<int, 3>, 2> faces = {{{0, 1, 2}, {0, 2, 3}}};
    for (int face = 0; face < 2; ++face) {
        const auto& c = faces[std::size_t(face)];
        builder.SetAttributeValuesForFace(position, draco::FaceIndex(face), corners[c[0]].data(), corners[c[1]].data(),
                                          corners[c[2]].data());
        builder.SetAttributeValuesForFace(texcoord, draco::FaceIndex(face), uvs[c[0]].data(), uvs[c[1]].data(),
                                          uvs[c[2]].data());
        builder.SetAttributeValuesForFace(color, draco::FaceIndex(face), colors[c[0]].data(), colors[c[1]].data(),
                                          colors[c[2]].data());
    }
    const auto mesh = builder.Finalize();
    if (!mesh || mesh->attribute(position)->unique_id() != 0 || mesh->attribute(texcoord)->unique_id() != 1 ||
        mesh->attribute(color)->unique_id() != 2) {
        std::fprintf(stderr, "make-draco-quad: unexpected mesh or attribute ids\n");
        return 1;
    }
    draco::Encoder encoder;
    draco::EncoderBuffer buffer;
    if (!encoder.EncodeMeshToBuffer(*mesh, &buffer).ok()) {
        std::fprintf(stderr, "make-draco-quad: encoding failed\n");
        return 1;
    }
    std::fwrite(buffer.data(), 1, buffer.size(), stdout);
    return 0;
}
