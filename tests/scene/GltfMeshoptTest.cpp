/** @file EXT_meshopt_compression: files built here by ENCODING a known cube with libmeshoptimizer's encoders (every
 *  mode, every filter) load with the cube's positions, normals, texture coordinates, indices and an animated rotation,
 *  within each filter's quantization; gltfpack's BoxMeshopt.glb (tests/scene/data) loads as the unit cube; hostile
 *  extension objects and streams are refused naming the file, the buffer view and what is wrong. */

#include "scene/Scene.h"

#include "SceneTestSupport.h"

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using nlohmann::json;

/** The cube [-1,1]^3: 8 corners, each with the unit normal pointing at it and texture coordinates (x, y) / 4 + 1/2
 *  (exact in float), 12 counter-clockwise triangles. */
struct SourceCube {
    std::vector<glm::vec3> positions = test::cubeCorners();
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> texcoords;
    std::vector<std::uint32_t> indices;

    SourceCube() {
        for (const glm::vec3& p : positions) {
            normals.push_back(glm::normalize(p));
            texcoords.emplace_back(p.x / 4 + 0.5f, p.y / 4 + 0.5f);
        }
        for (const glm::uvec4& quad : test::cubeQuads()) {
            for (const std::uint32_t corner : {quad.x, quad.y, quad.z, quad.x, quad.z, quad.w})
                indices.push_back(corner - 1);
        }
    }
};

/** A glTF document whose buffer 0 holds meshopt-compressed streams and buffer 1 is the placeholder the decoded views
 *  nominally live in (no data, marked `fallback`), as gltfpack writes them. */
class MeshoptFile {
public:
    json document = {{"asset", {{"version", "2.0"}}},
                     {"extensionsUsed", {"EXT_meshopt_compression"}},
                     {"extensionsRequired", {"EXT_meshopt_compression"}},
                     {"bufferViews", json::array()},
                     {"accessors", json::array()}};
    std::string compressed; ///< buffer 0

    /** A view of `count` elements of `stride` bytes compressed from `raw` in `mode` (ATTRIBUTES, TRIANGLES, INDICES)
     *  with `filter`; returns its index. */
    int addView(const std::string& raw, std::size_t count, std::size_t stride, const std::string& mode,
                const std::string& filter = "NONE", bool strideOnView = true) {
        EXPECT_EQ(raw.size(), count * stride);
        std::vector<unsigned char> encoded;
        if (mode == "ATTRIBUTES") {
            encoded.resize(meshopt_encodeVertexBufferBound(count, stride));
            encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), raw.data(), count, stride));
        } else {
            std::vector<std::uint32_t> indices(count);
            for (std::size_t i = 0; i < count; ++i) {
                std::uint32_t value = 0;
                std::memcpy(&value, raw.data() + i * stride, stride);
                indices[i] = value;
            }
            const std::size_t vertices = *std::max_element(indices.begin(), indices.end()) + 1;
            if (mode == "TRIANGLES") {
                encoded.resize(meshopt_encodeIndexBufferBound(count, vertices));
                encoded.resize(meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), indices.data(), count));
            } else {
                encoded.resize(meshopt_encodeIndexSequenceBound(count, vertices));
                encoded.resize(meshopt_encodeIndexSequence(encoded.data(), encoded.size(), indices.data(), count));
            }
        }
        EXPECT_GT(encoded.size(), 0u);
        const std::size_t offset = compressed.size();
        compressed.append(reinterpret_cast<const char*>(encoded.data()), encoded.size());
        while (compressed.size() % 4 != 0) compressed += '\0';
        json extension = {{"buffer", 0},          {"byteOffset", offset}, {"byteLength", encoded.size()},
                          {"byteStride", stride}, {"count", count},       {"mode", mode}};
        if (filter != "NONE") extension["filter"] = filter;
        json view = {{"buffer", 1},
                     {"byteOffset", mFallbackBytes},
                     {"byteLength", raw.size()},
                     {"extensions", {{"EXT_meshopt_compression", extension}}}};
        if (strideOnView) view["byteStride"] = stride;
        mFallbackBytes += (raw.size() + 3) / 4 * 4;
        document["bufferViews"].push_back(view);
        return int(document["bufferViews"].size() - 1);
    }

    int addAccessor(int view, std::size_t count, const std::string& type, int componentType, bool normalized = false) {
        document["accessors"].push_back({{"bufferView", view},
                                         {"count", count},
                                         {"type", type},
                                         {"componentType", componentType},
                                         {"normalized", normalized}});
        return int(document["accessors"].size() - 1);
    }

    json& extensionOf(int view) {
        return document["bufferViews"][std::size_t(view)]["extensions"]["EXT_meshopt_compression"];
    }

    std::string gltf() const {
        json file = document;
        file["buffers"] = {{{"uri", "data:application/octet-stream;base64," + test::base64(compressed)},
                            {"byteLength", compressed.size()}},
                           placeholder()};
        return file.dump();
    }

    std::string glb() const {
        json file = document;
        file["buffers"] = {{{"byteLength", compressed.size()}}, placeholder()};
        return test::glb(file.dump(), compressed);
    }

