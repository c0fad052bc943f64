#pragma once
/** @file The `inkgraph render` command line: parsing and help. No GL, no files touched. */

#include "passes/gbuffer/GBufferPrecision.h"
#include "scene/FaceOrientation.h"

#include <glm/glm.hpp>

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace inkgraph {

/** A wrong flag or value. The CLI prints it with a hint to --help and exits with 2. */
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

enum class ShadingMode { None, Flat, Gouraud, Lambert, Phong, Cel, Comic };

/** How one line type is drawn: --<type>-width and --<type>-color. */
struct LineStyle {
    double widthPixels = 2.0;
    glm::dvec4 color{0.0, 0.0, 0.0, 1.0}; ///< display RGBA in [0,1]
};

/** --shard K/N: this process renders the models whose 0-based list position p has p mod N == K. */
struct Shard {
    int index = 0; ///< K, 0 <= K < N (Slurm's SLURM_ARRAY_TASK_ID with --array=0-(N-1))
    int count = 1; ///< N
};

struct RenderOptions {
    std::string modelPath;                  ///< the model of this still (the first MODEL until a batch assigns it)
    std::vector<std::string> modelPaths;    ///< every MODEL argument, in order; with --list, a batch (app/Batch.h)
    std::string listPath;                   ///< --list FILE: more models, one per line ("-": standard input)
    std::optional<Shard> shard;             ///< --shard K/N: this process's share of the models
    std::string outputPath;                 ///< -o; may be empty with --print-plan only
    int width = 1024;
    int height = 1024;
    std::optional<glm::dvec3> eye;
    std::optional<glm::dvec3> target;
    std::optional<glm::dvec3> up;           ///< default: the glTF camera's, else 0,1,0
    std::optional<double> fovYDegrees;      ///< default 35 unless the glTF camera says otherwise
    std::optional<glm::dvec2> clipRange;    ///< --clip NEAR,FAR (0 < near < far); default: fitted to the model
    std::optional<glm::dvec3> towardLight;  ///< world direction toward the light
    ShadingMode shading = ShadingMode::Cel;
    double shininess = 32.0;                ///< phong and comic, [0, 1e6]
    std::optional<int> bands;               ///< cel: N even bands (default: seed 003's five)
    std::string shadeMapPath;               ///< cel (one row) or comic (2-D) PNG; empty = built-in map
    ViewVectorMode viewVector = ViewVectorMode::Exact;                         ///< comic
    FaceOrientationMethod faceOrientation = FaceOrientationMethod::Standard; ///< comic
    int frontRule = 3;                      ///< comic with during-vertices or after-vertices
    std::vector<std::string> lines;         ///< line types in drawing order; empty = none
    std::map<std::string, LineStyle> lineStyles; ///< one per known line type (defaults filled in)
    std::optional<double> silhouetteObjectWidth; ///< model units: the hull is offset in object space
    double creaseAngleDegrees = 30.0;       ///< crease and normal-edge: dihedral / normal angle above this
    double depthJump = 0.05;                ///< contour, suggestive(-object), depth-edge, normal-edge: relative depth break
    std::optional<double> suggestiveThreshold; ///< strength threshold (default: SuggestiveSettings, 0.01)
    std::optional<double> suggestiveFade;      ///< strength fade (default: SuggestiveSettings, 0.03)
    int suggestiveStencil = 3;                 ///< points of the central differences: 3 (fast) or 5 (fourth order)
    int supersample = 1;                    ///< data buffers and edge skeletons at S x the size
    GBufferPrecision gbufferPrecision = GBufferPrecision::Float32; ///< the G-buffer's direction fields
    glm::dvec3 background{1.0, 1.0, 1.0};
    std::vector<std::string> extraOutputs;  ///< --request: extra graph resources kept and dumped ("gbuffer.*")
    std::string dumpDirectory;
    std::string statsPath;
    std::string graphvizPath;               ///< --graphviz: the plan as DOT
    std::string contactSheetPath;           ///< --contact-sheet: every computed buffer in one labelled PNG
    std::string svgPath;                    ///< --svg: the line layers as vector paths
    double svgTolerance = 0.5;              ///< --svg-tolerance: simplification, output pixels
    bool printPlan = false;
    std::string eglPlatform = "auto";       ///< auto, device, surfaceless
    std::optional<std::size_t> memoryLimitBytes; ///< --memory-limit; default: half the machine's memory, >= 1 GiB
    std::string stylePath;                  ///< --style, for the stats (its settings are already in the options)
    bool quiet = false;
    bool help = false;                      ///< --help or -h in a flag's place: print help, do nothing else
};

/** Line types this build knows, in the order they are composited (later ones on top). */
const std::vector<std::string>& knownLineTypes();
/** Line types found in the float G-buffer by the post stage (postfx/). */
bool isImageSpaceLineType(const std::string& type);
/** Line types found on the mesh itself by a CPU pass (per-vertex curvature), hidden with the G-buffer depth. */
bool isObjectSpaceLineType(const std::string& type);
/** Line types drawn from the mesh's edges (the "mesh-edges" pass). */
bool isMeshEdgeLineType(const std::string& type);
/** Every flag that names an output path, with its field, in --help's order: -o, --dump, --stats, --graphviz,
 *  --contact-sheet, --svg. One list for the checks of one still (OutputSet) and of a batch (app/Batch.h). */
const std::vector<std::pair<std::string, std::string RenderOptions::*>>& outputPathFlags();

/** Whether a run renders (-o, --dump, --contact-sheet or --svg) rather than only showing the plan. */
bool rendersImages(const RenderOptions& options);
std::string shadingModeName(ShadingMode mode);
bool usesShadeMap(ShadingMode mode);

/** Parses the arguments after "render". Throws UsageError with a message naming the flag and the bad value.
 *  --help (or -h) where a flag may stand stops parsing and sets `help`; as the value of a flag it is just a value. */
RenderOptions parseRenderOptions(const std::vector<std::string>& arguments);

/** The same, with each argument's origin (app/StyleFile.h): a problem with an argument from a style file is reported
 *  with the file and line first. `origins` is empty or as long as `arguments`. */
RenderOptions parseRenderOptions(const std::vector<std::string>& arguments, const std::vector<std::string>& origins);

/** The text of `inkgraph render --help`. */
std::string renderHelp();
/** The text of `inkgraph --help`. */
std::string mainHelp();

} // namespace inkgraph
