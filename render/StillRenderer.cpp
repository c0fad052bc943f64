#include "render/StillRenderer.h"

#include "graph/Milliseconds.h"
#include "render/Messages.h"
#include "scene/MessageText.h"

#include "render/ImageFiles.h"
#include "render/UsageError.h"
#include "render/SceneShadeMaps.h"
#include "passes/lines/LineTypes.h"
#include "passes/shade/ShadingModel.h"
#include "graph/GraphCompiler.h"
#include "scene/MeshLabels.h"
#include "scene/Scene.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <iomanip>
#include <iostream>
#include <new>
#include <optional>

namespace inkgraph {
namespace {

/** Default key light: from the upper left, behind the camera, fixed in view space so every auto-framed still is lit
 *  the same way. */
glm::dvec3 defaultLight(const Camera& camera) {
    const glm::dvec3 towardLightView = glm::normalize(glm::dvec3(-0.4, 0.5, 0.77));
    return glm::normalize(glm::transpose(glm::dmat3(camera.viewMatrix())) * towardLightView);
}

/** "gbuffer.*" -> every image field the pass "gbuffer" declares (objects without a picture are data, not buffers);
 * other names pass through for compile() to check. Throws UsageError for a wildcard on a pass the graph does not have.
 */
std::vector<std::string> expandWildcards(const std::vector<std::string>& requests, const StillGraph& graph) {
    std::vector<std::string> expanded;
    for (const std::string& request : requests) {
        const ResourceName name = ResourceName::split(request);
        if (name.field != "*") {
            expanded.push_back(request);
            continue;
        }
        const Pass* pass = graph.findPass(name.pass);
        if (pass == nullptr) throw UsageError("--request: no pass named '" + name.pass + "' in this render graph");
        PassBuilder builder{name.pass};
        pass->declare(builder);
        for (const auto& write : builder.writes())
            if (write.isImage()) expanded.push_back(name.pass + "." + write.field); // not the strokes' data
    }
    return expanded;
}

/** Checks the frame, and the samples per pixel --msaa asks for, against what the driver can allocate. */
void checkDriverLimits(int width, int height, int msaa, const std::string& driver) {
    // The flag takes 1, 2, 4 or 8; what the driver draws is known only now that there is a context.
    if (msaa > 1 && msaa > maxSamples())
        throw UsageError("--msaa " + std::to_string(msaa) + ": this driver ('" + driver + "') draws at most " +
                         std::to_string(maxSamples()) + " samples per pixel (GL_MAX_SAMPLES)");
    GLint maxTextureSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTextureSize);
    GLint maxViewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
    const int limit = std::min(maxTextureSize, std::min(maxViewport[0], maxViewport[1]));
    if (width > limit || height > limit)
        throw UsageError("--size " + std::to_string(width) + "x" + std::to_string(height) +
                         " exceeds this driver's largest render target side, " + std::to_string(limit));
}

/** Keeps `warning` with the still and prints it; one without a file is about the model. */
void warnOf(PreparedStill& still, Warning warning, const StillLog& log) {
    if (warning.file.empty()) warning.file = still.request.modelPath;
    log.warn(still.request.modelPath, warning.message);
    still.warnings.push_back(std::move(warning));
}

/** time-unused for a --time that moves nothing: no animation poses the model, and no material has a UV animation
 *  for it to clock (the command line took it silently, where the library's SceneOptions::time refuses it). */
std::optional<Warning> unusedTimeWarning(const StillRequest& request, const Scene& scene) {
    if (!request.animation.empty() || request.animationTime == 0.0) return std::nullopt;
    const bool uvAnimated = std::any_of(scene.meshes.begin(), scene.meshes.end(), [](const Mesh& mesh) {
        const std::optional<MToonMaterial>& mtoon = mesh.material.mtoon;
        return mtoon && (mtoon->uvAnimationScrollXSpeedFactor != 0.0f || mtoon->uvAnimationScrollYSpeedFactor != 0.0f ||
                         mtoon->uvAnimationRotationSpeedFactor != 0.0f);
    });
    if (uvAnimated) return std::nullopt;
    return makeWarning(WarningKind::TimeUnused,
                       request.timeSetting + " " + detail::formatNumber(request.animationTime) +
                           " moves nothing: without " + request.animationSetting +
                           " it is only the clock of MToon's UV animation, and no material of the model has one");
}

/** --shading auto settles per model (cel without MToon materials, each material its own with them): the look's
 *  settings the model's materials then leave unused, which the flag checks, not knowing the model, let through. */
std::vector<Warning> unusedLookSettings(const Look& look, const Scene& scene) {
    std::vector<Warning> unused;
    if (look.shading != ShadingModel::Auto) return unused;
    const auto say = [&](const std::string& setting, const std::string& why) {
        unused.push_back(makeWarning(WarningKind::LookSettingUnused,
                                     setting + " changes nothing on this model: --shading auto draws " + why));
    };
    const bool allMToon = !scene.meshes.empty() && std::ranges::all_of(scene.meshes, [](const Mesh& mesh) {
        return mesh.material.mtoon.has_value();
    });
    if (shadingModelFor(look.shading, scene) == ShadingModel::Cel && look.ambient)
        say("--ambient", "it cel-shaded (it has no MToon material), and cel has no ambient term");
    if (allMToon && look.bands) say("--bands", "every material of it as MToon, which has no cel shade map");
    if (allMToon && !look.shadeMapPath.empty())
        say("--shademap", "every material of it as MToon, which has no cel shade map");
    return unused;
}

/** Where the still samples its model: the look's buffers, and whether its lines are drawn from the mesh itself. */
PictureSampling pictureSamplingOf(const Look& look, const Scene& scene) {
    PictureSampling sampling;
    sampling.supersample = look.supersample;
    sampling.msaaSamples = look.msaa;
    // MToon's outline shells: mtoon, or auto where some material has MToon.
    const ShadingModel shading = shadingModelFor(look.shading, scene);
    sampling.linesDrawTheMesh = shading == ShadingModel::MToon || shading == ShadingModel::Auto;
    for (const std::string& name : look.lines)
        if (const LineType* type = findLineType(name))
            sampling.linesDrawTheMesh = sampling.linesDrawTheMesh || type->family == LineFamily::GlDrawn ||
                                        type->family == LineFamily::MeshEdge;
    return sampling;
}

/** --strict: the still's first warning (printed already) as the error that fails it, before anything is written. */
void failIfStrict(const PreparedStill& still) {
    if (!still.request.strict || still.warnings.empty()) return;
    const std::size_t more = still.warnings.size() - 1;
    throw SceneError(
        "--strict: " + detail::quotedFileName(still.request.modelPath) + ": " + still.warnings.front().message +
        (more > 0 ? " (and " + std::to_string(more) + " more warning" + (more > 1 ? "s" : "") + ")" : std::string()));
}

/** Runs `step` (a part of the still's plan), turning what the user can fix into a UsageError: the driver or the
 *  process out of memory at this --size. A pass that failed on the model's own data (a texture it could not decode)
 *  is bad input, as a load error is: the executor nests the SceneError under the pass's name, and the SceneError's
 *  own message names the model and the problem. */
template <class Step>
void runMappingFailures(const PreparedStill& still, Step&& step) {
    const CameraRequest& camera = still.request.camera;
    const std::string size = "--size " + std::to_string(camera.width) + "x" + std::to_string(camera.height);
    const auto processOutOfMemory = [&](const std::string& what) {
        return UsageError(size + " with --supersample " + std::to_string(still.request.look.supersample) +
                          ": out of memory (" + what + "); make the image smaller, or give the process more memory");
    };
    try {
        step();
    } catch (const GlOutOfMemoryError& error) {
        throw UsageError(size + ": the driver ran out of memory (" + error.what() + "); make the image smaller");
    } catch (const OutOfMemoryError& error) {
        throw processOutOfMemory(error.what());
    } catch (const std::bad_alloc& error) {
        // An image of the still's size (a read-back, a kernel's working image) that the process could not allocate.
        throw processOutOfMemory(error.what());
    } catch (const cv::Exception& error) {
        if (error.code == cv::Error::StsNoMem) throw processOutOfMemory(error.err);
        throw;
    } catch (const std::exception& error) {
        try {
            std::rethrow_if_nested(error);
        } catch (const SceneError&) {
            throw;
        } catch (...) {
        }
        throw;
    }
}

} // namespace

