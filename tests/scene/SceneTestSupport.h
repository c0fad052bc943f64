#pragma once
/** @file Helpers for the scene tests: temporary model files, a tiny glTF writer and geometric checks. */

#include "scene/Scene.h"

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace inkgraph::test {

/** A file under the system temp directory with a unique name ending in `fileName`; removed on destruction. */
class TempFile {
public:
    TempFile(std::string_view fileName, std::string_view content) {
        static std::atomic<int> counter{0};
        const std::string unique = "inkgraph_scene_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) +
                                   "_" + std::string(fileName);
        mPath = (std::filesystem::temp_directory_path() / unique).string();
        std::ofstream file(mPath, std::ios::binary);
        file.write(content.data(), std::streamsize(content.size()));
        if (!file) {
            throw std::runtime_error("cannot write test file " + mPath);
        }
    }
    ~TempFile() {
        std::error_code ignored;
        std::filesystem::remove(mPath, ignored);
    }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;

    const std::string& path() const { return mPath; }
    std::string fileName() const { return std::filesystem::path(mPath).filename().string(); }

private:
    std::string mPath;
};

/** A folder under the system temp directory for a model and the files beside it (an OBJ and its .mtl and textures);
 *  removed with everything in it on destruction. */
class TempFolder {
public:
    TempFolder() {
        static std::atomic<int> counter{0};
        mPath = std::filesystem::temp_directory_path() /
                ("inkgraph_folder_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
        std::filesystem::create_directories(mPath);
    }
    ~TempFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(mPath, ignored);
    }
    TempFolder(const TempFolder&) = delete;
    TempFolder& operator=(const TempFolder&) = delete;

    /** Writes `content` to `name` in the folder; returns its path. */
    std::string write(const std::string& name, std::string_view content) const {
        const std::string file = path(name);
        std::ofstream out(file, std::ios::binary);
        out.write(content.data(), std::streamsize(content.size()));
        if (!out) {
            throw std::runtime_error("cannot write test file " + file);
        }
        return file;
    }
    std::string path(const std::string& name) const { return (mPath / name).string(); }

private:
    std::filesystem::path mPath;
};

/** A stored (local) position in world coordinates: Scene::origin + position. */
inline glm::dvec3 worldPosition(const Scene& scene, const glm::vec3& stored) {
    return scene.origin + glm::dvec3(stored);
}

inline std::string sourcePath(const std::string& relative) {
    return std::string(INKGRAPH_SOURCE_ROOT) + "/" + relative;
}

/** The message of the SceneError that `load` throws; fails the test if it throws nothing or something else. */
template <typename Function>
std::string sceneErrorMessage(Function&& load) {
    try {
        load();
    } catch (const SceneError& error) {
        return error.what();
    } catch (const std::exception& error) {
        ADD_FAILURE() << "expected SceneError, got another exception: " << error.what();
        return {};
    }
    ADD_FAILURE() << "expected SceneError, nothing was thrown";
    return {};
}

/** The 8 corners of the cube [-1,1]^3 and its 6 faces as counter-clockwise quads seen from outside (1-based, as in
 *  OBJ). */
inline const std::vector<glm::vec3>& cubeCorners() {
    static const std::vector<glm::vec3> corners = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                                   {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    return corners;
}

inline const std::vector<glm::uvec4>& cubeQuads() {
    static const std::vector<glm::uvec4> quads = {{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5},
                                                  {4, 8, 7, 3}, {1, 5, 8, 4}, {2, 3, 7, 6}};
    return quads;
}

/** The cube as 12 triangles of 36 separate corners (what STL stores), scaled and offset. */
inline std::vector<glm::vec3> cubeTriangleSoup(double scale = 1.0, glm::dvec3 offset = glm::dvec3(0.0)) {
    std::vector<glm::vec3> soup;
    for (const glm::uvec4& quad : cubeQuads()) {
        for (const glm::uvec3& triangle : {glm::uvec3(quad.x, quad.y, quad.z), glm::uvec3(quad.x, quad.z, quad.w)}) {
            for (int corner = 0; corner < 3; ++corner) {
                soup.emplace_back(glm::dvec3(cubeCorners()[triangle[corner] - 1]) * scale + offset);
            }
        }
    }
    return soup;
}

inline glm::dvec3 triangleCross(const Mesh& mesh, const glm::uvec3& triangle) {
    const glm::dvec3 a(mesh.positions[triangle.x]);
    const glm::dvec3 b(mesh.positions[triangle.y]);
    const glm::dvec3 c(mesh.positions[triangle.z]);
    return glm::cross(b - a, c - a);
}

/** Every triangle faces away from `center`: cross(b - a, c - a) . (centroid - center) > 0. */
inline void expectOutwardWinding(const Mesh& mesh, glm::dvec3 center) {
    std::size_t inward = 0;
    for (const glm::uvec3& triangle : mesh.triangles) {
        const glm::dvec3 centroid = (glm::dvec3(mesh.positions[triangle.x]) + glm::dvec3(mesh.positions[triangle.y]) +
                                     glm::dvec3(mesh.positions[triangle.z])) /
                                    3.0;
        if (!(glm::dot(triangleCross(mesh, triangle), centroid - center) > 0.0)) {
            ++inward;
        }
    }
    EXPECT_EQ(inward, 0u) << "triangles wound inward in mesh '" << mesh.name << "'";
}

/** Every corner's normal of `mesh` points along its triangle's winding normal, within 1 degree. */
inline void expectCornerNormalsAlongTheirFaces(const Mesh& mesh, const std::string& what) {
    for (const glm::uvec3& triangle : mesh.triangles) {
        const glm::dvec3 face = glm::normalize(triangleCross(mesh, triangle));
        for (int corner = 0; corner < 3; ++corner)
            EXPECT_GT(glm::dot(face, glm::dvec3(mesh.normals[triangle[corner]])), std::cos(3.14159265358979 / 180.0))
                << what << ": a corner's normal against its face";
    }
}

inline void expectUnitNormals(const Mesh& mesh, double tolerance = 1e-5) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    std::size_t bad = 0;
    for (const glm::vec3& normal : mesh.normals) {
        const double length = glm::length(glm::dvec3(normal));
        if (!std::isfinite(length) || std::abs(length - 1.0) > tolerance) {
            ++bad;
        }
    }
    EXPECT_EQ(bad, 0u) << "non-unit normals in mesh '" << mesh.name << "'";
}

inline std::string base64(std::string_view bytes) {
    static constexpr char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t chunk = std::uint32_t(std::uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) {
            chunk |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
        }
        if (i + 2 < bytes.size()) {
            chunk |= std::uint32_t(std::uint8_t(bytes[i + 2]));
        }
        out += alphabet[(chunk >> 18) & 63];
        out += alphabet[(chunk >> 12) & 63];
        out += i + 1 < bytes.size() ? alphabet[(chunk >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? alphabet[chunk & 63] : '=';
    }
    return out;
}

/** `json` and `binary` as a GLB container, each chunk padded to 4 bytes (JSON with spaces, the binary with zeros). */
inline std::string glb(std::string json, std::string binary) {
    while (json.size() % 4 != 0) json += ' ';
    while (binary.size() % 4 != 0) binary += '\0';
    const auto u32 = [](std::size_t value) {
        const std::uint32_t little = std::uint32_t(value);
        return std::string(reinterpret_cast<const char*>(&little), 4);
    };
    return "glTF" + u32(2) + u32(12 + 8 + json.size() + 8 + binary.size()) + u32(json.size()) + "JSON" + json +
           u32(binary.size()) + std::string("BIN\0", 4) + binary;
}

/** Writes the buffer part of a glTF file (one buffer, one view per accessor) and wraps a hand-written remainder
 *  (meshes, nodes, scenes, ...) into .gltf JSON or a .glb container. */
class GltfWriter {
public:
    /** A VEC3 FLOAT accessor; returns its index. */
    int addVec3(const std::vector<glm::vec3>& values) {
        return addAccessor(bytesOf(values.data(), values.size() * sizeof(glm::vec3)), values.size(), "VEC3", 5126);
    }

    /** A VEC2 FLOAT accessor (texture coordinates); returns its index. */
    int addVec2(const std::vector<glm::vec2>& values) {
        return addAccessor(bytesOf(values.data(), values.size() * sizeof(glm::vec2)), values.size(), "VEC2", 5126);
    }

    /** A FLOAT accessor of `type` ("SCALAR", "VEC4", "MAT4"), `values` its components in order; returns its index. */
    int addFloats(const std::vector<float>& values, const char* type, std::size_t components) {
        return addAccessor(bytesOf(values.data(), values.size() * sizeof(float)), values.size() / components, type,
                           5126);
    }

    /** A VEC4 UNSIGNED_BYTE accessor (JOINTS_0); returns its index. */
    int addJoints(const std::vector<std::uint8_t>& joints) {
        return addAccessor(bytesOf(joints.data(), joints.size()), joints.size() / 4, "VEC4", 5121);
    }

    /** A SCALAR index accessor of unsigned byte (1), short (2) or int (4) components; returns its index. */
    int addIndices(const std::vector<std::uint32_t>& indices, int bytesPerIndex) {
        std::string bytes;
        for (std::uint32_t index : indices) {
            char little[4];
            std::memcpy(little, &index, 4); // the test machines are little-endian, like glTF
            bytes.append(little, std::size_t(bytesPerIndex));
        }
        const int componentType = bytesPerIndex == 1 ? 5121 : bytesPerIndex == 2 ? 5123 : 5125;
        return addAccessor(bytes, indices.size(), "SCALAR", componentType);
    }

    /** Overrides the element count of an accessor, e.g. to make it read past its view. */
    void setAccessorCount(int accessor, std::size_t count) { mAccessorCounts[std::size_t(accessor)] = count; }

    /** `body` holds the remaining top-level members, e.g. "\"meshes\": [...], \"nodes\": [...]". */
    std::string gltf(const std::string& body) const {
        return json(body, "\"uri\": \"data:application/octet-stream;base64," + base64(mBinary) + "\", ");
    }

    /** JSON whose buffer lives in a separate file, `uri` relative to the .gltf; write binary() there. */
    std::string gltfWithExternalBuffer(const std::string& body, const std::string& uri) const {
        return json(body, "\"uri\": \"" + uri + "\", ");
    }

    const std::string& binary() const { return mBinary; }

    std::string glb(const std::string& body) const { return test::glb(json(body, ""), mBinary); }

private:
    static std::string bytesOf(const void* data, std::size_t size) {
        return std::string(static_cast<const char*>(data), size);
    }

    int addAccessor(const std::string& bytes, std::size_t count, const char* type, int componentType) {
        while (mBinary.size() % 4 != 0) {
            mBinary += '\0';
        }
        mViews.push_back("{\"buffer\": 0, \"byteOffset\": " + std::to_string(mBinary.size()) +
                         ", \"byteLength\": " + std::to_string(bytes.size()) + "}");
        mBinary += bytes;
        mAccessorTypes.push_back("\"type\": \"" + std::string(type) +
                                 "\", \"componentType\": " + std::to_string(componentType));
        mAccessorCounts.push_back(count);
        return int(mAccessorTypes.size() - 1);
    }

    std::string json(const std::string& body, const std::string& uri) const {
        std::string views;
        for (const std::string& view : mViews) {
            views += (views.empty() ? "" : ", ") + view;
        }
        std::string accessors;
        for (std::size_t i = 0; i < mAccessorTypes.size(); ++i) {
            accessors += (accessors.empty() ? "" : ", ") + std::string("{\"bufferView\": ") + std::to_string(i) +
                         ", \"count\": " + std::to_string(mAccessorCounts[i]) + ", " + mAccessorTypes[i] + "}";
        }
        return "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{" + uri +
               "\"byteLength\": " + std::to_string(mBinary.size()) + "}], \"bufferViews\": [" + views +
               "], \"accessors\": [" + accessors + "], " + body + "}";
    }

    std::string mBinary;
    std::vector<std::string> mViews;
    std::vector<std::string> mAccessorTypes;
    std::vector<std::size_t> mAccessorCounts;
};

} // namespace inkgraph::test