private:
    json placeholder() const {
        return {{"byteLength", mFallbackBytes}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}};
    }

    std::size_t mFallbackBytes = 0;
};

template <typename T>
std::string bytesOf(const std::vector<T>& values) {
    return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

/** The cube compressed every way a mesh can be: positions as floats through the EXPONENTIAL filter (24-bit mantissas
 *  hold +-1 exactly), normals as 16-bit normalized shorts through the OCTAHEDRAL filter (8-byte stride), texture
 *  coordinates as floats without a filter, indices as 32-bit TRIANGLES in one primitive; a second mesh draws the same
 *  triangles from 16-bit INDICES (the index-sequence codec) with the view's byteStride left out, as for index data. */
MeshoptFile compressedCube(const SourceCube& cube) {
    MeshoptFile file;
    std::vector<float> exponentInput;
    for (const glm::vec3& p : cube.positions) exponentInput.insert(exponentInput.end(), {p.x, p.y, p.z});
    std::vector<std::uint32_t> positions(exponentInput.size());
    meshopt_encodeFilterExp(positions.data(), cube.positions.size(), 12, 24, exponentInput.data());
    const int positionView = file.addView(bytesOf(positions), 8, 12, "ATTRIBUTES", "EXPONENTIAL");

    std::vector<float> octahedralInput;
    for (const glm::vec3& n : cube.normals) octahedralInput.insert(octahedralInput.end(), {n.x, n.y, n.z, 0.0f});
    std::vector<std::int16_t> normals(octahedralInput.size());
    meshopt_encodeFilterOct(normals.data(), cube.normals.size(), 8, 16, octahedralInput.data());
    const int normalView = file.addView(bytesOf(normals), 8, 8, "ATTRIBUTES", "OCTAHEDRAL");

    const int texcoordView = file.addView(bytesOf(cube.texcoords), 8, 8, "ATTRIBUTES");
    const int triangleView = file.addView(bytesOf(cube.indices), 36, 4, "TRIANGLES", "NONE", false);
    std::vector<std::uint16_t> shortIndices(cube.indices.begin(), cube.indices.end());
    const int sequenceView = file.addView(bytesOf(shortIndices), 36, 2, "INDICES", "NONE", false);

    const int position = file.addAccessor(positionView, 8, "VEC3", 5126);
    const int normal = file.addAccessor(normalView, 8, "VEC3", 5122, true);
    const int texcoord = file.addAccessor(texcoordView, 8, "VEC2", 5126);
    const int triangles = file.addAccessor(triangleView, 36, "SCALAR", 5125);
    const int sequence = file.addAccessor(sequenceView, 36, "SCALAR", 5123);
    const json attributes = {{"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", texcoord}};
    file.document["meshes"] = {{{"primitives", {{{"attributes", attributes}, {"indices", triangles}}}}},
                               {{"primitives", {{{"attributes", attributes}, {"indices", sequence}}}}}};
    file.document["nodes"] = {{{"name", "triangles"}, {"mesh", 0}},
                              {{"name", "sequence"}, {"mesh", 1}, {"translation", {4.0, 0.0, 0.0}}}};
    file.document["scenes"] = {{{"nodes", {0, 1}}}};
    file.document["scene"] = 0;
    return file;
}

/** `mesh` is the cube moved by `offset`: each source corner found once with its normal (within `normalTolerance`)
 *  and exact texture coordinates, and every triangle one of the source's, wound the same way. */
void expectCube(const Scene& scene, const Mesh& mesh, const SourceCube& cube, glm::dvec3 offset,
                double normalTolerance) {
    ASSERT_EQ(mesh.positions.size(), 8u) << mesh.name;
    ASSERT_EQ(mesh.normals.size(), 8u) << mesh.name;
    ASSERT_EQ(mesh.texcoords[0].size(), 8u) << mesh.name;
    std::vector<std::uint32_t> sourceOf(8, 8);
    for (std::size_t i = 0; i < 8; ++i) {
        const glm::dvec3 position = test::worldPosition(scene, mesh.positions[i]) - offset;
        for (std::uint32_t s = 0; s < 8; ++s)
            if (position == glm::dvec3(cube.positions[s])) sourceOf[i] = s;
        ASSERT_LT(sourceOf[i], 8u) << mesh.name << " vertex " << i << " at an unexpected place";
        EXPECT_LT(glm::length(mesh.normals[i] - cube.normals[sourceOf[i]]), normalTolerance) << mesh.name;
        EXPECT_EQ(mesh.texcoords[0][i], cube.texcoords[sourceOf[i]]) << mesh.name;
    }
    ASSERT_EQ(mesh.triangles.size(), 12u) << mesh.name;
    for (const glm::uvec3& triangle : mesh.triangles) {
        const std::array<std::uint32_t, 3> corners = {sourceOf[triangle.x], sourceOf[triangle.y], sourceOf[triangle.z]};
        bool found = false;
        for (std::size_t t = 0; t < cube.indices.size(); t += 3)
            for (int rotation = 0; rotation < 3; ++rotation)
                found = found || (corners[0] == cube.indices[t + std::size_t(rotation)] &&
                                  corners[1] == cube.indices[t + std::size_t(rotation + 1) % 3] &&
                                  corners[2] == cube.indices[t + std::size_t(rotation + 2) % 3]);
        EXPECT_TRUE(found) << mesh.name << " triangle " << corners[0] << " " << corners[1] << " " << corners[2];
    }
}

/** A 16-bit octahedral normal is off by at most about 2^-14 per component before renormalising. */
constexpr double kOctahedral16Tolerance = 2e-4;

TEST(GltfMeshopt, EncodedCubeLoadsAsItsSourceInEveryModeAndFilter) {
    const SourceCube cube;
    const MeshoptFile file = compressedCube(cube);
    for (const auto& [name, bytes] :
         {std::pair{std::string("cube.gltf"), file.gltf()}, std::pair{std::string("cube.glb"), file.glb()}}) {
        SCOPED_TRACE(name);
        const Scene scene = loadSceneFromMemory(name, bytes);
        ASSERT_EQ(scene.meshes.size(), 2u);
        expectCube(scene, scene.meshes[0], cube, glm::dvec3(0.0), kOctahedral16Tolerance);
        expectCube(scene, scene.meshes[1], cube, glm::dvec3(4.0, 0.0, 0.0), kOctahedral16Tolerance);
    }
}

/** An animation "turn" whose one rotation keyframe goes through the QUATERNION filter (16-bit components): the cube's
 *  corner (1, 1, 1) turned 90 degrees about Z lands at (-1, 1, 1), within the filter's precision. */
TEST(GltfMeshopt, QuaternionFilteredAnimationTurnsTheNode) {
    const SourceCube cube;
    MeshoptFile file = compressedCube(cube);
    const glm::quat turn = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1));
    const std::array<float, 4> rotation = {turn.x, turn.y, turn.z, turn.w}; // glTF's order
    std::vector<std::int16_t> encoded(4);
    meshopt_encodeFilterQuat(encoded.data(), 1, 8, 16, rotation.data());
    const int rotationView = file.addView(bytesOf(encoded), 1, 8, "ATTRIBUTES", "QUATERNION");
    const int timeView = file.addView(bytesOf(std::vector<float>{0.0f}), 1, 4, "ATTRIBUTES");
    const int output = file.addAccessor(rotationView, 1, "VEC4", 5122, true);
    const int input = file.addAccessor(timeView, 1, "SCALAR", 5126);
    file.document["accessors"][std::size_t(input)]["min"] = {0.0};
    file.document["accessors"][std::size_t(input)]["max"] = {0.0};
    json channel = {{"sampler", 0}, {"target", {{"node", 0}, {"path", "rotation"}}}};
    json sampler = {{"input", input}, {"output", output}};
    json animation = {{"name", "turn"}, {"samplers", json::array({sampler})}, {"channels", json::array({channel})}};
    file.document["animations"] = json::array({animation});
    LoadOptions options;
    options.animation = "turn";
    const Scene scene = loadSceneFromMemory("turn.gltf", file.gltf(), options);
    const Mesh& turned = scene.meshes[0];
    bool found = false;
    for (const glm::vec3& p : turned.positions) {
        const glm::dvec3 world = test::worldPosition(scene, p);
        found = found || glm::length(world - glm::dvec3(-1, 1, 1)) < 1e-4;
    }
    EXPECT_TRUE(found) << "no corner at (-1, 1, 1)";
    EXPECT_EQ(loadSceneFromMemory("rest.gltf", file.gltf()).meshes[0].positions.size(), 8u);
}

