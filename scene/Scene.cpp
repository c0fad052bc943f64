#include "scene/Scene.h"

#include "scene/FormatReaders.h"
#include "scene/MeshOps.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace inkgraph {

namespace detail {

void throwLoadError(const std::string& path, std::string_view problem) {
    throw SceneError("loadScene(): '" + path + "': " + std::string(problem));
}

void throwLoadErrorAtLine(const std::string& path, std::size_t line, std::string_view problem) {
    throw SceneError("loadScene(): '" + path + "' line " + std::to_string(line) + ": " + std::string(problem));
}

std::size_t MeshBudget::estimate(std::size_t vertices, std::size_t triangles) const {
    // Saturating: declared counts may be anything up to 2^64.
    const auto product = [](std::size_t count, std::size_t bytes) {
        return count > SIZE_MAX / bytes ? SIZE_MAX : count * bytes;
    };
    const auto sum = [](std::size_t a, std::size_t b) { return a > SIZE_MAX - b ? SIZE_MAX : a + b; };
    const std::size_t allVertices = sum(mVertices, vertices);
    const std::size_t allTriangles = sum(mTriangles, triangles);
    return sum(mFileBytes, sum(product(allVertices, kBytesPerVertex), product(allTriangles, kBytesPerTriangle)));
}

void MeshBudget::chargeFile(std::size_t bytes) {
    mFileBytes = mFileBytes > SIZE_MAX - bytes ? SIZE_MAX : mFileBytes + bytes;
    if (estimate(0, 0) > mLimitBytes)
        throwLoadError(mPath, "the file is " + std::to_string(bytes >> 20) + " MiB; the load would hold about " +
                                  std::to_string(estimate(0, 0) >> 20) + " MiB, above the memory limit of " +
                                  std::to_string(mLimitBytes >> 20) + " MiB (--memory-limit)");
}

void MeshBudget::check(std::size_t vertices, std::size_t triangles) const {
    const std::size_t bytes = estimate(vertices, triangles);
    if (bytes > mLimitBytes)
        throwLoadError(mPath, "the mesh would need about " + std::to_string(bytes >> 20) + " MiB (" +
                                  std::to_string(mVertices + vertices) + " vertices, " +
                                  std::to_string(mTriangles + triangles) + " triangles), above the memory limit of " +
                                  std::to_string(mLimitBytes >> 20) + " MiB (--memory-limit)");
}

void MeshBudget::charge(std::size_t vertices, std::size_t triangles) {
    check(vertices, triangles);
    mVertices += vertices;
    mTriangles += triangles;
}

} // namespace detail

