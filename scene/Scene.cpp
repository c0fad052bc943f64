#include "scene/Scene.h"

#include "scene/FormatReaders.h"
#include "scene/MeshOps.h"

#include <algorithm>
#include <cctype>
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

/** The whole file in memory: the text readers parse it in one pass without per-line stream overhead. */
std::string readWholeFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    if (!file) {
        detail::throwLoadError(path, "cannot open the file for reading");
    }
    const std::streamoff size = file.tellg();
    if (size < 0) {
        detail::throwLoadError(path, "cannot determine the file size");
    }
    std::string content(std::size_t(size), '\0');
    file.seekg(0);
    if (!file.read(content.data(), size)) {
        detail::throwLoadError(path, "read error");
    }
    return content;
}

bool startsWithGlbMagic(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    char magic[4] = {};
    return file.read(magic, sizeof magic) && std::string_view(magic, sizeof magic) == "glTF";
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
    if (!std::isfinite(options.weldTolerance) || options.weldTolerance < 0.0) {
        throw std::invalid_argument("loadScene(): weldTolerance must be finite and >= 0, got " +
                                    std::to_string(options.weldTolerance));
    }
    const FileKind kind = kindFromExtension(path);
    requireRegularFile(path);

    detail::RawScene raw;
    switch (kind) {
    case FileKind::Gltf:
        // The content decides between the JSON and binary container, whatever the extension says.
        raw = detail::readGltf(path, startsWithGlbMagic(path));
        break;
    case FileKind::Obj: raw = detail::readObj(path, readWholeFile(path)); break;
    case FileKind::Stl: raw = detail::readStl(path, readWholeFile(path)); break;
    }
    return finalizeScene(path, std::move(raw), options);
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