/** gltfpack's output (tests/scene/data/BoxMeshopt.glb): KHR_mesh_quantization's unsigned-short positions and byte
 *  normals in compressed views, the fallback buffer declaring 360 bytes the GLB does not hold, the node scaling by
 *  1/255 and moving by -1/2: the unit cube around the origin, each face's normal pointing out of it. */
TEST(GltfMeshopt, GltfpackBoxLoadsAsTheUnitCube) {
    const Scene scene = loadScene(test::sourcePath("tests/scene/data/BoxMeshopt.glb"));
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& box = scene.meshes[0];
    EXPECT_EQ(box.triangleCount(), 12u);
    ASSERT_EQ(box.normals.size(), box.positions.size());
    for (std::size_t i = 0; i < box.positions.size(); ++i) {
        const glm::dvec3 p = test::worldPosition(scene, box.positions[i]);
        for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(std::abs(p[axis]), 0.5, 1e-6) << "vertex " << i;
        // Each normal is a face's: one axis, pointing the way that corner lies along it.
        const glm::dvec3 n(box.normals[i]);
        int axis = 0;
        for (int a = 1; a < 3; ++a)
            if (std::abs(n[a]) > std::abs(n[axis])) axis = a;
        EXPECT_NEAR(std::abs(n[axis]), 1.0, 1e-6);
        EXPECT_GT(n[axis] * p[axis], 0.0) << "vertex " << i;
    }
    for (const glm::uvec3& triangle : box.triangles) {
        const glm::dvec3 centroid = (test::worldPosition(scene, box.positions[triangle.x]) +
                                     test::worldPosition(scene, box.positions[triangle.y]) +
                                     test::worldPosition(scene, box.positions[triangle.z])) /
                                    3.0;
        EXPECT_GT(glm::dot(test::triangleCross(box, triangle), centroid), 0.0) << "an inward-facing triangle";
    }
}

