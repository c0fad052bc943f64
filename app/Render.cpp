#include "app/Render.h"

#include "render/ImageFiles.h"
#include "render/InputFiles.h"
#include "render/MemoryBudget.h"
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

} // namespace

void requireStandardOutputWritten(std::ostream& out) {
    errno = 0;
    out.flush();
    if (!out || (&out == &std::cout && (std::fflush(stdout) != 0 || std::ferror(stdout))))
        throw FileError(std::string("renderStill(): cannot write the standard output") +
                        (errno ? std::string(": ") + std::strerror(errno) : ""));
}

std::size_t memoryLimitOf(const RenderOptions& options) {
    return options.memoryLimitBytes ? *options.memoryLimitBytes : defaultMemoryLimit();
}

StillRequest stillRequestOf(const RenderOptions& options) {
    StillRequest request;
    request.modelPath = options.modelPath;
    request.look = options.look;
    request.camera = cameraRequestOf(options);
    request.extraOutputs = options.extraOutputs;
    // --dump and --contact-sheet show every buffer the plan computed, so the executor keeps them all.
    if (!options.dumpDirectory.empty()) request.keepEveryBufferFor.push_back("--dump");
    if (!options.contactSheetPath.empty()) request.keepEveryBufferFor.push_back("--contact-sheet");
    request.keepEveryBuffer = !request.keepEveryBufferFor.empty();
    request.keepStrokePaths = !options.svgPath.empty();
    request.keepStrokePoints = !options.strokesPath.empty();
    // Per-pass milliseconds are only shown by --stats and --dump's manifest: other stills let passes overlap.
    request.timePasses = !options.statsPath.empty() || !options.dumpDirectory.empty();
    request.memoryLimitBytes = memoryLimitOf(options);
    request.memoryLimitGiven = options.memoryLimitBytes.has_value();
    request.loadsImageIo = outputsUseImageIoModule(options);
    request.animation = options.animation;
    request.animationTime = options.animationTime;
    request.strict = options.strict;
    request.pose = options.pose;
    request.expressions = options.expressions;
    request.lookAt = options.lookAt;
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

StillReport RenderSession::render(const RenderOptions& options, const StillBatchPosition* batch,
                                  CommitListener committed) {
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
    outputs->refuseInputs(inputsFoundByLoading(options.modelPath, still->scene()));
    mRenderer.plan(*still, log);

    const Plan& plan = still->plan;
    if (options.printPlan) {
        mOut << plan.describe() << still->graph.describeShading(plan);
        requireStandardOutputWritten(mOut); // before the commit: a run that fails puts no file in place
    }
    if (!options.graphvizPath.empty()) outputs->stageGraphviz(plan.graphviz());
    if (!renders) {
        outputs->commit();
        if (committed) committed({describeCamera(still->camera), describeLook(*still, options.stylePath)});
        return report;
    }
    budgetStill(*still);

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
        const MemoryEstimate estimate = estimateStill(*still);
        context.estimatedPeakBytes = estimate.total();
        context.estimatedTextureBytes = estimate.textures;
        pending->stats = statsDocument(context, mRenderer, *still, result);
    }
    if (committed) {
        pending->committed = std::move(committed);
        pending->description = {describeCamera(still->camera), describeLook(*still, options.stylePath)};
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
    if (pending->committed) pending->committed(pending->description);
    if (pending->talks) {
        mLog << "inkgraph: rendered " << pending->size << " in " << totalMilliseconds << " ms";
        if (!pending->outputPath.empty()) mLog << " -> '" << pending->outputPath << "'";
        mLog << "\n";
    }
}

} // namespace inkgraph
