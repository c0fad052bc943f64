#pragma once
/** @file The `inkgraph` command line: dispatch to the commands, one catch that maps each layer's exception to an exit
 *  code, and the help and version texts. The commands and the exit codes are listed once here, for --help, the man
 *  page and the bash completion (app/CommandLineDocs.h). */

#include <exception>
#include <iosfwd>
#include <string>
#include <vector>

namespace inkgraph {

/** What inkgraph is, in --help's first line and the man page's NAME. */
inline constexpr const char* kProgramSummary = "headless anime- and comic-style renderer";

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

/** A command of `inkgraph`, as --help, the man page and the bash completion show it. */
struct CommandInfo {
    std::vector<std::string> names; ///< "render"; "help", "--help", "-h" (the first is the one shown)
    std::string arguments;          ///< "MODEL... -o OUT.png [options]"
    std::string help;               ///< what it does; '\n' starts a new line in --help
    /** The words that may follow the name, for the shell's completion; `render` takes its flags from the flag table
     *  (app/FlagTable.h) instead. */
    std::vector<std::string> words;
};

/** Every command, in --help's order. */
const std::vector<CommandInfo>& commands();

/** The text of `inkgraph --help`. */
std::string mainHelp();

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