/** The message loading `file` (as cube.gltf) gives. */
std::string refusal(const MeshoptFile& file) {
    return test::sceneErrorMessage([&] { loadSceneFromMemory("cube.gltf", file.gltf()); });
}

void expectRefusal(const MeshoptFile& file, const std::string& expected) {
    const std::string message = refusal(file);
    EXPECT_NE(message.find("'cube.gltf'"), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
}

TEST(GltfMeshopt, TruncatedStreamIsRefused) {
    MeshoptFile file = compressedCube(SourceCube());
    json& extension = file.extensionOf(0);
    extension["byteLength"] = extension["byteLength"].get<std::size_t>() / 2;
    expectRefusal(file, "buffer view 0: EXT_meshopt_compression: meshoptimizer cannot decode its ");
    MeshoptFile indices = compressedCube(SourceCube());
    indices.extensionOf(3)["byteLength"] = 10;
    expectRefusal(indices, "buffer view 3: EXT_meshopt_compression: meshoptimizer cannot decode its 10 bytes as 36 "
                           "elements of mode TRIANGLES");
}

TEST(GltfMeshopt, CorruptStreamIsRefused) {
    MeshoptFile file = compressedCube(SourceCube());
    file.compressed[0] = '\x55'; // the attribute stream's header byte (0xa0)
    expectRefusal(file, "buffer view 0: EXT_meshopt_compression: meshoptimizer cannot decode");
}

TEST(GltfMeshopt, CountTimesStrideOverflowIsRefused) {
    MeshoptFile file = compressedCube(SourceCube());
    file.extensionOf(0)["count"] = std::uint64_t(1) << 62;
    expectRefusal(file, "buffer view 0: EXT_meshopt_compression: count 4611686018427387904 x byteStride 12 does not "
                        "equal the buffer view's byteLength 96");
    MeshoptFile mismatch = compressedCube(SourceCube());
    mismatch.extensionOf(2)["count"] = 9;
    expectRefusal(mismatch, "count 9 x byteStride 8 does not equal the buffer view's byteLength 64");
}

TEST(GltfMeshopt, CompressedBytesOutsideTheirBufferAreRefused) {
    MeshoptFile offset = compressedCube(SourceCube());
    offset.extensionOf(1)["byteOffset"] = 1u << 30;
    expectRefusal(offset, "buffer view 1: EXT_meshopt_compression: the compressed bytes (offset 1073741824, length ");
    MeshoptFile length = compressedCube(SourceCube());
    length.extensionOf(1)["byteLength"] = std::uint64_t(-1);
    expectRefusal(length, "exceed buffer 0 of ");
    MeshoptFile buffer = compressedCube(SourceCube());
    buffer.extensionOf(1)["buffer"] = 7;
    expectRefusal(buffer, "buffer view 1: EXT_meshopt_compression: buffer 7 out of range (file has 2 buffers)");
    MeshoptFile placeholder = compressedCube(SourceCube());
    placeholder.extensionOf(1)["buffer"] = 1;
    expectRefusal(placeholder, "buffer 1 is a placeholder for uncompressed data and holds no compressed bytes");
}

TEST(GltfMeshopt, UnknownModeAndFilterAreRefusedWithTheChoices) {
    MeshoptFile mode = compressedCube(SourceCube());
    mode.extensionOf(0)["mode"] = "STRIPS";
    expectRefusal(mode, "buffer view 0: EXT_meshopt_compression: mode 'STRIPS' is not 'ATTRIBUTES', 'TRIANGLES' or "
                        "'INDICES'");
    MeshoptFile filter = compressedCube(SourceCube());
    filter.extensionOf(0)["filter"] = 3;
    expectRefusal(filter, "filter '3' is not 'NONE', 'OCTAHEDRAL', 'QUATERNION' or 'EXPONENTIAL'");
    MeshoptFile missing = compressedCube(SourceCube());
    missing.extensionOf(0).erase("mode");
    expectRefusal(missing, "needs 'mode' ('ATTRIBUTES', 'TRIANGLES' or 'INDICES')");
}

TEST(GltfMeshopt, SpecificationRulesAreChecked) {
    const auto refused = [](int view, const json& changes, const std::string& expected) {
        MeshoptFile file = compressedCube(SourceCube());
        for (const auto& [key, value] : changes.items()) file.extensionOf(view)[key] = value;
        SCOPED_TRACE(changes.dump());
        expectRefusal(file, expected);
    };
    refused(2, {{"byteStride", 6}}, "byteStride 6 must be a multiple of 4 from 4 to 256 in mode ATTRIBUTES");
    refused(3, {{"byteStride", 8}}, "byteStride 8 must be 2 or 4 in mode TRIANGLES");
    refused(3, {{"filter", "OCTAHEDRAL"}}, "filter OCTAHEDRAL applies only to mode ATTRIBUTES, not TRIANGLES");
    refused(3, {{"count", 35}}, "count 35 is not a multiple of 3 in mode TRIANGLES");
    refused(0, {{"filter", "QUATERNION"}}, "byteStride 12 does not suit filter QUATERNION (8)");
    refused(0, {{"filter", "OCTAHEDRAL"}}, "byteStride 12 does not suit filter OCTAHEDRAL (4 or 8)");
    refused(0, {{"byteStride", -12}}, "'byteStride' must be a non-negative integer (it is -12)");
    refused(0, {{"count", 8.5}}, "'count' must be a non-negative integer (it is 8.5)");
    MeshoptFile stride = compressedCube(SourceCube());
    stride.document["bufferViews"][0]["byteStride"] = 16;
    expectRefusal(stride, "byteStride 12 differs from the buffer view's byteStride 16");
}

TEST(GltfMeshopt, UncompressedViewOfThePlaceholderIsRefused) {
    MeshoptFile file = compressedCube(SourceCube());
    file.document["bufferViews"][2].erase("extensions");
    expectRefusal(file, "buffer view 2 is not compressed, but its buffer 1 is EXT_meshopt_compression's placeholder, "
                        "which holds no data");
}

TEST(GltfMeshopt, DecodedBytesCountAgainstTheMemoryLimit) {
    // 2^26 elements of 16 bytes claimed by a stream of a few bytes: refused by the budget before anything is decoded.
    MeshoptFile file = compressedCube(SourceCube());
    file.document["bufferViews"][0]["byteLength"] = std::uint64_t(1) << 30;
    file.extensionOf(0)["count"] = std::uint64_t(1) << 26;
    file.extensionOf(0)["byteStride"] = 16;
    file.document["bufferViews"][0]["byteStride"] = 16;
    LoadOptions options;
    options.memoryLimitBytes = std::size_t(256) << 20;
    const std::string message =
        test::sceneErrorMessage([&] { loadSceneFromMemory("cube.gltf", file.gltf(), options); });
    EXPECT_NE(message.find("(with EXT_meshopt_compression's decoded buffer views), above the memory limit of 256 MiB"),
              std::string::npos)
        << message;
}

} // namespace
} // namespace inkgraph
