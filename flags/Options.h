#pragma once
/** @file The `inkgraph render` command line: what the flags fill, parsed and explained by the flag table
 *  (flags/FlagTable.h). No GL, no files touched. */

#include "passes/Look.h"
#include "render/DefaultLook.h"
#include "render/UsageError.h"
#include "scene/Camera.h"
#include "scene/Scene.h"
#include "scene/ViewSampling.h"

#include <glm/glm.hpp>

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace inkgraph {

/** --shard K/N: this process renders the models whose 0-based list position p has p mod N == K. */
struct Shard {
    int index = 0; ///< K, 0 <= K < N (Slurm's SLURM_ARRAY_TASK_ID with --array=0-(N-1))
    int count = 1; ///< N
};

/** The command line of `inkgraph render`: the models, the camera, the Look, the outputs and the run's settings. The
 *  renderer takes the parts (Look, CameraRequest); this struct is only what the flags fill. */
/** The cores this process may run on (its CPU affinity; a Slurm task or a container is often given fewer than the
 *  machine has), at least 1. */
int usableCores();

/** --jobs' default's ceiling, however many cores there are: every still in flight holds its memory. */
inline constexpr int kMaxDefaultJobs = 16;

/** --jobs' default: usableCores(), at most kMaxDefaultJobs. */
int defaultJobs();

/** How many threads OpenCV's parallel loops (the line kernels' bands, the composite's rows) get in each still's post
 *  stage while a batch runs `jobs` of them on workers beside the drawing thread: the usable cores shared among those
 *  jobs + 1 threads, at least 1. */
int postStageLoopThreads(int jobs);

/** The largest side of any buffer a render makes (the output times the supersampling): --size's bound, and the
 *  supersampled frame's. */
inline constexpr int kMaxImageSide = 16384;

struct RenderOptions {
    std::string modelPath;               ///< the model of this still (the first MODEL until a batch assigns it)
    std::vector<std::string> modelPaths; ///< every MODEL argument, in order; with --list, a batch (app/Batch.h)
    std::string listPath;                ///< --list FILE: more models, one per line ("-": standard input)
    std::optional<Shard> shard;          ///< --shard K/N: this process's share of the models
    std::string datasetDirectory;        ///< --dataset DIR: the run makes a data set there (app/Dataset.h)
    /** --jobs N: how many stills of a batch may be in their post stage and writing at once while the next draws;
     *  0 finishes each still before the next starts. Default: the cores this process may use. */
    int jobs = defaultJobs();
    /** --draw-threads N: how many threads draw a batch's stills, each with its own GL context; `jobs` is shared
     *  among them. */
    int drawThreads = 1;
    bool resume = false;    ///< --resume: skip the stills of --dataset that are complete
    std::string outputPath; ///< -o; may be empty with --print-plan only
    int width = 1024;
    int height = 1024;
    std::optional<glm::dvec3> eye;
    std::optional<Orbit> orbit; ///< --orbit AZIMUTH,ELEVATION[,DISTANCE]: the eye around the target
    std::optional<glm::dvec3> target;
    std::optional<glm::dvec3> up;        ///< default: the glTF camera's, else 0,1,0
    std::optional<double> fovYDegrees;   ///< default 35, or the glTF camera's when that camera places the view
    std::vector<std::string> frameNodes; ///< --frame NODE[,NODE...]: frame only the meshes under these nodes
    std::optional<glm::dvec2> clipRange; ///< --clip NEAR,FAR (0 < near < far); default: fitted to the model
    bool autoCamera = false;             ///< --camera auto: never the file's camera
    std::string animation;               ///< --animation: a glTF animation's name or index; empty: the rest pose
    double animationTime = 0.0;          ///< --time: seconds into `animation`
    std::string pose;                    ///< --pose: "a-pose" or a pose file (LoadOptions::pose); empty: none
    /** --expression: VRM expressions and their weights. */
    std::vector<ExpressionWeight> expressions;
    /** --look-at: the point a VRM character looks at (world). */
    std::optional<glm::dvec3> lookAt;
    /** --views N and its companions (--seed, --view-elevation, --view-distance-jitter, --light-jitter,
     *  --expressions, --poses): count is N. Used only when viewsGiven. */
    ViewSampling viewSampling;
    bool viewsGiven = false; ///< --views N: each model renders N sampled views (app/Batch.h)
    /** The sampled view of this still (set by app/Batch.h stillOptions() with --views, its orbit, light, expressions
     *  and pose already applied to the fields above), for --stats and the manifest. */
    std::optional<ViewSample> view;
    /** Shading, lines, supersampling, precision, paper, light; the default look (render/DefaultLook.h) draws
     *  lines. */
    Look look = defaultLook();
    /** The hidden-<type> entries --hidden-lines put in look.lines (not those --lines named), so a later --lines keeps
     *  them and a later --hidden-lines replaces them. */
    std::vector<std::string> hiddenLineTypes;
    std::vector<std::string> extraOutputs; ///< --request: extra graph resources kept and dumped ("gbuffer.*")
    std::string dumpDirectory;
    std::string statsPath;
    std::string graphvizPath;     ///< --graphviz: the plan as DOT
    std::string contactSheetPath; ///< --contact-sheet: every computed buffer in one labelled PNG
    std::string svgPath;          ///< --svg: the line layers as vector paths
    std::string strokesPath;      ///< --strokes: every kept stroke with its points' 3-D points, JSON
    double svgTolerance = 0.5;    ///< --svg-tolerance: simplification, output pixels
    bool printPlan = false;
    std::string eglPlatform = "auto";             ///< auto, device, surfaceless
    std::string readback = "auto";                ///< --readback: auto, early, late
    std::optional<std::size_t> memoryLimitBytes;  ///< --memory-limit; default: half the machine's memory, >= 1 GiB
    double weldTolerance = kDefaultWeldTolerance; ///< --weld-distance: LoadOptions::weldTolerance
    std::string stylePath;                        ///< --style, for the stats (its settings are already in the options)
    /** Where a style file gave --shademap ("--style 'F' line N"), for the messages of a map that cannot be read;
     *  empty when the command line gave it. */
    std::string shadeMapOrigin;
    bool quiet = false;
    bool strict = false; ///< --strict: every warning about the model or the view fails the still (exit 3)
    bool help = false;   ///< --help or -h in a flag's place: print help, do nothing else
};

/** Every flag that names an output path, with its field, in --help's order: -o, --dump, --stats, --graphviz,
 *  --contact-sheet, --svg. One list for the checks of one still (OutputSet) and of a batch (app/Batch.h). */
const std::vector<std::pair<std::string, std::string RenderOptions::*>>& outputPathFlags();

/** Whether a run renders (-o, --dump, --contact-sheet or --svg) rather than only showing the plan. */
bool rendersImages(const RenderOptions& options);

/** Each "--NAME=VALUE" of a flag that takes a value as the two arguments "--NAME" and "VALUE", the long-option form
 *  getopt_long() takes as well; "--NAME=VALUE" of a flag that takes none is refused (UsageError "--quiet: takes no
 *  value, got '1'"), and so is "-o=x.png" (a short flag takes its value as the next argument). A flag's own value
 *  is left whole ("-o --a=b.png" writes '--a=b.png'). `origins`, empty or one per argument, are split alongside. */
void separateAttachedValues(std::vector<std::string>& arguments, std::vector<std::string>& origins);

/** How a flag's value is given, and a flag given twice, for --help and the man page. */
inline constexpr const char* kFlagValueForms =
    "A flag's value is the argument after it or follows '=': --size 512x512 or --size=512x512. A flag given twice "
    "keeps its last value; --request and --frame add to their lists.";

/** Parses the arguments after "render" (separateAttachedValues() first). Throws UsageError with a message naming the
 *  flag and the bad value.
 *  --help (or -h) where a flag may stand stops parsing and sets `help`; as the value of a flag it is just a value. */
RenderOptions parseRenderOptions(const std::vector<std::string>& arguments);

/** The same, with each argument's origin (flags/StyleFile.h): a problem with an argument from a style file is reported
 *  with the file and line first. `origins` is empty or as long as `arguments`. */
RenderOptions parseRenderOptions(const std::vector<std::string>& arguments, const std::vector<std::string>& origins);

/** What parseRenderFlags() checks: each flag's value alone (one flag of a list still being built), or that and the
 *  rules between the flags that parseRenderOptions() applies (a flag without effect with the rest, --supersample times
 *  --size, ...). */
enum class FlagChecks { Values, ValuesAndRules };

/** Flags alone, for the library (api/), which takes the model and the outputs otherwise: a MODEL argument or --help is
 *  refused, neither MODEL nor an output is required, and everything `checks` names is checked as parseRenderOptions()
 *  checks it, with the same messages. */
RenderOptions parseRenderFlags(const std::vector<std::string>& arguments, const std::vector<std::string>& origins = {},
                               FlagChecks checks = FlagChecks::ValuesAndRules);

/** The rules between flags that parseRenderFlags() applies with FlagChecks::ValuesAndRules, for options built flag by
 *  flag (the library's typed looks and frames): `given` names each flag given ("--bands"). Throws UsageError. */
void checkFlagRules(const RenderOptions& options, const std::vector<std::string>& given);

/** --views' settings (RenderOptions::viewSampling) with --light, the direction the light jitter turns. */
ViewSampling viewSamplingOf(const RenderOptions& options);

/** The camera the flags ask for (--eye, --orbit, --target, --up, --fov, --clip, --camera, --frame, --size);
 *  resolveCamera() fills the rest. */
CameraRequest cameraRequestOf(const RenderOptions& options);

/** The text of `inkgraph render --help`. */
std::string renderHelp();

} // namespace inkgraph
