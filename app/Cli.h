#pragma once
/** @file The `inkgraph` command line: dispatch to the commands, one catch that maps each layer's exception to an exit
 *  code, and the help and version texts. */

#include <exception>
#include <iosfwd>
#include <string>

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

/** What the command line reports for an exception of any layer. */
struct ErrorReport {
    ExitCode exitCode = kExitInternal;
    std::string message;        ///< as printed after "inkgraph: " ("internal error: ..." for kExitInternal)
    bool showsHelpHint = false; ///< a usage error: "(see: inkgraph help render)" follows
};

/** The one mapping of each layer's exception to an exit code and message, shared by the command line and the library
 *  (api/: its Error::Kind follows the exit code). */
ErrorReport reportOf(const std::exception_ptr& error);

/** The whole CLI: parses argv, runs, catches once, prints "inkgraph: <message>" to `err`, returns the exit code.
 *  `--list -` reads std::cin. */
int runCommandLine(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

} // namespace inkgraph
