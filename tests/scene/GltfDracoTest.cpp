/** @file KHR_draco_mesh_compression: a quad compressed with libdraco's encoder (tests/scene/data/draco-quad.bin, made
 *  by make-draco-quad.cpp there) loads with the positions, texture coordinates and colours put in, and a morph target
 *  moves each decoded point by its own offset; broken Draco data is refused naming the extension. */

#include "scene/Scene.h"
#include "scene/formats/gltf/DracoMesh.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <dlfcn.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <tuple>
#include <vector>

namespace inkgraph {
namespace {

using test::TempFile;

/** The Draco attribute unique ids of tests/scene/data/draco-quad.bin (make-draco-quad.cpp made it). */
struct CompressedQuad {
    std::string bytes;
    std::uint32_t positionId = 0;
    std::uint32_t texcoordId = 1;
    std::uint32_t colorId = 2;
};

/** The quad's corners; its texture coordinates are (x / 2, y / 4) and its colours (255 x, 51 y, 0) / 255. */
constexpr std::array<std::array<float, 3>, 4> kCorners = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}};

CompressedQuad compressedQuad() {
    std::ifstream file(test::sourcePath("tests/scene/data/draco-quad.bin"), std::ios::binary);
    CompressedQuad quad;
    quad.bytes.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
    if (quad.bytes.empty()) throw std::runtime_error("cannot read tests/scene/data/draco-quad.bin");
    return quad;
}

/** A .gltf whose only buffer view is `bytes`, used by a primitive through the extension; the accessors have no
 *  buffer view, as the extension's files have. */
std::string dracoGltf(const std::string& bytes, const CompressedQuad& ids, bool required = true,
                      bool glbBuffer = false) {
    const std::string extensions = std::string("\"extensionsUsed\": [\"KHR_draco_mesh_compression\"]") +
                                   (required ? ", \"extensionsRequired\": [\"KHR_draco_mesh_compression\"]" : "");
    const std::string uri =
        glbBuffer ? "" : "\"uri\": \"data:application/octet-stream;base64," + test::base64(bytes) + "\", ";
    return "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{" + uri +
           "\"byteLength\": " + std::to_string(bytes.size()) +
           "}], \"bufferViews\": [{\"buffer\": 0, \"byteLength\": " + std::to_string(bytes.size()) +
           "}], \"accessors\": ["
           "{\"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\"},"
           "{\"componentType\": 5126, \"count\": 4, \"type\": \"VEC2\"},"
           "{\"componentType\": 5121, \"normalized\": true, \"count\": 4, \"type\": \"VEC3\"},"
           "{\"componentType\": 5123, \"count\": 6, \"type\": \"SCALAR\"}],"
           " \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"TEXCOORD_0\": 1, \"COLOR_0\": 2},"
           " \"indices\": 3, \"extensions\": {\"KHR_draco_mesh_compression\": {\"bufferView\": 0, \"attributes\": "
           "{\"POSITION\": " +
           std::to_string(ids.positionId) + ", \"TEXCOORD_0\": " + std::to_string(ids.texcoordId) +
           ", \"COLOR_0\": " + std::to_string(ids.colorId) +
           "}}}}]}], \"nodes\": [{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}], \"scene\": 0, " + extensions + "}";
}

TEST(GltfDraco, CompressedQuadLoadsWithItsAttributes) {
    const CompressedQuad quad = compressedQuad();
    const TempFile file("draco.gltf", dracoGltf(quad.bytes, quad));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    EXPECT_EQ(mesh.triangleCount(), 2u);
    ASSERT_EQ(mesh.positions.size(), 4u);
    ASSERT_EQ(mesh.texcoords[0].size(), 4u);
    ASSERT_EQ(mesh.colors.size(), 4u);
    for (const auto& corner : kCorners) {
        const glm::dvec3 expected(corner[0], corner[1], corner[2]);
        std::size_t found = mesh.positions.size();
        for (std::size_t i = 0; i < mesh.positions.size(); ++i)
            if (glm::length(test::worldPosition(scene, mesh.positions[i]) - expected) < 1e-6) found = i;
        ASSERT_LT(found, mesh.positions.size()) << "corner " << corner[0] << ", " << corner[1];
        EXPECT_EQ(mesh.texcoords[0][found], glm::vec2(corner[0] / 2, corner[1] / 4));
        EXPECT_EQ(mesh.colors[found], glm::vec4(corner[0], 0.2f * corner[1], 0, 1));
    }
    // Counter-clockwise seen from +Z, as the faces were given.
    for (const glm::uvec3& triangle : mesh.triangles) EXPECT_GT(test::triangleCross(mesh, triangle).z, 0.0);
}

/** The quad with one morph target at `weight`, its POSITION offsets `offsets` (one per decoded point, in Draco's
 *  order) as a plain accessor in a second buffer, as the extension's files carry targets. */
std::string dracoGltfWithMorphTarget(const CompressedQuad& quad, const std::vector<glm::vec3>& offsets,
                                     const std::string& weight) {
    std::string json = dracoGltf(quad.bytes, quad);
    const auto replace = [&](const std::string& from, const std::string& to) {
        const std::size_t at = json.find(from);
        if (at == std::string::npos) throw std::runtime_error("dracoGltf() changed: no '" + from + "'");
        json.replace(at, from.size(), to);
    };
    const std::string bytes(reinterpret_cast<const char*>(offsets.data()), offsets.size() * sizeof(glm::vec3));
    const std::string length = std::to_string(bytes.size());
    replace("\"buffers\": [{", "\"buffers\": [{\"uri\": \"data:application/octet-stream;base64," + test::base64(bytes) +
                                   "\", \"byteLength\": " + length + "}, {");
    replace("\"bufferViews\": [{\"buffer\": 0,",
            "\"bufferViews\": [{\"buffer\": 0, \"byteLength\": " + length + "}, {\"buffer\": 1,");
    replace("\"extensions\": {\"KHR_draco_mesh_compression\": {\"bufferView\": 0,",
            "\"extensions\": {\"KHR_draco_mesh_compression\": {\"bufferView\": 1,");
    replace("\"type\": \"SCALAR\"}]",
            "\"type\": \"SCALAR\"}, {\"bufferView\": 0, \"componentType\": 5126, \"count\": " +
                std::to_string(offsets.size()) + ", \"type\": \"VEC3\"}]");
    replace("\"indices\": 3,", "\"indices\": 3, \"targets\": [{\"POSITION\": 4}],");
    replace("\"meshes\": [{", "\"meshes\": [{\"weights\": [" + weight + "], ");
    return json;
}

