#include "app/BatchRun.h"

#include "graph/Milliseconds.h"
#include "render/BackgroundThreads.h"
#include "render/MemoryBudget.h"
#include "render/Messages.h"
#include "scene/MessageText.h"
#include "render/UsageError.h"

#include "app/Batch.h"
#include "app/Cli.h"
#include "app/Dataset.h"
#include "app/MemoryLedger.h"
#include "app/Render.h"
#include "scene/Scene.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <iomanip>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace inkgraph {
namespace {

/** "'models/x.vrm'", with --views "'models/x.vrm' view 04": a still in progress lines and the summary. */
std::string stillLabel(const BatchStill& still, const RenderOptions& options) {
    std::string label = detail::quotedFileName(still.model.path);
    if (still.view) {
        const std::string last = std::to_string(options.viewSampling.count - 1);
        std::string view = std::to_string(still.viewIndex);
        if (view.size() < last.size()) view.insert(0, last.size() - view.size(), '0');
        label += " view " + view;
    }
    return label;
}

/** "; 3 failed: 'a.obj', 'b.obj', 'c.obj'" for the summary line, or "" when none failed. A data set's batch may fail
 *  by the thousand (a folder of broken files): the first kFailedStillsNamed are named, the rest counted, as each
 *  failure's own line above has named it already. */
std::string failedStillsText(const std::vector<std::string>& failed) {
    constexpr std::size_t kFailedStillsNamed = 10;
    if (failed.empty()) return "";
    std::string text = "; " + std::to_string(failed.size()) + " failed:";
    const std::size_t named = std::min(failed.size(), kFailedStillsNamed);
    for (std::size_t i = 0; i < named; ++i) text += (i == 0 ? " " : ", ") + failed[i];
    if (failed.size() > named) text += " and " + std::to_string(failed.size() - named) + " more (named above)";
    return text;
}

/** A still left to render, known before the first so each still can name the next (its model then loads while this
 *  one draws). */
struct StillToRender {
    std::size_t index = 0; ///< into the batch's stills
    RenderOptions options;
    std::string digest; ///< a data set's settings digest
};

/** The stills of the list to render: all of them, less those --resume finds complete (counted in `skipped`). */
std::vector<StillToRender> stillsToRender(const RenderOptions& options, const BatchList& list,
                                          const std::vector<BatchStill>& stills, DatasetRun* dataset,
                                          std::size_t& skipped) {
    std::vector<StillToRender> toRender;
    for (std::size_t i = 0; i < stills.size(); ++i) {
        StillToRender still{i, stillOptions(options, stills[i], list.total), {}};
        if (dataset) {
            const StillKey key{stills[i].model.path, stills[i].model.position, stills[i].viewIndex};
            still.digest = dataset->settingsDigest(key, still.options);
            if (dataset->isComplete(key, still.digest)) {
                ++skipped;
                continue;
            }
        }
        toRender.push_back(std::move(still));
    }
    return toRender;
}

/** What every drawing thread of a batch shares: the stills and where each one's outcome is told. */
struct BatchShared {
    const RenderOptions& options;
    const BatchList& list;
    const std::vector<BatchStill>& stills;
    const std::vector<StillToRender>& toRender;
    std::ostream& log;
    DatasetRun* dataset;
    std::vector<std::string>& failed;
    int& exitCode;
    StillTurns* turns;    ///< several drawing threads: the order the stills are told in; else null
    MemoryLedger* ledger; ///< several drawing threads: the memory limit they share; else null
};

/** An error after the one that stopped the batch, told (one thread at a time: the turns have stopped). */
void tellError(const BatchShared& batch, std::exception_ptr error) {
    try {
        std::rethrow_exception(error);
    } catch (const std::exception& other) {
        const StillTurn turn(batch.turns, batch.toRender.size());
        batch.log << boundedMessage(std::string("inkgraph: error: ") + other.what()) + "\n"; // one write, one line
    } catch (...) {
    }
}

/** An error that stops the batch, as it is told: a UsageError (a setting this still cannot be drawn with, above all a
 *  memory limit, which depends on the model) gets the still's "[k/n] 'model'" in front, so a batch says which still
 *  it stopped at; any other error is told as it is. */
std::exception_ptr namingTheStill(std::exception_ptr error, const std::string& still) {
    try {
        std::rethrow_exception(error);
    } catch (const UsageError& usage) {
        return std::make_exception_ptr(UsageError(still + ": " + usage.what()));
    } catch (...) {
    }
    return error;
}

/** The stills in flight are finished after an error that stops the batch, so no completed still's outputs are lost.
 *  Their own failures, if any, are told. */
void finishAfterError(RenderSession& session, const BatchShared& batch) {
    for (;;) {
        try {
            session.finishPending();
            break;
        } catch (const std::exception&) {
            tellError(batch, std::current_exception());
        }
    }
}

/** MemoryLedger::pass() for a still when render() returns or throws (nothing without a ledger, or once let in). */
struct PassedOnLeaving {
    MemoryLedger* ledger;
    std::size_t still;
    ~PassedOnLeaving() {
        if (ledger) ledger->pass(still);
    }
};

/** Renders the stills first, first + step, ... of `toRender` in `session` (each model's views one after the other),
 *  each still's post stage and writing overlapping the next stills' drawing, and finishes them all. Every still's
 *  progress line or failure is told in list order, when it is finished. Bad input stops one still, not the batch:
 *  its label goes to `failed`. With a data set each committed still is journaled. */
void renderShare(const BatchShared& batch, std::size_t first, std::size_t step, RenderSession& session) {
    const std::vector<StillToRender>& toRender = batch.toRender;
    DatasetRun* const dataset = batch.dataset;
    for (std::size_t k = first; k < toRender.size(); k += step) {
        if (batch.turns && batch.turns->stopped()) break; // another thread's error stops the batch
        const BatchStill& batchStill = batch.stills[toRender[k].index];
        const RenderOptions& still = toRender[k].options;
        const StillKey key{batchStill.model.path, batchStill.model.position, batchStill.viewIndex};
        const std::string label = stillLabel(batchStill, batch.options);
        const std::string place =
            "[" + std::to_string(toRender[k].index + 1) + "/" + std::to_string(batch.stills.size()) + "] " + label;
        const std::string counter = "inkgraph: " + place;
        const auto fail = [&batch, dataset, counter, label, key, still](const std::exception& error) {
            batch.log << boundedMessage(counter + " failed: " + error.what()) + "\n";
            batch.failed.push_back(label);
            if (dataset) dataset->recordFailed(key, still, error.what());
            if (batch.exitCode == kExitOk) batch.exitCode = kExitBadInput;
        };
        try {
            StillCallbacks callbacks;
            if (dataset) {
                dataset->makeOutputFolders(still);
                callbacks.committed = [dataset, key, still, digest = toRender[k].digest](const CommittedStill& done) {
                    dataset->recordCommitted(key, still, digest, done.camera, done.look);
                };
            }
            callbacks.finished = [&log = batch.log, counter, quiet = batch.options.quiet,
                                  outputPath = still.outputPath](const StillReport& report) {
                if (quiet) return;
                log << counter;
                if (!outputPath.empty()) log << " -> " << detail::quotedFileName(outputPath);
                log << ": " << report.triangles << " triangles, " << std::fixed << std::setprecision(0)
                    << report.milliseconds << " ms\n";
            };
            callbacks.failed = fail;
            callbacks.turns = batch.turns;
            callbacks.turn = k;
            const StillBatchPosition position{batchStill.model.position, batch.list.total};
            // A still that fails before it draws, or draws nothing, lets the stills after it ask for memory.
            const PassedOnLeaving passed{batch.ledger, k};
            session.render(still, &position, std::move(callbacks),
                           k + step < toRender.size() ? &toRender[k + step].options : nullptr);
        } catch (const SceneError& error) {
            // Bad input stops one still, not the batch: the other stills' work is not lost. The stills before it
            // are told first; render() returned holding this still's turn.
            session.finishPending();
            const StillTurn turn(batch.turns, k);
            fail(error);
        } catch (const InputFileError& error) {
            session.finishPending();
            const StillTurn turn(batch.turns, k);
            fail(error);
        } catch (...) {
            const std::exception_ptr stop = namingTheStill(std::current_exception(), place);
            if (!batch.turns) std::rethrow_exception(stop); // the caller finishes the stills in flight
            // Any other error stops the batch, on every drawing thread. The first is kept before the turn goes on
            // (the caller throws it once every thread is done); this thread finishes what it has in flight.
            const bool firstToStop = batch.turns->stop(stop);
            batch.turns->leave(k); // render() may have returned holding it
            if (!firstToStop) tellError(batch, stop);
            finishAfterError(session, batch);
            return;
        }
    }
    session.finishPending();
}

/** --draw-threads N: the stills dealt out in turn to N threads, each drawing in a session of its own (its GL context
 *  made, used and destroyed on that thread), told and committed in the list's order (StillTurns). The first error
 *  that stops the batch is thrown once every thread has finished what it had in flight; later ones are told. */
void renderInThreads(const BatchShared& shared, std::ostream& out, int drawThreads) {
    StillTurns turns;
    BatchShared batch = shared;
    batch.turns = &turns;
    const int threads = int(std::min<std::size_t>(std::size_t(drawThreads), batch.toRender.size()));
    // The process and every GL context after the first are held whatever the stills need: when they alone pass the
    // limit, no still could keep to it (sixteen threads under --memory-limit 115 peaked at 227 MiB).
    const std::size_t limit = memoryLimitOf(batch.options);
    const std::size_t fixedBytes = std::size_t(threads - 1) * extraContextBytes();
    if (processBaselineBytes() + fixedBytes > limit) {
        const std::size_t mib = 1024 * 1024;
        const std::size_t fitting =
            limit > processBaselineBytes() ? 1 + (limit - processBaselineBytes()) / extraContextBytes() : 1;
        throw UsageError("--draw-threads " + std::to_string(drawThreads) + ": the process (about " +
                         std::to_string(processBaselineBytes() / mib) + " MiB) and " + std::to_string(threads - 1) +
                         (threads == 2 ? " more GL context (about " : " more GL contexts (about ") +
                         std::to_string(extraContextBytes() / mib) + " MiB each) need about " +
                         std::to_string((processBaselineBytes() + fixedBytes) / mib) +
                         " MiB before any still, above the memory limit of " + std::to_string(limit / mib) +
                         " MiB (--memory-limit); draw on at most " + std::to_string(fitting) +
                         (fitting == 1 ? " thread" : " threads") + ", or raise the limit");
    }
    MemoryLedger ledger(limit, threads, fixedBytes);
    batch.ledger = &ledger;
    const int jobsEach = batch.options.jobs == 0 ? 0 : std::max(1, (batch.options.jobs + threads - 1) / threads);
    // The batch stops on the first error; any other is told, as the errors of the stills finished after it are.
    const auto stopBy = [&turns, &batch](std::exception_ptr error) {
        if (!turns.stop(error)) tellError(batch, error);
    };
    const auto draw = [&](std::size_t first) {
        try {
            RenderSession session(out, batch.log, jobsEach, SessionShare{int(first), threads, &ledger});
            try {
                renderShare(batch, first, std::size_t(threads), session);
            } catch (...) {
                stopBy(std::current_exception());
                finishAfterError(session, batch);
            }
        } catch (...) { // the session's own start or end failed
            stopBy(std::current_exception());
        }
    };
    std::vector<std::thread> drawers;
    try {
        for (int thread = 1; thread < threads; ++thread) drawers.emplace_back(draw, std::size_t(thread));
    } catch (...) { // no thread to draw a share: the batch stops, and the threads started finish what they began
        stopBy(std::current_exception());
    }
    draw(0);
    for (std::thread& drawer : drawers) drawer.join();
    if (const std::exception_ptr error = turns.firstError()) std::rethrow_exception(error);
}

} // namespace

