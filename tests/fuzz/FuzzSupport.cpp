#include "tests/fuzz/FuzzSupport.h"

#include "scene/mesh/EdgeAdjacency.h"
#include "scene/mesh/MeshCurvature.h"
#include "scene/mesh/ObjectSuggestiveContours.h"

#include <cmath>
#include <stdexcept>

namespace inkgraph::fuzz {

void loadAndDerive(const char* name, std::string_view content) {
    LoadOptions options;
    options.memoryLimitBytes = kFuzzMemoryLimitBytes;
    Scene scene;
    try {
        scene = loadSceneFromMemory(name, content, options);
    } catch (const SceneError&) {
        return;
    }
    // A loaded scene keeps the loader's promises: triangles, finite positions, in-range indices.
    if (scene.meshes.empty()) throw std::logic_error("loadAndDerive(): a loaded scene has no meshes");
    const BoundingSphere sphere = computeBoundingSphere(scene);
    if (!std::isfinite(sphere.radius)) throw std::logic_error("loadAndDerive(): non-finite bounding radius");
    const double weldDistance = 1e-6 * std::max(sphere.radius, 1e-30);
    const glm::dvec3 eye = sphere.center + glm::dvec3(0.3, 0.4, 3.0) * std::max(sphere.radius, 1e-30);
    for (const Mesh& mesh : scene.meshes) {
        for (const glm::uvec3& triangle : mesh.triangles)
            for (int corner = 0; corner < 3; ++corner)
                if (triangle[corner] >= mesh.positions.size())
                    throw std::logic_error("loadAndDerive(): index past the positions in a loaded mesh");
        const EdgeAdjacency adjacency = buildEdgeAdjacency(mesh.positions, mesh.triangles, weldDistance);
        selectSilhouetteEdges(adjacency, eye);
        selectCreaseEdges(adjacency, 0.5);
        selectBorderEdges(adjacency);
        const MeshCurvature curvature = computeMeshCurvature(mesh.positions, mesh.triangles, weldDistance);
        ObjectSuggestiveSettings settings;
        settings.featureSize = 0.05 * std::max(sphere.radius, 1e-30);
        extractObjectSuggestiveContours(curvature, eye, settings);
    }
}

} // namespace inkgraph::fuzz