ShadeMap readShadeMapFile(const std::string& path, bool oneDimensional) {
    // Every message starts with the flag, as --style's and --list's do: the readers are told to speak for it.
    constexpr const char* kFlag = "--shademap";
    cv::Mat image;
    try {
        // PNG only, by its own reader (fuzz_shademap found OpenEXR allocating 1.6 GB for a 600-byte header), without
        // ancillary chunks (and libpng 1.9 GB for a 342-byte file's tEXt), and the header's size is judged before
        // the pixels are allocated: a map is at most 4096 a side, its file at most 64 MiB (4096² RGBA is 64 MiB raw).
        image = readPngImage(path, std::size_t(kMaxShadeMapSide) * kMaxShadeMapSide, std::size_t(64) << 20, kFlag);
    } catch (const FileError& error) {
        throw InputFileError(error.what());
    }
    if (image.depth() != CV_8U)
        throw InputFileError(std::string(kFlag) + ": " + detail::quotedFileName(path) +
                             " stores 16-bit pixels; a shade map is an 8-bit PNG");
    try {
        return shadeMapFromImage(image, path, oneDimensional, kFlag);
    } catch (const std::invalid_argument& error) {
        throw InputFileError(error.what());
    }
}

FrameParams frameParamsOf(const Look& look, const Scene& scene, const Camera& camera, const BoundingSphere& sphere) {
    FrameParams frame;
    frame.camera = camera;
    frame.worldOrigin = sphere.center;
    frame.towardLightWorld = look.towardLight ? *look.towardLight
                             : scene.light    ? scene.light->towardLight
                                              : defaultLight(camera);
    frame.background = glm::vec4(glm::vec3(look.background), 1.0f);
    frame.ambientLight = look.ambient ? glm::vec3(*look.ambient)
                                      : glm::vec3(traitsOf(shadingModelFor(look.shading, scene)).defaultAmbient);
    // A point (or empty) model has no radius; 1 keeps the radial field finite there.
    frame.radialLengthUnit = sphere.radius > 0.0 ? sphere.radius : 1.0;
    frame.boundScene(scene);
    return frame;
}

