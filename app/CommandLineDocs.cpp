#include "app/CommandLineDocs.h"

#include "render/BuildInfo.h"
#include "app/Cli.h"
#include "flags/FlagTable.h"
#include "flags/Options.h"
#include "render/ImageIoModule.h"
#include "gl/BinaryLocation.h"
#include "scene/Scene.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace inkgraph {
namespace {

// --- roff --------------------------------------------------------------------------------------------------------

/** `text` (UTF-8, one line) for roff: backslashes and minus signs escaped (so "--size" stays two hyphen-minus signs
 *  when copied from the page), every other character beyond ASCII as groff's \[uXXXX]. */
std::string roffText(const std::string& text) {
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c == '\\') {
            out += "\\e";
        } else if (c == '-') {
            out += "\\-";
        } else if (c < 0x80) {
            out += char(c);
        } else {
            // A UTF-8 sequence: its length from the lead byte, the code point from the payload bits.
            const int length = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : 2;
            unsigned codePoint = c & (0x7F >> length);
            for (int k = 1; k < length && i + 1 < text.size(); ++k)
                codePoint = (codePoint << 6) | (static_cast<unsigned char>(text[++i]) & 0x3F);
            char escape[16];
            std::snprintf(escape, sizeof escape, "\\[u%04X]", codePoint);
            out += escape;
        }
    }
    return out;
}

/** A line of running text: no leading blanks (they would break the line), and a leading '.' or '\'' kept from
 *  being read as a request. */
std::string roffLine(const std::string& text) {
    const std::size_t start = text.find_first_not_of(' ');
    if (start == std::string::npos) return "";
    const std::string line = roffText(text.substr(start));
    return (line[0] == '.' || line[0] == '\'' ? "\\&" : "") + line + "\n";
}

/** A macro argument in double quotes. */
std::string roffQuoted(const std::string& text) {
    std::string quoted;
    for (char c : roffText(text)) quoted += c == '"' ? std::string("\\(dq") : std::string(1, c);
    return "\"" + quoted + "\"";
}

std::string bold(const std::string& text) { return "\\fB" + roffText(text) + "\\fR"; }
std::string italic(const std::string& text) { return "\\fI" + roffText(text) + "\\fR"; }

/** A flag's tag: its names in bold, its value in italics ("-o, --output FILE"). */
std::string flagTag(const Flag& entry) {
    std::string tag;
    for (const std::string& name : entry.names) tag += (tag.empty() ? "" : ", ") + bold(name);
    if (!entry.valueName.empty()) tag += " " + italic(entry.valueName);
    return tag;
}

/** A help-only entry's label ("--TYPE-width PX", "MODEL..."): a flag pattern in bold, its value in italics. */
std::string labelTag(const std::string& label) {
    const std::size_t space = label.find(' ');
    if (label[0] != '-') return italic(label);
    if (space == std::string::npos) return bold(label);
    return bold(label.substr(0, space)) + " " + italic(label.substr(space + 1));
}

/** A help text as roff: paragraphs run on, each list item ("  outline: ...") on a line of its own. */
std::string roffHelp(const std::string& help) {
    std::string text;
    bool first = true;
    for (const std::string& block : helpBlocks(help)) {
        if (!first && block.rfind("  ", 0) == 0) text += ".br\n";
        text += roffLine(block);
        first = false;
    }
    return text;
}

std::string commandSynopsis(const CommandInfo& command) {
    return bold("inkgraph " + command.names.front()) + " " + roffText(command.arguments);
}

std::string renderFlagsSection() {
    std::string text =
        ".SH \"RENDER OPTIONS\"\n" + roffLine(std::string("The flags of inkgraph render, as inkgraph help render "
                                                          "lists them. -h or --help in a flag's place prints them "
                                                          "and does nothing else. ") +
                                              kFlagValueForms);
    for (HelpSection section : helpSections()) {
        text += ".SS " + roffQuoted(helpSectionTitle(section)) + "\n";
        std::vector<const Flag*> untold; // flags the section's patterns describe (--TYPE-width: --outline-width, ...)
        for (const Flag& entry : renderFlags()) {
            if (entry.section != section) continue;
            if (entry.help.empty()) {
                if (!entry.names.empty()) untold.push_back(&entry);
                continue;
            }
            if (entry.names.empty() && entry.helpLabel.empty()) {
                text += ".PP\n" + roffHelp(entry.help);
                continue;
            }
            text += ".TP\n" + (entry.helpLabel.empty() ? flagTag(entry) : labelTag(entry.helpLabel)) + "\n" +
                    roffHelp(entry.help);
        }
        if (!untold.empty()) {
            text += ".PP\n" + roffLine("The flags the patterns above stand for:") + ".RS\n";
            for (const Flag* entry : untold) text += flagTag(*entry) + "\n.br\n";
            text += ".RE\n";
        }
    }
    return text;
}

