#include "scene/Scene.h"

#include "scene/formats/FormatTable.h"
#include "scene/mesh/BackToBackSheets.h"
#include "scene/mesh/MeshOps.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace inkgraph {

namespace {

/** The row of the format table (formats/FormatTable.h) whose extensions hold `path`'s; any other extension is refused
 *  with the table's list. */
const detail::FormatReader& readerFor(const std::string& path) {
    if (const detail::FormatReader* reader = detail::formatReaderFor(path)) return *reader;
    const std::string extension = detail::lowercaseExtension(path);
    const std::string shown = extension.empty() ? "no extension" : "extension '" + extension + "'";
    detail::throwLoadError(path, "unsupported file type (" + shown + "); supported: " + detail::supportedExtensions());
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

detail::RawScene readContent(const std::string& path, std::string_view content, detail::MeshBudget& budget,
                             const LoadOptions& options) {
    const detail::FormatReader& reader = readerFor(path);
    detail::RawScene raw = reader.read(path, content, budget, options);
    if (!options.animation.empty() && !reader.hasAnimations) {
        raw.warnings.push_back(
            makeWarning(WarningKind::AnimationIgnored, "animation '" + detail::excerptForMessage(options.animation) +
                                                           "' ignored: " + raw.format + " files have no animations"));
    }
    // The glTF reader refuses a glTF without a VRM humanoid; the other formats have no bones at all.
    if (!options.pose.empty() && raw.format != "gltf" && raw.format != "glb") {
        detail::throwLoadError(path, "cannot take a humanoid pose: not a VRM model (" + raw.format +
                                         " files have no humanoid bones)");
    }
    // VRM is glTF: the other formats have no faces to set.
    if ((!options.expressions.empty() || options.lookAt) && raw.format != "gltf" && raw.format != "glb") {
        detail::throwLoadError(path, std::string(options.expressions.empty() ? "--look-at" : "--expression") + ": " +
                                         raw.format + " files have no VRM expressions or look-at");
    }
    // The model first, then what the reader opened beside it.
    raw.inputFiles.insert(raw.inputFiles.begin(), path);
    return raw;
}

} // namespace

namespace detail {

void checkLoadOptions(const LoadOptions& options, std::string_view function) {
    if (!std::isfinite(options.weldTolerance) || options.weldTolerance < 0.0) {
        throw std::invalid_argument(std::string(function) + ": weldTolerance must be finite and >= 0, got " +
                                    std::to_string(options.weldTolerance));
    }
    if (!std::isfinite(options.time) || options.time < 0.0) {
        throw std::invalid_argument(std::string(function) + ": time must be finite and >= 0, got " +
                                    std::to_string(options.time));
    }
    for (const ExpressionWeight& expression : options.expressions) {
        if (!(expression.weight >= 0.0 && expression.weight <= 1.0))
            throw std::invalid_argument(std::string(function) + ": expression weights must be in [0, 1], got " +
                                        std::to_string(expression.weight));
    }
    if (options.lookAt && !std::isfinite(options.lookAt->x + options.lookAt->y + options.lookAt->z))
        throw std::invalid_argument(std::string(function) + ": lookAt must be finite");
}

namespace {

/** Moves every raw position (relative to the reader's origin) to be relative to the model's bounding-box centre, in
 *  double before rounding, and sets scene.origin; refuses a model too large or too small for float rendering. */
void recentre(const std::string& path, RawScene& raw, Scene& scene, std::string_view function) {
    // Zero extent is a model whose triangles are all degenerate, reported as such by finalizeScene().
    BoundingBox modelBox;
    for (const RawMesh& mesh : raw.meshes) {
        for (const glm::vec3& p : mesh.positions) {
            modelBox.add(glm::dvec3(p));
        }
    }
    if (modelBox.empty()) {
        scene.origin = raw.origin; // what the camera's eye is relative to
        return;
    }
    checkModelExtent(path, modelBox.diagonal(), function);
    const glm::dvec3 centre = modelBox.center();
    scene.origin = raw.origin + centre;
    for (RawMesh& mesh : raw.meshes) {
        for (glm::vec3& p : mesh.positions) {
            p = glm::vec3(glm::dvec3(p) - centre);
        }
    }
    if (scene.camera) {
        scene.camera->eye -= centre;
    }
    for (SceneJoint& joint : scene.joints) {
        joint.lower -= centre;
        joint.upper -= centre;
    }
}

} // namespace

Scene finalizeScene(const std::string& path, RawScene raw, const LoadOptions& options, std::string_view function) {
    Scene scene;
    scene.camera = raw.camera;
    scene.light = raw.light;
    scene.front = raw.front;
    scene.images = std::move(raw.images);
    scene.joints = std::move(raw.joints);
    scene.report.format = raw.format;
    scene.report.warnings = std::move(raw.warnings);
    scene.report.inputFiles = std::move(raw.inputFiles);
    scene.report.missingImages = std::move(raw.missingImages);
    scene.report.weldTolerance = options.weldTolerance;
    recentre(path, raw, scene, function);

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
            mesh.positions.clear();
            mesh.normals.clear();
            mesh.fileTriangles.clear();
            mesh.cornersSwapped.clear();
            for (std::vector<glm::vec2>& texcoords : mesh.texcoords) texcoords.clear();
            mesh.colors.clear();
            scene.skippedMeshes.push_back({scene.meshes.size(), std::move(mesh)});
            scene.report.warnings.push_back(makeWarning(WarningKind::MeshDegenerate,
                                                        "mesh '" + excerptForMessage(name) + "': all " +
                                                            std::to_string(trianglesBefore) +
                                                            " triangles are degenerate; mesh skipped",
                                                        "", name));
        }
    }
    scene.report.backToBackOneSided = cullBackToBackSheets(scene.meshes, options.weldTolerance * modelDiagonal);
    if (scene.meshes.empty()) {
        if (scene.report.trianglesRead == 0) {
            throwLoadError(path, noTrianglesInTheFile(scene.report.warnings), function);
        }
        const bool weldedAway = std::ranges::any_of(scene.report.warnings, [](const Warning& warning) {
            return warning.code == warningCode(WarningKind::DetailsMerged);
        });
        throwLoadError(path,
                       "no triangles left: all " + std::to_string(scene.report.trianglesRead) +
                           " triangles are degenerate" +
                           (weldedAway ? " (smaller than the weld distance, " + formatNumber(options.weldTolerance) +
                                             " of the model's size: parts far apart for their size? --weld-distance 0 "
                                             "keeps them)"
                                       : std::string()),
                       function);
    }
    // A warning about the model as a whole names the model's file; a reader names another (a texture, a library).
    for (Warning& warning : scene.report.warnings)
        if (warning.file.empty()) warning.file = path;
    return scene;
}

} // namespace detail

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
    detail::checkLoadOptions(options);
    readerFor(path); // an unsupported extension is named before the file is looked at
    requireRegularFile(path);
    detail::MeshBudget budget(path, options.memoryLimitBytes);
    const std::string content = readWholeFile(path, budget);
    return detail::finalizeScene(path, readContent(path, content, budget, options), options);
}

Scene loadSceneFromMemory(const std::string& path, std::string_view content, const LoadOptions& options) {
    detail::checkLoadOptions(options);
    detail::MeshBudget budget(path, options.memoryLimitBytes);
    budget.chargeFile(content.size());
    return detail::finalizeScene(path, readContent(path, content, budget, options), options);
}

std::vector<std::string> referencedFiles(const std::string& path) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) return {}; // a FIFO would block; loading reports the rest
    const detail::FormatReader* reader = detail::formatReaderFor(path);
    if (reader == nullptr || reader->referencedFiles == nullptr) return {};
    return reader->referencedFiles(path);
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
