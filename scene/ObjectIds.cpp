#include "scene/ObjectIds.h"

#include "scene/MeshNumbering.h"

#include <map>
#include <utility>

namespace inkgraph {

SceneObjects sceneObjects(const Scene& scene) {
    SceneObjects result;
    const MeshNumbering numbering(scene);
    result.ofMesh.reserve(numbering.size());
    // Keyed on the instance first: it differs between nodes in glTF, so most lookups compare no path.
    std::map<std::pair<std::size_t, std::vector<std::string>>, std::uint32_t> indexOf;
    for (std::size_t number = 0; number < numbering.size(); ++number) {
        const Mesh& mesh = numbering.mesh(number);
        const auto [entry, added] =
            indexOf.try_emplace({mesh.nodeInstance, mesh.nodePath}, std::uint32_t(result.objects.size()));
        if (added) {
            SceneObject object;
            object.name = !mesh.nodePath.empty() && !mesh.nodePath.back().empty() ? mesh.nodePath.back() : mesh.name;
            object.nodePath = mesh.nodePath;
            result.objects.push_back(std::move(object));
        }
        result.objects[entry->second].meshes.push_back(number);
        result.ofMesh.push_back(entry->second);
    }
    return result;
}

} // namespace inkgraph
