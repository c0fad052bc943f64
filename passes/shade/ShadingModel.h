#pragma once
/** @file The shading models: one enum and one trait table. Everything that asks "does this model take a shade map,
 *  a shininess, face-orientation methods, can it shade the G-buffer?" (the flag table, the shade pass, the stats)
 *  reads the table, so a new
 *  model is one row here plus its branch in shaders/shade/shade.frag. */

#include <string>
#include <string_view>
#include <vector>

namespace inkgraph {

enum class ShadingModel { None, Flat, Gouraud, Lambert, Phong, Cel, Comic, MToon };

struct ShadingModelTraits {
    ShadingModel model;
    const char* name;       ///< the --shading value: "cel"
    const char* define;     ///< shade.frag's define, "MODEL_CEL 1"; null for none (no shade pass)
    bool specular;          ///< takes --shininess
    bool shadeMap;          ///< indexed into a shade map (--shademap, the materials' maps)
    bool oneDimensionalMap; ///< its map is one row (cel); else 2-D (comic)
    bool bands;             ///< takes --bands (evenly spaced bands as its built-in map)
    bool faceOrientation;   ///< takes --view-vector, --face-orientation, --front-rule (Winnemöller & Bangay 2002)
    /** Its colour is a function of the pixel's normal, view vector and base colour alone, so it can shade the
     *  G-buffer's fields (deferred) instead of drawing the meshes again; false for a model that needs faces,
     *  vertices or per-material parameters (flat, gouraud, mtoon). ShadePass::chooseMode() decides. */
    bool perPixel;
    const char* help; ///< --help's description, lines after the first indented by the help writer
};

/** Every model, in the enum's order. */
const std::vector<ShadingModelTraits>& shadingModels();
/** The row of `model`. */
const ShadingModelTraits& traitsOf(ShadingModel model);
/** The row named `name`, or null. */
const ShadingModelTraits* findShadingModel(std::string_view name);
/** "phong and comic": the names of the models whose trait `has` holds, for messages. */
std::string shadingModelsWith(bool ShadingModelTraits::*has);

} // namespace inkgraph
