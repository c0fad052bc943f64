#include "flags/FlagTable.h"

#include "gl/HeadlessContext.h"
#include "graph/Resource.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/lines/LineTypes.h"
#include "render/MemoryBudget.h"
#include "render/StillRenderer.h"
#include "scene/MessageText.h"
#include "scene/TextureImage.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace inkgraph {
namespace {

constexpr double kMinFovDegrees = 0.01;
constexpr double kMaxFovDegrees = 179.0;
constexpr double kMaxShininess = 1e6;
/** A thousandth of a pixel: no line is seen thinner, and the stroke stage's single floats hold it (a width of 1e-46
 *  passed the flag as a double and reached the strokes as 0). */
constexpr double kMinLineWidthPixels = 0.001;
constexpr double kMaxLineWidthPixels = 256.0;
constexpr double kMinClipDistance = 1e-30;
constexpr double kMaxClipDistance = 1e30;
constexpr double kMaxClipRatio = 1e30;
constexpr int kMaxMemoryLimitMib = 1 << 24; // 16 TiB
/** --hidden-dash's range for ON and for an OFF that is not 0, in output pixels. */
constexpr double kMinDashPixels = 1.0;
constexpr double kMaxDashPixels = 4096.0;
/** --weld-distance's largest: a hundredth of the model's size already merges whole features of a detailed model. */
constexpr double kMaxWeldTolerance = 0.01;
/** At +-90 degrees of --orbit elevation the view would be parallel to up. */
constexpr double kMaxOrbitElevationDegrees = 89.9;
constexpr double kMaxOrbitAzimuthDegrees = 360.0;
/** As --eye's coordinates (parsePoint): the eye stays within what double subtracts meaningfully. */
constexpr double kMaxOrbitDistance = 1e15;
/** --orbit AZ,EL,xS: a thousand times the framing distance already shows the model as a speck. */
constexpr double kMaxOrbitDistanceScale = 1000.0;
const std::vector<std::string> kOutputExtensions = {".png", ".exr", ".tif", ".tiff", ".jpg", ".jpeg"};

std::string lowercaseExtension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

double parseNumber(const std::string& flag, const std::string& text) {
    try {
        return parseFlagNumber(flag, text);
    } catch (const std::invalid_argument& error) {
        throw UsageError(error.what());
    }
}

std::vector<std::string> splitList(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream stream(text);
    while (std::getline(stream, part, separator)) parts.push_back(part);
    if (!text.empty() && text.back() == separator) parts.push_back("");
    return parts;
}

/** The items of a LIST flag that also takes 'none' alone. 'none' inside a list is refused for what it is: read as an
 *  item, it was called an unknown type ("--lines outline,none"), which it is not. */
std::vector<std::string> listItemsBesideNone(const std::string& flag, const std::string& value) {
    std::vector<std::string> items = splitList(value, ',');
    if (std::find(items.begin(), items.end(), "none") != items.end())
        throw UsageError(flag + ": 'none' is given alone, not in a list (got '" + value + "')");
    return items;
}

glm::dvec3 parseVector(const std::string& flag, const std::string& text) {
    const std::vector<std::string> parts = splitList(text, ',');
    if (parts.size() != 3)
        throw UsageError(flag + ": expected X,Y,Z (three comma-separated numbers), got '" + text + "'");
    return {parseNumber(flag, parts[0]), parseNumber(flag, parts[1]), parseNumber(flag, parts[2])};
}

/** A point in world units. Bounded so that differences of points stay finite and meaningful in double (at 1e15
 *  adjacent doubles are 0.125 apart); beyond it the camera's distances overflow and the messages mislead. */
glm::dvec3 parsePoint(const std::string& flag, const std::string& text) {
    constexpr double kMaxCoordinate = 1e15;
    const glm::dvec3 point = parseVector(flag, text);
    if (std::max({std::abs(point.x), std::abs(point.y), std::abs(point.z)}) > kMaxCoordinate)
        throw UsageError(flag + ": coordinates must lie within +-1e15, got '" + text + "'");
    return point;
}

/** A direction, made unit length. Scaled by its largest component first, so any finite input keeps its direction
 *  (1e300,1e300,0 would overflow the length and normalise to zero; 1e-300,0,0 would underflow). */
glm::dvec3 parseDirection(const std::string& flag, const std::string& text) {
    const glm::dvec3 direction = parseVector(flag, text);
    const double largest = std::max({std::abs(direction.x), std::abs(direction.y), std::abs(direction.z)});
    if (largest == 0.0) throw UsageError(flag + ": the direction must not be zero, got '" + text + "'");
    return glm::normalize(direction / largest);
}

/** AZIMUTH,ELEVATION[,DISTANCE]: degrees, degrees, world units or xS (S times the auto-framing distance). */
Orbit parseOrbit(const std::string& flag, const std::string& text) {
    const std::vector<std::string> parts = splitList(text, ',');
    if (parts.size() != 2 && parts.size() != 3)
        throw UsageError(flag + ": expected AZIMUTH,ELEVATION or AZIMUTH,ELEVATION,DISTANCE, got '" + text + "'");
    Orbit orbit;
    orbit.azimuthDegrees = parseNumber(flag, parts[0]);
    orbit.elevationDegrees = parseNumber(flag, parts[1]);
    if (std::abs(orbit.azimuthDegrees) > kMaxOrbitAzimuthDegrees)
        throw UsageError(flag + ": the azimuth must lie in [-360, 360] degrees, got '" + text + "'");
    if (std::abs(orbit.elevationDegrees) > kMaxOrbitElevationDegrees)
        throw UsageError(flag + ": the elevation must lie in [-89.9, 89.9] degrees (at +-90 the view is parallel to " +
                         "--up), got '" + text + "'");
    if (parts.size() == 3 && !parts[2].empty() && parts[2][0] == 'x') {
        // xS: S times the auto-framing distance, as --views' distance jitter places a view.
        orbit.distanceScale = parseNumber(flag, parts[2].substr(1));
        if (!(orbit.distanceScale > 0.0 && orbit.distanceScale <= kMaxOrbitDistanceScale))
            throw UsageError(flag + ": the distance scale xS must have S above 0 and at most 1000, got '" + text + "'");
    } else if (parts.size() == 3) {
        orbit.distance = parseNumber(flag, parts[2]);
        if (!(*orbit.distance > 0.0 && *orbit.distance <= kMaxOrbitDistance))
            throw UsageError(flag + ": the distance must be above 0 and at most 1e15, got '" + text + "'");
    }
    return orbit;
}

/** Decimal digits only, after an optional '+' (as every number may carry): a count written "16.0" or "1e1" is taken
 *  for a typing slip, not read as 16 or 10. */
bool isDigits(const std::string& text) {
    const std::size_t start = text.starts_with('+') ? 1 : 0;
    return text.size() > start && text.find_first_not_of("0123456789", start) == std::string::npos;
}

void parseSize(const std::string& text, int& width, int& height) {
    const auto cross = text.find('x');
    if (cross == std::string::npos) throw UsageError("--size: expected WxH such as 1024x768, got '" + text + "'");
    const std::string widthText = text.substr(0, cross), heightText = text.substr(cross + 1);
    const double w = isDigits(widthText) ? parseNumber("--size", widthText) : std::nan(""); // refused below
    const double h = isDigits(heightText) ? parseNumber("--size", heightText) : std::nan("");
    if (w != std::floor(w) || h != std::floor(h) || w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide)
        throw UsageError("--size: width and height must be whole numbers from 1 to " + std::to_string(kMaxImageSide) +
                         ", got '" + text + "'");
    width = static_cast<int>(w);
    height = static_cast<int>(h);
}

/** `value` as --help writes a number: the shortest text that reads back as it, exponents without '+' and leading
 *  zeros (1e-6, 1e6). */
std::string helpNumber(double value) {
    std::string text = detail::formatNumber(value);
    const std::size_t exponent = text.find('e');
    if (exponent == std::string::npos) return text;
    std::string digits = text.substr(exponent + 1);
    const bool negative = !digits.empty() && digits[0] == '-';
    if (!digits.empty() && (digits[0] == '-' || digits[0] == '+')) digits.erase(0, 1);
    digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size() - 1));
    return text.substr(0, exponent) + "e" + (negative ? "-" : "") + digits;
}

/** A float setting as --help writes it: the shortest text that reads back as the float (0.15, not 0.15000000596). */
std::string helpNumber(float value) {
    char text[32];
    const auto [end, error] = std::to_chars(text, text + sizeof text, value);
    return error == std::errc() ? std::string(text, end) : helpNumber(double(value));
}

/** Numbers joined by commas, as a flag takes them ("6,4", "1,1,1"). */
std::string helpNumbers(const std::vector<double>& values) {
    std::string text;
    for (double value : values) {
        // Appended in two steps: GCC 12 warns (-Wrestrict, a false positive) of "," + a temporary string here.
        if (!text.empty()) text += ',';
        text += helpNumber(value);
    }
    return text;
}

/** "a, b or c" (or "a, b and c" with lastJoin " and "): a list for help and messages, from the table that holds it. */
std::string alternatives(const std::vector<std::string>& items, const char* lastJoin = " or ") {
    std::string text;
    for (std::size_t i = 0; i < items.size(); ++i)
        text += (i == 0 ? "" : i + 1 == items.size() ? lastJoin : ", ") + items[i];
    return text;
}

/** --dump's G-buffer files, from the pass's own table: "normal.exr, view.exr, ... and zbuffer.exr". */
std::string gbufferDumpFiles() {
    std::vector<std::string> files;
    for (const GBufferPass::Field& field : GBufferPass::fields()) files.push_back(field.fileName);
    files.push_back(GBufferPass::kZBufferFile);
    return alternatives(files, " and ");
}

std::string joined(const std::vector<std::string>& items) {
    std::string text;
    for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
    return text.empty() ? "(none in this version)" : text;
}

/** One word of a flag that takes a fixed set of words: the value it stands for, and what it means for --help (empty:
 * the word says it). A flag's help list, its completion words and its parser all come from its one table of these, so
 * the three cannot disagree. */
template <typename Value>
struct Choice {
    std::string word;
    Value value;
    std::string meaning;
};

template <typename Value>
std::vector<std::string> wordsOf(const std::vector<Choice<Value>>& choices) {
    std::vector<std::string> words;
    for (const Choice<Value>& choice : choices) words.push_back(choice.word);
    return words;
}

/** "a (default) | b | c": the words, the one standing for `defaultValue` marked. */
template <typename Value>
std::string choiceListText(const std::vector<Choice<Value>>& choices, const Value& defaultValue) {
    std::string text;
    for (const Choice<Value>& choice : choices)
        text += (text.empty() ? "" : " | ") + choice.word + (choice.value == defaultValue ? " (default)" : "");
    return text;
}

/** A list item per word with a meaning ("\n  a: meaning"), which --help hangs under the flag as --shading's models. */
template <typename Value>
std::string choiceMeaningsText(const std::vector<Choice<Value>>& choices) {
    std::string text;
    for (const Choice<Value>& choice : choices)
        if (!choice.meaning.empty()) text += "\n  " + choice.word + ": " + choice.meaning;
    return text;
}

