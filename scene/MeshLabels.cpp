#include "scene/MeshLabels.h"

#include "scene/MaterialIds.h"
#include "scene/ObjectIds.h"

#include <stdexcept>

namespace inkgraph {

SceneLabels sceneLabels(const Scene& scene) {
    SceneLabels labels;
    const SceneObjects objects = sceneObjects(scene);
    const std::vector<std::uint32_t> materials = materialIds(scene);
    std::size_t firstTriangle = 0;
    for (std::size_t index = 0; index < scene.meshes.size(); ++index) {
        const Mesh& mesh = scene.meshes[index];
        labels.meshes.push_back({std::uint32_t(index + 1), mesh.name, mesh.nodePath, objects.ofMesh[index] + 1,
                                 materials[index] + 1, firstTriangle, mesh.triangleCount()});
        firstTriangle += mesh.triangleCount();
        // Ids are dense in the order of each material's first mesh, so a new id is always the next one.
        if (materials[index] == labels.materials.size())
            labels.materials.push_back({materials[index] + 1, mesh.material.name});
    }
    return labels;
}

std::size_t globalTriangleIndex(const Scene& scene, std::size_t meshIndex, std::size_t triangle) {
    if (meshIndex >= scene.meshes.size())
        throw std::out_of_range("globalTriangleIndex(): mesh " + std::to_string(meshIndex) + " of a scene of " +
                                std::to_string(scene.meshes.size()));
    if (triangle >= scene.meshes[meshIndex].triangleCount())
        throw std::out_of_range("globalTriangleIndex(): triangle " + std::to_string(triangle) + " of mesh " +
                                std::to_string(meshIndex) + ", which has " +
                                std::to_string(scene.meshes[meshIndex].triangleCount()));
    std::size_t first = 0;
    for (std::size_t index = 0; index < meshIndex; ++index) first += scene.meshes[index].triangleCount();
    return first + triangle;
}

std::optional<Warning> triangleIdWarning(std::size_t triangleCount) {
    if (triangleCount <= kExactTriangleIds) return std::nullopt;
    return makeWarning(WarningKind::TriangleIdInexact, "the scene has " + std::to_string(triangleCount) +
                                                           " triangles: gbuffer.triangleId (float32) " +
                                                           "is exact only up to " + std::to_string(kExactTriangleIds) +
                                                           ", so larger ids round to a neighbour's");
}

} // namespace inkgraph