int renderBatch(const RenderOptions& options, std::istream& standardInput, std::ostream& out, std::ostream& log,
                const std::vector<std::string>& givenArguments, const std::vector<std::string>& expandedArguments) {
    const BatchList list = batchList(options, standardInput);
    checkBatchOutputs(options, list);
    const std::vector<BatchStill> stills = batchStills(options, list);
    // One still reads its files as it loads; checking them first would only read them twice.
    if (stills.size() > 1) checkBatchInputs(options);
    std::unique_ptr<DatasetRun> dataset;
    if (!options.datasetDirectory.empty())
        dataset = std::make_unique<DatasetRun>(options, list, stills, givenArguments, expandedArguments);
    RenderSession session(out, log, options.jobs);
    const std::string share = options.shard
                                  ? " (shard " + std::to_string(options.shard->index) + "/" +
                                        std::to_string(options.shard->count) + " of " + std::to_string(list.total) + ")"
                                  : "";
    // Only --shard can leave a share empty (a list of no models is refused): with N above the list's length some
    // shards have nothing to do, which is not an error in an array job.
    if (list.models.empty()) {
        if (!options.quiet) log << "inkgraph: no models in this share" << share << "\n";
        if (dataset) dataset->finish(log); // an empty index and card: check-dataset then sees every shard
        return kExitOk;
    }
    // A data set's still goes the batch's way even alone: a bad model is recorded as failed in its index.
    if (!list.isBatch && !dataset) {
        session.render(stillOptions(options, stills.front(), list.total));
        return kExitOk;
    }
    // The stills' post stages run on `jobs` workers beside the drawing thread: OpenCV's own loops inside each would
    // only add threads competing for the same cores (the 36-still comic batch on 2 cores: 1.56 -> 1.50 s, 3% less
    // CPU, with one thread each; docs/performance.md). With --jobs 0 each still has the cores to itself.
    std::optional<ParallelLoopThreads> loopThreads;
    if (options.jobs > 0) loopThreads.emplace(postStageLoopThreads(options.jobs));
    const auto batchStart = std::chrono::steady_clock::now();
    int exitCode = kExitOk;
    std::vector<std::string> failed;
    std::size_t skipped = 0;
    const std::vector<StillToRender> toRender = stillsToRender(options, list, stills, dataset.get(), skipped);
    const BatchShared batch{options, list, stills, toRender, log, dataset.get(), failed, exitCode, nullptr, nullptr};
    // Several drawing threads only where each still draws: --print-plan's plans go to standard output in order.
    if (options.drawThreads > 1 && rendersImages(options) && !options.printPlan && toRender.size() > 1) {
        renderInThreads(batch, out, options.drawThreads);
    } else {
        try {
            renderShare(batch, 0, 1, session);
        } catch (...) {
            // The batch stops; the stills in flight are finished first, and the error that stopped it thrown.
            finishAfterError(session, batch);
            throw;
        }
    }
    if (dataset) dataset->finish(log);
    if (!options.quiet || !failed.empty()) {
        std::ostringstream summary;
        summary << "inkgraph: rendered " << stills.size() - failed.size() - skipped << " of " << stills.size();
        if (options.viewsGiven)
            summary << " stills (" << list.models.size() << (list.models.size() == 1 ? " model x " : " models x ")
                    << options.viewSampling.count << (options.viewSampling.count == 1 ? " view)" : " views)");
        else
            summary << " models";
        summary << share << " in " << std::fixed << std::setprecision(1) << millisecondsSince(batchStart) / 1000.0
                << " s" << failedStillsText(failed);
        log << boundedMessage(summary.str()) + "\n"; // one write, one line
    }
    return exitCode;
}

} // namespace inkgraph