/** The value word `text` stands for; throws UsageError "<flag>: unknown value '<text>' (available: a, b, c)", as
 *  --shading refuses a model (the library's tests read the names back from that list). */
template <typename Value>
Value parseChoice(const std::string& flag, const std::string& text, const std::vector<Choice<Value>>& choices) {
    for (const Choice<Value>& choice : choices)
        if (choice.word == text) return choice.value;
    std::string words;
    for (const Choice<Value>& choice : choices) words += (words.empty() ? "" : ", ") + choice.word;
    throw UsageError(flag + ": unknown value '" + text + "' (available: " + words + ")");
}

int parseWholeNumber(const std::string& flag, const std::string& text, int low, int high) {
    const double value = isDigits(text) ? parseNumber(flag, text) : std::nan(""); // refused below
    if (!(value >= low && value <= high) || value != std::floor(value))
        throw UsageError(flag + ": expected a whole number from " + std::to_string(low) + " to " +
                         std::to_string(high) + ", got '" + text + "'");
    return static_cast<int>(value);
}

/** K/N with 0 <= K < N (N at most a million: more shards than that is a mistake, not a cluster). */
Shard parseShard(const std::string& flag, const std::string& text) {
    const auto slash = text.find('/');
    if (slash == std::string::npos)
        throw UsageError(flag + ": expected K/N (this process's share K of N, 0 <= K < N), got '" + text + "'");
    Shard shard;
    shard.count = parseWholeNumber(flag, text.substr(slash + 1), 1, 1000000);
    shard.index = parseWholeNumber(flag, text.substr(0, slash), 0, shard.count - 1);
    return shard;
}

/** NAME=WEIGHT[,NAME=WEIGHT...] with weights in [0, 1] and no name twice (--expression, an --expressions
 *  alternative). */
std::vector<ExpressionWeight> parseExpressions(const std::string& flag, const std::string& value) {
    std::vector<ExpressionWeight> expressions;
    for (const std::string& part : splitList(value, ',')) {
        const std::size_t equals = part.rfind('=');
        if (equals == std::string::npos || equals == 0)
            throw UsageError(flag + ": expected NAME=WEIGHT[,NAME=WEIGHT...], got '" + value + "'");
        ExpressionWeight expression{part.substr(0, equals), parseNumber(flag, part.substr(equals + 1))};
        if (expression.weight < 0.0 || expression.weight > 1.0)
            throw UsageError(flag + ": the weight of '" + expression.name + "' must lie in [0, 1], got '" +
                             part.substr(equals + 1) + "'");
        if (std::ranges::find(expressions, expression.name, &ExpressionWeight::name) != expressions.end())
            throw UsageError(flag + ": '" + expression.name + "' is given twice");
        expressions.push_back(std::move(expression));
    }
    return expressions;
}

/** A whole number from 0 to 2^64 - 1, in decimal (--seed). */
std::uint64_t parseSeed(const std::string& flag, const std::string& text) {
    std::uint64_t value = 0;
    const std::size_t start = text.size() > 1 && text[0] == '+' ? 1 : 0; // from_chars takes no '+'
    const auto [stop, error] = std::from_chars(text.data() + start, text.data() + text.size(), value);
    if (error != std::errc() || stop != text.data() + text.size()) // an unsigned reading takes no '-' either
        throw UsageError(flag + ": expected a whole number from 0 to 18446744073709551615, got '" + text + "'");
    return value;
}

/** MEAN,SD[,LOW,HIGH] in degrees (--view-elevation). */
void parseViewElevation(const std::string& flag, const std::string& text, ViewSampling& sampling) {
    const std::vector<std::string> parts = splitList(text, ',');
    if (parts.size() != 2 && parts.size() != 4)
        throw UsageError(flag + ": expected MEAN,SD or MEAN,SD,LOW,HIGH (degrees), got '" + text + "'");
    const double mean = parseNumber(flag, parts[0]);
    const double deviation = parseNumber(flag, parts[1]);
    const double low = parts.size() == 4 ? parseNumber(flag, parts[2]) : sampling.elevationLow;
    const double high = parts.size() == 4 ? parseNumber(flag, parts[3]) : sampling.elevationHigh;
    for (const double degrees : {mean, low, high})
        if (std::abs(degrees) > kMaxOrbitElevationDegrees)
            throw UsageError(flag +
                             ": MEAN, LOW and HIGH must lie in [-89.9, 89.9] degrees (--orbit's elevations), "
                             "got '" +
                             text + "'");
    if (deviation < 0.0 || deviation > 180.0)
        throw UsageError(flag + ": SD must lie in [0, 180] degrees, got '" + text + "'");
    if (low > high) throw UsageError(flag + ": LOW must not exceed HIGH, got '" + text + "'");
    sampling.elevationMean = mean;
    sampling.elevationDeviation = deviation;
    sampling.elevationLow = low;
    sampling.elevationHigh = high;
}

/** A number from `low` to `high`. */
double parseNumberIn(const std::string& flag, const std::string& text, double low, double high,
                     const std::string& what) {
    const double value = parseNumber(flag, text);
    if (value < low || value > high) throw UsageError(flag + ": expected " + what + ", got '" + text + "'");
    return value;
}

/** A view flag that only --views uses. */
std::function<std::string(const RenderOptions&)> onlyWithViews(const std::string& flag) {
    return [flag](const RenderOptions& options) -> std::string {
        return options.viewsGiven ? "" : flag + " applies to --views N, which is not given";
    };
}

/** R,G,B or R,G,B,A with channels in [0, 1]. */
glm::dvec4 parseColor(const std::string& flag, const std::string& text) {
    const std::vector<std::string> parts = splitList(text, ',');
    if (parts.size() != 3 && parts.size() != 4)
        throw UsageError(flag + ": expected R,G,B or R,G,B,A with channels in [0,1], got '" + text + "'");
    glm::dvec4 color(0.0, 0.0, 0.0, 1.0);
    for (std::size_t channel = 0; channel < parts.size(); ++channel) {
        color[int(channel)] = parseNumber(flag, parts[channel]);
        if (color[int(channel)] < 0.0 || color[int(channel)] > 1.0)
            throw UsageError(flag + ": channels must lie in [0, 1], got '" + text + "'");
    }
    return color;
}

/** --face-orientation's words: the GPU's culling, or Winnemöller & Bangay 2002's CPU marking. */
const std::vector<Choice<FaceOrientationMethod>> kOrientationMethods = {
    {"standard", FaceOrientationMethod::Standard, "the GPU culls and lights per pixel"},
    {"during-triangles", FaceOrientationMethod::DuringTriangles, ""},
    {"during-vertices", FaceOrientationMethod::DuringVertices, ""},
    {"after-vertices", FaceOrientationMethod::AfterVertices, ""},
};

bool contains(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

std::string commaJoined(const std::vector<std::string>& names, const char* separator = ", ") {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : separator) + name;
    return text;
}

/** A number parameter's accepted range for --help, from its declaration: "; R above 0, up to 100". Empty for a
 *  choice, whose help names its words. */
std::string acceptedRangeText(const LineParameter& parameter) {
    if (parameter.isChoice()) return "";
    const std::string low = helpNumber(parameter.low);
    const std::string value = "; " + parameter.valueName + " ";
    if (!(parameter.high < std::numeric_limits<double>::max()))
        return value + (parameter.lowOpen ? "above " : "at least ") + low;
    const std::string high = helpNumber(parameter.high);
    if (parameter.lowOpen) return value + "above " + low + (parameter.highOpen ? " and below " : ", up to ") + high;
    return value + "from " + low + (parameter.highOpen ? ", below " : " to ") + high;
}

/** A line parameter's help with its default written in where the help says "{default}" (LineParameter::help). */
std::string lineParameterHelp(const LineParameter& parameter) {
    static const std::string kPlaceholder = "{default}";
    std::string help = parameter.help;
    for (std::size_t at = help.find(kPlaceholder); at != std::string::npos; at = help.find(kPlaceholder, at)) {
        if (!parameter.isChoice() && !parameter.defaultNumber)
            throw std::logic_error("lineParameterHelp(): '" + parameter.name + "' states a default it does not have");
        const std::string value = parameter.isChoice() ? parameter.defaultChoice : helpNumber(*parameter.defaultNumber);
        help.replace(at, kPlaceholder.size(), value);
        at += value.size();
    }
    return help;
}

/** The shading models with an ambient term whose default ambient is `model`'s: "flat, gouraud, lambert and phong". */
std::string modelsWithDefaultAmbientOf(ShadingModel model) {
    std::vector<std::string> names;
    for (const ShadingModelTraits& traits : shadingModels())
        if (traits.ambient && traits.defaultAmbient == traitsOf(model).defaultAmbient) names.push_back(traits.name);
    return alternatives(names, " and ");
}

// --- "has no effect" rules --------------------------------------------------------------------------------------

/** A shading flag that only the models with trait `has` take. */
std::function<std::string(const RenderOptions&)> onlyWithModels(const std::string& flag,
                                                                bool ShadingModelTraits::*has) {
    return [flag, has](const RenderOptions& options) -> std::string {
        if (traitsOf(options.look.shading).*has) return "";
        return flag + " has no effect with --shading " + traitsOf(options.look.shading).name + " (it applies to " +
               shadingModelsWith(has) + ")";
    };
}

/** A flag that only the line types in `types` use. */
std::function<std::string(const RenderOptions&)> onlyWithLineTypes(const std::string& flag,
                                                                   std::vector<std::string> types) {
    std::sort(types.begin(), types.end()); // named in messages alphabetically
    return [flag, types](const RenderOptions& options) -> std::string {
        for (const std::string& type : types)
            if (options.look.draws(type)) return "";
        return flag + " has no effect: none of the line types it applies to (" + commaJoined(types) + ") is in --lines";
    };
}

// --- the table ---------------------------------------------------------------------------------------------------

Flag flag(std::vector<std::string> names, std::string valueName, HelpSection section, std::string help,
          std::function<void(const std::string&, RenderOptions&)> apply) {
    Flag entry;
    entry.names = std::move(names);
    entry.valueName = std::move(valueName);
    entry.section = section;
    entry.help = std::move(help);
    entry.apply = std::move(apply);
    return entry;
}

Flag styleFlag(Flag entry) {
    entry.inStyle = true;
    return entry;
}

Flag helpOnly(HelpSection section, std::string label, std::string help) {
    Flag entry;
    entry.section = section;
    entry.helpLabel = std::move(label);
    entry.help = std::move(help);
    return entry;
}

/** A flag that takes one word of `choices`: its help is "<before>a (default) | b<after>" and a list item per meaning,
 *  the word marked default the one standing for `defaultValue` (the code's own default, so the mark cannot drift);
 *  its completion words and its parser come from the same table, and `store` puts the chosen value into the options. */
