#include "scene/ObjectIds.h"

#include <map>
#include <utility>

namespace inkgraph {

SceneObjects sceneObjects(const Scene& scene) {
    SceneObjects result;
    result.ofMesh.reserve(scene.meshes.size());
    // Keyed on the instance first: it differs between nodes in glTF, so most lookups compare no path.
    std::map<std::pair<std::size_t, std::vector<std::string>>, std::uint32_t> indexOf;
    for (std::size_t index = 0; index < scene.meshes.size(); ++index) {
        const Mesh& mesh = scene.meshes[index];
        const auto [entry, added] =
            indexOf.try_emplace({mesh.nodeInstance, mesh.nodePath}, std::uint32_t(result.objects.size()));
        if (added) {
            SceneObject object;
            object.name = !mesh.nodePath.empty() && !mesh.nodePath.back().empty() ? mesh.nodePath.back() : mesh.name;
            object.nodePath = mesh.nodePath;
            result.objects.push_back(std::move(object));
        }
        result.objects[entry->second].meshes.push_back(index);
        result.ofMesh.push_back(entry->second);
    }
    return result;
}

} // namespace inkgraph
