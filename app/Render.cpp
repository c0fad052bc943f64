#include "app/Render.h"

#include "app/ImageFiles.h"
#include "app/MemoryBudget.h"
#include "app/OutputFiles.h"
#include "app/StillOutputs.h"

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <future>
#include <iostream>

#include <unistd.h>

namespace inkgraph {
namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/** The whole run's peak for the plan, as an upper bound (app/MemoryBudget.h): the process, the scene, every GL target
 *  as llvmpipe stores it, and the post stage's read-backs, working images and encoders at their largest moment.
 *  Without the scene (not loaded yet) its meshes add nothing. */
std::size_t estimatePlanBytes(const Plan& plan, const RenderOptions& options, const Scene* scene) {
    return estimateRunMemory(plan, options, scene ? sceneSizeOf(*scene) : SceneSize{}).total();
}

/** --dump and --contact-sheet show every buffer the plan computed, so the executor keeps them all. */
bool keepsEveryBuffer(const RenderOptions& options) {
    return !options.dumpDirectory.empty() || !options.contactSheetPath.empty();
}

/** llvmpipe stores textures in 64x64 tiles, so a side is rounded up before its size is judged. */
std::size_t paddedSide(int side) { return (std::size_t(side) + 63) / 64 * 64; }

/** Refuses sizes that would fail deep inside the driver or outgrow the process's memory: one texture of 2 GiB or more
 *  (GL's byte counts are 32-bit), or a whole run estimated above the memory limit. Both name every flag that makes
 *  the buffers that large (--size, and --supersample for the supersampled ones), not only --size. */
void checkFrameBudget(const Plan& plan, const RenderOptions& options, const Scene* scene = nullptr) {
    for (const PlannedResource& resource : plan.resources) {
        const std::size_t textureBytes = paddedSide(options.width * resource.desc.scale) *
                                         paddedSide(options.height * resource.desc.scale) *
                                         std::size_t(bytesPerPixel(resource.desc.format));
        if (textureBytes < kMaxTextureBytes) continue;
        const std::string size = "--size " + std::to_string(options.width) + "x" + std::to_string(options.height);
        const std::string cause = resource.desc.scale > 1
                                      ? size + " with --supersample " + std::to_string(resource.desc.scale) + " (" +
                                            std::to_string(options.width * resource.desc.scale) + "x" +
                                            std::to_string(options.height * resource.desc.scale) + ")"
                                      : size;
        throw UsageError(cause + " makes '" + resource.name + "' " + std::to_string(textureBytes >> 20) +
                         " MiB; one buffer must stay under 2048 MiB (at most 11584x11584 for float RGBA)");
    }
    const std::size_t needed = estimatePlanBytes(plan, options, scene);
    const std::size_t bound = memoryLimitOf(options);
    const std::size_t neededMib = (needed + (1 << 20) - 1) >> 20; // rounded up: "needs 600" never fits a 600 limit
    if (needed > bound)
        throw UsageError(memoryDriversText(plan, options) + " needs about " + std::to_string(neededMib) +
                         " MiB for the whole run; the memory limit is " + std::to_string(bound >> 20) + " MiB" +
                         (options.memoryLimitBytes ? " (--memory-limit)" : ", half this machine's memory") +
                         " (make the image smaller, lower --supersample, or request or dump fewer buffers)");
}

} // namespace

void requireStandardOutputWritten(std::ostream& out) {
    errno = 0;
    out.flush();
    if (!out || (&out == &std::cout && (std::fflush(stdout) != 0 || std::ferror(stdout))))
        throw FileError(std::string("renderStill(): cannot write the standard output") +
                        (errno ? std::string(": ") + std::strerror(errno) : ""));
}

std::vector<RunInput> inputsFoundByLoading(const RenderOptions& options, const Scene& scene) {
    // Appended, not "'" + name: GCC 12 warns falsely (-Wrestrict, bug 105329) on that inlined.
    std::string model = "'";
    model.append(std::filesystem::path(options.modelPath).filename().string()).append("'");
    std::vector<RunInput> inputs;
    for (const std::string& file : scene.report.inputFiles)
        inputs.push_back({file, "a file the model " + model + " reads"});
    for (const Mesh& mesh : scene.meshes)
        if (!mesh.material.shadeMapPath.empty())
            inputs.push_back({mesh.material.shadeMapPath, "the shade map of mesh '" + mesh.name + "' of " + model});
    return inputs;
}

