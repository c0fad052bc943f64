#include "scene/MeshLabels.h"

#include "scene/MaterialIds.h"
#include "scene/ObjectIds.h"

#include <algorithm>
#include <stdexcept>

namespace inkgraph {

SceneLabels sceneLabels(const Scene& scene) {
    SceneLabels labels;
    const SceneObjects objects = sceneObjects(scene);
    const std::vector<std::uint32_t> materials = materialIds(scene);
    const TriangleNumbering numbering(scene);
    for (std::size_t index = 0; index < scene.meshes.size(); ++index) {
        const Mesh& mesh = scene.meshes[index];
        labels.meshes.push_back({std::uint32_t(index + 1), mesh.name, mesh.nodePath, objects.ofMesh[index] + 1,
                                 materials[index] + 1, numbering.firstOfMesh(index), mesh.numberedTriangleCount()});
        // Ids are dense in the order of each material's first mesh, so a new id is always the next one.
        if (materials[index] == labels.materials.size())
            labels.materials.push_back({materials[index] + 1, mesh.material.name});
    }
    return labels;
}

TriangleNumbering::TriangleNumbering(const Scene& scene) : mScene(scene) {
    mFirst.reserve(scene.meshes.size() + 1);
    std::size_t first = 0;
    for (const Mesh& mesh : scene.meshes) {
        mFirst.push_back(first);
        first += mesh.numberedTriangleCount();
    }
    mFirst.push_back(first);
}

std::size_t TriangleNumbering::global(std::size_t meshIndex, std::size_t triangle) const {
    if (meshIndex >= mScene.meshes.size())
        throw std::out_of_range("TriangleNumbering::global(): mesh " + std::to_string(meshIndex) + " of a scene of " +
                                std::to_string(mScene.meshes.size()));
    const Mesh& mesh = mScene.meshes[meshIndex];
    if (triangle >= mesh.triangleCount())
        throw std::out_of_range("TriangleNumbering::global(): triangle " + std::to_string(triangle) + " of mesh " +
                                std::to_string(meshIndex) + ", which has " + std::to_string(mesh.triangleCount()));
    return mFirst[meshIndex] + mesh.fileTriangleOf(triangle);
}

std::optional<std::size_t> TriangleNumbering::meshOf(std::size_t global) const {
    if (global >= total()) return std::nullopt;
    // The last mesh starting at or before it (a mesh without triangles starts where the next does).
    return std::size_t(std::upper_bound(mFirst.begin(), mFirst.end(), global) - mFirst.begin()) - 1;
}

std::optional<TriangleNumbering::Loaded> TriangleNumbering::loaded(std::size_t global) const {
    const std::optional<std::size_t> meshIndex = meshOf(global);
    if (!meshIndex) return std::nullopt;
    const Mesh& mesh = mScene.meshes[*meshIndex];
    const std::size_t inFile = global - mFirst[*meshIndex];
    if (mesh.fileTriangles.empty()) {
        if (inFile >= mesh.triangleCount()) return std::nullopt;
        return Loaded{*meshIndex, inFile};
    }
    const auto found = std::lower_bound(mesh.fileTriangles.begin(), mesh.fileTriangles.end(), inFile);
    if (found == mesh.fileTriangles.end() || *found != inFile) return std::nullopt;
    return Loaded{*meshIndex, std::size_t(found - mesh.fileTriangles.begin())};
}

std::optional<Warning> triangleIdWarning(std::size_t idCount) {
    if (idCount <= kExactTriangleIds) return std::nullopt;
    return makeWarning(WarningKind::TriangleIdInexact,
                       "the scene's files give " + std::to_string(idCount) +
                           " triangles: the triangle ids of gbuffer.triangleId and gbuffer.barycentric's alpha "
                           "(float32) are exact only up to " +
                           std::to_string(kExactTriangleIds) + ", so larger ids round to a neighbour's");
}

} // namespace inkgraph
