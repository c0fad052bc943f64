/** @file sceneFromArrays(): the arrays checked with the file readers' limits, then turned into the raw mesh the OBJ
 *  reader makes of the same `v`, `vn`, `vt` and `f` lines, and finished by the readers' own finalizeScene(). */

#include "scene/MeshArrays.h"

#include "scene/formats/FormatReaders.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

namespace inkgraph {

namespace {

/** The first-use numbering's mark for a vertex no triangle has used yet. */
constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();

class ArraysReader {
public:
    ArraysReader(const MeshArrays& arrays, const LoadOptions& options)
        : mArrays(arrays), mName(detail::excerptForMessage(arrays.name.empty() ? "arrays" : arrays.name)),
          mBudget(mName, options.memoryLimitBytes, arrays.caller, "LoadOptions::memoryLimitBytes") {}

    detail::RawScene read() {
        checkCounts();
        // Charged like a file's vertices and triangles, before any copy is made.
        mBudget.charge(mArrays.vertexCount, mArrays.faceCount);
        checkIndices();
        checkFinite(mArrays.vertices, "xyz", "vertices");
        checkFinite(mArrays.normals, "xyz", "normals");
        checkFinite(mArrays.uvs, "uv", "uvs");
        checkFinite(mArrays.colors, std::string_view("rgba").substr(0, std::size_t(mArrays.colorChannels)), "colors");
        return buildScene();
    }

    /** The mesh's name as messages quote it. */
    const std::string& name() const { return mName; }

private:
    [[noreturn]] void fail(const std::string& problem) const { detail::throwLoadError(mName, problem, mArrays.caller); }

    void checkCounts() const {
        if (mArrays.vertices == nullptr && mArrays.vertexCount > 0) {
            fail("vertices is null but vertexCount is " + std::to_string(mArrays.vertexCount));
        }
        if (mArrays.faces == nullptr && mArrays.faceCount > 0) {
            fail("faces is null but faceCount is " + std::to_string(mArrays.faceCount));
        }
        if (mArrays.faceCount == 0) {
            fail("no faces: faceCount is 0");
        }
        // Mesh indices are 32-bit, and the weld keeps the largest value as its "no vertex" mark (as OBJ's reader
        // refuses an index beyond it).
        if (mArrays.vertexCount > std::numeric_limits<std::uint32_t>::max()) {
            fail("vertexCount " + std::to_string(mArrays.vertexCount) + " is more than the " +
                 std::to_string(std::numeric_limits<std::uint32_t>::max()) + " vertices 32-bit indices reach");
        }
        if (mArrays.faceCount > std::numeric_limits<std::size_t>::max() / (3 * sizeof(std::uint32_t))) {
            fail("faceCount " + std::to_string(mArrays.faceCount) +
                 " overflows: its 3 indices a face would need more bytes than memory can address");
        }
        if (mArrays.colors != nullptr && mArrays.colorChannels != 3 && mArrays.colorChannels != 4) {
            fail("colorChannels is " + std::to_string(mArrays.colorChannels) +
                 "; colors need 3 (RGB) or 4 (RGBA) values per vertex");
        }
    }

    void checkIndices() const {
        for (std::size_t t = 0; t < mArrays.faceCount; ++t) {
            for (std::size_t corner = 0; corner < 3; ++corner) {
                const std::uint32_t index = mArrays.faces[3 * t + corner];
                if (index >= mArrays.vertexCount) {
                    fail("face " + std::to_string(t) + ": vertex index " + std::to_string(index) +
                         " out of range (vertices has " + std::to_string(mArrays.vertexCount) + " rows)");
                }
            }
        }
    }

    /** Every value of an optional per-vertex array finite (`components` names a row's values): a NaN or infinity
     *  would reach the renderer's buffers. */
    void checkFinite(const float* values, std::string_view components, std::string_view array) const {
        if (values == nullptr) {
            return;
        }
        const std::size_t perVertex = components.size();
        for (std::size_t vertex = 0; vertex < mArrays.vertexCount; ++vertex) {
            for (std::size_t i = 0; i < perVertex; ++i) {
                const float value = values[perVertex * vertex + i];
                if (!std::isfinite(value)) {
                    fail(std::string(array) + ": vertex " + std::to_string(vertex) + ": " + components[i] +
                         " is not finite (" + detail::formatNumber(value) + ")");
                }
            }
        }
    }

    glm::vec4 colour(std::size_t vertex) const {
        // As OBJ's `v x y z r g b [a]`: clamped to [0, 1], alpha 1 when not given.
        glm::vec4 colour(1.0f);
        const std::size_t channels = std::size_t(mArrays.colorChannels);
        for (std::size_t i = 0; i < channels; ++i) {
            colour[int(i)] = std::clamp(mArrays.colors[channels * vertex + i], 0.0f, 1.0f);
        }
        return colour;
    }

