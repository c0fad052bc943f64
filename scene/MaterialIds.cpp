#include "scene/MaterialIds.h"

#include "scene/MeshNumbering.h"

namespace inkgraph {
namespace {

bool sameMaterial(const Mesh& a, const Mesh& b) { return a.material == b.material; }

} // namespace

std::vector<std::uint32_t> materialIds(const Scene& scene) {
    // Each new material is compared with the first mesh of every material so far: scenes have few materials, and
    // exact float equality needs no ordering (a map key would).
    const MeshNumbering numbering(scene);
    std::vector<const Mesh*> firstMeshOf; // per id
    std::vector<std::uint32_t> ids;
    ids.reserve(numbering.size());
    for (std::size_t number = 0; number < numbering.size(); ++number) {
        const Mesh& mesh = numbering.mesh(number);
        std::size_t id = 0;
        while (id < firstMeshOf.size() && !sameMaterial(*firstMeshOf[id], mesh)) ++id;
        if (id == firstMeshOf.size()) firstMeshOf.push_back(&mesh);
        ids.push_back(std::uint32_t(id));
    }
    return ids;
}

} // namespace inkgraph
