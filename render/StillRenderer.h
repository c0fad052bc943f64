#pragma once
/** @file The renderer of one still, as a library: a model path, a Look and a camera request in, the scene, the plan
 *  and every computed buffer out. No command line and no files written: app/Render.h turns flags into a
 *  StillRequest (the library, api/, turns its typed looks and frames into one) and the result into files
 * (app/StillOutputs.h, app/Stats.h). One StillRenderer keeps one GL context (made by the first still that executes) and
 * one ShaderLibrary that keeps every program, so a batch makes the context once and compiles each program once. */

#include "gl/GraphExecutor.h"
#include "gl/HeadlessContext.h"
#include "gl/ShaderLibrary.h"
#include "gl/TexturePool.h"
#include "graph/Plan.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/Look.h"
#include "passes/StillGraph.h"
#include "passes/shade/ShadeMap.h"
#include "scene/Camera.h"
#include "scene/Scene.h"
#include "scene/SceneDerivedData.h"

#include <cstddef>
#include <iosfwd>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {

/** An input file other than the model (--shademap, a material's map) is missing or unusable; exit code 3 like a bad
 *  model. The message names the flag and the file. */
class InputFileError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/** One buffer must stay under 2 GiB: GL's byte counts are 32-bit (llvmpipe refuses larger RGBA32F targets). */
inline constexpr std::size_t kMaxTextureBytes = std::size_t(2) << 30;

/** Reads and checks a shade map file: 8-bit, 1 to 4 channels, at most 4096 a side (judged from the header before
 *  the pixels are read), one row when `oneDimensional`. Throws InputFileError naming --shademap and the file. */
ShadeMap readShadeMapFile(const std::string& path, bool oneDimensional);

/** The per-still parameters of `camera` for the look (its light, else the file's light, else the default key light;
 *  its ambient light, else the model's default; its background) and the model's bounding sphere. */
FrameParams frameParamsOf(const Look& look, const Scene& scene, const Camera& camera, const BoundingSphere& sphere);

/** --readback. */
enum class ReadbackTiming { Auto, Early, Late };

/** What to render. */
struct StillRequest {
    std::string modelPath;
    /** The model, loaded already (the library's Scene, api/): load() takes it instead of reading `modelPath` again,
     *  which then only names it in messages, and the stills that share it share its data. */
    std::shared_ptr<const Scene> loadedScene;
    /** `loadedScene` is what an earlier still of the batch loaded from `modelPath` with the same load options
     *  (app/RecentModel.h): its warnings are told again, as loading the file would, and --stats says model_reused. */
    bool reusesEarlierLoad = false;
    /** `loadedScene` was loaded with no animation (the library's scene), so `animationTime` clocks only MToon's UV
     *  animation, and time-unused is judged as for a load of the still's own. */
    bool loadedWithoutAnimation = false;
    /** What earlier stills of `loadedScene` derived from it whatever the view (adjacency, curvature, ...), shared with
     *  them; null for a fresh one. Ignored unless it is `loadedScene`'s. */
    std::shared_ptr<SceneDerivedData> loadedSceneDerived;
    Look look;
    CameraRequest camera;                  ///< what the caller fixes; resolveCamera() fills the rest from the file
    std::vector<std::string> extraOutputs; ///< more resources to compute and keep ("gbuffer.*" expands)
    bool keepEveryBuffer = false;          ///< keep every computed buffer (dumps, contact sheets)
    /** What keeps every buffer, for the memory budget's messages ("--dump", "--contact-sheet"). */
    std::vector<std::string> keepEveryBufferFor;
    /** Wait for each pass to finish so its milliseconds are its own (--stats, --dump's manifest); without, the
     *  driver may overlap one pass's drawing with the next pass's submission. */
    bool timePasses = true;
    /** Bounds the model load (scene/Scene.h) and the still's estimated peak (render/MemoryBudget.h budgetStill()). */
    std::size_t memoryLimitBytes = std::size_t(1) << 30;
    bool memoryLimitGiven = false; ///< the limit was asked for (--memory-limit), not the machine's default
    bool loadsImageIo = false;     ///< the outputs load the OpenImageIO module (its libraries count in the budget)
    /** Keep the stroke stage's strokes (StillGraph::strokePathsResource()) for StillGraph::svgLayers() (--svg). */
    bool keepStrokePaths = false;
    /** Keep what StillGraph::strokeRecords() reads (StillGraph::strokePointResources(): --strokes, Still::strokes()).
     */
    bool keepStrokePoints = false;
    std::string animation; ///< LoadOptions::animation: the pose to load
    /** LoadOptions::expressions and lookAt: the VRM face to load. */
    std::vector<ExpressionWeight> expressions;
    std::optional<glm::dvec3> lookAt;
    /** LoadOptions::time, and the render's time (FrameParams::time: MToon's UV animation), even without an
     *  animation. */
    double animationTime = 0.0;
    /** How the caller's messages name `animationTime` and `animation` (time-unused): the flags, or the library's
     *  fields. */
    std::string timeSetting = "--time";
    std::string animationSetting = "--animation";
    /** Every warning fails the still (--strict): a SceneError once the warning is printed, before anything is
     *  written. */
    bool strict = false;
    std::string pose;                             ///< LoadOptions::pose: a VRM humanoid pose to load the model in
    double weldTolerance = kDefaultWeldTolerance; ///< LoadOptions::weldTolerance
    EglPlatform eglPlatform = EglPlatform::Any;
    /** When the host passes' inputs leave the GPU (ExecuteOptions::readBackEarly): early, late, or by the renderer
     *  (late on software rasterizers, early on GPUs). */
    ReadbackTiming readback = ReadbackTiming::Auto;
};