// --- bash --------------------------------------------------------------------------------------------------------

/** `words` for a single-quoted bash word list; they must be plain (flag names, choices), so nothing needs quoting. */
std::string shellWords(const std::vector<std::string>& words) {
    std::string text;
    for (const std::string& word : words) {
        const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
            return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' || c == '/';
        });
        if (!plain) throw std::logic_error("bashCompletion(): '" + word + "' is not a plain word");
        text += (text.empty() ? "" : " ") + word;
    }
    return "'" + text + "'";
}

/** What the value of `entry` completes to, as the body of its case branch; empty: nothing to offer. */
std::string valueCompletion(const Flag& entry) {
    if (!entry.choices.empty()) {
        if (entry.commaList) return "_inkgraph_list " + shellWords(entry.choices);
        return "COMPREPLY=($(compgen -W " + shellWords(entry.choices) + " -- \"$cur\"))";
    }
    const std::string& value = entry.valueName;
    if (value == "DIR") return "_inkgraph_folders";
    if (entry.pathValue || value == "FILE") return "_inkgraph_files";
    if (value.rfind("FILE.", 0) == 0) return "_inkgraph_files '*." + shellWords({value.substr(5)}).substr(1);
    return "";
}

} // namespace

std::string manPage() {
    std::string text = ".\\\" inkgraph(1), generated by `inkgraph help --man` from app/Cli.cpp's commands and "
                       "flags/FlagTable.cpp's flags; do not edit.\n";
    text += ".TH INKGRAPH 1 \"\" " + roffQuoted(std::string("inkgraph ") + inkgraphVersion()) + " \"User Commands\"\n";
    text += ".nh\n.ad l\n"; // no hyphenation, ragged right: flags and file names must read as they are typed
    text += ".SH NAME\ninkgraph \\- " + roffText(kProgramSummary) + "\n";

    text += ".SH SYNOPSIS\n";
    for (const CommandInfo& command : commands()) text += ".br\n" + commandSynopsis(command) + "\n";

    text += ".SH DESCRIPTION\n" +
            roffLine("inkgraph renders 3-D models (" + modelFormatNames() +
                     ") as anime- and comic-style stills: "
                     "shading and line drawings (silhouettes, contours, suggestive contours, creases and more) "
                     "computed by a render graph that runs only the passes the requested outputs need. It needs no "
                     "window or display: OpenGL 4.5 core through EGL, on a GPU's driver or on Mesa's software "
                     "renderer (llvmpipe). Several models in one run share one GL context (a batch); --shard splits "
                     "a batch over the tasks of an array job.");

    text += ".SH COMMANDS\n";
    for (const CommandInfo& command : commands()) {
        std::string names;
        for (const std::string& name : command.names) names += (names.empty() ? "" : ", ") + bold(name);
        text += ".TP\n" + names + " " + roffText(command.arguments) + "\n";
        std::string help = command.help;
        std::replace(help.begin(), help.end(), '\n', ' ');
        text += roffLine(help);
    }

    text += renderFlagsSection();

    text += ".SH \"EXIT STATUS\"\n";
    for (const ExitCodeMeaning& exit : exitCodeMeanings())
        text += ".TP\n" + bold(std::to_string(exit.code)) + "\n" + roffLine(exit.meaning);

    const std::vector<std::pair<std::string, std::string>> environment = {
        {"INKGRAPH_SHADER_DIR",
         "the folder of the GLSL shaders, instead of the one installed with the program (see FILES)"},
        {"INKGRAPH_IMAGEIO_MODULE", "the OpenImageIO module to load for formats other than PNG, instead of the "
                                    "installed one"},
        {"INKGRAPH_EGL_PLATFORM", "device or surfaceless: the only EGL platform to try (as --egl-platform)"},
        {"INKGRAPH_GL_DEBUG", "1: print the driver's KHR_debug messages on the standard error"},
        {"LP_NUM_THREADS", "the threads of Mesa's llvmpipe (software rendering); 1 gives steadier timings on small "
                           "machines"},
        {"EGL_LOG_LEVEL", "debug: Mesa explains why no EGL display or context could be made"},
    };
    text += ".SH ENVIRONMENT\n";
    for (const auto& [name, meaning] : environment) text += ".TP\n" + bold(name) + "\n" + roffLine(meaning);

    text +=
        ".SH FILES\n" + roffLine("PREFIX is the folder above the one holding the inkgraph binary (/usr for the Debian "
                                 "package), so an installed tree can be moved as a whole.");
    const std::vector<std::pair<std::string, std::string>> files = {
        {"PREFIX/" + installedShaderFolder().string() + "/", "the GLSL shaders (INKGRAPH_SHADER_DIR overrides them)"},
        {"PREFIX/" + (installedDataFolder() / "shademaps").string() + "/",
         "the bundled shade maps, for --shademap (README.md describes them)"},
        {"PREFIX/" + (installedModuleFolder() / kImageIoModuleName).string(),
         "the OpenImageIO module, loaded only by a run that reads or writes a format other than PNG"},
    };
    for (const auto& [path, meaning] : files) text += ".TP\n" + italic(path) + "\n" + roffLine(meaning);

    text += ".SH \"SEE ALSO\"\n" + roffLine("inkgraph --version --verbose (what the program runs on); README.md and "
                                            "docs/ of the source tree: docs/install.md, docs/batch.md, docs/lines.md, "
                                            "docs/shading.md.");
    return text;
}

