#pragma once
/** @file Style files (--style FILE): a look saved as text, one render setting per line, so a studio keeps its house
 *  style in version control and renders with `-o` and a model only.
 *
 *      # inkgraph style
 *      shading = comic
 *      shademap = maps/metallic.png      # relative to this file
 *      lines = contour, suggestive
 *      contour-color = 0.1, 0.1, 0.2
 *
 *  A setting is a look flag of `inkgraph render` without its dashes (styleSettingNames()); its value is checked by the
 *  flag's own parser. Settings come before the command line's flags, so a flag given there wins. */

#include <string>
#include <string_view>
#include <vector>

namespace inkgraph {

/** Arguments with, for each, where it came from: "" for the command line, "--style 'look.style' line 3" for a
 *  setting from a style file (messages about it start with that). */
struct SourcedArguments {
    std::vector<std::string> arguments;
    std::vector<std::string> origins;
};

/** The settings a style file may hold: look, lines and size; not the model, camera or outputs. */
const std::vector<std::string>& styleSettingNames();

/** The flags a style file's text stands for, in its order: "shading = comic" -> "--shading", "comic". `source` names
 *  the file in messages; a relative shademap path is resolved against `directory`. Throws UsageError naming the
 *  source and line for a line that is not `name = value`, an unknown or repeated name, or an empty value. */
SourcedArguments styleArguments(std::string_view text, const std::string& source, const std::string& directory);

/** The arguments as the parser takes them: each "--NAME=VALUE" apart (separateAttachedValues()), and the settings of
 *  `--style FILE` before every argument (which keep `--style FILE`, so the options record the file). Throws
 *  UsageError naming the file when it cannot be read, is above 64 KiB, or holds a bad line; at most one --style. */
SourcedArguments expandStyleFile(const std::vector<std::string>& arguments);

} // namespace inkgraph