template <typename Value>
Flag choiceFlag(std::vector<std::string> names, std::string valueName, HelpSection section, const std::string& before,
                const std::vector<Choice<Value>>& choices, const Value& defaultValue, const std::string& after,
                std::function<void(const Value&, RenderOptions&)> store) {
    const std::string flagName = names.back();
    Flag entry = flag(std::move(names), std::move(valueName), section,
                      before + choiceListText(choices, defaultValue) + after + choiceMeaningsText(choices),
                      [flagName, choices, store](const std::string& value, RenderOptions& options) {
                          store(parseChoice(flagName, value, choices), options);
                      });
    entry.choices = wordsOf(choices);
    return entry;
}

/** The width, colour and parameter flags of every registered line type. */
void addLineTypeFlags(std::vector<Flag>& flags) {
    const LineStyle style;
    flags.push_back(helpOnly(HelpSection::Lines, "--TYPE-width PX",
                             "line width in pixels, " + helpNumber(kMinLineWidthPixels) + " to " +
                                 helpNumber(kMaxLineWidthPixels) + " (default " + helpNumber(style.widthPixels) +
                                 "), constant across distance, field of\n"
                                 "view and resolution, anti-aliased (for outline: the width showing outside the\n"
                                 "silhouette; outline and silhouette are drawn from their GL band's middle line)"));
    flags.push_back(helpOnly(HelpSection::Lines, "--TYPE-color R,G,B[,A]",
                             "line colour, channels in [0,1] (default " +
                                 helpNumbers({style.color.r, style.color.g, style.color.b}) + ")"));
    for (const LineType& type : lineTypes()) {
        const std::string name = type.name;
        const auto notDrawn = [name](const std::string& flagName) {
            return [name, flagName](const RenderOptions& options) -> std::string {
                return options.look.draws(name)
                           ? ""
                           : flagName + ": the '" + name + "' line type is not drawn (add it to --lines)";
            };
        };
        Flag width = styleFlag(flag({"--" + name + "-width"}, "PX", HelpSection::Lines, "",
                                    [name](const std::string& value, RenderOptions& options) {
                                        const std::string flagName = "--" + name + "-width";
                                        const double pixels = parseNumber(flagName, value);
                                        if (!(pixels >= kMinLineWidthPixels && pixels <= kMaxLineWidthPixels))
                                            throw UsageError(flagName + ": pixels must be from 0.001 to 256, got '" +
                                                             value + "'");
                                        options.look.lineStyles[name].widthPixels = pixels;
                                    }));
        width.noEffect = notDrawn("--" + name + "-width");
        flags.push_back(width);
        Flag color = styleFlag(flag({"--" + name + "-color"}, "R,G,B[,A]", HelpSection::Lines, "",
                                    [name](const std::string& value, RenderOptions& options) {
                                        options.look.lineStyles[name].color = parseColor("--" + name + "-color", value);
                                    }));
        color.noEffect = notDrawn("--" + name + "-color");
        flags.push_back(color);
    }
    for (const LineParameter* parameter : lineParameters()) {
        const std::vector<std::string> types = lineTypesUsing(parameter);
        const std::string flagName = "--" + parameter->name;
        Flag entry =
            styleFlag(flag({flagName}, parameter->valueName, HelpSection::Lines,
                           commaJoined(types) + ": " + lineParameterHelp(*parameter) + acceptedRangeText(*parameter),
                           [parameter](const std::string& value, RenderOptions& options) {
                               try {
                                   options.look.lineParameters.set(*parameter, parameter->parse(value));
                               } catch (const std::invalid_argument& error) {
                                   throw UsageError(error.what());
                               }
                           }));
        entry.noEffect = onlyWithLineTypes(flagName, types);
        entry.choices = parameter->choices;
        flags.push_back(entry);
    }
}

/** The types --hidden-lines takes: each registered type T with a registered hidden-lines type "hidden-T". */
std::vector<std::string> typesWithHiddenLines() {
    std::vector<std::string> names;
    for (const LineType& type : lineTypes()) {
        if (type.hiddenLines) continue;
        const LineType* hidden = findLineType("hidden-" + type.name);
        if (hidden && hidden->hiddenLines) names.push_back(type.name);
    }
    return names;
}

/** --hidden-lines and --hidden-dash (docs/lines.md, "Hidden lines"); the types come from the registry. */
void addHiddenLineFlags(std::vector<Flag>& flags) {
    const std::vector<std::string> types = typesWithHiddenLines();
    Flag hiddenLines = styleFlag(
        flag({"--hidden-lines"}, "LIST", HelpSection::Lines,
             "none (default) or comma-separated types (" + commaJoined(types) +
                 "): also draw the parts of\n"
                 "each that the model hides, as the line type hidden-<type> (its own layer, --hidden-<type>-width\n"
                 "and -color, lines-hidden-<type>.png), dashed by --hidden-dash and drawn under every visible line\n"
                 "(docs/lines.md)",
             [types](const std::string& value, RenderOptions& options) {
                 for (const std::string& hidden : options.hiddenLineTypes)
                     options.look.lines.erase(std::remove(options.look.lines.begin(), options.look.lines.end(), hidden),
                                              options.look.lines.end());
                 options.hiddenLineTypes.clear();
                 if (value == "none") return;
                 std::vector<std::string> listed;
                 for (const std::string& type : listItemsBesideNone("--hidden-lines", value)) {
                     if (!contains(types, type))
                         throw UsageError("--hidden-lines: '" + type +
                                          "' has no hidden lines (available: " + joined(types) + "; or 'none')");
                     if (contains(listed, type)) throw UsageError("--hidden-lines: '" + type + "' is listed twice");
                     listed.push_back(type);
                     const std::string hidden = "hidden-" + type;
                     if (options.look.draws(hidden)) continue; // --lines named it already
                     options.look.lines.push_back(hidden);
                     options.hiddenLineTypes.push_back(hidden);
                 }
             }));
    hiddenLines.choices = {"none"};
    for (const std::string& type : types) hiddenLines.choices.push_back(type);
    hiddenLines.commaList = true;
    flags.push_back(hiddenLines);

    std::vector<std::string> hiddenTypes;
    for (const LineType& type : lineTypes())
        if (type.hiddenLines) hiddenTypes.push_back(type.name);
    Flag dash = styleFlag(
        flag({"--hidden-dash"}, "ON,OFF", HelpSection::Lines,
             "the dash of every hidden-<type> layer: ON output pixels drawn, OFF left out, along each\n"
             "stroke from its start (default " +
                 helpNumbers({StrokeStyle{}.hiddenDashOn, StrokeStyle{}.hiddenDashOff}) + "; each " +
                 helpNumber(kMinDashPixels) + " to " + helpNumber(kMaxDashPixels) +
                 ": a dash or gap under a pixel would be\n"
                 "no dash, only millions of paths); OFF 0, or none, draws them solid. The picture and the --svg\n"
                 "(one path per dash) cut the same dashes",
             [](const std::string& value, RenderOptions& options) {
                 StrokeStyle& strokes = options.look.strokes;
                 if (value == "none") {
                     strokes.hiddenDashOff = 0.0;
                     return;
                 }
                 const std::vector<std::string> parts = splitList(value, ',');
                 const std::string expected =
                     "--hidden-dash: expected ON,OFF in output pixels (ON 1 to 4096, OFF 0 or 1 to 4096) "
                     "or none, got '" +
                     value + "'";
                 if (parts.size() != 2) throw UsageError(expected);
                 const double on = parseNumber("--hidden-dash", parts[0]);
                 const double off = parseNumber("--hidden-dash", parts[1]);
                 // A pixel at least: the dashes a stroke is cut into are kept as strokes of their own
                 // (and SVG paths), so 1e-6 px dashes took the machine's memory before any limit.
                 const bool onInRange = on >= kMinDashPixels && on <= kMaxDashPixels;
                 const bool offInRange = off == 0.0 || (off >= kMinDashPixels && off <= kMaxDashPixels);
                 if (!onInRange || !offInRange) throw UsageError(expected);
                 strokes.hiddenDashOn = on;
                 strokes.hiddenDashOff = off;
             }));
    dash.noEffect = onlyWithLineTypes("--hidden-dash", hiddenTypes);
    flags.push_back(dash);
}

std::string lineTypesHelp() {
    std::string text =
        "comma-separated line types, or none (default " + commaJoined(kDefaultLines, ",") +
        ": no model white on white, the contour also around a flat card seen face-on; docs/lines.md), each "
        "written to lines-<type>.png by --dump, "
        "composited in this order:";
    for (const LineType& type : lineTypes()) {
        std::string help = type.help;
        std::string indented;
        for (char c : help) indented += c == '\n' ? std::string("\n       ") : std::string(1, c);
        text += "\n  " + type.name + ": " + indented;
    }
    return text;
}

std::string shadingHelp() {
    std::string text;
    for (const ShadingModelTraits& traits : shadingModels())
        text +=
            std::string(text.empty() ? "" : " | ") + traits.name + (traits.model == Look{}.shading ? " (default)" : "");
    text += ": every model uses the material's textured base colour (docs/materials.md) and lights a VRM's MToon\n"
            "materials, whose KHR_materials_unlit is only the exporters' fallback (docs/shading.md)";
    for (const ShadingModelTraits& traits : shadingModels()) {
        std::string indented;
        for (const char* c = traits.help; *c; ++c)
            indented += *c == '\n' ? std::string("\n       ") : std::string(1, *c);
        text += "\n  " + std::string(traits.name) + ": " + indented;
    }
    return text;
}

