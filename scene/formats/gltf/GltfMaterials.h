#pragma once
/** @file The glTF reader's materials: each material of the file read once, when a primitive first uses it (its
 *  warnings too), as the renderer sees it (scene/Material.h). Internal to the glTF reader. */

#include "scene/formats/FormatReaders.h"

#include <tiny_gltf.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace inkgraph::detail {

/** Extensions named one by one in a message (unsupported required ones, a texture's image extensions); the rest are
 *  counted. */
inline constexpr std::size_t kMaxNamedExtensions = 10;

class GltfMaterials {
public:
    /** `warnings` (RawScene::warnings) receives each material's warnings, once. */
    GltfMaterials(const std::string& path, const tinygltf::Model& model, std::vector<Warning>& warnings);
    ~GltfMaterials();
    GltfMaterials(const GltfMaterials&) = delete;
    GltfMaterials& operator=(const GltfMaterials&) = delete;

    /** Material `materialIndex` (in range: the caller checked it), read on first use: the glTF material (factors
     *  clamped into their ranges with a warning, ShaderValues.h; textures with their image, coordinate set, sampler and
     *  KHR_texture_transform; KHR_materials_pbrSpecularGlossiness's diffuse as the base colour,
     *  KHR_materials_emissive_strength and _unlit; alpha mode and cutoff; double-sidedness; the
     *  inkgraph shade-map extra), then a VRM character's MToon. Throws SceneError for an index out of range inside it
     *  (a texture, an image, a sampler) or a value it cannot use, naming the material. */
    const Material& material(int materialIndex);

private:
    struct Reader;
    std::unique_ptr<Reader> mReader;
};

} // namespace inkgraph::detail
