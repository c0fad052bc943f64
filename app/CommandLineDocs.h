#pragma once
/** @file The man page and the bash completion of `inkgraph`, generated from the commands (app/Cli.h) and the flag
 *  table (flags/FlagTable.h), so neither lists a flag of its own. `inkgraph help --man` and `inkgraph help
 *  --bash-completion` print them; the build writes them into build/share/ for the install (docs/install.md). */

#include <string>

namespace inkgraph {

/** inkgraph(1) in roff (man macros): NAME, SYNOPSIS, DESCRIPTION, COMMANDS, every render flag under its help section
 *  with its help text, EXIT STATUS, ENVIRONMENT, FILES, SEE ALSO. ASCII only (other characters as groff escapes). */
std::string manPage();

/** A bash script that defines the completion of `inkgraph`: the commands and their words, every render flag, the
 *  values of the flags that take a fixed set (comma lists item by item), file names for MODEL and for the flags
 *  whose value is a file (only *.EXT for FILE.EXT), folders for DIR. Needs no bash-completion package. */
std::string bashCompletion();

} // namespace inkgraph