std::vector<Flag> makeFlags() {
    using S = HelpSection;
    // The code's own defaults: the help states each flag's default from these, so the two cannot disagree.
    const RenderOptions defaults;
    std::vector<Flag> flags;
    // Output
    flags.push_back(flag({"-o", "--output"}, "FILE", S::Output, "the final picture: " + alternatives(kOutputExtensions),
                         [](const std::string& value, RenderOptions& options) {
                             options.outputPath = value;
                             const std::string extension = lowercaseExtension(value);
                             if (std::find(kOutputExtensions.begin(), kOutputExtensions.end(), extension) ==
                                 kOutputExtensions.end())
                                 throw UsageError("-o: '" + value + "' has no picture extension I write (use " +
                                                  alternatives(kOutputExtensions) + ")");
                         }));
    flags.push_back(styleFlag(flag(
        {"--size"}, "WxH", S::Output,
        "image size in pixels (default " + std::to_string(defaults.width) + "x" + std::to_string(defaults.height) +
            ", at most " + std::to_string(kMaxImageSide) + " a side; one buffer of the plan at most " +
            std::to_string(kMaxTextureBytes >> 20) +
            " MiB, so a float RGBA G-buffer field, --size times --supersample, at most " +
            std::to_string(largestFloatRgbaSquareSide()) + "x" + std::to_string(largestFloatRgbaSquareSide()) + ")",
        [](const std::string& value, RenderOptions& options) { parseSize(value, options.width, options.height); })));
    flags.push_back(flag(
        {"--dump"}, "DIR", S::Output,
        "also write every buffer the plan computed, and manifest.json. What is computed follows\n"
        "from the request: shading reads the G-buffer only where lines do; add --request 'gbuffer.*' for\n"
        "every G-buffer field: " +
            gbufferDumpFiles() +
            " (the manifest names the objects and meshes). Also shading.png, final.png, lines-<type>.png, and\n"
            "what the line stages drew: band-<type>.png, skeleton-<type>.png, mesh-edges-<type>.png (README's\n"
            "dump table lists them all). An earlier dump in DIR is replaced once everything is written; DIR\n"
            "must be new, empty, or hold exactly an earlier dump, and its parent writable (the new dump is staged\n"
            "beside it)",
        [](const std::string& value, RenderOptions& options) { options.dumpDirectory = value; }));
    flags.push_back(flag({"--request"}, "LIST", S::Output,
                         "compute and keep extra graph outputs, comma-separated: 'gbuffer.wVec', or 'gbuffer.*'\n"
                         "for all of them, the data-set labels meshId, triangleId and barycentric included\n"
                         "(docs/datasets.md); requesting is what makes a pass compute a buffer, dumping never does",
                         [](const std::string& value, RenderOptions& options) {
                             for (const std::string& resource : splitList(value, ',')) {
                                 const ResourceName name = ResourceName::split(resource);
                                 if (name.pass.empty() || name.field.empty())
                                     throw UsageError("--request: '" + resource +
                                                      "' is not a resource name like 'gbuffer.normal' or 'gbuffer.*'");
                                 options.extraOutputs.push_back(resource);
                             }
                         }));
    flags.push_back(flag({"--stats"}, "FILE.json", S::Output,
                         "milliseconds per pass (prepare and execute), culled passes with reasons, load, context\n"
                         "and write times, whether the OpenImageIO module was loaded (image_io_module: only formats\n"
                         "other than PNG and --dump need it), the estimated peak memory and its model's parts\n"
                         "(estimated_textures_mib, estimated_meshes_mib, estimated_derived_mib: what the passes\n"
                         "derive from the meshes), the peak and huge-page resident memory (peak_rss_mib,\n"
                         "huge_pages_mib), the malloc tunables the process ran with\n"
                         "(glibc_tunables), scene and GL facts, the look (shading, shade map, each line type), and\n"
                         "for comic the face-orientation numbers (front shares, holes, cut-off, marking ms)",
                         [](const std::string& value, RenderOptions& options) { options.statsPath = value; }));
    flags.push_back(flag({"--print-plan"}, "", S::Output,
                         "print the compiled render plan (without -o, print it and stop: no GL needed)",
                         [](const std::string&, RenderOptions& options) { options.printPlan = true; }));
    flags.push_back(flag({"--graphviz"}, "FILE.dot", S::Output,
                         "write the plan as a Graphviz graph (culled passes dashed)",
                         [](const std::string& value, RenderOptions& options) { options.graphvizPath = value; }));
    flags.push_back(flag({"--contact-sheet"}, "FILE.png", S::Output,
                         "every buffer the plan computed (normal, view, w, n.v, depth, each line layer, shading,\n"
                         "final) side by side in one labelled picture, each shown by what it holds: unit vectors\n"
                         "as 0.5 + 0.5 x, n.v blue-white-red on a fixed scale, depth normalised over the model, lines\n"
                         "as ink, colour over a checker; NaN and Inf in magenta",
                         [](const std::string& value, RenderOptions& options) {
                             options.contactSheetPath = value;
                             if (lowercaseExtension(value) != ".png")
                                 throw UsageError("--contact-sheet: '" + value + "' must be a .png file");
                         }));
    flags.push_back(flag({"--svg"}, "FILE.svg", S::Output,
                         "the line layers as vector paths, one group (an Inkscape layer) per line type in the\n"
                         "composite's order, in the lines' widths and colours: one path per stroke the picture was\n"
                         "drawn from, at sub-pixel positions where the kernel found them (outline and silhouette\n"
                         "bands thinned to their centre lines), simplified within --svg-tolerance; with\n"
                         "--line-weight, filled outlines",
                         [](const std::string& value, RenderOptions& options) {
                             options.svgPath = value;
                             if (lowercaseExtension(value) != ".svg")
                                 throw UsageError("--svg: '" + value + "' must be a .svg file");
                         }));
    flags.push_back(flag({"--strokes"}, "FILE.json", S::Output,
                         "every kept stroke of every drawn line type as JSON: its type, whether it is visible,\n"
                         "and per point the output pixel (x, y), the world point it came from, its mesh and\n"
                         "triangle, with the still's camera (K, [R|t]), so two views' strokes correspond through\n"
                         "their cameras (format and accuracy in docs/datasets.md, schema\n"
                         "docs/schemas/strokes.schema.json)",
                         [](const std::string& value, RenderOptions& options) {
                             options.strokesPath = value;
                             if (lowercaseExtension(value) != ".json")
                                 throw UsageError("--strokes: '" + value + "' must be a .json file");
                         }));
    Flag svgTolerance =
        flag({"--svg-tolerance"}, "PX", S::Output,
             "--svg: how far a simplified path may leave the traced pixels, in output pixels\n"
             "(default " +
                 helpNumber(defaults.svgTolerance) + "; 0 keeps every pixel)",
             [](const std::string& value, RenderOptions& options) {
                 options.svgTolerance = parseNumber("--svg-tolerance", value);
                 if (options.svgTolerance < 0.0 || options.svgTolerance > 100.0)
                     throw UsageError("--svg-tolerance: expected output pixels from 0 to 100, got '" + value + "'");
             });
    svgTolerance.noEffect = [](const RenderOptions& options) -> std::string {
        return options.svgPath.empty() ? "--svg-tolerance: applies to --svg, which is not given" : "";
    };
    flags.push_back(svgTolerance);
    flags.push_back(flag({"-q", "--quiet"}, "", S::Output,
                         "no progress lines on stderr (errors and warnings still go there)",
                         [](const std::string&, RenderOptions& options) { options.quiet = true; }));

    // Camera
    flags.push_back(flag({"--animation"}, "NAME", S::Camera,
                         "pose a glTF model by its animation NAME (or its index, 0 for the first) at --time;\n"
                         "skins, morph weights and node transforms follow, and so does auto-framing (default: the\n"
                         "rest pose, the file's own node transforms and morph weights). A name the file does not\n"
                         "have is refused with the list of those it has; ignored with a warning for OBJ, STL and PLY.\n"
                         "An existing FILE.vrma (VRM Animation) instead poses a VRM character through its humanoid\n"
                         "bones: rotations retargeted in VRM's normalized pose, the hips scaled by the hips heights\n"
                         "(docs/posing.md)",
                         [](const std::string& value, RenderOptions& options) {
                             if (value.empty()) throw UsageError("--animation: expected a name or an index, got ''");
                             options.animation = value;
                         }));
    Flag animationTime =
        flag({"--time"}, "SECONDS", S::Camera,
             "seconds into --animation (default " + helpNumber(defaults.animationTime) +
                 "); each channel holds its first or last keyframe\n"
                 "outside its keyframe times; LINEAR (quaternions by slerp), STEP and CUBICSPLINE\n"
                 "keyframes are interpolated. Also the clock of MToon's UV animation (--shading mtoon,\n"
                 "docs/mtoon.md), with or without --animation; without --animation on a model with no\n"
                 "UV animation it moves nothing (warning time-unused)",
             [](const std::string& value, RenderOptions& options) {
                 const double seconds = parseNumber("--time", value);
                 if (seconds < 0.0) throw UsageError("--time: expected seconds >= 0, got '" + value + "'");
                 options.animationTime = seconds;
             });
    flags.push_back(animationTime);
    flags.push_back(flag({"--pose"}, "POSE", S::Camera,
                         "pose a VRM character's humanoid bones (after --animation): a-pose (both upper arms\n"
                         "lowered 45 degrees from the rest T-pose) or FILE.json, {\"boneName\": [x, y, z, w], ...}:\n"
                         "each bone's rotation from the T-pose about world axes of a character facing +Z (VRM's\n"
                         "normalized pose), so one file poses every VRM, 0.x or 1.0, alike. An unknown bone name is\n"
                         "refused with the list; a bone the model lacks is a warning; a model that is not a VRM is\n"
                         "refused (docs/posing.md)",
                         [](const std::string& value, RenderOptions& options) { options.pose = value; }));
    flags.push_back(flag(
        {"--expression"}, "NAME=W[,...]", S::Camera,
        "a VRM character's expressions at weights W in [0, 1] (e.g. happy=1,blink=0.5): VRM 1.0's presets\n"
        "(happy, angry, sad, relaxed, surprised, aa, ih, ou, ee, oh, blink, blinkLeft, blinkRight, lookUp,\n"
        "lookDown, lookLeft, lookRight, neutral) and custom names; a VRM 0.x group by its 1.0 preset name (joy is\n"
        "happy, a is aa) or its own name. Morph targets, material colours and texture transforms follow,\n"
        "with isBinary and VRM 1.0's override rules (docs/vrm.md). Names are case-sensitive; one the file\n"
        "lacks is refused with the list of those it has",
        [](const std::string& value, RenderOptions& options) {
            options.expressions = parseExpressions("--expression", value);
        }));
    flags.push_back(flag(
        {"--look-at"}, "X,Y,Z", S::Camera,
        "a VRM character looks at this point (world units of the file, within +-1e15): its eye\n"
        "bones turn, or its look expressions are weighted, as the file's look-at settings say\n"
        "(docs/vrm.md); refused for a file without them",
        [](const std::string& value, RenderOptions& options) { options.lookAt = parsePoint("--look-at", value); }));
    flags.push_back(choiceFlag<bool>(
        {"--camera"}, "C", S::Camera, "",
        {{"file", false,
          "the glTF file's first perspective camera when it has one: its place, up and field of view; --up and --fov "
          "replace their own, "
          "and a view that --eye, --orbit or --frame places takes none of the three"},
         {"auto", true, "never the file's camera: auto-framed unless --eye or --orbit places it"}},
        defaults.autoCamera,
        ": whether the file's camera places the view. A view the file's camera does not place has field of view " +
            helpNumber(Camera{}.fovYDegrees) +
            " unless --fov. A view that shows none of the model (every vertex behind the camera, beyond one side of "
            "its view or outside its clip planes) renders the background with a warning naming the camera",
        [](const bool& autoCamera, RenderOptions& options) { options.autoCamera = autoCamera; }));
    flags.push_back(
        flag({"--eye"}, "X,Y,Z", S::Camera, "camera position, in world units (coordinates within +-1e15)",
             [](const std::string& value, RenderOptions& options) { options.eye = parsePoint("--eye", value); }));
    Flag orbit =
        flag({"--orbit"}, "AZ,EL[,DIST|,xS]", S::Camera,
             "the eye around the target (default: the framed centre), instead of --eye: AZ degrees about\n"
             "--up from the model's front (the side auto-framing looks from: a VRM character's face, else +Z, or -Y\n"
             "for a Z-up --up), positive toward the front view's right (counter-clockwise seen from above: with up\n"
             "+Y and front +Z, 90 looks from +X), -360 to 360; EL degrees above the horizontal, -89.9 to 89.9;\n"
             "DIST world units (default: the auto-framing distance), or xS for S times the auto-framing distance\n"
             "(x1.1: 10% farther; what a view of --views records). 0,0 looks straight at the front, 180,0 at the\n"
             "back (a model that faces the other way); the default view is 0,14.04. --stats reports the camera\n"
             "source orbit",
             [](const std::string& value, RenderOptions& options) { options.orbit = parseOrbit("--orbit", value); });
    orbit.noEffect = [](const RenderOptions& options) -> std::string {
        return options.eye ? "--orbit and --eye both place the eye: give one" : "";
    };
    flags.push_back(orbit);
    Flag frame = flag({"--frame"}, "NODE[,NODE...]", S::Camera,
                      "frame only the meshes under these nodes (a node and all its descendants; glTF node names,\n"
                      "an OBJ's o name), or the posed vertices a skin joint (its node name) or a VRM humanoid bone\n"
                      "(head, leftHand, ...) and its child joints weight: the default target and the auto-framing\n"
                      "and --orbit distance fit their bounding sphere, so a character on a large ground fills the\n"
                      "picture and --frame head a skinned face; the clip planes still fit the whole model. The\n"
                      "file's camera is not used. A name the model lacks fails its still (exit 3; in a batch the\n"
                      "other models are drawn), listing the model's node, bone and joint names (docs/posing.md)",
                      [](const std::string& value, RenderOptions& options) {
                          for (const std::string& name : splitList(value, ',')) {
                              if (name.empty()) throw UsageError("--frame: empty node name in '" + value + "'");
                              options.frameNodes.push_back(name);
                          }
                      });
    frame.noEffect = [](const RenderOptions& options) -> std::string {
        const bool distanceGiven = options.eye || (options.orbit && options.orbit->distance);
        return options.target && distanceGiven
                   ? "--frame has no effect: --target and " +
                         std::string(options.eye ? "--eye" : "--orbit's distance") + " fix the view it would frame"
                   : "";
    };
    flags.push_back(frame);
    flags.push_back(
        flag({"--target"}, "X,Y,Z", S::Camera,
             "point looked at (default: the bounding-sphere centre of the model, or of the --frame\n"
             "nodes; within +-1e15)",
             [](const std::string& value, RenderOptions& options) { options.target = parsePoint("--target", value); }));
    flags.push_back(
        flag({"--up"}, "X,Y,Z", S::Camera,
             "up direction (default: the glTF camera's, else 0,1,0); auto-framing looks from the\n"
             "front, slightly above, as this up defines it (for a Z-up up, from -Y as Blender's front view;\n"
             "a model that faces +Y shows its back there: --orbit 180,14.04 turns to its face); it must lie\n"
             "at least 0.05 degrees off the view direction (for an eye straight above, give --up 0,0,-1)",
             [](const std::string& value, RenderOptions& options) { options.up = parseDirection("--up", value); }));
    flags.push_back(styleFlag(flag({"--fov"}, "DEG", S::Camera,
                                   "vertical field of view in degrees, " + helpNumber(kMinFovDegrees) + " to " +
                                       helpNumber(kMaxFovDegrees) + " (default " + helpNumber(Camera{}.fovYDegrees) +
                                       ", or the glTF\n"
                                       "camera's when that camera places the view)",
                                   [](const std::string& value, RenderOptions& options) {
                                       const double fov = parseNumber("--fov", value);
                                       if (!(fov >= kMinFovDegrees && fov <= kMaxFovDegrees))
                                           throw UsageError("--fov: degrees must lie in [0.01, 179], got " + value);
                                       options.fovYDegrees = fov;
                                   })));
    flags.push_back(flag(
        {"--clip"}, "NEAR,FAR", S::Camera,
        "near and far clip distances along the view axis, 0 < NEAR < FAR, both in [1e-30, 1e30],\n"
        "FAR/NEAR at most 1e30 (default: fitted to the bounding sphere's depth along the view axis, so a model off\n"
        "the axis is not clipped, with far/near at most 1e4); depth is reversed-Z float, so ratios up to 1e6 and\n"
        "beyond keep about 1e-7 of the distance apart; --stats reports clip (near, far, far_over_near, source)",
        [](const std::string& value, RenderOptions& options) {
            const std::vector<std::string> parts = splitList(value, ',');
            if (parts.size() != 2)
                throw UsageError("--clip: expected NEAR,FAR (two comma-separated distances), got '" + value + "'");
            const glm::dvec2 clip(parseNumber("--clip", parts[0]), parseNumber("--clip", parts[1]));
            if (!(clip.x > 0.0 && clip.x < clip.y))
                throw UsageError("--clip: expected 0 < NEAR < FAR, got '" + value + "'");
            // The shaders get the planes, and reversed-z depth (about NEAR / distance), as float32, where 1e-38 is
            // already subnormal and flushed to zero: every depth then reads as the far plane, a blank picture.
            // Within these bounds every depth stays a normal float32 (tests/pipeline/ExtremesGLTest.cpp renders
            // 1e-6,1e6 like the fitted range).
            if (clip.x < kMinClipDistance || clip.y > kMaxClipDistance || clip.y / clip.x > kMaxClipRatio)
                throw UsageError("--clip: NEAR and FAR must lie in [1e-30, 1e30] with FAR/NEAR at most 1e30 (depth "
                                 "is float32), got '" +
                                 value + "'");
            options.clipRange = clip;
        }));

    // Look
    flags.push_back(
        flag({"--style"}, "FILE", S::Look,
             "settings from a style file, one NAME = VALUE per line (# comments): any flag of this\n"
             "section and of Lines, --size and --fov, without the dashes; e.g. \"shading = comic\",\n"
             "\"lines = contour, suggestive\". A relative file (shademap) is found next to the style file;\n"
             "flags on the command line win over the file's, and a setting the look leaves unused (a width\n"
             "of a line type not drawn, the shininess of a look without highlights) is left out. Problems\n"
             "are reported with the file and line",
             [](const std::string& value, RenderOptions& options) {
                 options.stylePath = value; // its settings were put first by expandStyleFile()
             }));
    flags.push_back(styleFlag(
        flag({"--shading"}, "MODE", S::Look, shadingHelp(), [](const std::string& value, RenderOptions& options) {
            const ShadingModelTraits* traits = findShadingModel(value);
            if (traits == nullptr) {
                std::vector<std::string> names;
                for (const ShadingModelTraits& model : shadingModels()) names.push_back(model.name);
                throw UsageError("--shading: unknown value '" + value + "' (available: " + commaJoined(names) + ")");
            }
            options.look.shading = traits->model;
        })));
    for (const ShadingModelTraits& model : shadingModels()) flags.back().choices.push_back(model.name);
    Flag shininess =
        styleFlag(flag({"--shininess"}, "N", S::Look,
                       "specular exponent for " + shadingModelsWith(&ShadingModelTraits::specular) + ", 0 to " +
                           helpNumber(kMaxShininess) + " (default " + helpNumber(defaults.look.shininess) +
                           "; both ends give no NaN and no speckle)",
                       [](const std::string& value, RenderOptions& options) {
                           options.look.shininess = parseNumber("--shininess", value);
                           if (options.look.shininess < 0.0 || options.look.shininess > kMaxShininess)
                               throw UsageError("--shininess: expected a number from 0 to 1e6, got '" + value + "'");
                       }));
    shininess.noEffect = onlyWithModels("--shininess", &ShadingModelTraits::specular);
    flags.push_back(shininess);
    Flag bands = styleFlag(flag({"--bands"}, "N", S::Look,
                                shadingModelsWith(&ShadingModelTraits::bands) +
                                    ": N even bands, 2 to 256, instead of the default shade map",
                                [](const std::string& value, RenderOptions& options) {
                                    options.look.bands = parseWholeNumber("--bands", value, 2, 256);
                                }));
    bands.noEffect = onlyWithModels("--bands", &ShadingModelTraits::bands);
    flags.push_back(bands);
    Flag shadeMap =
        styleFlag(flag({"--shademap"}, "FILE", S::Look,
                       "an 8-bit PNG, at most 4096 a side, for " + shadingModelsWith(&ShadingModelTraits::shadeMap) +
                           ": cel (and auto's cel materials) read one row; comic a 2-D image (left dark -> right\n"
                           "lit, bottom no highlight -> top full highlight); multiplied with the material colour.\n"
                           "inkgraph's own are in shademaps/ (shademaps/README.md)",
                       [](const std::string& value, RenderOptions& options) { options.look.shadeMapPath = value; }));
    shadeMap.pathValue = true;
    shadeMap.noEffect = [model = onlyWithModels("--shademap", &ShadingModelTraits::shadeMap)](
                            const RenderOptions& options) -> std::string {
        if (std::string refusal = model(options); !refusal.empty()) return refusal;
        // --bands is set only when given: both choose the cel map.
        return options.look.bands ? "--bands and --shademap both choose the cel shade map: give one" : "";
    };
    flags.push_back(shadeMap);
    Flag viewVector = styleFlag(choiceFlag<ViewVectorMode>(
        {"--view-vector"}, "V", S::Look, "comic: ",
        {{"exact", ViewVectorMode::Exact, "per pixel"},
         {"constant", ViewVectorMode::Constant,
          "Winnemöller & Bangay's V_c toward the bounding-sphere centre; falls back to exact when the eye is inside "
          "or within 2 radii of the sphere"}},
        defaults.look.viewVector, "",
        [](const ViewVectorMode& mode, RenderOptions& options) { options.look.viewVector = mode; }));
    viewVector.noEffect = onlyWithModels("--view-vector", &ShadingModelTraits::faceOrientation);
    flags.push_back(viewVector);
    Flag faceOrientation = styleFlag(choiceFlag<FaceOrientationMethod>(
        {"--face-orientation"}, "M", S::Look, "comic: ", kOrientationMethods, defaults.look.faceOrientation,
        ": the GPU's culling, or Winnemöller & Bangay's CPU marking with per-vertex lighting (errata fixed: no "
        "holes; --stats reports front shares, holes and milliseconds)",
        [](const FaceOrientationMethod& method, RenderOptions& options) { options.look.faceOrientation = method; }));
    faceOrientation.noEffect = onlyWithModels("--face-orientation", &ShadingModelTraits::faceOrientation);
    flags.push_back(faceOrientation);
    // The rule's words are its numbers; the parser stays a whole-number one, bounded by the table's first and last.
    const std::vector<Choice<int>> frontRules = {{"1", 1, "all three of its vertices"},
                                                 {"2", 2, "at least two of its vertices"},
                                                 {"3", 3, "at least one of its vertices"}};
    Flag frontRule =
        styleFlag(flag({"--front-rule"}, "R", S::Look,
                       "during-vertices, after-vertices: " + choiceListText(frontRules, defaults.look.frontRule) +
                           ": a triangle is front when these are front" + choiceMeaningsText(frontRules),
                       [low = frontRules.front().value, high = frontRules.back().value](const std::string& value,
                                                                                        RenderOptions& options) {
                           options.look.frontRule = parseWholeNumber("--front-rule", value, low, high);
                       }));
    frontRule.choices = wordsOf(frontRules);
    frontRule.noEffect = [comic = onlyWithModels("--front-rule", &ShadingModelTraits::faceOrientation)](
                             const RenderOptions& options) -> std::string {
        if (std::string refusal = comic(options); !refusal.empty()) return refusal;
        const FaceOrientationMethod method = options.look.faceOrientation;
        if (method == FaceOrientationMethod::DuringVertices || method == FaceOrientationMethod::AfterVertices)
            return "";
        return "--front-rule applies to --face-orientation during-vertices and after-vertices, not '" +
               faceOrientationMethodName(method) + "'";
    };
    flags.push_back(frontRule);
    flags.push_back(styleFlag(flag({"--light"}, "X,Y,Z", S::Look,
                                   "world direction toward the light (default: the glTF directional light, else from\n"
                                   "the upper left behind the camera)",
                                   [](const std::string& value, RenderOptions& options) {
                                       options.look.towardLight = parseDirection("--light", value);
                                   })));
    Flag ambient = styleFlag(flag(
        {"--ambient"}, "R,G,B", S::Look,
        "the uniform ambient light, linear, channels in [0,1] (one number: grey), for " +
            shadingModelsWith(&ShadingModelTraits::ambient) + ":\n" + modelsWithDefaultAmbientOf(ShadingModel::Flat) +
            " light base x (ambient + (1 - ambient) max(n.l, 0)) (default " +
            helpNumber(traitsOf(ShadingModel::Flat).defaultAmbient) + "); " +
            modelsWithDefaultAmbientOf(ShadingModel::MToon) +
            " add MToon's global illumination ambient x lit colour (default " +
            helpNumber(traitsOf(ShadingModel::MToon).defaultAmbient) +
            ", the MToon conformance scene's; docs/shading.md)",
        [](const std::string& value, RenderOptions& options) {
            const std::vector<std::string> parts = splitList(value, ',');
            if (parts.size() != 1 && parts.size() != 3)
                throw UsageError("--ambient: expected R,G,B or one grey value with channels in [0,1], got '" + value +
                                 "'");
            glm::dvec3 color(parseNumber("--ambient", parts[0]));
            for (std::size_t channel = 1; channel < parts.size(); ++channel)
                color[int(channel)] = parseNumber("--ambient", parts[channel]);
            for (int c = 0; c < 3; ++c)
                if (color[c] < 0.0 || color[c] > 1.0)
                    throw UsageError("--ambient: channels must lie in [0, 1], got '" + value + "'");
            options.look.ambient = color;
        }));
    ambient.noEffect = onlyWithModels("--ambient", &ShadingModelTraits::ambient);
    flags.push_back(ambient);
    flags.push_back(styleFlag(flag(
        {"--background"}, "R,G,B", S::Look,
        "paper colour, channels in [0,1] (default " +
            helpNumbers({defaults.look.background.r, defaults.look.background.g, defaults.look.background.b}) + ")",
        [](const std::string& value, RenderOptions& options) {
            if (splitList(value, ',').size() != 3)
                throw UsageError("--background: expected R,G,B, three channels in [0,1] (the paper is opaque: the "
                                 "picture has no alpha channel), got '" +
                                 value + "'");
            const glm::dvec3 color = parseVector("--background", value);
            for (int c = 0; c < 3; ++c)
                if (color[c] < 0.0 || color[c] > 1.0)
                    throw UsageError("--background: channels must lie in [0, 1], got '" + value + "'");
            options.look.background = color;
        })));

    // Lines
    flags.push_back(styleFlag(
        flag({"--lines"}, "LIST", S::Lines, lineTypesHelp(), [](const std::string& value, RenderOptions& options) {
            options.look.lines.clear();
            // --hidden-lines' types stay, whichever of the two flags comes first; one this list names is its own.
            const std::vector<std::string> listed =
                value == "none" ? std::vector<std::string>{} : splitList(value, ',');
            std::vector<std::string> kept;
            for (const std::string& hidden : options.hiddenLineTypes)
                if (!contains(listed, hidden)) kept.push_back(hidden);
            options.hiddenLineTypes = kept;
            options.look.lines = kept;
            if (value == "none") return;
            std::vector<std::string> known;
            for (const LineType& type : lineTypes()) known.push_back(type.name);
            for (const std::string& type : listItemsBesideNone("--lines", value)) {
                if (!findLineType(type))
                    throw UsageError("--lines: unknown line type '" + type + "' (available: " + joined(known) +
                                     "; or 'none')");
                if (options.look.draws(type)) throw UsageError("--lines: '" + type + "' is listed twice");
                options.look.lines.push_back(type);
            }
        })));
    flags.back().choices = {"none"};
    for (const LineType& type : lineTypes()) flags.back().choices.push_back(type.name);
    flags.back().commaList = true;
    addLineTypeFlags(flags);
    Flag supersample =
        styleFlag(flag({"--supersample"}, "S", S::Lines,
                       "find the G-buffer, mesh-edge and object-space lines at S x the size (1 to 8,\n"
                       "default " +
                           std::to_string(defaults.look.supersample) +
                           ") and area-downsample only the final line images: smoother, better-placed\n"
                           "lines, S^2 the work. Outline and silhouette are drawn by GL at the output size.",
                       [](const std::string& value, RenderOptions& options) {
                           options.look.supersample = parseWholeNumber("--supersample", value, 1, 8);
                       }));
    supersample.noEffect = onlyWithLineTypes("--supersample", lineTypesUsing(nullptr));
    flags.push_back(supersample);
    const std::vector<Choice<int>> msaaSamples = {{"1", 1, "off"}, {"2", 2, ""}, {"4", 4, ""}, {"8", 8, ""}};
    Flag msaa = styleFlag(choiceFlag<int>(
        {"--msaa"}, "N", S::Look, "samples per pixel for the shading and MToon's outline shells: ", msaaSamples,
        defaults.look.msaa,
        ": anti-aliased fill edges; forward shading only. More than the driver draws is refused (llvmpipe: 4;\n"
        "docs/shading.md)",
        [](const int& samples, RenderOptions& options) { options.look.msaa = samples; }));
    // Its refusal says what the words are, as it did before the table: "expected 1 (off), 2, 4 or 8 samples per
    // pixel" (the library and the Python module report it to their callers as it is).
    msaa.apply = [msaaSamples](const std::string& value, RenderOptions& options) {
        std::vector<std::string> described;
        for (const Choice<int>& samples : msaaSamples) {
            if (samples.word == value) {
                options.look.msaa = samples.value;
                return;
            }
            described.push_back(samples.word + (samples.meaning.empty() ? "" : " (" + samples.meaning + ")"));
        }
        throw UsageError("--msaa: expected " + alternatives(described) + " samples per pixel, got '" + value + "'");
    };
    msaa.noEffect = [](const RenderOptions& options) -> std::string {
        if (traitsOf(options.look.shading).define != nullptr) return "";
        return "--msaa has no effect with --shading none (only the shading is multisampled)";
    };
    flags.push_back(msaa);
    std::vector<std::string> allLineTypes;
    for (const LineType& type : lineTypes()) allLineTypes.push_back(type.name);
    Flag minStrokeLength = styleFlag(
        flag({"--min-stroke-length"}, "F", S::Lines,
             "line pixels are chained into strokes through junctions, across small gaps and from one\n"
             "type into the next where they run on; a chain shorter than F x the picture's height is\n"
             "not drawn (from its first pixel to its last; above 1024 rows plus height/1024 - 1 px,\n"
             "so the same line passes at every size; default " +
                 helpNumber(defaults.look.strokes.minLength) + ": " +
                 std::to_string(std::lround(defaults.look.strokes.minLength * defaults.height)) + " px at " +
                 std::to_string(defaults.height) + "; 0 keeps every speck; docs/strokes.md)",
             [](const std::string& value, RenderOptions& options) {
                 const double share = parseNumber("--min-stroke-length", value);
                 if (!(share >= 0.0 && share <= 1.0))
                     throw UsageError("--min-stroke-length: expected a share of the height from 0 to 1, got '" + value +
                                      "'");
                 options.look.strokes.minLength = share;
             }));
    minStrokeLength.noEffect = onlyWithLineTypes("--min-stroke-length", allLineTypes);
    flags.push_back(minStrokeLength);
    // Each word of --line-weight turns on one setting of the strokes; none turns them all off.
    const std::vector<Choice<bool StrokeStyle::*>> lineWeights = {
        {"depth", &StrokeStyle::weightByDepth, "the width falls to half from the model's near side to its far side"},
        {"strength", &StrokeStyle::weightByStrength, "faded lines thinner: 0.5 + 0.5 x strength"},
        {"taper", &StrokeStyle::taperEnds, "stroke ends narrow to a quarter over 3% of the height"}};
    bool anyWeightByDefault = false;
    for (const Choice<bool StrokeStyle::*>& weight : lineWeights)
        anyWeightByDefault = anyWeightByDefault || defaults.look.strokes.*weight.value;
    Flag lineWeight =
        styleFlag(flag({"--line-weight"}, "LIST", S::Lines,
                       std::string(anyWeightByDefault ? "none" : "none (default)") + " or any of " +
                           alternatives(wordsOf(lineWeights), " and ") +
                           ", comma-separated; in the picture and the --svg alike" + choiceMeaningsText(lineWeights),
                       [lineWeights](const std::string& value, RenderOptions& options) {
                           StrokeStyle& strokes = options.look.strokes;
                           for (const Choice<bool StrokeStyle::*>& weight : lineWeights) strokes.*weight.value = false;
                           if (value == "none") return;
                           for (const std::string& item : listItemsBesideNone("--line-weight", value)) {
                               const auto weight =
                                   std::find_if(lineWeights.begin(), lineWeights.end(),
                                                [&item](const auto& choice) { return choice.word == item; });
                               if (weight == lineWeights.end())
                                   throw UsageError("--line-weight: expected none or any of " +
                                                    commaJoined(wordsOf(lineWeights)) + "; got '" + item + "'");
                               bool& setting = strokes.*weight->value;
                               if (setting) throw UsageError("--line-weight: '" + item + "' is listed twice");
                               setting = true;
                           }
                       }));
    lineWeight.choices = {"none"};
    for (const std::string& word : wordsOf(lineWeights)) lineWeight.choices.push_back(word);
    lineWeight.commaList = true;
    lineWeight.noEffect = onlyWithLineTypes("--line-weight", allLineTypes);
    flags.push_back(lineWeight);
    Flag overlapping = styleFlag(choiceFlag<bool>(
        {"--overlapping-lines"}, "M", S::Lines, "",
        {{"draw", false, "every type draws its own lines"},
         {"merge", true,
          "where two types draw the same line (the contour along the outline, a crease along a contour), only the "
          "one earlier in the composite order draws it (less ink, one SVG path per line)"}},
        defaults.look.strokes.mergeOverlaps, "",
        [](const bool& merge, RenderOptions& options) { options.look.strokes.mergeOverlaps = merge; }));
    overlapping.noEffect = onlyWithLineTypes("--overlapping-lines", allLineTypes);
    flags.push_back(overlapping);
    addHiddenLineFlags(flags);
    flags.push_back(styleFlag(choiceFlag<GBufferPrecision>(
        {"--gbuffer-precision"}, "P", S::Lines, "",
        {{"float", GBufferPrecision::Float32, ""},
         {"half", GBufferPrecision::Float16,
          "the G-buffer's normal, view, w, n.v and radial fields as 16-bit floats (depth and material ids stay "
          "32-bit): half the memory, noisier suggestive contours (docs/accuracy.md measures it)"}},
        defaults.look.gbufferPrecision, ": the G-buffer's precision, also for --request 'gbuffer.*'",
        [](const GBufferPrecision& precision, RenderOptions& options) { options.look.gbufferPrecision = precision; })));
    Flag widthMap = styleFlag(flag(
        {"--outline-width-map"}, "SOURCE", S::Lines,
        "scale the outline, silhouette and MToon outline widths per vertex by a value in [0, 1] (0\n"
        "hides the line there): color:C, channel C (R, G, B or A) of the vertex colour COLOR_0, or\n"
        "texture:FILE:C, channel C of an image (" +
            std::string(kTextureFormatNames) +
            ", relative to the working directory; or the name of\n"
            "an image of the model when no file is there) at the vertex's TEXCOORD_0, read as data (stored value /\n"
            "255); none (default) leaves them. Times MToon's width texture. A mesh without the colours or\n"
            "coordinates keeps its widths, with a warning (docs/lines.md \"Width from the model\")",
        [](const std::string& value, RenderOptions& options) {
            try {
                options.look.outlineWidthMap = parseWidthMap(value);
            } catch (const std::invalid_argument& error) {
                throw UsageError(error.what());
            }
        }));
    widthMap.noEffect = [](const RenderOptions& options) -> std::string {
        if (!options.look.outlineWidthMap.enabled() || options.look.draws("outline") ||
            options.look.draws("silhouette") || traitsOf(options.look.shading).materialOutlines)
            return "";
        return "--outline-width-map has no effect: it scales outline and silhouette, neither of which is in --lines, "
               "and MToon's outlines, which --shading " +
               std::string(traitsOf(options.look.shading).name) + " does not draw";
    };
    flags.push_back(widthMap);
    flags.push_back(helpOnly(S::Lines, "",
                             "Outline and silhouette draw nothing when the eye is inside the model (they would flood "
                             "the picture), and say so (warning lines-skipped). A type the settings given leave "
                             "without a visible stroke (a transparent colour, a threshold or --min-stroke-length "
                             "past every line) is said too (warning lines-empty)."));

    // Batch
    flags.push_back(helpOnly(S::Batch, "MODEL...",
                             "several models render one after the other; every output path must then hold {name}\n"
                             "(the model's file name without extension) or {index} (its list position from 1,\n"
                             "zero-padded), e.g. -o 'out/{name}.png' --stats 'out/{name}.json'"));
    flags.push_back(flag({"--list"}, "FILE", S::Batch,
                         "more models, one path per line (blank lines and # comments skipped; relative paths\n"
                         "from the current folder); '-' reads standard input",
                         [](const std::string& value, RenderOptions& options) { options.listPath = value; }));
    flags.push_back(
        flag({"--shard"}, "K/N", S::Batch,
             "render only the models at list positions p (from 0) with p mod N = K, 0 <= K < N: one\n"
             "task of an array job (Slurm: --shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT)",
             [](const std::string& value, RenderOptions& options) { options.shard = parseShard("--shard", value); }));
    flags.push_back(flag({"--dataset"}, "DIR", S::Batch,
                         "make the run a data set in DIR: every output path must lie inside DIR; each still's\n"
                         "files are journaled as they are committed, and the run ends by writing DIR/index.jsonl\n"
                         "(one line per still: model, view, camera, files, checksums) and the card DIR/README.md\n"
                         "(command, version, look, counts)\n"
                         "(with --shard K/N: index-K-of-N.jsonl, README-K-of-N.md). A DIR that holds a data set is\n"
                         "refused without --resume; `inkgraph check-dataset DIR` verifies it (docs/datasets.md)",
                         [](const std::string& value, RenderOptions& options) { options.datasetDirectory = value; }));
    flags.back().noEffect = [](const RenderOptions& options) -> std::string {
        return rendersImages(options) ? "" : "--dataset: nothing is rendered; give -o or --dump inside the data set";
    };
    Flag resume = flag({"--resume"}, "", S::Batch,
                       "with --dataset: skip each still whose recorded settings match and whose files are all\n"
                       "there with their sizes and checksums; render the rest (an interrupted run, a changed flag):\n"
                       "after a kill -9 at any moment it gives the files of one uninterrupted run",
                       [](const std::string&, RenderOptions& options) { options.resume = true; });
    resume.noEffect = [](const RenderOptions& options) -> std::string {
        return options.datasetDirectory.empty() ? "--resume: needs --dataset DIR (the data set to resume)" : "";
    };
    flags.push_back(resume);
    flags.push_back(
        flag({"--jobs"}, "N", S::Batch,
             "how many stills may be in their post stage (line kernels, strokes, composite) and\n"
             "writing at once, on worker threads, while the next still loads and draws: 0 to 64\n"
             "(default: the cores this process may use, at most " +
                 std::to_string(kMaxDefaultJobs) +
                 "; 0 finishes each still before the\n"
                 "next starts). With N above 0 each still's post stage runs its parallel loops on the\n"
                 "usable cores / (N + 1) threads, at least 1. The files are the same bytes with any N; the\n"
                 "memory limit counts every still in flight (docs/batch.md)",
             [](const std::string& value, RenderOptions& options) {
                 options.jobs = parseWholeNumber("--jobs", value, 0, 64);
             }));
    flags.push_back(
        flag({"--draw-threads"}, "N", S::Batch,
             "how many threads draw a batch's stills, each with a GL context of its own: 1 to 16\n"
             "(default " +
                 std::to_string(defaults.drawThreads) +
                 "). On a GPU one thread leaves the GPU waiting while it plans, reads back\n"
                 "and hands each still on: more threads draw more stills at once. On llvmpipe, whose\n"
                 "rasterizers already use every core, more threads are slower. The files, progress lines and\n"
                 "exit status are the same with any N; --jobs is shared among the threads, and they\n"
                 "share the memory limit: a still draws once it fits beside what every thread holds,\n"
                 "in the list's order when memory is short (docs/batch.md)",
             [](const std::string& value, RenderOptions& options) {
                 options.drawThreads = parseWholeNumber("--draw-threads", value, 1, 16);
             }));
    flags.push_back(helpOnly(
        S::Batch, "",
        "Each model gets a progress line. A model that cannot be read is reported and the others go on; the run then\n"
        "ends with exit 3. Any other error stops the batch; models already done keep their files."));

    // Views
    Flag views = flag({"--views"}, "N", S::Views,
                      "render N views of each model, 1 to 100000, each from a sampled orbit: azimuth uniform in\n"
                      "[0, 360), elevation as --view-elevation, distance the auto-framing distance times\n"
                      "1 +- --view-distance-jitter; with --light-jitter, --expressions and --poses also a light,\n"
                      "expressions and a pose. Every output path then holds {view} (the view index, zero-padded to\n"
                      "the width of N-1) when N > 1. Each still's view is keyed by --seed, the model path as listed\n"
                      "and the view index alone, so a run, a shard or a rerun draws it alike; --stats and --dump's\n"
                      "manifest record it (\"view\"). Not with --eye or --orbit: views place the eye",
                      [](const std::string& value, RenderOptions& options) {
                          options.viewSampling.count = std::size_t(parseWholeNumber("--views", value, 1, 100000));
                          options.viewsGiven = true;
                      });
    views.noEffect = [](const RenderOptions& options) -> std::string {
        if (options.eye) return "--views places the eye of each view: it does not go with --eye";
        if (options.orbit) return "--views places the eye of each view: it does not go with --orbit";
        return "";
    };
    flags.push_back(views);
    Flag seed = flag({"--seed"}, "S", S::Views,
                     "the random seed of --views, a whole number from 0 to 2^64-1 (default " +
                         std::to_string(defaults.viewSampling.seed) +
                         "): the same seed\n"
                         "gives the same views, on any machine and in any --shard split (byte-identical stills with\n"
                         "the same GL driver)",
                     [](const std::string& value, RenderOptions& options) {
                         options.viewSampling.seed = parseSeed("--seed", value);
                     });
    seed.noEffect = onlyWithViews("--seed");
    flags.push_back(seed);
    Flag elevation =
        flag({"--view-elevation"}, "MEAN,SD[,LOW,HIGH]", S::Views,
             "--views' elevation in degrees: normal about MEAN with standard deviation SD (0 to 180),\n"
             "clamped to [LOW, HIGH]; MEAN, LOW and HIGH within -89.9 to 89.9 (default " +
                 helpNumbers({defaults.viewSampling.elevationMean, defaults.viewSampling.elevationDeviation,
                              defaults.viewSampling.elevationLow, defaults.viewSampling.elevationHigh}) +
                 ")",
             [](const std::string& value, RenderOptions& options) {
                 parseViewElevation("--view-elevation", value, options.viewSampling);
             });
    elevation.noEffect = onlyWithViews("--view-elevation");
    flags.push_back(elevation);
    Flag distanceJitter = flag({"--view-distance-jitter"}, "J", S::Views,
                               "--views' distance: the auto-framing distance times 1 + J u, u uniform in [-1, 1],\n"
                               "J from 0 to 0.9 (default " +
                                   helpNumber(defaults.viewSampling.distanceJitter) + ")",
                               [](const std::string& value, RenderOptions& options) {
                                   options.viewSampling.distanceJitter = parseNumberIn(
                                       "--view-distance-jitter", value, 0.0, 0.9, "a number from 0 to 0.9");
                               });
    distanceJitter.noEffect = onlyWithViews("--view-distance-jitter");
    flags.push_back(distanceJitter);
    Flag lightJitter = flag({"--light-jitter"}, "DEG", S::Views,
                            "--views' light: a direction drawn uniformly from those within DEG degrees of --light's\n"
                            "(a spherical cap), 0 to 180 (default " +
                                helpNumber(defaults.viewSampling.lightJitterDegrees) +
                                ": --light as given). Needs --light: the default\n"
                                "light follows the camera and the file",
                            [](const std::string& value, RenderOptions& options) {
                                options.viewSampling.lightJitterDegrees =
                                    parseNumberIn("--light-jitter", value, 0.0, 180.0, "degrees from 0 to 180");
                            });
    lightJitter.noEffect = [onlyViews = onlyWithViews("--light-jitter")](const RenderOptions& options) {
        if (std::string refusal = onlyViews(options); !refusal.empty()) return refusal;
        return options.viewSampling.lightJitterDegrees > 0.0 && !options.look.towardLight
                   ? std::string("--light-jitter turns --light's direction: give --light X,Y,Z (the default light "
                                 "follows the camera and the file)")
                   : std::string();
    };
    flags.push_back(lightJitter);
    Flag expressionChoices =
        flag({"--expressions"}, "SET;SET...", S::Views,
             "--views' expressions: each view takes one of these alternatives, drawn uniformly; an\n"
             "alternative is an --expression set (happy=1,blink=0.5) or none, e.g. 'happy=1;angry=1,blink=0.5;none'.\n"
             "Not with --expression",
             [](const std::string& value, RenderOptions& options) {
                 std::vector<std::vector<ExpressionWeight>> choices;
                 for (const std::string& alternative : splitList(value, ';')) {
                     if (alternative.empty())
                         throw UsageError("--expressions: an empty alternative in '" + value +
                                          "' (separate alternatives by ';'; write none for no expression)");
                     choices.push_back(alternative == "none" ? std::vector<ExpressionWeight>{}
                                                             : parseExpressions("--expressions", alternative));
                 }
                 options.viewSampling.expressionChoices = std::move(choices);
             });
    expressionChoices.noEffect = [onlyViews = onlyWithViews("--expressions")](const RenderOptions& options) {
        if (std::string refusal = onlyViews(options); !refusal.empty()) return refusal;
        return options.expressions.empty() ? std::string()
                                           : std::string("--expressions chooses each view's expressions: it does not "
                                                         "go with --expression");
    };
    flags.push_back(expressionChoices);
    Flag poseChoices = flag({"--poses"}, "POSE,POSE...", S::Views,
                            "--views' poses: each view takes one of these, drawn uniformly: rest (no pose), a-pose or\n"
                            "a FILE.json as --pose takes it, e.g. rest,a-pose,wave.json. Not with --pose",
                            [](const std::string& value, RenderOptions& options) {
                                std::vector<std::string> choices = splitList(value, ',');
                                for (const std::string& choice : choices)
                                    if (choice.empty())
                                        throw UsageError("--poses: an empty alternative in '" + value +
                                                         "' (rest, a-pose or FILE.json, separated by ',')");
                                options.viewSampling.poseChoices = std::move(choices);
                            });
    poseChoices.noEffect = [onlyViews = onlyWithViews("--poses")](const RenderOptions& options) {
        if (std::string refusal = onlyViews(options); !refusal.empty()) return refusal;
        return options.pose.empty() ? std::string()
                                    : std::string("--poses chooses each view's pose: it does not go with --pose");
    };
    flags.push_back(poseChoices);

    // System
    flags.push_back(choiceFlag<std::string>(
        {"--egl-platform"}, "P", S::System, "",
        {{"auto", "auto", "device first, then surfaceless"},
         {"device", "device", ""},
         {"surfaceless", "surfaceless", ""}},
        defaults.eglPlatform, ": the EGL platform the GL context is made on",
        [](const std::string& platform, RenderOptions& options) { options.eglPlatform = platform; }));
    flags.push_back(choiceFlag<std::string>(
        {"--readback"}, "WHEN", S::System, "",
        {{"auto", "auto",
          "late on software rasterizers (llvmpipe, where early costs 15% more: the copy waits on this thread either "
          "way), early on GPUs"},
         {"early", "early",
          "each copy starts as soon as the pass writing it has run, while later passes draw (pixel-pack buffers and "
          "fences)"},
         {"late", "late", "each is copied when the post stage asks for it"}},
        defaults.readback, ": when the buffers the CPU post stage reads leave the GPU. The pictures are the same",
        [](const std::string& when, RenderOptions& options) { options.readback = when; }));
    flags.push_back(choiceFlag<PostStageDevice>(
        {"--post-stage"}, "D", S::System, "",
        {{"auto", PostStageDevice::Auto,
          "cpu on a software rasterizer (" + commaJoined(softwareRasterizerNames()) +
              ": measured faster there, docs/performance.md), else gpu for the line kernels and cpu for the "
              "composite (gpu only when asked: a plan that ends on the GPU leaves a batch no post stage to overlap)"},
         {"cpu", PostStageDevice::Cpu, "on the CPU over read-back G-buffer fields"},
         {"gpu", PostStageDevice::Gpu, "as compute shaders, with only what they find read back"}},
        defaults.look.postStage,
        ": where the image-space line kernels (contour, depth-edge, normal-edge) and the composite run; the lines "
        "agree within 1e-3 px, the composite to the byte. --stats says which ran (post_stage.device)",
        [](const PostStageDevice& device, RenderOptions& options) { options.look.postStage = device; }));
    flags.push_back(flag({"--strict"}, "", S::System,
                         "make every warning an error: the still fails with exit 3 and writes nothing (a missing\n"
                         "or undecodable texture, a value clamped into range, the model outside the view, ...).\n"
                         "Without it a warning is printed and the still is drawn as the warning says",
                         [](const std::string&, RenderOptions& options) { options.strict = true; }));
    flags.push_back(
        flag({"--memory-limit"}, "MIB", S::System,
             "the most memory the process may take for one still, 64 to " + std::to_string(kMaxMemoryLimitMib) +
                 " (default: half this\n"
                 "machine's memory, at least 1024). Checked before allocating: the model load from the\n"
                 "file's size and declared counts (exit 3), then the whole run's peak from the plan (the\n"
                 "process, the scene, every buffer at --size and --supersample, read-backs, encoding; exit\n"
                 "2), naming the flags that need the memory. --stats reports the estimate\n"
                 "(estimated_peak_mib) and the measured peak (peak_rss_mib); docs/batch.md sizes a task",
             [](const std::string& value, RenderOptions& options) {
                 options.memoryLimitBytes =
                     std::size_t(parseWholeNumber("--memory-limit", value, 64, kMaxMemoryLimitMib)) << 20;
             }));
    flags.push_back(flag({"--weld-distance"}, "R", S::System,
                         "when loading, merge vertices closer than R x the model's size (its bounding box's\n"
                         "diagonal), 0 to " +
                             helpNumber(kMaxWeldTolerance) + " (default " + helpNumber(defaults.weldTolerance) +
                             "; 0: only vertices at the same point). Lower it for\n"
                             "details under a millionth of the model (a part of a survey kilometres wide), which the\n"
                             "default merges away with the warning details-merged; raise it so that faces written a\n"
                             "little apart count as joined (no border line along the crack, the hull closed over it);\n"
                             "--stats gives scene.weld_distance",
                         [](const std::string& value, RenderOptions& options) {
                             options.weldTolerance =
                                 parseNumberIn("--weld-distance", value, 0.0, kMaxWeldTolerance, "0 to 0.01");
                         }));
    return flags;
}

} // namespace

