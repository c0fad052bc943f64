#include "render/SceneShadeMaps.h"

#include "render/StillRenderer.h"

#include <map>
#include <string_view>

namespace inkgraph {
namespace {

/** "mesh 'Teapot' (glTF material 'Metal')", or without the material when the mesh has no named one. */
std::string meshLabel(const Mesh& mesh) {
    return "mesh '" + mesh.name + "'" +
           (mesh.material.name.empty() ? "" : " (glTF material '" + mesh.material.name + "')");
}

} // namespace

std::vector<std::optional<ShadeMap>> readSceneShadeMaps(const Scene& scene, ShadingModel shading,
                                                        std::vector<Warning>* warnings) {
    std::vector<std::optional<ShadeMap>> maps(scene.meshes.size());
    const bool usesMaps = traitsOf(shading).shadeMap;
    if (!usesMaps) {
        // Reading files nothing will draw with could only fail the run; say why the file's maps do not show instead.
        std::size_t naming = 0;
        for (const Mesh& mesh : scene.meshes)
            if (!mesh.material.shadeMapPath.empty()) ++naming;
        if (naming > 0 && warnings)
            warnings->push_back(
                makeWarning(WarningKind::ShadeMapUnused,
                            naming == 1 ? "1 mesh names a shade map, which only --shading " +
                                              shadingModelsWith(&ShadingModelTraits::shadeMap) + " use"
                                        : std::to_string(naming) + " meshes name shade maps, which only --shading " +
                                              shadingModelsWith(&ShadingModelTraits::shadeMap) + " use"));
        return maps;
    }

    // One read per file: a scene of many parts usually shares a few maps, and cv::Mat copies share the pixels.
    std::map<std::string, ShadeMap> read;
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const Mesh& mesh = scene.meshes[i];
        if (mesh.material.shadeMapPath.empty()) continue;
        auto found = read.find(mesh.material.shadeMapPath);
        if (found == read.end()) {
            try {
                found = read.emplace(mesh.material.shadeMapPath,
                                     readShadeMapFile(mesh.material.shadeMapPath, traitsOf(shading).oneDimensionalMap))
                            .first;
            } catch (const InputFileError& error) {
                // readShadeMapFile() speaks for --shademap; here the file came from the model, so name the mesh.
                constexpr std::string_view kFlagPrefix = "--shademap: ";
                std::string_view reason = error.what();
                if (reason.starts_with(kFlagPrefix)) reason.remove_prefix(kFlagPrefix.size());
                throw InputFileError(meshLabel(mesh) + " shade map: " + std::string(reason));
            }
        }
        maps[i] = found->second;
    }
    return maps;
}

} // namespace inkgraph
