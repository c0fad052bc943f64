#pragma once
/** @file What a failure is, for whoever reports it: each layer's exception mapped once to an exit code (the command
 *  line's) and a bounded message. The command line prints it (app/Cli.h); the library's Error::Kind follows the exit
 *  code (api/). */

#include <exception>
#include <string>
#include <vector>

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

struct ExitCodeMeaning {
    ExitCode code;
    std::string meaning; ///< "bad command line"
};

/** Every exit code with what it means, in the order `inkgraph help render` lists them (0 first, 1 last). */
const std::vector<ExitCodeMeaning>& exitCodeMeanings();

/** What the command line reports for an exception of any layer. */
struct ErrorReport {
    ExitCode exitCode = kExitInternal;
    std::string message;        ///< as printed after "inkgraph: " ("internal error: ..." for kExitInternal)
    bool showsHelpHint = false; ///< a usage error: "(see: inkgraph help render)" follows
};

/** The one mapping of each layer's exception to an exit code and message, shared by the command line and the library
 *  (api/: its Error::Kind follows the exit code). */
ErrorReport reportOf(const std::exception_ptr& error);

} // namespace inkgraph