const std::vector<HelpSection>& helpSections() {
    static const std::vector<HelpSection> kSections = {HelpSection::Output, HelpSection::Camera, HelpSection::Look,
                                                       HelpSection::Lines,  HelpSection::Batch,  HelpSection::Views,
                                                       HelpSection::System};
    return kSections;
}

const char* helpSectionTitle(HelpSection section) {
    switch (section) {
    case HelpSection::Output: return "Output";
    case HelpSection::Camera:
        return "Camera (right-handed world, OpenGL lookAt/perspective; default: the glTF camera, else auto-framed)";
    case HelpSection::Look: return "Look";
    case HelpSection::Lines:
        return "Lines (any subset; only the passes the listed types need run: see --stats \"culled\")";
    case HelpSection::Batch:
        return "Batch (several models in one process: one GL context, each shader program compiled once; "
               "docs/batch.md)";
    case HelpSection::Views:
        return "Views (data sets: N sampled views of each model, reproducible from --seed; docs/datasets.md)";
    case HelpSection::System: return "System";
    }
    return "";
}

const std::vector<Flag>& renderFlags() {
    static const std::vector<Flag> kFlags = makeFlags();
    return kFlags;
}

const Flag* findFlag(const std::string& name) {
    for (const Flag& entry : renderFlags())
        if (std::find(entry.names.begin(), entry.names.end(), name) != entry.names.end()) return &entry;
    return nullptr;
}