/** The options `request`'s model is loaded with (loadScene()). */
LoadOptions loadOptionsOf(const StillRequest& request);

/** Where a still's progress lines go. */
struct StillLog {
    std::ostream& log;
    bool talks = true;  ///< per-still lines ("loaded ..."); a batch prints its own line per still instead
    bool quiet = false; ///< nothing but warnings

    /** "inkgraph: warning: <warning>", the model named first when the still does not talk (a batch's line). */
    void warn(const std::string& modelPath, const std::string& warning) const;
};

/** A still loaded, framed and planned; nothing executed, no GL touched. Fixed in memory: the graph points at it. */
struct PreparedStill {
    StillRequest request;
    std::shared_ptr<const Scene> loadedScene; ///< read by load(), or the request's
    /** The scene's view-independent derived data: the request's loadedSceneDerived, or a fresh one. */
    std::shared_ptr<SceneDerivedData> sceneDerived;
    double loadMilliseconds = 0.0; ///< 0 for the request's loadedScene
    BoundingSphere sphere;
    Camera camera;
    FrameParams frame;
    std::optional<ShadeMap> shadeMap;                   ///< the request's shade map, read
    std::vector<std::optional<ShadeMap>> meshShadeMaps; ///< per mesh, the map its material names
    std::unique_ptr<GpuScene> gpuScene;
    /** Every warning of this still, as StillLog printed it: the loader's (a loaded scene's too, which its loader
     *  printed), the shade maps', the camera's, and after execute() the textures' decoding. */
    std::vector<Warning> warnings;
    StillGraph graph;
    Plan plan;
    PreparedStill() = default;
    PreparedStill(const PreparedStill&) = delete;
    PreparedStill& operator=(const PreparedStill&) = delete;

    const Scene& scene() const { return *loadedScene; }
};

/** What executing a plan did. The store holds the requested buffers (every computed one with keepEveryBuffer). */
struct StillResult {
    std::unique_ptr<GraphExecutor> executor; ///< its buffers come from, and go back to, the renderer's TexturePool
    std::size_t texturesCreated = 0;         ///< by this still
    std::size_t texturesReused = 0;          ///< taken from an earlier still's (or its own earlier passes')
    std::vector<PassTiming> timings;
    double contextMilliseconds = 0.0; ///< making the context; 0 when reused
    bool contextReused = false;
    std::size_t programsCompiled = 0; ///< by this still
    std::size_t programsReused = 0;   ///< taken from an earlier still of the process
    bool readBackEarly = false;       ///< ExecuteOptions::readBackEarly, as --readback chose it
    ResourceStore& store() { return executor->store(); }
};

class StillRenderer {
public:
    StillRenderer();
    ~StillRenderer();
    StillRenderer(const StillRenderer&) = delete;
    StillRenderer& operator=(const StillRenderer&) = delete;

