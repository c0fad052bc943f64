#pragma once
/** @file One still of `inkgraph render` from its command line: every output place checked before any work, the
 *  still prepared and executed by the renderer (render/StillRenderer.h), its outputs and stats staged
 *  (app/StillOutputs.h, app/Stats.h) and committed all or none (app/OutputFiles.h). */

#include "flags/Options.h"
#include "app/Stats.h"
#include "render/StillRenderer.h"

#include "app/OutputFiles.h"
#include "app/MemoryLedger.h"
#include "app/RecentModel.h"
#include "app/StillTurns.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>
#include <iosfwd>

namespace inkgraph {

/** --memory-limit, else defaultMemoryLimit(): the bound on one model load (checked before allocating, from the file's
 *  declared counts) and on the whole run's estimated peak (checked before any GL work). */
std::size_t memoryLimitOf(const RenderOptions& options);

/** What the renderer is asked for by the options of one still. */
StillRequest stillRequestOf(const RenderOptions& options);

/** What one still did, for the batch's progress line. */
struct StillReport {
    std::size_t triangles = 0;
    double milliseconds = 0.0;
};

/** A still whose outputs were just committed, for --dataset's journal (app/Dataset.h). */
struct CommittedStill {
    nlohmann::ordered_json camera; ///< describeCamera()
    nlohmann::ordered_json look;   ///< describeLook()
};
/** Called once the still's outputs are all in place (the still's own options are the caller's to keep). */
using CommitListener = std::function<void(const CommittedStill&)>;

/** What a batch hears of one still, on the thread that called render(), in the order the stills were given. */
struct StillCallbacks {
    CommitListener committed; ///< after the still's commit, before `finished`
    /** The still is finished: its outputs are in place (or it wrote none). */
    std::function<void(const StillReport&)> finished;
    /** The still's post stage failed on bad input (SceneError, InputFileError) after render() returned; without
     *  this the error is thrown from whichever call finishes the still. */
    std::function<void(const std::exception&)> failed;
    /** With several drawing threads (--draw-threads): the turns that keep every still's telling and commit in the
     *  list's order, and this still's place in it (0-based). When render() throws for a batch's still, it returns
     *  holding the still's turn (its warnings told): the caller tells the failure and leaves it. */
    StillTurns* turns = nullptr;
    std::size_t turn = 0;
};

/** One of the sessions that draw a batch's stills at once, each on its own thread (--draw-threads). */
struct SessionShare {
    int index = 0; ///< the first tells the driver's line ("inkgraph: llvmpipe ..."), once for the process
    int count = 1;
    /** With several: the memory limit they share, each still let in, in the list's order, when it fits beside what
     *  every session holds; null for one session, which keeps its own stills in flight within the limit. */
    MemoryLedger* ledger = nullptr;
};

/** The stills of one process, in one StillRenderer (one GL context, every program compiled once), pipelined: while
 *  a still's post stage (the plan's host tail: line kernels, strokes, composite) runs and its picture is encoded on a
 *  worker thread, the next still loads and draws on this one. Outputs are committed in the order of the stills. */
class RenderSession {
public:
    /** `out` receives --print-plan, `log` the progress lines. `jobs`: how many stills may be in their post stage at
     *  once while the next draws (--jobs); 0 finishes each still before the next starts. `share`: this session's
     *  place among the sessions that draw at once (--draw-threads). */
    RenderSession(std::ostream& out, std::ostream& log, int jobs = 0, SessionShare share = {});
    ~RenderSession();
    RenderSession(const RenderSession&) = delete;
    RenderSession& operator=(const RenderSession&) = delete;

    /** Renders one still as the options say (the model and outputs of that still: app/Batch.h stillOptions()).
     *  With `batch`, the still's own progress lines are left to the caller, and the still may return unfinished
     *  (its post stage and writing in flight, at most `jobs` of them, and as many as the memory limit allows);
     *  callbacks.finished tells when it is done. Without, it is finished before render() returns. Throws the layer's
     *  own exceptions (SceneError, InputFileError, HeadlessContextError, FileError, UsageError, GraphError), for this
     *  still or for an earlier one it finished (FileError, and bad input without callbacks.failed); runCommandLine
     *  maps them to exit codes. */
    /** `next`, in a batch: the still the next render() is for (that call passes this same object as its `options`).
     *  Its model starts loading (parsed, welded, its shade
     *  maps read) on a second thread as soon as this still's is loaded, and the next render() takes it; its warnings
     *  are told with it. */
    StillReport render(const RenderOptions& options, const StillBatchPosition* batch = nullptr,
                       StillCallbacks callbacks = {}, const RenderOptions* next = nullptr);

