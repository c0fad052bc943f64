#include "scene/MeshLabels.h"

#include "scene/MaterialIds.h"
#include "scene/ObjectIds.h"

#include <algorithm>
#include <stdexcept>

namespace inkgraph {

SceneLabels sceneLabels(const Scene& scene) {
    SceneLabels labels;
    const MeshNumbering meshes(scene);
    const SceneObjects objects = sceneObjects(scene);
    const std::vector<std::uint32_t> materials = materialIds(scene);
    const TriangleNumbering numbering(scene);
    for (std::size_t number = 0; number < meshes.size(); ++number) {
        const Mesh& mesh = meshes.mesh(number);
        labels.meshes.push_back({std::uint32_t(number + 1), meshes.drawnIndex(number).has_value(), mesh.name,
                                 mesh.nodePath, objects.ofMesh[number] + 1, materials[number] + 1,
                                 numbering.firstOfNumber(number), mesh.numberedTriangleCount()});
        // Ids are dense in the order of each material's first mesh, so a new id is always the next one.
        if (materials[number] == labels.materials.size())
            labels.materials.push_back({materials[number] + 1, mesh.material.name});
    }
    return labels;
}

TriangleNumbering::TriangleNumbering(const Scene& scene) : mScene(scene), mMeshes(scene) {
    mFirst.reserve(mMeshes.size() + 1);
    std::size_t first = 0;
    for (std::size_t number = 0; number < mMeshes.size(); ++number) {
        mFirst.push_back(first);
        first += mMeshes.mesh(number).numberedTriangleCount();
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
    return firstOfMesh(meshIndex) + mesh.fileTriangleOf(triangle);
}

std::optional<std::size_t> TriangleNumbering::meshNumberOf(std::size_t global) const {
    if (global >= total()) return std::nullopt;
    // The last mesh starting at or before it (a mesh without triangles starts where the next does).
    return std::size_t(std::upper_bound(mFirst.begin(), mFirst.end(), global) - mFirst.begin()) - 1;
}

std::optional<TriangleNumbering::Loaded> TriangleNumbering::loaded(std::size_t global) const {
    const std::optional<std::size_t> number = meshNumberOf(global);
    if (!number) return std::nullopt;
    const std::optional<std::size_t> meshIndex = mMeshes.drawnIndex(*number);
    if (!meshIndex) return std::nullopt; // a skipped mesh's numbers name no triangle
    const Mesh& mesh = mScene.meshes[*meshIndex];
    const std::size_t inFile = global - mFirst[*number];
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