void StillLog::warn(const std::string& modelPath, const std::string& warning) const {
    // Bounded like every message (render/Messages.h).
    log << boundedMessage("inkgraph: warning: " + (talks ? "" : detail::quotedFileName(modelPath) + ": ") + warning)
        << "\n";
}

namespace {

/** The one turn at a software driver for every renderer of the process (StillRenderer::driverTurn()). */
std::mutex& softwareDriverMutex() {
    static std::mutex mutex;
    return mutex;
}

} // namespace

StillRenderer::StillRenderer() { mShaders.keepPrograms(true); }

StillRenderer::~StillRenderer() {
    if (mContext) mTeardownTurn = driverTurn();
}

std::unique_lock<std::mutex> StillRenderer::driverTurn() const {
    if (mContext && !mContext->isSoftware()) return {};
    return std::unique_lock<std::mutex>(softwareDriverMutex());
}

std::unique_ptr<PreparedStill> StillRenderer::prepare(StillRequest request, const StillLog& log) {
    std::unique_ptr<PreparedStill> still = load(std::move(request), log);
    plan(*still, log);
    return still;
}

LoadOptions loadOptionsOf(const StillRequest& request) {
    LoadOptions options;
    options.memoryLimitBytes = request.memoryLimitBytes;
    options.animation = request.animation;
    options.time = request.animationTime;
    options.pose = request.pose;
    options.expressions = request.expressions;
    options.lookAt = request.lookAt;
    options.weldTolerance = request.weldTolerance;
    return options;
}

