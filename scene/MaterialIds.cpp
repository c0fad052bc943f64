#include "scene/MaterialIds.h"

namespace inkgraph {
namespace {

bool sameMaterial(const Mesh& a, const Mesh& b) { return a.material == b.material; }

} // namespace

std::vector<std::uint32_t> materialIds(const Scene& scene) {
    // Each new material is compared with the first mesh of every material so far: scenes have few materials, and
    // exact float equality needs no ordering (a map key would).
    std::vector<std::size_t> firstMeshOf; // per id
    std::vector<std::uint32_t> ids;
    ids.reserve(scene.meshes.size());
    for (std::size_t index = 0; index < scene.meshes.size(); ++index) {
        const Mesh& mesh = scene.meshes[index];
        std::size_t id = 0;
        while (id < firstMeshOf.size() && !sameMaterial(scene.meshes[firstMeshOf[id]], mesh)) ++id;
        if (id == firstMeshOf.size()) firstMeshOf.push_back(index);
        ids.push_back(std::uint32_t(id));
    }
    return ids;
}

} // namespace inkgraph
