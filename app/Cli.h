#pragma once
/** @file The `inkgraph` command line: dispatch to the commands, one catch that maps each layer's exception to an exit
 *  code, and the help and version texts. The commands and the exit codes are listed once here, for --help, the man
 *  page and the bash completion (app/CommandLineDocs.h). */

#include "render/ErrorReport.h"

#include <exception>
#include <iosfwd>
#include <string>
#include <vector>

namespace inkgraph {

/** What inkgraph is, in --help's first line and the man page's NAME. */
inline constexpr const char* kProgramSummary = "headless anime- and comic-style renderer";

/** A command of `inkgraph`, as --help, the man page and the bash completion show it. */
struct CommandInfo {
    std::vector<std::string> names; ///< "render"; "help", "--help", "-h" (the first is the one shown)
    std::string arguments;          ///< "MODEL... -o OUT.png [options]"
    std::string help;               ///< what it does; '\n' starts a new line in --help
    /** The words that may follow the name, for the shell's completion; `render` takes its flags from the flag table
     *  (flags/FlagTable.h) instead. */
    std::vector<std::string> words;
};

/** Every command, in --help's order. */
const std::vector<CommandInfo>& commands();

/** The text of `inkgraph --help`. */
std::string mainHelp();

/** The whole CLI: parses argv, runs, catches once, prints "inkgraph: <message>" to `err`, returns the exit code.
 *  `--list -` reads std::cin. */
int runCommandLine(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

} // namespace inkgraph