std::unique_ptr<PreparedStill> StillRenderer::load(StillRequest request, const StillLog& log) {
    auto still = std::make_unique<PreparedStill>();
    still->request = std::move(request);
    const StillRequest& req = still->request;
    const Look& look = req.look;
    const ShadingModelTraits& shading = traitsOf(look.shading);
    if (!look.shadeMapPath.empty()) still->shadeMap = readShadeMapFile(look.shadeMapPath, shading.oneDimensionalMap);

    if (req.loadedScene) {
        still->loadedScene = req.loadedScene;
    } else {
        const auto loadStart = std::chrono::steady_clock::now();
        still->loadedScene = std::make_shared<const Scene>(loadScene(req.modelPath, loadOptionsOf(req)));
        still->loadMilliseconds = millisecondsSince(loadStart);
    }
    // A scene given loaded had its warnings told by whoever loaded it, unless it stands for this still's own load.
    // The still carries them likewise: a library's scene carries its own (Scene::warnings()), which every still of
    // it repeated.
    if (!req.loadedScene || req.reusesEarlierLoad) {
        for (const Warning& warning : still->scene().report.warnings) log.warn(req.modelPath, warning.message);
        still->warnings = still->scene().report.warnings;
    }
    const Scene& scene = still->scene();
    still->sceneDerived = req.loadedSceneDerived && &req.loadedSceneDerived->scene() == &scene
                              ? req.loadedSceneDerived
                              : std::make_shared<SceneDerivedData>(scene);
    if (log.talks && !log.quiet && !req.loadedScene) {
        log.log << std::fixed << std::setprecision(1) << "inkgraph: loaded " << detail::quotedFileName(req.modelPath)
                << ": " << scene.triangleCount() << " triangles, " << scene.vertexCount() << " vertices ("
                << scene.report.degenerateDropped << " degenerate dropped"
                << (scene.report.repeatedDropped > 0
                        ? "; " + std::to_string(scene.report.repeatedDropped) + " given twice dropped"
                        : std::string())
                << (scene.report.backToBackDropped > 0
                        ? "; " + std::to_string(scene.report.backToBackDropped) +
                              " back to back with another of a two-sided material dropped"
                        : std::string())
                << (scene.report.backToBackOneSided > 0
                        ? "; " + std::to_string(scene.report.backToBackOneSided) +
                              " back to back with another side of their own drawn from the front only"
                        : std::string())
                << ") in " << still->loadMilliseconds << " ms\n";
    }

    // The maps the model's materials name (glTF extras), each file read once; exit 3 like --shademap.
    std::vector<Warning> shadeMapWarnings;
    still->meshShadeMaps = readSceneShadeMaps(scene, look.shading, &shadeMapWarnings);
    for (Warning& warning : shadeMapWarnings) warnOf(*still, std::move(warning), log);
    for (Warning& warning : unusedLookSettings(look, scene)) warnOf(*still, std::move(warning), log);
    // Judged where the still stands for its own load: only then is `animation` the one the scene was loaded with.
    if (!req.loadedScene || req.reusesEarlierLoad || req.loadedWithoutAnimation)
        if (std::optional<Warning> unused = unusedTimeWarning(req, scene)) warnOf(*still, std::move(*unused), log);
    failIfStrict(*still);
    return still;
}

