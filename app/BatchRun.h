#pragma once
/** @file Running every model of `inkgraph render` (app/Batch.h says which) in one RenderSession. */

#include "flags/Options.h"

#include <iosfwd>
#include <string>
#include <vector>

namespace inkgraph {

/** Every still of the run (each model, with --views N each of its N views: app/Batch.h batchStills()) in one
 *  RenderSession, with a progress line per still on `log` (unless --quiet) when there are several. A still whose model
 *  cannot be read (exit 3) is reported and the others go on; the first such failure's exit code is returned after the
 *  last still. Any other error stops the batch (models done so far keep their outputs).
 *  `standardInput` is read for --list -. With --dataset (app/Dataset.h) the run is a data set: `givenArguments` (the
 *  arguments after "render" as typed) go into its card, `expandedArguments` (with --style's settings) into each
 *  still's settings digest. Returns the exit code. */
int renderBatch(const RenderOptions& options, std::istream& standardInput, std::ostream& out, std::ostream& log,
                const std::vector<std::string>& givenArguments = {},
                const std::vector<std::string>& expandedArguments = {});

} // namespace inkgraph
