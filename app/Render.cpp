#include "app/Render.h"

#include "app/OutputFiles.h"
#include "app/StillOutputs.h"
#include "graph/Milliseconds.h"
#include "render/ImageFiles.h"
#include "render/InputFiles.h"
#include "render/MemoryBudget.h"
#include "scene/MessageText.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <future>
#include <iostream>

#include <nlohmann/json.hpp>
#include <unistd.h>

namespace inkgraph {

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
    request.weldTolerance = options.weldTolerance;
    request.expressions = options.expressions;
    request.lookAt = options.lookAt;
    if (options.readback == "early") request.readback = ReadbackTiming::Early;
    if (options.readback == "late") request.readback = ReadbackTiming::Late;
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

/** Frees what `owned` holds when it leaves its scope: declared after a lock, so the object goes while it is held. */
template <typename T>
struct FreedOnLeaving {
    std::unique_ptr<T>& owned;
    ~FreedOnLeaving() { owned.reset(); }
};

/** What the worker did for one still: its host tail, then its picture encoded when the picture was on the CPU. */
struct RenderSession::TailOutcome {
    bool staged = false; ///< the -o file encoded and written beside its place (OutputSet::stageFinalImage()) here
    double tailMilliseconds = 0.0;
    double encodeMilliseconds = 0.0; ///< encoding and staging
};

/** A still that has drawn: everything it needs until its commit. Made and destroyed on the thread that calls
 *  render(), which holds the context its GL objects (the scene's buffers, the graph's programs, the store's
 *  textures) belong to; the worker only runs the host tail and encodes. */
struct RenderSession::PendingStill {
    RenderOptions options;
    /** A batch's still tells its warnings when it is finished, before its progress line, whatever ran meanwhile. */
    std::shared_ptr<std::ostringstream> log;
    std::optional<StillBatchPosition> batch;
    std::unique_ptr<PreparedStill> still;
    StillResult result;
    std::unique_ptr<OutputSet> outputs;
    StillCallbacks callbacks;
    StillReport report;
    bool talks = false;
    std::size_t estimatedBytes = 0;
    double drawnMilliseconds = 0.0; ///< from the still's start to the hand-off
    /** Last, so it is destroyed first: its destructor waits for the worker, which uses the members above. */
    std::future<TailOutcome> tail;
};

RenderSession::RenderSession(std::ostream& out, std::ostream& log, int jobs, SessionShare share)
    : mOut(out), mLog(log), mJobs(jobs), mShare{share.index, std::max(share.count, 1), share.ledger} {
    mRenderer.tellsContext = mShare.index == 0;
}

RenderSession::~RenderSession() {
    // A batch stopped by an error: the stills in flight are dropped uncommitted, but their workers must end before
    // what they use is freed (each future's destructor waits), and their GL objects go while the context lives.
    for (const auto& pending : mPending) pending->tail.wait();
    {
        const std::unique_lock<std::mutex> driver = mRenderer.driverTurn();
        mPending.clear();
    }
    if (mTidying.valid()) mTidying.wait();
    if (mPrefetch && mPrefetch->still.valid()) mPrefetch->still.wait();
    if (mShare.ledger) {
        // The other drawing threads' stills may have this session's memory once it is freed.
        mPrefetch.reset();
        try {
            if (mRenderer.context()) mRenderer.dropFreeTextures();
        } catch (...) { // the context goes with the renderer next, and its textures with it
        }
        mShare.ledger->update(mShare.index, {});
    }
}

bool RenderSession::prefetches(const RenderOptions* next, bool renders) const {
    return next != nullptr && mJobs > 0 && renders && rendersImages(*next);
}

StillRequest RenderSession::requestTakingRecentModel(const RenderOptions& options,
                                                     std::optional<RecentModel::Key>& key) {
    StillRequest request = stillRequestOf(options);
    key = RecentModel::keyOf(request);
    RecentModel::Model recent = mRecentModel.find(key);
    request.loadedScene = std::move(recent.scene);
    request.loadedSceneDerived = std::move(recent.derived);
    request.reusesEarlierLoad = request.loadedScene != nullptr;
    if (!request.reusesEarlierLoad) mRecentModel.forget();
    return request;
}

void RenderSession::prefetch(const RenderOptions& next) {
    if (mPrefetch && mPrefetch->still.valid()) mPrefetch->still.wait(); // one ahead at most; an unused one is dropped
    mPrefetch.reset();
    auto log = std::make_shared<std::ostringstream>();
    std::optional<RecentModel::Key> key;
    StillRequest request = requestTakingRecentModel(next, key);
    std::future<std::unique_ptr<PreparedStill>> still =
        std::async(std::launch::async, [this, log, request = std::move(request), quiet = next.quiet]() mutable {
            // StillRenderer::load() reads files and builds the scene: nothing the drawing thread touches.
            return mRenderer.load(std::move(request), StillLog{*log, false, quiet});
        });
    mPrefetch = Prefetch{&next, next.modelPath, std::move(key), log, std::move(still)};
}

std::size_t RenderSession::bytesInFlight() const {
    std::size_t bytes = 0;
    for (const auto& pending : mPending) bytes += pending->estimatedBytes;
    return bytes;
}

StillReport RenderSession::render(const RenderOptions& options, const StillBatchPosition* batch,
                                  StillCallbacks callbacks, const RenderOptions* next) {
    const auto processStart = std::chrono::steady_clock::now();
    // In a batch the progress line per still replaces the lines of one still.
    const bool talks = !options.quiet && batch == nullptr;
    // A batch's still keeps what it has to say until it is finished (PendingStill::log).
    auto stillLog = batch ? std::make_shared<std::ostringstream>() : nullptr;
    const StillLog log{stillLog ? *stillLog : mLog, talks, options.quiet};
    StillTurns* const turns = callbacks.turns;
    const std::size_t turn = callbacks.turn;
    try {
        return renderStill(options, batch, std::move(callbacks), next, log, stillLog, processStart);
    } catch (...) {
        tellHoldings(); // a still let in that failed holds nothing now
        // An earlier still's commit failed, which stops the batch (its turns stopped in finishOldest()): that is the
        // error, and the stills in flight after it are the caller's to finish and tell, not to throw in its place.
        if (stillLog && mFinishingFailure && mFinishingFailure == std::current_exception()) {
            if (turns) turns->enter(turn);
            tellLog(stillLog.get());
            throw;
        }
        // The stills before it are told first, then what this one had to say, in its turn; the caller tells its
        // failure and leaves the turn.
        if (stillLog) {
            try {
                finishPending();
            } catch (...) {
                // An earlier still's commit failed, which stops the batch: the stills in flight here will not take
                // their turns, so none may wait for them.
                if (turns) {
                    turns->stop();
                    turns->enter(turn);
                }
                tellLog(stillLog.get());
                throw;
            }
            if (turns) turns->enter(turn);
            tellLog(stillLog.get());
        }
        throw;
    }
}

StillReport RenderSession::renderStill(const RenderOptions& options, const StillBatchPosition* batch,
                                       StillCallbacks callbacks, const RenderOptions* next, const StillLog& log,
                                       const std::shared_ptr<std::ostringstream>& stillLog,
                                       std::chrono::steady_clock::time_point processStart) {
    const bool renders = rendersImages(options);
    const bool talks = log.talks;
    // Only a run that writes other formats than PNG (or a dump) loads OpenImageIO; its ~0.2 s of dynamic linking then
    // overlaps loading the model and making the context, though Mesa's own library loading waits for the dynamic
    // loader's lock meanwhile, so such runs still pay part of it.
    if (outputsUseImageIoModule(options)) preloadImageIo();
    finishDueStills();
    StillReport report;

    // Every output place is checked before any work; outputs are staged and put in place only at the end.
    auto outputs = std::make_unique<OutputSet>(options);
    std::unique_ptr<PreparedStill> still;
    std::optional<RecentModel::Key> modelKey;
    if (mPrefetch && mPrefetch->options == &options && mPrefetch->modelPath == options.modelPath && renders &&
        mRenderer.context() != nullptr) {
        Prefetch prefetched = std::move(*mPrefetch);
        mPrefetch.reset();
        // The load ends first: its thread writes the log until then, and read before, a warning it had yet to write
        // was lost (a data race; a sanitized CI run dropped one still's warning). Told before get() rethrows a
        // failed load's error, as before.
        prefetched.still.wait();
        log.log << prefetched.log->str(); // its warnings, in this still's place
        still = prefetched.still.get();
        modelKey = std::move(prefetched.modelKey);
    } else {
        // One load at a time: a model loaded ahead for another still is waited for and dropped.
        if (mPrefetch && mPrefetch->still.valid()) mPrefetch->still.wait();
        mPrefetch.reset();
        StillRequest request = requestTakingRecentModel(options, modelKey);
        // The process's first still: the next model loads too while the context is made, which keeps one core
        // busy for 80 ms on llvmpipe while this model takes a fraction of that on the other; the same model (the
        // next view) is taken from this still's load instead, below.
        if (mRenderer.context() == nullptr && prefetches(next, renders) &&
            !(modelKey && RecentModel::keyOf(stillRequestOf(*next)) == modelKey))
            prefetch(*next);
        still = loadWhileMakingContext(std::move(request), renders, log);
    }
    mRecentModel.remember(modelKey, {still->loadedScene, still->sceneDerived});
    // The next model loads while this still plans, draws and waits for its read-backs.
    if (prefetches(next, renders) && !(mPrefetch && mPrefetch->options == next)) prefetch(*next);
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
        finishPending(); // commits stay in the order of the stills
        const StillTurn turn(callbacks.turns, callbacks.turn);
        outputs->commit();
        if (callbacks.committed)
            callbacks.committed({describeCamera(still->camera), describeLook(*still, options.stylePath)});
        tellLog(stillLog.get());
        report.milliseconds = millisecondsSince(processStart);
        if (callbacks.finished) callbacks.finished(report);
        return report;
    }
    budgetStill(*still);
    // The stills in flight hold their memory until they finish: the oldest finish first until this one fits too. A
    // still in flight holds its model (meshes and textures) and its CPU images; the process's baseline is counted once
    // and the GL targets go back to the shared pool at the hand-off, so this still's need is what budgetStill()
    // judges, and the model loading ahead is counted with the stills in flight.
    const MemoryEstimate estimate = estimateStill(*still);
    const std::size_t neededBytes = estimate.total() - estimate.textures;
    const std::size_t heldBytes = estimate.scene + estimate.cpuImages + estimate.textures;
    mAheadBytes = mPrefetch ? heldBytes : 0; // the next model's size is not known yet: this one's
    if (mShare.ledger) {
        // While it waits it holds its model, loaded (its textures are decoded only when it draws).
        waitForMemory(callbacks.turn, callbacks.turns, estimate.baseline, neededBytes - estimate.baseline,
                      estimate.scene);
    } else {
        while (!mPending.empty() && bytesInFlight() + mAheadBytes + neededBytes > still->request.memoryLimitBytes)
            finishOldest();
    }