std::size_t memoryLimitOf(const RenderOptions& options) {
    if (options.memoryLimitBytes) return *options.memoryLimitBytes;
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long pageSize = ::sysconf(_SC_PAGE_SIZE);
    const std::size_t physical = pages > 0 && pageSize > 0 ? std::size_t(pages) * std::size_t(pageSize) : 0;
    return std::max<std::size_t>(physical / 2, std::size_t(1) << 30);
}

CameraRequest cameraRequestOf(const RenderOptions& options) {
    CameraRequest request;
    request.eye = options.eye;
    request.orbit = options.orbit;
    request.target = options.target;
    request.frameNodes = options.frameNodes;
    request.up = options.up;
    request.fovYDegrees = options.fovYDegrees;
    request.ignoreFileCamera = options.autoCamera;
    if (options.clipRange) {
        request.zNear = options.clipRange->x;
        request.zFar = options.clipRange->y;
    }
    request.width = options.width;
    request.height = options.height;
    return request;
}

void budgetStill(PreparedStill& still, const RenderOptions& options) {
    checkFrameBudget(still.plan, options, &still.scene());
    // The textures are decoded during the run, only those a pass samples: they get what the estimate leaves.
    const std::size_t estimated = estimatePlanBytes(still.plan, options, &still.scene());
    const std::size_t limit = memoryLimitOf(options);
    still.gpuScene->materials().setTextureMemoryLimit(limit > estimated ? limit - estimated : 0);
}

StillRequest stillRequestOf(const RenderOptions& options) {
    StillRequest request;
    request.modelPath = options.modelPath;
    request.look = options.look;
    request.camera = cameraRequestOf(options);
    request.extraOutputs = options.extraOutputs;
    request.keepEveryBuffer = keepsEveryBuffer(options);
    request.keepStrokePaths = !options.svgPath.empty();
    // Per-pass milliseconds are only shown by --stats and --dump's manifest: other stills let passes overlap.
    request.timePasses = !options.statsPath.empty() || !options.dumpDirectory.empty();
    request.memoryLimitBytes = memoryLimitOf(options);
    request.animation = options.animation;
    request.animationTime = options.animationTime;
    if (options.eglPlatform == "device") request.eglPlatform = EglPlatform::Device;
    if (options.eglPlatform == "surfaceless") request.eglPlatform = EglPlatform::Surfaceless;
    return request;
}

std::unique_ptr<PreparedStill> RenderSession::loadWhileMakingContext(StillRequest request, bool renders,
                                                                     const StillLog& log) {
    const EglPlatform platform = request.eglPlatform;
    // The model loads on a second thread while this one makes the GL context (the first still of a process only;
    // the context must be current here, where the passes run). Neither touches what the other does.
    std::future<std::unique_ptr<PreparedStill>> loading =
        std::async(std::launch::async, [this, &request, &log] { return mRenderer.load(std::move(request), log); });
    std::exception_ptr contextFailure;
    if (renders) {
        try {
            mRenderer.makeContext(platform);
        } catch (...) {
            contextFailure = std::current_exception();
        }
    }
    // A bad model is reported before a missing driver, as when the two ran one after the other.
    std::unique_ptr<PreparedStill> still = loading.get();
    if (contextFailure) std::rethrow_exception(contextFailure);
    return still;
}

