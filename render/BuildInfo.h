#pragma once
/** @file What this build is. Both functions live in one small source generated at build time
 *  (cmake/BuildInfo.cmake), rewritten only when the commit changes, so a new commit recompiles that file alone. */

namespace inkgraph {

/** The project's version, "0.1.0". */
const char* inkgraphVersion();

/** The short git commit the build was made from, "6e6311c"; "unknown" when it was not built from a git checkout. */
const char* inkgraphGitCommit();

} // namespace inkgraph
