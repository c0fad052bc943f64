#pragma once
/** @file --stats: what one still did, as JSON: the scene, the camera, the GL context, the look, every pass's time,
 *  the post stage, the culled passes with reasons, the memory estimate and the measured peak. */

#include "app/Options.h"
#include "app/StillRenderer.h"

#include <cstddef>
#include <string>

namespace inkgraph {

/** Where a still stands in a batch, for its --stats. */
struct StillBatchPosition {
    std::size_t position = 0; ///< 0-based, in the whole list
    std::size_t listLength = 0;
};

/** The facts --stats reports that the renderer does not know. */
struct StatsContext {
    const RenderOptions& options;
    const StillBatchPosition* batch = nullptr;
    double writeMilliseconds = 0.0; ///< encoding the outputs so far
    double totalMilliseconds = 0.0; ///< the still so far
    std::size_t estimatedPeakBytes = 0;
};

/** The --stats document of a still that executed with `renderer`. */
std::string statsText(const StatsContext& context, const StillRenderer& renderer, const PreparedStill& still,
                      const StillResult& result);

} // namespace inkgraph