    StillResult result;
    try {
        result = mRenderer.executeUntilHostTail(*still, log);
    } catch (...) {
        const std::unique_lock<std::mutex> driver = mRenderer.driverTurn(); // its GL objects go in a turn too
        still.reset();
        throw;
    }
    auto pending = std::make_unique<PendingStill>();
    pending->options = options;
    pending->log = stillLog;
    if (batch) pending->batch = *batch;
    pending->still = std::move(still);
    pending->result = std::move(result);
    pending->outputs = std::move(outputs);
    pending->callbacks = std::move(callbacks);
    pending->report = report;
    pending->talks = talks;
    pending->estimatedBytes = heldBytes;
    pending->drawnMilliseconds = millisecondsSince(processStart);
    // At most `jobs` stills in their post stage at once: the oldest finish (in order) before this one starts its own.
    while (!mPending.empty() && mPending.size() >= std::size_t(std::max(mJobs, 1))) finishOldest();
    PendingStill& handed = *pending;
    // The still's own log (a batch's buffered, PendingStill::log keeps it), which only the tail writes while it runs.
    const auto runTail = [&handed, tailLog = log] {
        TailOutcome outcome;
        const auto tailStart = std::chrono::steady_clock::now();
        StillRenderer::runHostTail(*handed.still, handed.result, tailLog);
        outcome.tailMilliseconds = millisecondsSince(tailStart);
        const std::string& finalResource = handed.still->graph.finalResource;
        // A picture the host tail made is encoded here; one still on the GPU is read back by the context's thread.
        if (!handed.options.outputPath.empty() && !handed.result.store().holdsTexture(finalResource)) {
            const auto encodeStart = std::chrono::steady_clock::now();
            // Staged here too: its write and fsync (1-2 ms on a VM's disk) then wait on this worker, not on the
            // drawing thread, which only renames it into place at the commit, in the stills' order.
            handed.outputs->stageFinalImage(
                encodeImageFile(handed.options.outputPath, handed.result.store().image(finalResource)));
            outcome.staged = true;
            outcome.encodeMilliseconds = millisecondsSince(encodeStart);
        }
        return outcome;
    };
    if (mJobs > 0 && batch != nullptr) {
        pending->tail = std::async(std::launch::async, runTail);
    } else {
        std::promise<TailOutcome> done; // no worker: the tail runs here, its failure kept for finishOldest()
        try {
            done.set_value(runTail());
        } catch (...) {
            done.set_exception(std::current_exception());
        }
        pending->tail = done.get_future();
    }
    mPending.push_back(std::move(pending));
    // Handed over: its GL targets are back in the pool, which keeps them for the next still.
    mPoolBytes = estimate.glTargets;
    tellHoldings();
    if (batch == nullptr || mJobs == 0) finishPending();
    return report;
}

