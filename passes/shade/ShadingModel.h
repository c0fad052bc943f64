#pragma once
/** @file The shading models: one enum and one trait table. Everything that asks "does this model take a shade map,
 *  a shininess, face-orientation methods, can it shade the G-buffer, does the shade pass do more than its shader
 *  branch?" (the flag table, the shade pass, the stats) reads the table, so a new
 *  model is one row here plus its branch in shaders/shade/shade.frag. */

#include <string>
#include <string_view>
#include <vector>

namespace inkgraph {

struct Scene;

enum class ShadingModel { None, Flat, Gouraud, Lambert, Phong, Cel, Comic, MToon, Auto };

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
     *  vertices or per-material parameters (flat, gouraud, mtoon). ShadePass::forwardReason() decides. */
    bool perPixel;
    /** The work ShadePass does for the model beyond its shader branch, asked of these traits and never of the model:
     *  constantView: --view-vector may give Winnemöller & Bangay's constant view vector V_c (checked unit, a uniform,
     *  VIEW_CONSTANT; deferred then reads no gbuffer.view); orientationSets: with a CPU face-orientation method the
     *  front sets are drawn with the CPU's per-vertex (s, t) (SHADE_COORDS); specularRowBands: the 2-D map's specular
     *  rows are found by comparisons (SPECULAR_ROW_BANDS, ShadeMap.h specularRowBands()); materialOutlines: the
     *  materials' own outlines (MToon) are drawn by the mtoon-outline pass and laid into the shading. */
    bool constantView;
    bool orientationSets;
    bool specularRowBands;
    bool materialOutlines;
    /** It has an ambient term, which --ambient sets (FrameParams::ambientLight): flat, gouraud, lambert and phong
     *  light base x (ambient + (1 - ambient) max(n.l, 0)); mtoon (and auto's MToon materials) add MToon's global
     *  illumination ambient x lit colour, and mtoon's metallic-roughness materials ambient x diffuse colour. */
    bool ambient;
    /** The ambient light when --ambient is not given (grey). The normalised models' 0.15 keeps the lit side at the
     *  base colour; the MToon family's 0.05 is the reference scene of the MToon conformance suite (three.js ambient
     *  light 0.5 x 0.3, i.e. 0.15 / pi of irradiance), where the lit side adds it. 0 for the models without one. */
    float defaultAmbient;
    const char* help; ///< --help's description, lines after the first indented by the help writer
};

/** Every model, in the enum's order. */
const std::vector<ShadingModelTraits>& shadingModels();
/** The row of `model`. */
const ShadingModelTraits& traitsOf(ShadingModel model);
/** The row named `name`, or null. */
const ShadingModelTraits* findShadingModel(std::string_view name);
/** The model a still of `scene` runs for `requested`: auto stays auto where some material has MToon and is cel where
 *  none has (the same picture, and cel may then shade the G-buffer); every other model is itself. */
ShadingModel shadingModelFor(ShadingModel requested, const Scene& scene);
/** "phong and comic": the names of the models whose trait `has` holds, for messages. */
std::string shadingModelsWith(bool ShadingModelTraits::*has);

} // namespace inkgraph