namespace {

enum class FileKind { Gltf, Obj, Stl };

std::string lowercaseExtension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::ranges::transform(extension, extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

FileKind kindFromExtension(const std::string& path) {
    const std::string extension = lowercaseExtension(path);
    if (extension == ".gltf" || extension == ".glb") {
        return FileKind::Gltf;
    }
    if (extension == ".obj") {
        return FileKind::Obj;
    }
    if (extension == ".stl") {
        return FileKind::Stl;
    }
    const std::string shown = extension.empty() ? "no extension" : "extension '" + extension + "'";
    detail::throwLoadError(path, "unsupported file type (" + shown + "); supported: .gltf, .glb, .obj, .stl");
}

void requireRegularFile(const std::string& path) {
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    if (status.type() == std::filesystem::file_type::not_found) {
        detail::throwLoadError(path, "file not found");
    }
    if (error) {
        detail::throwLoadError(path, "cannot access the file: " + error.message());
    }
    if (status.type() != std::filesystem::file_type::regular) {
        detail::throwLoadError(path, "not a regular file");
    }
}

/** The whole file in memory: the readers parse it in one pass without per-line stream overhead. Its size is charged to
 *  the budget before the bytes are allocated. */
std::string readWholeFile(const std::string& path, detail::MeshBudget& budget) {
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    if (!file) {
        detail::throwLoadError(path, "cannot open the file for reading");
    }
    const std::streamoff size = file.tellg();
    if (size < 0) {
        detail::throwLoadError(path, "cannot determine the file size");
    }
    budget.chargeFile(std::size_t(size));
    std::string content(std::size_t(size), '\0');
    file.seekg(0);
    if (!file.read(content.data(), size)) {
        detail::throwLoadError(path, "read error");
    }
    return content;
}

void checkLoadOptions(const LoadOptions& options) {
    if (!std::isfinite(options.weldTolerance) || options.weldTolerance < 0.0) {
        throw std::invalid_argument("loadScene(): weldTolerance must be finite and >= 0, got " +
                                    std::to_string(options.weldTolerance));
    }
}

detail::RawScene readContent(const std::string& path, std::string_view content, detail::MeshBudget& budget) {
    switch (kindFromExtension(path)) {
    case FileKind::Gltf: return detail::readGltf(path, content, budget); // JSON or GLB: the content decides
    case FileKind::Obj: return detail::readObj(path, content, budget);
    case FileKind::Stl: return detail::readStl(path, content, budget);
    }
    throw std::logic_error("loadScene(): unhandled file kind");
}

Scene finalizeScene(const std::string& path, detail::RawScene raw, const LoadOptions& options) {
    Scene scene;
    scene.camera = raw.camera;
    scene.light = raw.light;
    scene.report.format = raw.format;
    scene.report.warnings = std::move(raw.warnings);

    // One model size for every mesh, so the weld and degenerate thresholds follow the file's units, not each part's.
    BoundingBox modelBox;
    for (const RawMesh& mesh : raw.meshes) {
        for (const glm::vec3& p : mesh.positions) {
            modelBox.add(glm::dvec3(p));
        }
    }
    const double modelDiagonal = modelBox.diagonal();

    for (RawMesh& rawMesh : raw.meshes) {
        const std::string name = rawMesh.name;
        const std::size_t trianglesBefore = rawMesh.triangles.size();
        Mesh mesh = finalizeMesh(std::move(rawMesh), modelDiagonal, options, scene.report);
        if (!mesh.triangles.empty()) {
            scene.meshes.push_back(std::move(mesh));
        } else if (trianglesBefore > 0) {
            scene.report.warnings.push_back("mesh '" + name + "': all " + std::to_string(trianglesBefore) +
                                            " triangles are degenerate; mesh skipped");
        }
    }
    if (scene.meshes.empty()) {
        if (scene.report.trianglesRead == 0) {
            detail::throwLoadError(path, "no triangles in the file");
        }
        detail::throwLoadError(path, "no triangles left: all " + std::to_string(scene.report.trianglesRead) +
                                         " triangles are degenerate");
    }
    return scene;
}

} // namespace

std::size_t Scene::triangleCount() const {
    std::size_t count = 0;
    for (const Mesh& mesh : meshes) {
        count += mesh.triangles.size();
    }
    return count;
}

std::size_t Scene::vertexCount() const {
    std::size_t count = 0;
    for (const Mesh& mesh : meshes) {
        count += mesh.positions.size();
    }
    return count;
}

Scene loadScene(const std::string& path, const LoadOptions& options) {
    checkLoadOptions(options);
    kindFromExtension(path); // an unsupported extension is named before the file is looked at
    requireRegularFile(path);
    detail::MeshBudget budget(path, options.memoryLimitBytes);
    const std::string content = readWholeFile(path, budget);
    return finalizeScene(path, readContent(path, content, budget), options);
}

Scene loadSceneFromMemory(const std::string& path, std::string_view content, const LoadOptions& options) {
    checkLoadOptions(options);
    detail::MeshBudget budget(path, options.memoryLimitBytes);
    budget.chargeFile(content.size());
    return finalizeScene(path, readContent(path, content, budget), options);
}

BoundingSphere computeBoundingSphere(const Scene& scene) {
    BoundingBox box;
    for (const Mesh& mesh : scene.meshes) {
        for (const glm::vec3& p : mesh.positions) {
            box.add(glm::dvec3(p));
        }
    }
    if (box.empty()) {
        throw SceneError("computeBoundingSphere(): the scene has no vertices");
    }
    BoundingSphere sphere;
    sphere.center = box.center();
    double maxDistanceSquared = 0.0;
    for (const Mesh& mesh : scene.meshes) {
        for (const glm::vec3& p : mesh.positions) {
            const glm::dvec3 offset = glm::dvec3(p) - sphere.center;
            maxDistanceSquared = std::max(maxDistanceSquared, glm::dot(offset, offset));
        }
    }
    sphere.radius = std::sqrt(maxDistanceSquared);
    return sphere;
}

} // namespace inkgraph