void StillRenderer::plan(PreparedStill& still, const StillLog& log) {
    const StillRequest& req = still.request;
    const Look& look = req.look;
    const Scene& scene = still.scene();

    still.sphere = computeBoundingSphere(scene);
    try {
        still.camera = resolveCamera(req.camera, scene);
    } catch (const std::invalid_argument& error) {
        throw UsageError(error.what()); // the loader has validated the file's camera: what is left is the flags
    }
    if (std::optional<Warning> outside = modelOutsideView(still.camera, scene, pictureSamplingOf(look, scene)))
        warnOf(still, std::move(*outside), log);
    failIfStrict(still);
    still.frame = frameParamsOf(look, scene, still.camera, still.sphere);
    still.frame.time = req.animationTime; // the pose's time is the UV animation's too
    still.gpuScene = makeSceneImport(scene, still.sphere.center, still.frame, look, still.sceneDerived);
    buildGraph(still);
    // Any G-buffer's (the picture's, or the coarser one the suggestive contours read at 2048 rows and above); the
    // barycentric field's alpha is a triangle id too.
    const bool readsTriangleIds =
        std::any_of(still.plan.resources.begin(), still.plan.resources.end(), [](const PlannedResource& resource) {
            const std::string field = ResourceName::split(resource.name).field;
            return field == "triangleId" || field == "barycentric";
        });
    if (readsTriangleIds)
        if (std::optional<Warning> inexact = triangleIdWarning(TriangleNumbering(scene).total()))
            warnOf(still, std::move(*inexact), log);
    failIfStrict(still);
}

void StillRenderer::buildGraph(PreparedStill& still) {
    const StillRequest& req = still.request;
    StillGraphSetup setup{req.look,        mShaders,    still.scene(), still.sphere,
                          *still.gpuScene, still.frame, still.shadeMap};
    setup.meshShadeMaps = still.meshShadeMaps;
    // --post-stage auto decides by the GL renderer: the command line makes the context before it plans a still that
    // renders; a plan made without one (nothing to render, or the library's first still) takes the CPU kernels, and
    // execute() builds it again if the context it makes chooses the GPU.
    if (mContext) setup.glRenderer = mContext->renderer();
    still.graph = buildStillGraph(setup);

    std::vector<std::string> requested = {still.graph.finalResource};
    if (req.keepStrokePaths && !still.graph.strokePathsResource().empty())
        requested.push_back(still.graph.strokePathsResource());
    if (req.keepStrokePoints)
        for (const std::string& resource : still.graph.strokePointResources())
            if (std::find(requested.begin(), requested.end(), resource) == requested.end())
                requested.push_back(resource);
    for (const std::string& extra : expandWildcards(req.extraOutputs, still.graph))
        if (std::find(requested.begin(), requested.end(), extra) == requested.end()) requested.push_back(extra);
    try {
        still.plan = still.graph.compilePlan(requested);
    } catch (const GraphError& error) {
        // The registered passes are consistent (tests/graph, tests/app); a problem here comes from --request.
        throw UsageError(std::string("--request: ") + error.what());
    }
}

void StillRenderer::makeContext(EglPlatform platform) {
    if (mContext) return;
    const std::lock_guard<std::mutex> turn(softwareDriverMutex()); // the renderer is not known yet
    HeadlessContextOptions contextOptions;
    contextOptions.platform = platform;
    const auto contextStart = std::chrono::steady_clock::now();
    mContext.emplace(contextOptions);
    mUnreportedContextMilliseconds = millisecondsSince(contextStart);
}

StillResult StillRenderer::executeUntilHostTail(PreparedStill& still, const StillLog& log) {
    makeContext(still.request.eglPlatform);
    const std::unique_lock<std::mutex> turn = driverTurn();
    StillResult result = executeOnContext(still, log);
    // The rasterizer's threads done too before another renderer takes the turn.
    if (turn.owns_lock()) glFinish();
    return result;
}