/** The decoded quad's points in Draco's order, as a generator following the extension's implementation note reads
 *  them back to write the uncompressed data (here the morph target) in that order. */
std::vector<glm::vec3> decodedPoints(const CompressedQuad& quad) {
    const detail::DracoMesh mesh = detail::decodeDracoMesh(reinterpret_cast<const unsigned char*>(quad.bytes.data()),
                                                           quad.bytes.size(), [](std::size_t, std::size_t) {});
    EXPECT_EQ(mesh.error, "");
    const std::vector<float>& values = mesh.attributes.at(quad.positionId).values;
    std::vector<glm::vec3> points;
    for (std::size_t i = 0; i + 2 < values.size(); i += 3) points.emplace_back(values[i], values[i + 1], values[i + 2]);
    return points;
}

TEST(GltfDraco, MorphTargetOfACompressedPrimitiveMovesEachDecodedPoint) {
    const CompressedQuad quad = compressedQuad();
    const std::vector<glm::vec3> points = decodedPoints(quad);
    ASSERT_EQ(points.size(), 4u);
    // Each point's offset depends on where it is, so a target applied in any other order puts some corner wrong:
    // corner (x, y, 0) moves by (0, 0, x + 2y + 1), which weight 0.5 halves.
    std::vector<glm::vec3> offsets;
    for (const glm::vec3& p : points) offsets.emplace_back(0.0f, 0.0f, p.x + 2.0f * p.y + 1.0f);
    const TempFile weighted("draco-morph.gltf", dracoGltfWithMorphTarget(quad, offsets, "0.5"));
    const Scene scene = loadScene(weighted.path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    ASSERT_EQ(mesh.positions.size(), 4u);
    for (const auto& corner : kCorners) {
        const glm::dvec3 expected(corner[0], corner[1], 0.5 * (corner[0] + 2.0 * corner[1] + 1.0));
        std::size_t found = 0;
        for (const glm::vec3& p : mesh.positions)
            if (glm::length(test::worldPosition(scene, p) - expected) < 1e-6) ++found;
        EXPECT_EQ(found, 1u) << "corner " << corner[0] << ", " << corner[1] << " not at z " << expected.z;
    }
    // At weight 0 the quad stays flat.
    const TempFile rest("draco-morph-rest.gltf", dracoGltfWithMorphTarget(quad, offsets, "0"));
    const Scene flat = loadScene(rest.path());
    for (const glm::vec3& p : flat.meshes[0].positions) EXPECT_EQ(test::worldPosition(flat, p).z, 0.0);
}

TEST(GltfDraco, MorphTargetCountingOtherThanTheDecodedPointsIsRefused) {
    const CompressedQuad quad = compressedQuad();
    const TempFile file("draco-morph-short.gltf",
                        dracoGltfWithMorphTarget(quad, std::vector<glm::vec3>(3, glm::vec3(0, 0, 1)), "1"));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("morph target 0 POSITION has 3 elements but POSITION has 4"), std::string::npos) << message;
}

TEST(GltfDraco, CompressedQuadLoadsFromAGlb) {
    const CompressedQuad quad = compressedQuad();
    const TempFile file("draco.glb", test::glb(dracoGltf(quad.bytes, quad, true, true), quad.bytes));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].triangleCount(), 2u);
    EXPECT_EQ(scene.meshes[0].colors.size(), 4u);
    EXPECT_EQ(scene.report.format, "glb");
}

TEST(GltfDraco, UndecodableDataIsRefusedNamingTheExtension) {
    const CompressedQuad quad = compressedQuad();
    std::string broken = quad.bytes.substr(0, quad.bytes.size() / 2);
    const TempFile file("draco-broken.gltf", dracoGltf(broken, quad));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("KHR_draco_mesh_compression: Draco cannot decode buffer view 0"), std::string::npos)
        << message;
}

TEST(GltfDraco, AttributeIdMissingFromTheDataIsRefused) {
    CompressedQuad quad = compressedQuad();
    quad.texcoordId = 77;
    const TempFile file("draco-bad-id.gltf", dracoGltf(quad.bytes, quad, false));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("KHR_draco_mesh_compression: attribute 'TEXCOORD_0': the Draco data has no attribute "
                           "with id 77"),
              std::string::npos)
        << message;
}

/** Debian's libdraco carries its own tinygltf (another version); linked wrongly (CMakeLists.txt says how), it replaces
 *  Debian's in the executable and loading crashes. The reader's tinygltf must be libtinygltf.so's. */
TEST(GltfDraco, TinygltfComesFromItsOwnLibrary) {
    Dl_info info{};
    ASSERT_NE(dladdr(reinterpret_cast<void*>(&tinygltf::ReadWholeFile), &info), 0);
    ASSERT_NE(info.dli_fname, nullptr);
    EXPECT_NE(std::string(info.dli_fname).find("libtinygltf"), std::string::npos) << info.dli_fname;
}

} // namespace
} // namespace inkgraph
