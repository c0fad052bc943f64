// libFuzzer target: VRM MToon materials (scene/formats/gltf/VrmMaterials.cpp): VRM 0.x's root materialProperties and
// VRM 1.0's VRMC_materials_mtoon, reached through the glTF reader as a .vrm (JSON or GLB; the content decides). A
// material the reader returns keeps readVrmMaterial()'s promise: a bad value becomes a warning and its default, never a
// non-finite parameter.
#include "tests/fuzz/FuzzSupport.h"

#include <cmath>
#include <stdexcept>

namespace {

void requireFinite(float value, const char* what) {
    if (!std::isfinite(value)) throw std::logic_error(std::string("FuzzMToon: non-finite ") + what);
}

void requireFinite(const glm::vec3& value, const char* what) {
    for (int i = 0; i < 3; ++i) requireFinite(value[i], what);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    inkgraph::LoadOptions options;
    options.memoryLimitBytes = inkgraph::fuzz::kFuzzMemoryLimitBytes;
    inkgraph::Scene scene;
    try {
        scene = inkgraph::loadSceneFromMemory("fuzz.vrm", inkgraph::fuzz::bytesOf(data, size), options);
    } catch (const inkgraph::SceneError&) {
        return 0;
    }
    for (const inkgraph::Mesh& mesh : scene.meshes) {
        const inkgraph::Material& material = mesh.material;
        for (int i = 0; i < 4; ++i) requireFinite(material.baseColorFactor[i], "base colour");
        requireFinite(material.alphaCutoff, "alpha cutoff");
        if (!material.mtoon) continue;
        const inkgraph::MToonMaterial& mtoon = *material.mtoon;
        requireFinite(mtoon.shadeColorFactor, "shadeColorFactor");
        requireFinite(mtoon.shadingShiftFactor, "shadingShiftFactor");
        requireFinite(mtoon.shadingToonyFactor, "shadingToonyFactor");
        requireFinite(mtoon.parametricRimColorFactor, "parametricRimColorFactor");
        requireFinite(mtoon.parametricRimFresnelPowerFactor, "parametricRimFresnelPowerFactor");
        requireFinite(mtoon.parametricRimLiftFactor, "parametricRimLiftFactor");
        requireFinite(mtoon.rimLightingMixFactor, "rimLightingMixFactor");
        requireFinite(mtoon.matcapFactor, "matcapFactor");
        requireFinite(mtoon.outlineWidthFactor, "outlineWidthFactor");
        requireFinite(mtoon.outlineColorFactor, "outlineColorFactor");
        requireFinite(mtoon.outlineLightingMixFactor, "outlineLightingMixFactor");
        for (const inkgraph::TextureRef* texture :
             {&material.baseColorTexture, &mtoon.shadeMultiplyTexture, &mtoon.outlineWidthMultiplyTexture})
            if (texture->present() && std::size_t(texture->image) >= scene.images.size())
                throw std::logic_error("FuzzMToon: a texture past the scene's images");
    }
    return 0;
}