    /** load() then plan(). */
    std::unique_ptr<PreparedStill> prepare(StillRequest request, const StillLog& log);
    /** Reads the shade maps (the request's and the ones the materials name) and loads the model, unless the request
     *  brings it loaded. Throws SceneError and InputFileError. */
    std::unique_ptr<PreparedStill> load(StillRequest request, const StillLog& log);
    /** Resolves the camera, builds the graph and compiles the plan for the final picture plus what the request keeps.
     *  Warns through `log` of a camera that sees none of the model (modelOutsideView()). Throws UsageError for a
     *  request the scene cannot satisfy (a camera, a --request name). No GL. */
    void plan(PreparedStill& still, const StillLog& log);
    /** Makes the process's GL context now, unless it exists: app/Render.cpp calls it while the model loads on another
     *  thread, so the two overlap. Touches nothing load() uses. Throws HeadlessContextError. */
    void makeContext(EglPlatform platform);
    /** Makes (unless makeContext() did) or reuses the context, checks the frame against the driver, runs the plan. A
     *  plan made before there was a context (the library's first still) with --post-stage auto is built again first
     *  when the context's renderer chooses the other device (passes/PostStage.h). Throws HeadlessContextError,
     * UsageError (the driver's limits, out of memory), GraphError. */
    StillResult execute(PreparedStill& still, const StillLog& log);
    /** execute() in two halves. This one, on the thread that holds the context, runs the plan's GPU part and hands
     *  its host tail the images it reads (GraphExecutor::runUntilHostTail()); runHostTail() finishes the still on
     *  any thread. Throws as execute() does. */
    StillResult executeUntilHostTail(PreparedStill& still, const StillLog& log);
    /** The second half: runs the still's host tail (its post stage) on the calling thread, which need not hold the
     *  context, and fills `result.timings`. Touches nothing of the renderer, so it may overlap the next still's
     *  executeUntilHostTail(). Then says what the post stage found the picture lacks (lines-empty) to `log`, which
     *  must be the still's own while it runs there. Throws as execute() does. */
    static void runHostTail(PreparedStill& still, StillResult& result, const StillLog& log);

    /** A turn at the driver, for GL work of this renderer's stills outside its own calls (a still's GL objects
     *  freed, buffers read back at its commit): held while the context is software (llvmpipe) or not made yet,
     *  empty on a GPU. llvmpipe's contexts are not safe to use at once from several threads (a race inside Mesa
     *  22.3 crashed 3 to 8 of 300 batches of 60 stills on four drawing threads), so on a software renderer the
     *  renderers of one process take turns: makeContext(), executeUntilHostTail(), execute(), dropFreeTextures()
     *  and the destructor take it themselves, and the caller takes it around the rest. Never held while waiting
     *  for another thread. */
    std::unique_lock<std::mutex> driverTurn() const;

    /** Deletes the textures and read-back buffers kept for the next still (none is in use between stills) and makes
     *  the driver free them (TexturePool::returnFreeMemory()), so a batch drawing on several threads can give their
     *  memory to another thread's still. On the thread that holds the context. */
    void dropFreeTextures();

    /** Whether the first still executed tells the context's driver ("inkgraph: llvmpipe ... via EGL device
     *  platform"): a process whose batch draws on several renderers tells it once. */
    bool tellsContext = true;

    /** The context, once a still has executed. */
    const HeadlessContext* context() const { return mContext ? &*mContext : nullptr; }
    HeadlessContext* context() { return mContext ? &*mContext : nullptr; }

private:
    /** executeUntilHostTail() once the context is made and the driver's turn taken. */
    StillResult executeOnContext(PreparedStill& still, const StillLog& log);
    /** plan()'s graph and compile, with --post-stage auto resolved against the context when there is one. */
    void buildGraph(PreparedStill& still);

    /** The driver's turn (driverTurn()) taken by the destructor: declared first, so it is let go of last, once
     *  the context and everything made in it are gone. */
    std::unique_lock<std::mutex> mTeardownTurn;
    std::optional<HeadlessContext> mContext; ///< declared before the programs, so they are deleted first
    /** The stills' buffers, kept from one still to the next: a batch's stills have one size, and a texture made
     *  once is not allocated, page-faulted and cleared by the driver again for every model. */
    TexturePool mTextures;
    std::pair<int, int> mTextureFrame{0, 0}; ///< the frame size mTextures' free textures were made for
    /** Set by makeContext() until the next execute() reports it as that still's context time. */
    std::optional<double> mUnreportedContextMilliseconds;
    ShaderLibrary mShaders;
};

} // namespace inkgraph
