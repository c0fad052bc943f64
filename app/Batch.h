#pragma once
/** @file Several models in one process (`inkgraph render A.obj B.glb ...`, `--list FILE`, `--shard K/N`): which
 *  models this process renders, and the options of each still. No GL: app/Render.cpp renders them in one session,
 *  re-using the GL context and the compiled programs.
 *
 *  Output paths (-o, --dump, --stats, --graphviz, --contact-sheet, --svg) may hold `{name}` (the model file's name
 *  without its extension) and `{index}` (its 1-based position in the whole list, zero-padded to the list's width);
 *  when there is more than one model, each given output path must hold one of them. */

#include "flags/Options.h"

#include <cstddef>
#include <iosfwd>
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
    /** True when the run names several models or a list: then each still gets a progress line. */
    bool isBatch = false;
};

/** The MODEL arguments, then --list's lines (blank lines and lines starting with '#' skipped, surrounding spaces
 *  trimmed, relative paths taken from the current folder like `tar -T`), then the --shard share. `standardInput`
 *  is read for `--list -`. Throws UsageError naming --list and the file (and line) for an unreadable list, one over
 *  16 MiB, a line with a NUL byte, or a list of no models. */
BatchList batchList(const RenderOptions& options, std::istream& standardInput);

/** `pattern` with `{name}` and `{index}` replaced for `model` of a list of `total`. */
std::string expandOutputPattern(const std::string& pattern, const BatchModel& model, std::size_t total);

/** The options of one still: `options` with the model and every output path expanded. */
RenderOptions stillOptions(const RenderOptions& options, const BatchModel& model, std::size_t total);

/** Checks the outputs of every still before any work: with several models, each output path must name `{name}` or
 *  `{index}`; no two stills may write the same place (two models of one name: use `{index}`), and no still may
 *  write over a model of the list. Throws UsageError naming the flag and both models. */
void checkBatchOutputs(const RenderOptions& options, const BatchList& list);

} // namespace inkgraph