    /** The OBJ reader's raw scene for the same lines (ObjReader.cpp buildScene()). */
    detail::RawScene buildScene() const {
        detail::RawScene scene;
        scene.format = "arrays";
        std::vector<glm::vec3> positions;
        {
            // In double, as OBJ reads its `v` lines, so storeNearModel() places the model as it places the file's.
            std::vector<glm::dvec3> world(mArrays.vertexCount);
            for (std::size_t v = 0; v < mArrays.vertexCount; ++v) {
                world[v] =
                    glm::dvec3(mArrays.vertices[3 * v], mArrays.vertices[3 * v + 1], mArrays.vertices[3 * v + 2]);
            }
            scene.origin = detail::storeNearModel(mName, world, positions, mArrays.caller);
        }
        RawMesh mesh;
        mesh.name = mArrays.name.empty() ? "arrays" : mArrays.name;
        if (!mArrays.name.empty()) mesh.nodePath = {mArrays.name};
        if (mArrays.colors != nullptr) {
            // The base colour multiplies the vertex colours (glTF's rule): white shows them as given.
            mesh.material.baseColorFactor = glm::vec4(1.0f);
        }
        mesh.triangles.resize(mArrays.faceCount);
        if (mArrays.normals == nullptr && mArrays.uvs == nullptr) {
            // OBJ with positions (and colours) alone: every vertex as it is, in its order; finalizeMesh() drops the
            // ones no triangle uses.
            mesh.positions = std::move(positions);
            if (mArrays.colors != nullptr) {
                mesh.colors.resize(mArrays.vertexCount);
                for (std::size_t v = 0; v < mArrays.vertexCount; ++v) mesh.colors[v] = colour(v);
            }
            for (std::size_t t = 0; t < mArrays.faceCount; ++t) {
                mesh.triangles[t] =
                    glm::uvec3(mArrays.faces[3 * t], mArrays.faces[3 * t + 1], mArrays.faces[3 * t + 2]);
            }
        } else {
            // OBJ with `vn` or `vt`: one vertex per distinct corner, numbered in the order the faces first use them.
            // Each array's row is its vertex's, so a corner is its position index.
            std::vector<std::uint32_t> vertexOf(mArrays.vertexCount, kUnused);
            for (std::size_t c = 0; c < 3 * mArrays.faceCount; ++c) {
                const std::uint32_t input = mArrays.faces[c];
                if (vertexOf[input] == kUnused) {
                    vertexOf[input] = std::uint32_t(mesh.positions.size());
                    mesh.positions.push_back(positions[input]);
                    if (mArrays.normals != nullptr) {
                        const float* normal = mArrays.normals + 3 * std::size_t(input);
                        mesh.normals.emplace_back(normal[0], normal[1], normal[2]);
                    }
                    if (mArrays.uvs != nullptr) {
                        const float* uv = mArrays.uvs + 2 * std::size_t(input);
                        mesh.texcoords[0].emplace_back(uv[0], float(1.0 - double(uv[1])));
                    }
                    if (mArrays.colors != nullptr) {
                        mesh.colors.push_back(colour(input));
                    }
                }
                mesh.triangles[c / 3][int(c % 3)] = vertexOf[input];
            }
        }
        scene.meshes.push_back(std::move(mesh));
        warnOfColoursOutOfRange(scene);
        return scene;
    }

    /** value-out-of-range for colours outside [0, 1], which colour() clamps: 0 to 255 (bytes given as float, a uint8
     *  array made float) drew every channel above 1/255 at full strength, without a word. */
    void warnOfColoursOutOfRange(detail::RawScene& scene) const {
        if (mArrays.colors == nullptr) return;
        std::size_t outside = 0;
        float farthest = 0.5f;
        for (std::size_t i = 0; i < mArrays.vertexCount * std::size_t(mArrays.colorChannels); ++i) {
            const float value = mArrays.colors[i];
            if (value >= 0.0f && value <= 1.0f) continue;
            ++outside;
            if (std::abs(value - 0.5f) > std::abs(farthest - 0.5f)) farthest = value;
        }
        if (outside == 0) return;
        scene.warnings.push_back(makeWarning(
            WarningKind::ValueOutOfRange,
            "colors: " + std::to_string(outside) + " vertex colour component" + (outside == 1 ? " lies" : "s lie") +
                " outside [0, 1] (as far out as " + detail::formatNumber(farthest) +
                (farthest > 1.5f ? "; colours of 0 to 255? give them divided by 255" : "") + "); clamped into [0, 1]"));
    }

    const MeshArrays& mArrays;
    std::string mName; ///< as messages quote it
    detail::MeshBudget mBudget;
};

} // namespace

Scene sceneFromArrays(const MeshArrays& arrays, const LoadOptions& options) {
    detail::checkLoadOptions(options, arrays.caller);
    ArraysReader reader(arrays, options);
    detail::RawScene raw = reader.read();
    if (!options.animation.empty()) {
        raw.warnings.push_back(
            makeWarning(WarningKind::AnimationIgnored, "animation '" + detail::excerptForMessage(options.animation) +
                                                           "' ignored: arrays have no animations"));
    }
    return detail::finalizeScene(reader.name(), std::move(raw), options, arrays.caller);
}

} // namespace inkgraph
