#include "flags/Options.h"

#include "render/ErrorReport.h"
#include "flags/FlagTable.h"

#include <algorithm>
#include <set>
#include <thread>

#include <sched.h>

namespace inkgraph {

int usableCores() {
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    int cores = sched_getaffinity(0, sizeof(allowed), &allowed) == 0 ? CPU_COUNT(&allowed) : 0;
    if (cores <= 0) cores = int(std::thread::hardware_concurrency());
    return std::max(cores, 1);
}

int defaultJobs() { return std::min(usableCores(), kMaxDefaultJobs); }

int postStageLoopThreads(int jobs) { return std::max(1, usableCores() / (std::max(jobs, 0) + 1)); }

namespace {

/** Whether `argument` names a flag of the table that takes a value (so the argument after it is that value). */
bool takesValue(const std::string& argument) {
    const Flag* flag = findFlag(argument);
    return flag != nullptr && flag->apply && !flag->valueName.empty();
}

} // namespace

void separateAttachedValues(std::vector<std::string>& arguments, std::vector<std::string>& origins) {
    std::vector<std::string> apart;
    std::vector<std::string> apartOrigins;
    const bool sourced = !origins.empty();
    auto keep = [&](std::string argument, std::size_t from) {
        apart.push_back(std::move(argument));
        if (sourced) apartOrigins.push_back(origins[from]);
    };
    for (std::size_t i = 0; i < arguments.size(); ++i) {
        const std::string& argument = arguments[i];
        const std::size_t equals = argument.find('=');
        if (takesValue(argument)) {
            keep(argument, i);
            if (i + 1 < arguments.size()) {
                ++i;
                keep(arguments[i], i);
            }
        } else if (argument.rfind('-', 0) == 0 && equals != std::string::npos) {
            const std::string name = argument.substr(0, equals);
            const Flag* flag = findFlag(name);
            if (flag == nullptr || !flag->apply) {
                keep(argument, i); // refused by the parser as an unknown option, as typed
            } else if (flag->valueName.empty()) {
                throw UsageError(name + ": takes no value, got '" + argument.substr(equals + 1) + "'");
            } else if (name.rfind("--", 0) != 0) {
                // As getopt: "-o=x.png" would be the file "=x.png"; the long name takes '='.
                const std::string value = equals + 1 < argument.size() ? argument.substr(equals + 1) : flag->valueName;
                throw UsageError("'" + argument + "': " + name + " takes its value as the next argument (" + name +
                                 " " + value + ", or " + flag->names.back() + "=" + value + ")");
            } else {
                keep(name, i);
                keep(argument.substr(equals + 1), i);
            }
        } else {
            keep(argument, i);
        }
    }
    arguments = std::move(apart);
    if (sourced) origins = std::move(apartOrigins);
}

namespace {

/** Applies arguments[i] (and its value: i then points at it) to `options`. Returns false at --help, where parsing
 *  stops. Records each flag given in `given`. */
bool parseArgument(const std::vector<std::string>& arguments, std::size_t& i, RenderOptions& options,
                   std::vector<const Flag*>& given, bool flagsOnly) {
    const std::string& argument = arguments[i];
    if (flagsOnly && (argument.empty() || argument[0] != '-')) {
        // A flag's name without its dashes (Look::set("shading", ...)) is named with them.
        const Flag* meant = argument.empty() ? nullptr : findFlag("--" + argument);
        throw UsageError("'" + argument + "' is not a flag" +
                         (meant != nullptr && meant->apply ? " (did you mean '--" + argument + "'?)" : ""));
    }
    if (argument == "--help" || argument == "-h") {
        if (flagsOnly) throw UsageError("unknown option '" + argument + "'");
        options.help = true;
        return false;
    }
    if (argument.empty() || argument[0] != '-') {
        if (options.modelPaths.empty()) options.modelPath = argument;
        options.modelPaths.push_back(argument);
        return true;
    }
    const Flag* flag = findFlag(argument);
    if (flag == nullptr || !flag->apply) throw UsageError("unknown option '" + argument + "'");
    std::string value;
    if (!flag->valueName.empty()) {
        if (i + 1 >= arguments.size()) throw UsageError(argument + ": missing value");
        if (arguments[i + 1].empty()) throw UsageError(argument + ": empty value");
        value = arguments[++i];
    }
    flag->apply(value, options);
    if (std::find(given.begin(), given.end(), flag) == given.end()) given.push_back(flag);
    return true;
}

/** The given flags whose rule `which` selects: the refusal of the first that changes nothing, in the table's order. */
template <typename Which>
void refuseWithoutEffect(const RenderOptions& options, const std::vector<const Flag*>& given, Which which) {
    for (const Flag& flag : renderFlags())
        if (flag.noEffect && which(flag) && std::find(given.begin(), given.end(), &flag) != given.end())
            if (const std::string refusal = flag.noEffect(options); !refusal.empty()) throw UsageError(refusal);
}

/** After parsing: every flag given that would change nothing is refused, so a typo'd mode or a missing line type is
 *  not silently rendered without what the user asked for; then what no single flag can judge alone. In this order:
 *  the look's flags, the lines' settings, the data size, the line types'
 *  widths and colours, the outputs. */
void checkGivenFlags(const RenderOptions& options, const std::vector<const Flag*>& given, bool flagsOnly) {
    // Width and colour flags, one pair per line type, are the entries without help of their own.
    auto isStyle = [](const Flag& flag) { return flag.section == HelpSection::Lines && flag.help.empty(); };
    refuseWithoutEffect(options, given, [](const Flag& flag) { return flag.section == HelpSection::Look; });
    refuseWithoutEffect(options, given,
                        [&](const Flag& flag) { return flag.section == HelpSection::Lines && !isStyle(flag); });
    const Look& look = options.look;
    if (std::size_t(options.width) * look.supersample > std::size_t(kMaxImageSide) ||
        std::size_t(options.height) * look.supersample > std::size_t(kMaxImageSide))
        throw UsageError("--supersample: " + std::to_string(look.supersample) + " x --size " +
                         std::to_string(options.width) + "x" + std::to_string(options.height) +
                         " exceeds the largest buffer side, " + std::to_string(kMaxImageSide));
    refuseWithoutEffect(options, given, isStyle);
    if (!flagsOnly && options.outputPath.empty() && !options.printPlan && options.dumpDirectory.empty() &&
        options.graphvizPath.empty() && options.contactSheetPath.empty() && options.svgPath.empty() &&
        options.strokesPath.empty())
        throw UsageError("missing -o OUT.png (or --print-plan / --graphviz to only show the plan)");
    if (options.eye && options.target && *options.eye == *options.target)
        throw UsageError("--eye and --target must differ");
    refuseWithoutEffect(options, given, [](const Flag& flag) {
        return flag.section != HelpSection::Look && flag.section != HelpSection::Lines;
    });
    if (!options.svgPath.empty() && look.lines.empty()) throw UsageError("--svg: no line types to write (add --lines)");
    if (!options.strokesPath.empty() && look.lines.empty())
        throw UsageError("--strokes: no line types to write (add --lines)");
    if (!options.statsPath.empty() && !rendersImages(options))
        throw UsageError("--stats needs -o or --dump: with --print-plan alone nothing is rendered or timed");
    // '-' reads standard input for --list; an output named so was silently a file called '-'.
    for (const auto& [flag, field] : outputPathFlags())
        if (options.*field == "-")
            throw UsageError(flag + " '-': outputs are written to files, not to standard output; name a file (a file "
                                    "called '-' is './-')");
}

} // namespace

const std::vector<std::pair<std::string, std::string RenderOptions::*>>& outputPathFlags() {
    static const std::vector<std::pair<std::string, std::string RenderOptions::*>> kFlags = {
        {"-o", &RenderOptions::outputPath},
        {"--dump", &RenderOptions::dumpDirectory},
        {"--stats", &RenderOptions::statsPath},
        {"--graphviz", &RenderOptions::graphvizPath},
        {"--contact-sheet", &RenderOptions::contactSheetPath},
        {"--svg", &RenderOptions::svgPath},
        {"--strokes", &RenderOptions::strokesPath},
    };
    return kFlags;
}

bool rendersImages(const RenderOptions& options) {
    return !options.outputPath.empty() || !options.dumpDirectory.empty() || !options.contactSheetPath.empty() ||
           !options.svgPath.empty() || !options.strokesPath.empty();
}

RenderOptions parseRenderOptions(const std::vector<std::string>& arguments) {
    return parseRenderOptions(arguments, {});
}

namespace {

/** Whether an argument of this origin is a style file's setting (styleArguments() names its file and line). */
bool fromStyleFile(const std::vector<std::string>& origins, std::size_t index) {
    return !origins.empty() && origins[index].starts_with("--style ");
}

/** The style file's settings that the rest of the command line makes moot: each given by the style file alone that
 *  changes nothing with the options parsed (a width for a line type --lines leaves out, the shininess of a look
 *  --shading replaced), or that chooses what a flag on the command line chooses (--bands and --shademap). A style is
 *  a house style, used with many looks: its settings are defaults the command line wins over, not requests. */
std::set<const Flag*> mootStyleSettings(const RenderOptions& options, const std::vector<const Flag*>& fromStyle,
                                        const std::vector<const Flag*>& fromCommandLine) {
    const auto onCommandLine = [&](std::string_view name) {
        return std::ranges::any_of(fromCommandLine, [&](const Flag* flag) { return flag->names.back() == name; });
    };
    std::set<const Flag*> moot;
    for (const Flag* flag : fromStyle) {
        if (std::ranges::find(fromCommandLine, flag) != fromCommandLine.end()) continue;
        const std::string& name = flag->names.back();
        if ((flag->noEffect && !flag->noEffect(options).empty()) ||
            (name == "--bands" && onCommandLine("--shademap")) || (name == "--shademap" && onCommandLine("--bands")))
            moot.insert(flag);
    }
    return moot;
}

/** parseRenderOptions() and parseRenderFlags(): `flagsOnly` takes flags alone and requires neither MODEL nor output. */
RenderOptions parse(std::vector<std::string> arguments, std::vector<std::string> origins, bool flagsOnly,
                    FlagChecks checks) {
    if (!origins.empty() && origins.size() != arguments.size())
        throw std::invalid_argument("parseRenderOptions(): " + std::to_string(origins.size()) + " origins for " +
                                    std::to_string(arguments.size()) + " arguments");
    separateAttachedValues(arguments, origins);
    RenderOptions options;
    std::vector<const Flag*> given, fromStyle, fromCommandLine;
    for (std::size_t i = 0; i < arguments.size(); ++i) {
        const std::size_t flagIndex = i;
        try {
            if (!parseArgument(arguments, i, options, given, flagsOnly)) return options;
        } catch (const UsageError& error) {
            if (origins.empty() || origins[flagIndex].empty()) throw;
            throw UsageError(origins[flagIndex] + ": " + error.what());
        }
        if (const Flag* flag = findFlag(arguments[flagIndex]); flag != nullptr) {
            (fromStyleFile(origins, flagIndex) ? fromStyle : fromCommandLine).push_back(flag);
            if (flag->names.back() == "--shademap")
                options.shadeMapOrigin = fromStyleFile(origins, flagIndex) ? origins[flagIndex] : std::string();
        }
    }
    if (!flagsOnly && options.modelPaths.empty() && options.listPath.empty())
        throw UsageError("missing MODEL (a " + modelFileExtensions() + " file, or --list FILE)");
    if (checks == FlagChecks::ValuesAndRules) {
        // Parsed again without them: a moot setting's value may still stand in the options (--bands beside
        // --shademap). Each round leaves out at least one setting, so this ends.
        if (const std::set<const Flag*> moot = mootStyleSettings(options, fromStyle, fromCommandLine); !moot.empty()) {
            std::vector<std::string> keptArguments, keptOrigins;
            for (std::size_t i = 0; i < arguments.size(); ++i) {
                // A style's settings come as pairs, the flag and its value (styleArguments()).
                const std::size_t count = fromStyleFile(origins, i) ? 2 : 1;
                if (count == 1 || !moot.contains(findFlag(arguments[i])))
                    for (std::size_t k = i; k < std::min(i + count, arguments.size()); ++k) {
                        keptArguments.push_back(arguments[k]);
                        keptOrigins.push_back(origins[k]);
                    }
                i += count - 1;
            }
            return parse(std::move(keptArguments), std::move(keptOrigins), flagsOnly, checks);
        }
        checkGivenFlags(options, given, flagsOnly);
    }
    return options;
}

} // namespace

RenderOptions parseRenderOptions(const std::vector<std::string>& arguments, const std::vector<std::string>& origins) {
    return parse(arguments, origins, false, FlagChecks::ValuesAndRules);
}

RenderOptions parseRenderFlags(const std::vector<std::string>& arguments, const std::vector<std::string>& origins,
                               FlagChecks checks) {
    return parse(arguments, origins, true, checks);
}

void checkFlagRules(const RenderOptions& options, const std::vector<std::string>& given) {
    std::vector<const Flag*> flags;
    for (const std::string& name : given) {
        const Flag* flag = findFlag(name);
        if (flag == nullptr) throw std::logic_error("checkFlagRules(): no flag '" + name + "'");
        if (std::find(flags.begin(), flags.end(), flag) == flags.end()) flags.push_back(flag);
    }
    checkGivenFlags(options, flags, true);
}

ViewSampling viewSamplingOf(const RenderOptions& options) {
    ViewSampling sampling = options.viewSampling;
    sampling.light = options.look.towardLight;
    return sampling;
}

CameraRequest cameraRequestOf(const RenderOptions& options) {
    CameraRequest request;
    request.eye = options.eye;
    request.orbit = options.orbit;
    request.target = options.target;
    request.frameNodes = options.frameNodes;
    request.up = options.up;
    request.fovYDegrees = options.fovYDegrees;
    request.ignoreFileCamera = options.autoCamera;
    if (options.clipRange) {
        request.zNear = options.clipRange->x;
        request.zFar = options.clipRange->y;
    }
    request.width = options.width;
    request.height = options.height;
    return request;
}

std::string renderHelp() {
    constexpr std::size_t kLineWidth = 100;
    std::string exitCodes = "Exit codes:";
    std::size_t lineStart = 0;
    for (const ExitCodeMeaning& exit : exitCodeMeanings()) {
        const std::string item =
            std::to_string(exit.code) + " " + exit.meaning + (&exit == &exitCodeMeanings().back() ? "." : ",");
        if (exitCodes.size() - lineStart + 1 + item.size() > kLineWidth) {
            exitCodes += "\n";
            lineStart = exitCodes.size();
        } else {
            exitCodes += " ";
        }
        exitCodes += item;
    }
    std::string valueForms;
    appendWrapped(valueForms, kFlagValueForms, 0, 0);
    return "Usage: inkgraph render MODEL... -o OUT.png [options]\n\n"
           "Renders one still of each MODEL (" +
           modelFileExtensions() + ") with no window or display (EGL).\n" + valueForms + renderFlagsHelp() + "\n" +
           exitCodes + "\n";
}

} // namespace inkgraph
