#pragma once
/** @file --stats: what one still did, as JSON: the scene, the camera, the GL context, the look, every pass's time,
 *  the post stage, the culled passes with reasons, the memory estimate and the measured peak. */

#include "flags/Options.h"
#include "render/StillRenderer.h"

#include <nlohmann/json_fwd.hpp>

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
    std::size_t estimatedPeakBytes = 0;
    std::size_t estimatedTextureBytes = 0; ///< the part of estimatedPeakBytes that is the model's textures
    /** The part that is the model's meshes (MemoryEstimate::meshes()) and what the passes derive
     *  from them (MemoryEstimate::derived): what a larger model of the same look adds in proportion. */
    std::size_t estimatedMeshBytes = 0;
    std::size_t estimatedDerivedBytes = 0;
};

/** The --stats document of a still that executed with `renderer`, but for what only writing its outputs tells:
 *  finishedStatsText() fills that in. Made while the still's GL objects live; it refers to none of them. */
nlohmann::ordered_json statsDocument(const StatsContext& context, const StillRenderer& renderer,
                                     const PreparedStill& still, const StillResult& result);

/** A still's sampled view (--views), as --stats and --dump's manifest record it: {index, count, seed, azimuth,
 *  elevation, distance_scale, light (null without --light-jitter), expression (the --expressions alternative as
 *  --expression writes it, or "none"; null without --expressions), pose (as --poses gives it; null without),
 *  orbit (the --orbit value that places this view)}. Null for a still without a view. */
nlohmann::ordered_json viewRecord(const RenderOptions& options);

/** The document's text with "write_ms" (encoding and writing the outputs), "peak_rss_mib" (measured now) and
 *  "total_ms" (the still from its start until its outputs are written) filled in. */
std::string finishedStatsText(nlohmann::ordered_json stats, double writeMilliseconds, double totalMilliseconds);

} // namespace inkgraph
