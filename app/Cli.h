#pragma once
/** @file The `inkgraph` command line: dispatch to the commands, one catch that maps each layer's exception to an exit
 *  code, and the help and version texts. */

#include <iosfwd>

namespace inkgraph {

/** Exit codes of the command line (README "Errors and exit codes"). */
enum ExitCode : int {
    kExitOk = 0,
    kExitInternal = 1,
    kExitUsage = 2,
    kExitBadInput = 3,
    kExitNoGl = 4,
    kExitOutput = 5,
};

/** The whole CLI: parses argv, runs, catches once, prints "inkgraph: <message>" to `err`, returns the exit code.
 *  `--list -` reads std::cin. */
int runCommandLine(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

} // namespace inkgraph