void RenderSession::tellHoldings(std::size_t waitingBytes) {
    if (mShare.ledger == nullptr) return;
    MemoryHoldings holdings;
    holdings.working = bytesInFlight();
    if (!mPending.empty()) holdings.earliestStill = mPending.front()->callbacks.turn;
    holdings.sheddable = mPoolBytes + (mPrefetch ? mAheadBytes : 0);
    holdings.waiting = waitingBytes;
    mShare.ledger->update(mShare.index, holdings);
}

void RenderSession::waitForMemory(std::size_t turn, StillTurns* turns, std::size_t baselineBytes,
                                  std::size_t drawingBytes, std::size_t waitingBytes) {
    MemoryLedger& ledger = *mShare.ledger;
    for (;;) {
        if (turns && turns->stopped()) ledger.stop(); // the stills before this one may never ask
        tellHoldings(waitingBytes);
        MemoryHoldings drawing;
        // This still's need counts its GL targets, which the pool's free textures become, and the model loading ahead.
        drawing.working = bytesInFlight() + drawingBytes;
        drawing.earliestStill = mPending.empty() ? turn : std::min(turn, mPending.front()->callbacks.turn);
        drawing.sheddable = mPrefetch ? mAheadBytes : 0;
        if (ledger.tryLetIn(turn, mShare.index, drawing, baselineBytes, !mPending.empty())) return;
        if (!mPending.empty()) {
            // The oldest of this session's stills comes before this one: it finishes in its turn, which cannot wait
            // for this still (only stills before it hold memory this one waits for).
            finishOldest();
            continue;
        }
        if (ledger.shouldShed() && (mPoolBytes > 0 || mPrefetch)) {
            // Another still before this one needs what this session keeps while it waits.
            shedKeptMemory();
            continue;
        }
        ledger.waitForChange(mShare.index, std::chrono::milliseconds(20));
    }
}