StillResult StillRenderer::executeOnContext(PreparedStill& still, const StillLog& log) {
    StillResult result;
    // One context for every still of the process: the first that renders makes it (the platform is the same for all
    // of them), later ones find it current with the programs the earlier ones compiled.
    makeContext(still.request.eglPlatform);
    result.contextReused = !mUnreportedContextMilliseconds.has_value();
    if (!result.contextReused) {
        result.contextMilliseconds = *mUnreportedContextMilliseconds;
        mUnreportedContextMilliseconds.reset();
        if (!log.quiet && tellsContext) log.log << "inkgraph: " << mContext->describe() << "\n";
    }
    const CameraRequest& camera = still.request.camera;
    checkDriverLimits(camera.width, camera.height, still.request.look.msaa, mContext->renderer());
    if (resolvePostStage(still.request.look.postStage, mContext->renderer()) != still.graph.postStageDevice)
        buildGraph(still); // planned before the context: the same passes, the kernels on the device auto now takes
    const std::size_t programsCompiledBefore = mShaders.compiledCount();
    const std::size_t programsReusedBefore = mShaders.reusedCount();

    // Another size (a batch has one) would find nothing to reuse: the free textures of the last size go.
    if (mTextureFrame != std::make_pair(camera.width, camera.height)) {
        mTextures.dropFree();
        mTextureFrame = {camera.width, camera.height};
    }
    const std::size_t texturesCreatedBefore = mTextures.createdCount();
    const std::size_t texturesReusedBefore = mTextures.reusedCount();
    result.executor = std::make_unique<GraphExecutor>(mTextures);
    ExecuteOptions executeOptions;
    executeOptions.frameWidth = camera.width;
    executeOptions.frameHeight = camera.height;
    executeOptions.keepAllResources = still.request.keepEveryBuffer;
    executeOptions.waitForEachPass = still.request.timePasses;
    // On llvmpipe a read-back into a pixel-pack buffer waits on this thread as a direct one does, and then costs a
    // second copy (the comic batch of docs/performance.md: 15% slower); on a GPU the copy overlaps later passes.
    executeOptions.readBackEarly = still.request.readback == ReadbackTiming::Early ||
                                   (still.request.readback == ReadbackTiming::Auto && !mContext->isSoftware());
    result.readBackEarly = executeOptions.readBackEarly;
    // The scene data the live passes import is derived once, before they prepare (passes/GpuScene.h).
    GpuScene& gpuScene = *still.gpuScene;
    executeOptions.importData = [&gpuScene](const std::string& name) { gpuScene.importDerived(name); };
    runMappingFailures(
        still, [&] { result.executor->runUntilHostTail(still.plan, still.graph.mutableView(), executeOptions); });
    // What decoding the textures had to say (an image shrunk to the driver's largest texture), as the loader's
    // warnings.
    for (const Warning& warning : still.gpuScene->materials().warnings()) warnOf(still, warning, log);
    // A line type the user asked for that this view left out (the eye inside the model) is said, not just missing.
    for (Warning& warning : still.graph.lineWarnings()) warnOf(still, std::move(warning), log);
    failIfStrict(still);
    result.texturesCreated = mTextures.createdCount() - texturesCreatedBefore;
    result.texturesReused = mTextures.reusedCount() - texturesReusedBefore;
    result.programsCompiled = mShaders.compiledCount() - programsCompiledBefore;
    result.programsReused = mShaders.reusedCount() - programsReusedBefore;
    return result;
}

StillResult StillRenderer::execute(PreparedStill& still, const StillLog& log) {
    StillResult result = executeUntilHostTail(still, log);
    runHostTail(still, result, log);
    return result;
}

void StillRenderer::runHostTail(PreparedStill& still, StillResult& result, const StillLog& log) {
    runMappingFailures(still, [&] { result.timings = result.executor->runHostTail(); });
    // A line type the user's settings left without a visible stroke is said, not just missing.
    for (Warning& warning : still.graph.emptyLineWarnings()) warnOf(still, std::move(warning), log);
    failIfStrict(still);
}

void StillRenderer::dropFreeTextures() {
    const std::unique_lock<std::mutex> turn = driverTurn();
    mTextures.returnFreeMemory();
}

} // namespace inkgraph
