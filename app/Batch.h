#pragma once
/** @file Several models in one process (`inkgraph render A.obj B.glb ...`, `--list FILE`, `--shard K/N`): which
 *  models this process renders, and the options of each still. No GL: app/Render.cpp renders them in one session,
 *  re-using the GL context and the compiled programs.
 *
 *  With --views N each model renders N stills, its views 0 to N-1 (scene/ViewSampling.h), one after the other in
 *  the process that has the model (--shard splits by model), so a still is a model and a view index.
 *
 *  Output paths (-o, --dump, --stats, --graphviz, --contact-sheet, --svg) may hold `{name}` (the model file's name
 *  without its extension), `{index}` (its 1-based position in the whole list, zero-padded to the list's width) and
 *  `{view}` (the view index from 0, zero-padded to the width of N-1; 0 without --views); when there is more than one
 *  model, each given output path must hold {name} or {index}, and with N > 1 views also {view}. */

#include "flags/Options.h"

#include <cstddef>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** One model of a run. */
struct BatchModel {
    std::string path;
    std::size_t position = 0; ///< 0-based, in the whole list (MODEL arguments, then --list), before sharding
};

/** The models of a run. */
struct BatchList {
    std::vector<BatchModel> models; ///< this process's share, in list order
    std::size_t total = 0;          ///< the whole list's length
    /** With --shard: the whole list's paths, in order, so the outputs of the other shares can be checked against
     *  this share's (array tasks write into one folder). Empty without --shard. */
    std::vector<std::string> everyPath;
    /** True when the run names several models or a list: then each still gets a progress line. */
    bool isBatch = false;
};

/** One still of a run: a model of the list and, with --views, one of its views. */
struct BatchStill {
    BatchModel model;
    std::size_t viewIndex = 0;      ///< 0 to N-1 with --views N; 0 without
    std::optional<ViewSample> view; ///< with --views: the view drawn for (seed, model path, viewIndex)
};

/** The MODEL arguments, then --list's lines (blank lines and lines starting with '#' skipped, surrounding spaces
 *  trimmed, relative paths taken from the current folder like `tar -T`), then the --shard share. `standardInput`
 *  is read for `--list -`, a pipe (`--list <(...)`) as it comes. Throws UsageError naming --list and the file (and
 *  line) for an unreadable list, one over 16 MiB, a line with a NUL byte, or a list of no models. */
BatchList batchList(const RenderOptions& options, std::istream& standardInput);

/** The most stills one process renders (its share of the models times --views): each is held from the start
 *  (about 1 KiB with its view and records), so more is refused, pointing to --shard. */
inline constexpr std::size_t kMaxStillsPerProcess = 1000000;
/** Up to this many stills in the whole list (all shares times --views), a sharded run checks its outputs against
 *  every other share's, by their paths; above it, only against its own share's. */
inline constexpr std::size_t kMaxStillsCheckedAcrossShards = 20000000;

/** Every still of this process's share, in the order they render: each model of `list` in list order, with --views
 *  N its views 0 to N-1 (each sampled), else one still per model. */
std::vector<BatchStill> batchStills(const RenderOptions& options, const BatchList& list);

/** `pattern` with `{name}` and `{index}` replaced for `model` of a list of `total`, and `{view}` by `viewIndex`
 *  zero-padded to the width of `viewCount` - 1. */
std::string expandOutputPattern(const std::string& pattern, const BatchModel& model, std::size_t total,
                                std::size_t viewIndex = 0, std::size_t viewCount = 1);

/** The options of one still: `options` with the model and every output path expanded, and with its view the view's
 *  orbit (azimuth, elevation, the auto-framing distance times the scale), light, expressions and pose in place of the
 *  flags' and `view` set, for the records. */
RenderOptions stillOptions(const RenderOptions& options, const BatchStill& still, std::size_t total);

/** Checks the outputs of every still before any work: with several models, each output path must name `{name}` or
 *  `{index}`, with several views `{view}`; no two stills may write the same place (two models of one name: use
 *  `{index}`), and no still may write over a model of the list, its own included, nor over a file every still reads
 *  (--list, --style, --shademap, --outline-width-map's image: inputsNamedBesidesModel()). Throws UsageError naming
 *  the flag and the path, and for two stills both. */
void checkBatchOutputs(const RenderOptions& options, const BatchList& list);

/** Reads, before any work, the files every still reads besides its model and judges them as a still would: the
 *  --shademap, --pose's pose file and each of --poses' (readShadeMapFile(), checkPoseFile()). A bad one fails the
 *  run before its first still, where each still would fail alike, and --poses' only in the views drawing it, found
 *  as the run reaches them. Throws InputFileError or SceneError naming the flag and the file. */
void checkBatchInputs(const RenderOptions& options);

} // namespace inkgraph
