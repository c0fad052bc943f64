#include "passes/shade/ShadingModel.h"

#include "scene/Scene.h"

#include <algorithm>
#include <stdexcept>

namespace inkgraph {

const std::vector<ShadingModelTraits>& shadingModels() {
    // model, name, define, specular, shadeMap, oneDimensionalMap, bands, faceOrientation, perPixel,
    // constantView, orientationSets, specularRowBands, materialOutlines, ambient, defaultAmbient, help
    static const std::vector<ShadingModelTraits> kModels = {
        {ShadingModel::None, "none", nullptr, false, false, false, false, false, false, false, false, false, false,
         false, 0.0f, "no shading pass: the paper colour, and the lines"},
        {ShadingModel::Flat, "flat", "MODEL_FLAT 1", false, false, false, false, false, false, false, false, false,
         false, true, 0.15f, "ambient + diffuse per face"},
        {ShadingModel::Gouraud, "gouraud", "MODEL_GOURAUD 1", false, false, false, false, false, false, false, false,
         false, false, true, 0.15f, "ambient + diffuse per vertex"},
        {ShadingModel::Lambert, "lambert", "MODEL_LAMBERT 1", false, false, false, false, false, true, false, false,
         false, false, true, 0.15f, "ambient + diffuse per pixel"},
        {ShadingModel::Phong, "phong", "MODEL_PHONG 1", true, false, false, false, false, true, false, false, false,
         false, true, 0.15f, "ambient + diffuse + white specular per pixel"},
        {ShadingModel::Cel, "cel", "MODEL_CEL 1", false, true, true, true, false, true, false, false, false, false,
         false, 0.0f,
         "1-D shade map indexed by the half-Lambert (n.l + 1)/2; default: Qu, Chen & Zwicker's five\n"
         "     bands {0, .25, .5, .75, 1} x the material colour"},
        {ShadingModel::Comic, "comic", "MODEL_COMIC 1", true, true, false, false, true, true, true, true, true, false,
         false, 0.0f,
         "2-D shade map indexed by diffuse max(n.l, 0) (across) and specular\n"
         "     max(r.v, 0)^shininess (up), Winnemöller & Bangay 2002"},
        {ShadingModel::MToon, "mtoon", "MODEL_MTOON 1", false, false, false, false, false, false, false, false, false,
         true, true, 0.05f,
         "the file's MToon materials (VRM): lit and shade colours, shading shift and toony, rim\n"
         "     (VRMC_materials_mtoon-1.0's formulas, docs/mtoon.md); other materials: glTF's\n"
         "     metallic-roughness"},
        {ShadingModel::Auto, "auto", "MODEL_AUTO 1", false, true, true, true, false, false, false, false, false, true,
         true, 0.05f,
         "each material its own model, as VRM viewers show the file: MToon where the material has\n"
         "     it (as mtoon), cel elsewhere (as cel: --bands and --shademap apply); a model without MToon is\n"
         "     exactly cel"},
    };
    return kModels;
}

const ShadingModelTraits& traitsOf(ShadingModel model) {
    for (const ShadingModelTraits& traits : shadingModels())
        if (traits.model == model) return traits;
    throw std::logic_error("traitsOf(): a shading model without a row in shadingModels()");
}

const ShadingModelTraits* findShadingModel(std::string_view name) {
    for (const ShadingModelTraits& traits : shadingModels())
        if (name == traits.name) return &traits;
    return nullptr;
}

ShadingModel shadingModelFor(ShadingModel requested, const Scene& scene) {
    if (requested != ShadingModel::Auto) return requested;
    const bool hasMToon = std::any_of(scene.meshes.begin(), scene.meshes.end(),
                                      [](const Mesh& mesh) { return mesh.material.mtoon.has_value(); });
    return hasMToon ? ShadingModel::Auto : ShadingModel::Cel;
}

std::string shadingModelsWith(bool ShadingModelTraits::*has) {
    std::vector<std::string> names;
    for (const ShadingModelTraits& traits : shadingModels())
        if (traits.*has) names.push_back(traits.name);
    std::string text;
    for (std::size_t i = 0; i < names.size(); ++i)
        text += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
    return text;
}

} // namespace inkgraph