/** `line` broken at spaces so that with `indent` it fits kHelpWidth; continuation lines get `continuation` more
 *  spaces (list items hang under their text). */
void appendWrapped(std::string& text, const std::string& line, std::size_t indent, std::size_t continuation) {
    constexpr std::size_t kHelpWidth = 118;
    std::string rest = line;
    std::size_t lineIndent = indent;
    while (lineIndent + rest.size() > kHelpWidth) {
        std::size_t cut = rest.rfind(' ', kHelpWidth - lineIndent);
        if (cut == std::string::npos || cut == 0) break;
        text += std::string(lineIndent, ' ') + rest.substr(0, cut) + "\n";
        rest = rest.substr(cut + 1);
        lineIndent = indent + continuation;
    }
    text += std::string(lineIndent, ' ') + rest + "\n";
}

/** A help text as the blocks the writer wraps: its '\n' are soft, except before a list item (a line that starts with
 *  two spaces and a word); lines indented deeper continue the item above. */
std::vector<std::string> helpBlocks(const std::string& help) {
    std::vector<std::string> blocks;
    for (const std::string& line : splitList(help, '\n')) {
        const std::size_t indent = line.find_first_not_of(' ');
        const std::string words = indent == std::string::npos ? "" : line.substr(indent);
        if (blocks.empty() || indent == 2)
            blocks.push_back(line);
        else
            blocks.back() += " " + words;
    }
    return blocks;
}

