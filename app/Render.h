#pragma once
/** @file One still of `inkgraph render` from its command line: every output place checked before any work, the
 *  still prepared and executed by the renderer (render/StillRenderer.h), its outputs and stats staged
 *  (app/StillOutputs.h, app/Stats.h) and committed all or none (app/OutputFiles.h). */

#include "flags/Options.h"
#include "app/Stats.h"
#include "render/StillRenderer.h"

#include "app/OutputFiles.h"

#include <cstddef>
#include <functional>
#include <future>
#include <memory>
#include <optional>
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

/** The stills of one process, in one StillRenderer (one GL context, every program compiled once). */
class RenderSession {
public:
    /** `out` receives --print-plan, `log` the progress lines. */
    RenderSession(std::ostream& out, std::ostream& log) : mOut(out), mLog(log) {}

    /** Renders one still as the options say (the model and outputs of that still: app/Batch.h stillOptions()).
     *  With `batch`, the still's own progress lines are left to the caller. Throws the layer's own exceptions
     *  (SceneError, InputFileError, HeadlessContextError, FileError, UsageError, GraphError); runCommandLine maps
     *  them to exit codes. `committed`, when given, is called after the still's commit (in finishPending() for a
     *  batch's still). */
    StillReport render(const RenderOptions& options, const StillBatchPosition* batch = nullptr,
                       CommitListener committed = {});

    /** A batch's still (`batch` given) returns from render() with its picture still being encoded on a second thread,
     *  which overlaps the next still; the next render() finishes it (writes the picture and --stats, commits its
     *  outputs) once that still has executed, and the caller finishes the last one with this. Throws the writing's
     *  FileError. A still alone is finished before render() returns. */
    void finishPending();

private:
    /** StillRenderer::load() on a second thread while this one makes the GL context when the run `renders`; the
     *  load's error wins over the context's. */
    std::unique_ptr<PreparedStill> loadWhileMakingContext(StillRequest request, bool renders, const StillLog& log);

    /** A picture encoded in memory, and how long that took. */
    struct EncodedPicture {
        std::vector<unsigned char> bytes;
        double milliseconds = 0.0;
    };
    /** A still that executed, its outputs staged but the picture (being encoded) and --stats, none committed. It
     *  holds no GL object: the still's own are freed on this thread before the next still runs. */
    struct PendingStill {
        std::unique_ptr<OutputSet> outputs;
        std::future<EncodedPicture> encoding;        ///< invalid without -o
        std::optional<nlohmann::ordered_json> stats; ///< --stats, less the writing's facts
        std::string outputPath;
        std::string size; ///< "WxH", for the progress line
        bool talks = false;
        double stagedMilliseconds = 0.0;   ///< staging the other outputs
        double renderedMilliseconds = 0.0; ///< from the still's start to the hand-over
        CommitListener committed;
        CommittedStill description; ///< for `committed`
    };

    std::ostream& mOut;
    std::ostream& mLog;
    StillRenderer mRenderer;
    std::unique_ptr<PendingStill> mPending;
};

/** Standard output that cannot be written (--print-plan > /dev/full, a closed pipe) fails the run: throws FileError. */
void requireStandardOutputWritten(std::ostream& out);

} // namespace inkgraph
