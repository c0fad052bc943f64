#pragma once
/** @file What a still looks like, as plain data: the shading model and its settings, the line types drawn and theirs,
 *  the data resolution and precision, the paper and the light. The renderer (render/StillRenderer.h) and the graph of
 *  one still (passes/StillGraph.h) take this; the command line (flags/Options.h) fills it from flags and style files,
 *  and benchmarks and tests build it directly. */

#include "passes/PostStage.h"
#include "passes/gbuffer/GBufferPrecision.h"
#include "passes/lines/LineParameter.h"
#include "passes/shade/ShadingModel.h"
#include "passes/WidthMap.h"
#include "scene/mesh/FaceOrientation.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** How one line type is drawn: --<type>-width and --<type>-color. */
struct LineStyle {
    double widthPixels = 2.0;
    glm::dvec4 color{0.0, 0.0, 0.0, 1.0}; ///< display RGBA in [0,1]
};

/** How line pixels become strokes (postfx/Strokes.h, docs/lines.md "Strokes"). Lengths are shares of the picture's
 *  height, so the same strokes are drawn at every size. */
struct StrokeStyle {
    /** A chain of strokes shorter than this share of the height is not drawn (--min-stroke-length; 0 keeps all). */
    double minLength = 0.01;
    /** Line weight (--line-weight): width by depth, by strength, tapered ends. */
    bool weightByDepth = false;
    bool weightByStrength = false;
    bool taperEnds = false;
    /** Where two types draw the same line, only the one earlier in the composite's order (--overlapping-lines merge;
     *  off by default: the type giving way keeps only the pieces where the two part, which change with the view). */
    bool mergeOverlaps = false;
    /** --hidden-dash ON,OFF: every hidden-lines type's strokes (LineType::hiddenLines) are cut into dashes ON output
     *  pixels long with gaps OFF long, along their arc length; OFF 0 draws them solid (--hidden-dash none). */
    double hiddenDashOn = 6.0;
    double hiddenDashOff = 4.0;
};

struct Look {
    /** auto: each material its own model (MToon where it has it, else cel); shadingModelFor() resolves it. */
    ShadingModel shading = ShadingModel::Auto;
    double shininess = 32.0;                           ///< phong and comic, [0, 1e6]
    std::optional<int> bands;                          ///< cel: N even bands (default: Qu, Chen & Zwicker's five)
    std::string shadeMapPath;                          ///< cel (one row) or comic (2-D) PNG; empty = built-in map
    ViewVectorMode viewVector = ViewVectorMode::Exact; ///< comic
    FaceOrientationMethod faceOrientation = FaceOrientationMethod::Standard; ///< comic
    int frontRule = 3;              ///< comic with during-vertices or after-vertices
    std::vector<std::string> lines; ///< line types drawn (composited in the registry's order); empty = none
    std::map<std::string, LineStyle> lineStyles; ///< per line type; a type without an entry has LineStyle{}
    LineParameterValues lineParameters;          ///< the line types' other settings (passes/lines/LineParameter.h)
    StrokeStyle strokes;                         ///< how line pixels become strokes, for every type
    int supersample = 1;                         ///< data buffers and edge skeletons at S x the size
    int msaa = 1; ///< samples per pixel of the colour passes (shading, MToon's outline shells): 1, 2, 4 or 8
    GBufferPrecision gbufferPrecision = GBufferPrecision::Float32; ///< the G-buffer's direction fields
    glm::dvec3 background{1.0, 1.0, 1.0};
    std::optional<glm::dvec3> towardLight; ///< world direction toward the light; default: the file's, else a key light
    /** Linear RGB of the uniform ambient light (--ambient), for the models with an ambient term; default: the model's
     *  (ShadingModelTraits::defaultAmbient). */
    std::optional<glm::dvec3> ambient;
    /** --outline-width-map: the outline, silhouette and MToon-outline widths scaled per vertex by a vertex colour or
     *  texture channel (passes/WidthMap.h); Source::None leaves them as they are. */
    WidthMap outlineWidthMap;
    /** --post-stage: where the image-space line kernels run (passes/PostStage.h); Auto is resolved against the GL
     *  renderer when the graph is built (StillGraphSetup::glRenderer). Changes no line beyond 1e-3 px. */
    PostStageDevice postStage = PostStageDevice::Auto;

    bool draws(const std::string& type) const { return std::find(lines.begin(), lines.end(), type) != lines.end(); }
    LineStyle styleOf(const std::string& type) const {
        auto found = lineStyles.find(type);
        return found == lineStyles.end() ? LineStyle{} : found->second;
    }
};

} // namespace inkgraph