std::string renderFlagsHelp() {
    constexpr std::size_t kHelpColumn = 25;
    std::string text;
    for (HelpSection section : helpSections()) {
        text += std::string("\n") + helpSectionTitle(section) + "\n";
        for (const Flag& entry : renderFlags()) {
            if (entry.section != section || entry.help.empty()) continue;
            std::string label = entry.helpLabel;
            if (label.empty() && !entry.names.empty()) {
                for (const std::string& name : entry.names) label += (label.empty() ? "" : ", ") + name;
                if (!entry.valueName.empty()) label += " " + entry.valueName;
            }
            const std::vector<std::string> blocks = helpBlocks(entry.help);
            if (label.empty()) { // a note: the section's own words, two spaces in
                for (const std::string& block : blocks) appendWrapped(text, block, 2, 0);
                continue;
            }
            std::string first = "  " + label;
            if (first.size() + 1 > kHelpColumn) {
                text += first + "\n";
                first.clear();
            }
            for (std::size_t i = 0; i < blocks.size(); ++i) {
                // List items ("  outline: ...") hang their continuation lines under their text.
                const bool item = blocks[i].rfind("  ", 0) == 0;
                std::string wrapped;
                appendWrapped(wrapped, blocks[i], kHelpColumn, item ? 7 : 0);
                if (i == 0 && !first.empty()) wrapped.replace(0, first.size(), first);
                text += wrapped;
            }
        }
    }
    return text;
}

} // namespace inkgraph