StillReport RenderSession::render(const RenderOptions& options, const StillBatchPosition* batch) {
    const auto processStart = std::chrono::steady_clock::now();
    const bool renders = rendersImages(options);
    // In a batch the progress line per still replaces the lines of one still.
    const bool talks = !options.quiet && batch == nullptr;
    const StillLog log{mLog, talks, options.quiet};
    // Only a run that writes other formats than PNG (or a dump) loads OpenImageIO; its ~0.2 s of dynamic linking then
    // overlaps loading the model and making the context, though Mesa's own library loading waits for the dynamic
    // loader's lock meanwhile, so such runs still pay part of it.
    if (outputsUseImageIoModule(options)) preloadImageIo();
    StillReport report;

    // Every output place is checked before any work; outputs are staged and put in place only at the end.
    auto outputs = std::make_unique<OutputSet>(options);
    std::unique_ptr<PreparedStill> still = loadWhileMakingContext(stillRequestOf(options), renders, log);
    report.triangles = still->scene().triangleCount();
    outputs->refuseInputs(inputsFoundByLoading(options, still->scene()));
    mRenderer.plan(*still, log);

    const Plan& plan = still->plan;
    if (options.printPlan) {
        mOut << plan.describe() << still->graph.describeShading(plan);
        requireStandardOutputWritten(mOut); // before the commit: a run that fails puts no file in place
    }
    if (!options.graphvizPath.empty()) outputs->stageGraphviz(plan.graphviz());
    if (!renders) {
        outputs->commit();
        return report;
    }
    budgetStill(*still, options);

    StillResult result = mRenderer.execute(*still, log);
    // The previous still of a batch is finished now: its picture was encoded while this one loaded and rendered.
    finishPending();
    const auto writeStart = std::chrono::steady_clock::now();
    auto pending = std::make_unique<PendingStill>();
    stageStillOutputs(options, *still, result, *outputs);
    if (!options.outputPath.empty()) {
        // The picture is a CPU image the store shares with this thread; encoding it needs nothing else.
        const cv::Mat picture = result.store().image(still->graph.finalResource);
        pending->encoding = std::async(std::launch::async, [picture, path = std::filesystem::path(options.outputPath)] {
            const auto encodeStart = std::chrono::steady_clock::now();
            EncodedPicture encoded{encodeImageFile(path, picture), 0.0};
            encoded.milliseconds = millisecondsSince(encodeStart);
            return encoded;
        });
    }
    if (!options.statsPath.empty()) {
        StatsContext context{options, batch};
        context.estimatedPeakBytes = estimatePlanBytes(plan, options, &still->scene());
        pending->stats = statsDocument(context, mRenderer, *still, result);
    }
    pending->outputs = std::move(outputs);
    pending->outputPath = options.outputPath;
    pending->size = std::to_string(options.width) + "x" + std::to_string(options.height);
    pending->talks = talks;
    pending->stagedMilliseconds = millisecondsSince(writeStart);
    pending->renderedMilliseconds = millisecondsSince(processStart);
    report.milliseconds = pending->renderedMilliseconds;
    mPending = std::move(pending);
    // One still alone is finished at once, once its GL objects and meshes are freed while the picture is encoded; in
    // a batch the next still finishes it, the caller the last one (finishPending()).
    if (batch == nullptr) {
        result = StillResult{};
        still.reset();
        finishPending();
    }
    return report;
}

void RenderSession::finishPending() {
    if (!mPending) return;
    const std::unique_ptr<PendingStill> pending = std::move(mPending);
    double writeMilliseconds = pending->stagedMilliseconds;
    if (pending->encoding.valid()) {
        const EncodedPicture encoded = pending->encoding.get();
        const auto stageStart = std::chrono::steady_clock::now();
        pending->outputs->stageFinalImage(encoded.bytes);
        writeMilliseconds += encoded.milliseconds + millisecondsSince(stageStart);
    }
    // The still's own time: up to the hand-over, plus its writing (not the next still's work it overlapped).
    const double totalMilliseconds = pending->renderedMilliseconds - pending->stagedMilliseconds + writeMilliseconds;
    if (pending->stats)
        pending->outputs->stageStats(finishedStatsText(*pending->stats, writeMilliseconds, totalMilliseconds));
    pending->outputs->commit();
    if (pending->talks) {
        mLog << "inkgraph: rendered " << pending->size << " in " << totalMilliseconds << " ms";
        if (!pending->outputPath.empty()) mLog << " -> '" << pending->outputPath << "'";
        mLog << "\n";
    }
}

} // namespace inkgraph