    /** Finishes every still in flight, oldest first: waits for its post stage and picture, writes the picture and
     *  --stats, stages the other outputs, commits. Throws the writing's FileError (the stills after it stay in
     *  flight: call again, or let the destructor wait for them). */
    void finishPending();

private:
    /** StillRenderer::load() on a second thread while this one makes the GL context when the run `renders`; the
     *  load's error wins over the context's. */
    std::unique_ptr<PreparedStill> loadWhileMakingContext(StillRequest request, bool renders, const StillLog& log);

    /** render()'s work, telling through `log` (a batch's still: `stillLog`, told when it is finished). */
    StillReport renderStill(const RenderOptions& options, const StillBatchPosition* batch, StillCallbacks callbacks,
                            const RenderOptions* next, const StillLog& log,
                            const std::shared_ptr<std::ostringstream>& stillLog,
                            std::chrono::steady_clock::time_point processStart);
    /** Whether `next` (render()'s) is loaded ahead: a still after one that renders, with worker threads. */
    bool prefetches(const RenderOptions* next, bool renders) const;
    /** Starts loading `next`'s model on a second thread (render()'s `next`). */
    void prefetch(const RenderOptions& next);
    /** What `options` asks the renderer for, taking the model an earlier still loaded when this still loads the same
     *  file the same way (mRecentModel: --views, a model listed twice in a row); `key` receives its load's key. A
     *  model it does not take is let go of first, so two models are never held for one still. */
    StillRequest requestTakingRecentModel(const RenderOptions& options, std::optional<RecentModel::Key>& key);

    struct PendingStill;
    struct TailOutcome;
    /** A model loading ahead (prefetch()). */
    struct Prefetch {
        const RenderOptions* options = nullptr; ///< the batch's options object of the still it is for (render()'s next)
        std::string modelPath;
        std::optional<RecentModel::Key> modelKey;
        std::shared_ptr<std::ostringstream> log;
        std::future<std::unique_ptr<PreparedStill>> still;
    };
    /** Writes what a batch's still had to say (its warnings, buffered in `stillLog`) to the log, once; nothing for a
     *  still alone (null). */
    void tellLog(std::ostringstream* stillLog);
    /** Finishes the oldest still in flight (finishPending()'s step), then tells the ledger what is left. */
    void finishOldest();
    void finishOldestStill();
    /** With turns: finishes the oldest stills in flight while their post stage is done and their turn is due, so the
     *  other drawing threads' stills after them need not wait for this session's next limit. */
    void finishDueStills();
    /** In finishOldest()'s handler of an error that stops the batch: keeps it (mFinishingFailure), and with turns
     *  stops them while `pending` holds its turn. */
    void stopFor(const PendingStill& pending);
    /** finishOldest() once the still's post stage succeeded: stages, writes and commits its outputs, then tells. */
    void commitFinished(PendingStill& pending, TailOutcome& outcome);
    /** The memory the stills in flight are estimated to hold (MemoryEstimate, less the model's textures). */
    std::size_t bytesInFlight() const;
    /** With a ledger (several drawing threads): waits until `turn`'s still may draw, needing `drawingBytes` beyond
     *  the process's `baselineBytes` and holding `waitingBytes` (its model) meanwhile; finishes this session's stills
     *  in flight as they come due, and lets go of its pool and loaded-ahead model when a still before it needs them. */
    void waitForMemory(std::size_t turn, StillTurns* turns, std::size_t baselineBytes, std::size_t drawingBytes,
                       std::size_t waitingBytes);
    /** With a ledger: lets go of what this session only keeps (the pool's free textures, the model loaded ahead) and
     *  tells the ledger, so a still of another drawing thread that waits for that memory can draw. */
    void shedKeptMemory();
    /** Tells the ledger what this session holds between stills (`waitingBytes`: a loaded model waiting to draw). */
    void tellHoldings(std::size_t waitingBytes = 0);

    std::ostream& mOut;
    std::ostream& mLog;
    int mJobs = 0;
    SessionShare mShare;
    StillRenderer mRenderer;
    std::deque<std::unique_ptr<PendingStill>> mPending; ///< oldest first
    std::optional<Prefetch> mPrefetch;
    /** The model of the last still loaded, for the stills after it that load the same file the same way. */
    RecentModel mRecentModel;
    /** The error of the last still whose finishing failed (finishOldest()): render() tells it from a failure of its
     *  own still, which must first finish the stills before it. */
    std::exception_ptr mFinishingFailure;
    /** The last committed still's OutputSet::removeReplaced(), on a thread of its own (commitFinished()). */
    std::future<void> mTidying;
    std::size_t mPoolBytes = 0;  ///< the GL targets the renderer's pool keeps from the last still drawn (estimated)
    std::size_t mAheadBytes = 0; ///< the model loading ahead (estimated as the still that started it)
};

/** Standard output that cannot be written (--print-plan > /dev/full, a closed pipe) fails the run: throws FileError. */
void requireStandardOutputWritten(std::ostream& out);

} // namespace inkgraph