void RenderSession::shedKeptMemory() {
    if (mPoolBytes == 0 && !mPrefetch) return;
    // The pool's textures go, and the model loaded ahead is dropped (its still loads it again when it draws).
    mRenderer.dropFreeTextures();
    mPoolBytes = 0;
    if (mPrefetch && mPrefetch->still.valid()) mPrefetch->still.wait();
    mPrefetch.reset();
    tellHoldings();
}

void RenderSession::tellLog(std::ostringstream* stillLog) {
    if (stillLog == nullptr) return;
    mLog << stillLog->str();
    stillLog->str(std::string()); // told once, though render() may still tell it on a failure
}

void RenderSession::finishPending() {
    while (!mPending.empty()) finishOldest();
    if (mTidying.valid()) mTidying.wait(); // the run's files are as the user will find them
}

void RenderSession::finishDueStills() {
    while (!mPending.empty()) {
        const PendingStill& oldest = *mPending.front();
        if (oldest.callbacks.turns == nullptr || !oldest.callbacks.turns->isDue(oldest.callbacks.turn) ||
            oldest.tail.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
            return;
        finishOldest();
    }
}

void RenderSession::finishOldest() {
    // Its turn may wait for another drawing thread's still before it, and that still for memory this session only
    // keeps (its texture pool, a model loaded ahead), which it would never let go of while it waits here: neither
    // would move (3 of 8 runs of six models on three threads under a tight --memory-limit hung). So it lets go first.
    const PendingStill& oldest = *mPending.front();
    if (mShare.ledger && oldest.callbacks.turns && !oldest.callbacks.turns->isDue(oldest.callbacks.turn))
        shedKeptMemory();
    try {
        finishOldestStill();
    } catch (...) {
        tellHoldings(); // its memory is freed either way
        throw;
    }
    tellHoldings();
}

void RenderSession::finishOldestStill() {
    std::unique_ptr<PendingStill> pending = std::move(mPending.front());
    mPending.pop_front();
    // Told and committed in its turn (several drawing threads), after every still before it.
    const StillTurn turn(pending->callbacks.turns, pending->callbacks.turn);
    pending->tail.wait(); // its worker uses no GL: waited for before the driver's turn is taken
    // The commit reads buffers back and the still's GL objects are freed: both in a turn at the driver
    // (StillRenderer::driverTurn()), the still freed before the turn is let go of.
    const std::unique_lock<std::mutex> driver = mRenderer.driverTurn();
    const FreedOnLeaving<PendingStill> freed{pending};
    TailOutcome outcome;
    try {
        outcome = pending->tail.get();
    } catch (const SceneError& error) {
        // Bad input found in the post stage is that still's failure, told in its place among the others.
        tellLog(pending->log.get());
        if (!pending->callbacks.failed) throw;
        pending->callbacks.failed(error);
        return;
    } catch (const InputFileError& error) {
        tellLog(pending->log.get());
        if (!pending->callbacks.failed) throw;
        pending->callbacks.failed(error);
        return;
    } catch (...) {
        tellLog(pending->log.get());
        stopFor(*pending);
        throw;
    }
    try {
        commitFinished(*pending, outcome);
    } catch (...) {
        tellLog(pending->log.get()); // its warnings before the error that stops the batch
        stopFor(*pending);
        throw;
    }
}

void RenderSession::stopFor(const PendingStill& pending) {
    mFinishingFailure = std::current_exception();
    // Stopped while this still holds its turn, so no still after it takes one first and is taken for the first error.
    if (pending.callbacks.turns) pending.callbacks.turns->stop(mFinishingFailure);
}

void RenderSession::commitFinished(PendingStill& pending, TailOutcome& outcome) {
    const RenderOptions& options = pending.options;
    PreparedStill& still = *pending.still;
    StillResult& result = pending.result;
    OutputSet& outputs = *pending.outputs;
    const auto writeStart = std::chrono::steady_clock::now();
    stageStillOutputs(options, still, result, outputs);
    if (!options.outputPath.empty() && !outcome.staged)
        outputs.stageFinalImage(encodeImageFile(options.outputPath, result.store().image(still.graph.finalResource)));
    // The still's own time: its drawing, its post stage and its writing, not the other stills' work it overlapped.
    const double writeMilliseconds = outcome.encodeMilliseconds + millisecondsSince(writeStart);
    const double totalMilliseconds = pending.drawnMilliseconds + outcome.tailMilliseconds + writeMilliseconds;
    if (!options.statsPath.empty()) {
        StatsContext context{options, pending.batch ? &*pending.batch : nullptr};
        const MemoryEstimate estimate = estimateStill(still);
        context.estimatedPeakBytes = estimate.total();
        context.estimatedTextureBytes = estimate.textures;
        context.estimatedMeshBytes = estimate.meshes();
        context.estimatedDerivedBytes = estimate.derived;
        outputs.stageStats(
            finishedStatsText(statsDocument(context, mRenderer, still, result), writeMilliseconds, totalMilliseconds));
    }
    outputs.commit();
    // In a pipelined batch the files the commit replaced (a rerun's) are freed on another thread: on the VM's disk
    // that took about 0.6 ms a picture of the drawing thread (22 ms of the 36-still comic batch rerun into its
    // outputs). One at a time.
    if (mJobs == 0) {
        outputs.removeReplaced();
    } else {
        if (mTidying.valid()) mTidying.wait();
        mTidying =
            std::async(std::launch::async, [committed = std::move(pending.outputs)] { committed->removeReplaced(); });
    }
    if (pending.callbacks.committed)
        pending.callbacks.committed({describeCamera(still.camera), describeLook(still, options.stylePath)});
    tellLog(pending.log.get());
    if (pending.talks) {
        mLog << "inkgraph: rendered " << options.width << "x" << options.height << " in " << totalMilliseconds << " ms";
        if (!options.outputPath.empty()) mLog << " -> " << detail::quotedFileName(options.outputPath);
        mLog << "\n";
    }
    pending.report.milliseconds = totalMilliseconds;
    if (pending.callbacks.finished) pending.callbacks.finished(pending.report);
}

} // namespace inkgraph
