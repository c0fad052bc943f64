/** @file make_draco_grid N OUT: writes a Draco mesh (Edgebreaker, positions quantized to 11 bits) of an N x N vertex
 *  grid in the z = 0 plane, 2 (N - 1)^2 triangles, for DecoderBudgetGLTest: a few hundred kilobytes that decode to
 *  millions of triangles. Links Debian's libdraco.a alone (no tinygltf: scene/CMakeLists.txt says why that matters). */

#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: make_draco_grid N OUT\n");
        return 2;
    }
    const int side = std::atoi(argv[1]);
    if (side < 2 || side > 4000) {
        std::fprintf(stderr, "make_draco_grid: N must lie in 2..4000\n");
        return 2;
    }
    draco::Mesh mesh;
    const auto points = static_cast<unsigned>(side * side);
    draco::GeometryAttribute position;
    position.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
    const int attribute = mesh.AddAttribute(position, true, points);
    mesh.set_num_points(points);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const std::array<float, 3> value = {float(x) / float(side - 1), float(y) / float(side - 1), 0.0f};
            mesh.attribute(attribute)->SetAttributeValue(draco::AttributeValueIndex(unsigned(y * side + x)),
                                                         value.data());
        }
    for (int y = 0; y + 1 < side; ++y)
        for (int x = 0; x + 1 < side; ++x) {
            const auto at = [side](int column, int row) { return draco::PointIndex(unsigned(row * side + column)); };
            mesh.AddFace({at(x, y), at(x + 1, y), at(x + 1, y + 1)});
            mesh.AddFace({at(x, y), at(x + 1, y + 1), at(x, y + 1)});
        }
    draco::Encoder encoder;
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 11);
    draco::EncoderBuffer buffer;
    if (const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer); !status.ok()) {
        std::fprintf(stderr, "make_draco_grid: %s\n", status.error_msg());
        return 1;
    }
    std::FILE* out = std::fopen(argv[2], "wb");
    if (out == nullptr || std::fwrite(buffer.data(), 1, buffer.size(), out) != buffer.size() || std::fclose(out) != 0) {
        std::fprintf(stderr, "make_draco_grid: cannot write %s\n", argv[2]);
        return 1;
    }
    return 0;
}
