#pragma once
/** @file The flags of `inkgraph render`, declared once each: names, value, help section and text, whether a style
 *  file may set it, how its value is checked and stored, and when it has no effect with the rest of the command line.
 *  Parsing (flags/Options.cpp), `--help`, the style files' setting names (flags/StyleFile.h), the range checks and the
 *  "has no effect" refusals are all generated from this table. The line types' width, colour and parameter flags
 *  come from the line-type registry (passes/lines/LineTypes.h), the shading models' from their trait table
 *  (passes/shade/ShadingModel.h). */

#include "flags/Options.h"

#include <functional>
#include <string>
#include <vector>

namespace inkgraph {

enum class HelpSection { Output, Camera, Look, Lines, Batch, Views, System };

struct Flag {
    std::vector<std::string> names; ///< "--size", or "-o" and "--output"; empty for a help-only entry
    std::string valueName;          ///< "WxH"; empty: the flag takes no value
    HelpSection section = HelpSection::Output;
    std::string help;       ///< --help's text; '\n' starts a new line; empty: not in --help
    std::string helpLabel;  ///< --help's left column when not "<names> <valueName>" ("--TYPE-width PX")
    bool inStyle = false;   ///< a style file may set it, as its long name without the dashes
    bool pathValue = false; ///< its value is a file: in a style file, relative to the style file
    /** The values it takes when they are a fixed set, for the shell's completion (the parser in `apply` judges, and
     *  tests/app/CommandLineDocsTest.cpp checks it takes each);
     *  empty: any value. */
    std::vector<std::string> choices;
    bool commaList = false; ///< its value is a comma-separated list (of `choices`, when it has them)
    /** Checks `value` and stores it; throws UsageError naming the flag. Null for help-only entries. */
    std::function<void(const std::string& value, RenderOptions& options)> apply;
    /** After parsing, when given: the refusal if the flag changes nothing with these options, else "". */
    std::function<std::string(const RenderOptions& options)> noEffect;
};

/** Every flag of `inkgraph render`, in --help's order within each section. */
const std::vector<Flag>& renderFlags();
/** The flag named `name` ("--size", "-o"), or null. */
const Flag* findFlag(const std::string& name);
/** The text of `inkgraph render --help`. */
std::string renderFlagsHelp();

/** The help sections in --help's order, and each one's title. */
const std::vector<HelpSection>& helpSections();
const char* helpSectionTitle(HelpSection section);

/** A flag's help text as the paragraphs --help wraps: its '\n' are soft, except before a list item (a line that
 *  starts with two spaces and a word, kept with its indent); lines indented deeper continue the item above. */
std::vector<std::string> helpBlocks(const std::string& help);

/** `line` appended to `text` broken at spaces to fit --help's width with `indent` spaces before it; continuation
 *  lines get `continuation` more. */
void appendWrapped(std::string& text, const std::string& line, std::size_t indent, std::size_t continuation);

} // namespace inkgraph
