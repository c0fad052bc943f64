#include "app/BatchRun.h"

#include "render/BackgroundThreads.h"
#include "render/Messages.h"

#include "app/Batch.h"
#include "app/Cli.h"
#include "app/Dataset.h"
#include "app/Render.h"
#include "scene/Scene.h"

#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>

namespace inkgraph {
namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/** "'models/x.vrm'", with --views "'models/x.vrm' view 04": a still in progress lines and the summary. */
std::string stillLabel(const BatchStill& still, const RenderOptions& options) {
    std::string label = "'" + still.model.path + "'";
    if (still.view) {
        const std::string last = std::to_string(options.viewSampling.count - 1);
        std::string view = std::to_string(still.viewIndex);
        if (view.size() < last.size()) view.insert(0, last.size() - view.size(), '0');
        label += " view " + view;
    }
    return label;
}

/** Renders every still of the list in `session` (each model's views one after the other), each still's post stage
 *  and writing overlapping the next stills' drawing, and finishes them all. Every still's progress line or failure
 *  is told in list order, when it is finished. Bad input stops one still, not the batch: its label goes to `failed`.
 *  With a data set, stills --resume finds complete are skipped (counted in `skipped`, no progress line) and each
 *  committed one journaled. */
void renderEach(const RenderOptions& options, const BatchList& list, const std::vector<BatchStill>& stills,
                RenderSession& session, std::ostream& log, DatasetRun* dataset, std::vector<std::string>& failed,
                std::size_t& skipped, int& exitCode) {
    // What is left to render, known before the first still so each still can name the next (its model then loads
    // while this one draws).
    struct Still {
        std::size_t index = 0; ///< into `stills`
        RenderOptions options;
        std::string digest; ///< a data set's settings digest
    };
    std::vector<Still> toRender;
    for (std::size_t i = 0; i < stills.size(); ++i) {
        Still still{i, stillOptions(options, stills[i], list.total), {}};
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
    for (std::size_t k = 0; k < toRender.size(); ++k) {
        const BatchStill& batchStill = stills[toRender[k].index];
        const RenderOptions& still = toRender[k].options;
        const StillKey key{batchStill.model.path, batchStill.model.position, batchStill.viewIndex};
        const std::string label = stillLabel(batchStill, options);
        const std::string counter =
            "inkgraph: [" + std::to_string(toRender[k].index + 1) + "/" + std::to_string(stills.size()) + "] " + label;
        const auto fail = [&log, &failed, dataset, &exitCode, counter, label, key, still](const std::exception& error) {
            log << boundedMessage(counter + " failed: " + error.what()) << "\n";
            failed.push_back(label);
            if (dataset) dataset->recordFailed(key, still, error.what());
            if (exitCode == kExitOk) exitCode = kExitBadInput;
        };
        try {
            StillCallbacks callbacks;
            if (dataset) {
                dataset->makeOutputFolders(still);
                callbacks.committed = [dataset, key, still, digest = toRender[k].digest](const CommittedStill& done) {
                    dataset->recordCommitted(key, still, digest, done.camera, done.look);
                };
            }
            callbacks.finished = [&log, counter, quiet = options.quiet,
                                  outputPath = still.outputPath](const StillReport& report) {
                if (quiet) return;
                log << counter;
                if (!outputPath.empty()) log << " -> '" << outputPath << "'";
                log << ": " << report.triangles << " triangles, " << std::fixed << std::setprecision(0)
                    << report.milliseconds << " ms\n";
            };
            callbacks.failed = fail;
            const StillBatchPosition position{batchStill.model.position, list.total};
            session.render(still, &position, std::move(callbacks),
                           k + 1 < toRender.size() ? &toRender[k + 1].options : nullptr);
        } catch (const SceneError& error) {
            // Bad input stops one still, not the batch: the other stills' work is not lost. The stills before it
            // are told first.
            session.finishPending();
            fail(error);
        } catch (const InputFileError& error) {
            session.finishPending();
            fail(error);
        }
    }
    session.finishPending();
}

} // namespace

int renderBatch(const RenderOptions& options, std::istream& standardInput, std::ostream& out, std::ostream& log,
                const std::vector<std::string>& givenArguments, const std::vector<std::string>& expandedArguments) {
    const BatchList list = batchList(options, standardInput);
    checkBatchOutputs(options, list);
    const std::vector<BatchStill> stills = batchStills(options, list);
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
    try {
        renderEach(options, list, stills, session, log, dataset.get(), failed, skipped, exitCode);
    } catch (...) {
        // The batch stops; the stills in flight are finished first, so no completed still's outputs are lost. Their
        // own failures, if any, are told, and the one that stopped the batch thrown.
        for (;;) {
            try {
                session.finishPending();
                break;
            } catch (const std::exception& error) {
                log << boundedMessage(std::string("inkgraph: error: ") + error.what()) << "\n";
            }
        }
        throw;
    }
    if (dataset) dataset->finish(log);
    if (!options.quiet || !failed.empty()) {
        log << "inkgraph: rendered " << stills.size() - failed.size() - skipped << " of " << stills.size();
        if (options.viewsGiven)
            log << " stills (" << list.models.size() << (list.models.size() == 1 ? " model x " : " models x ")
                << options.viewSampling.count << (options.viewSampling.count == 1 ? " view)" : " views)");
        else
            log << " models";
        log << share << " in " << std::fixed << std::setprecision(1) << millisecondsSince(batchStart) / 1000.0 << " s";
        if (!failed.empty()) {
            log << "; " << failed.size() << " failed:";
            for (std::size_t i = 0; i < failed.size(); ++i) log << (i == 0 ? " " : ", ") << failed[i];
        }
        log << "\n";
    }
    return exitCode;
}

} // namespace inkgraph