std::string bashCompletion() {
    std::vector<std::string> allNames;
    for (const CommandInfo& command : commands())
        for (const std::string& name : command.names) allNames.push_back(name);

    std::string text =
        "# bash completion for inkgraph, generated by `inkgraph help --bash-completion` from app/Cli.cpp's commands\n"
        "# and flags/FlagTable.cpp's flags; do not edit.\n\n"
        "# File names for the word being completed: those matching the glob $1 (and folders), else all.\n"
        "_inkgraph_files() {\n"
        "    local IFS=$'\\n'\n"
        "    compopt -o filenames 2>/dev/null\n"
        "    if [[ -n $1 ]]; then\n"
        "        COMPREPLY=($(compgen -f -X \"!$1\" -- \"$cur\") $(compgen -d -- \"$cur\"))\n"
        "    else\n"
        "        COMPREPLY=($(compgen -f -- \"$cur\"))\n"
        "    fi\n"
        "}\n\n"
        "_inkgraph_folders() {\n"
        "    local IFS=$'\\n'\n"
        "    compopt -o filenames 2>/dev/null\n"
        "    COMPREPLY=($(compgen -d -- \"$cur\"))\n"
        "}\n\n"
        "# One of the words $1 after the last comma of a comma-separated list.\n"
        "_inkgraph_list() {\n"
        "    local prefix=\n"
        "    [[ $cur == *,* ]] && prefix=${cur%,*},\n"
        "    compopt -o nospace 2>/dev/null\n"
        "    COMPREPLY=($(compgen -P \"$prefix\" -W \"$1\" -- \"${cur##*,}\"))\n"
        "}\n\n"
        "_inkgraph() {\n"
        "    local cur=${COMP_WORDS[COMP_CWORD]} prev=${COMP_WORDS[COMP_CWORD - 1]}\n"
        "    COMPREPLY=()\n"
        "    if ((COMP_CWORD == 1)); then\n"
        "        COMPREPLY=($(compgen -W " +
        shellWords(allNames) +
        " -- \"$cur\"))\n"
        "        return\n"
        "    fi\n"
        "    case ${COMP_WORDS[1]} in\n";
    for (const CommandInfo& command : commands()) {
        std::string pattern;
        for (const std::string& name : command.names) pattern += (pattern.empty() ? "" : "|") + name;
        if (command.names.front() == "render") {
            text += "    " + pattern + ") ;;\n";
            continue;
        }
        text += "    " + pattern + ")\n";
        if (!command.words.empty())
            text += "        if ((COMP_CWORD == 2)); then\n"
                    "            COMPREPLY=($(compgen -W " +
                    shellWords(command.words) +
                    " -- \"$cur\"))\n"
                    "        fi\n";
        text += "        return ;;\n";
    }
    text += "    *) return ;;\n"
            "    esac\n"
            "    # inkgraph render: the value of the flag before, else a flag, else a model file.\n"
            "    case $prev in\n";
    std::vector<std::string> flagNames;
    std::string noCompletion; // the flags whose value is free text: nothing to offer
    for (const Flag& entry : renderFlags()) {
        for (const std::string& name : entry.names) flagNames.push_back(name);
        if (entry.names.empty() || entry.valueName.empty()) continue;
        std::string pattern;
        for (const std::string& name : entry.names) pattern += (pattern.empty() ? "" : "|") + name;
        const std::string completion = valueCompletion(entry);
        if (completion.empty())
            noCompletion += (noCompletion.empty() ? "" : "|") + pattern;
        else
            text += "    " + pattern + ") " + completion + "; return ;;\n";
    }
    flagNames.push_back("--help");
    if (!noCompletion.empty()) text += "    " + noCompletion + ") return ;;\n";
    text += "    esac\n"
            "    if [[ $cur == -* ]]; then\n"
            "        COMPREPLY=($(compgen -W " +
            shellWords(flagNames) +
            " -- \"$cur\"))\n"
            "    else\n"
            "        _inkgraph_files\n"
            "    fi\n"
            "}\n\n"
            "complete -F _inkgraph inkgraph\n";
    return text;
}

} // namespace inkgraph
