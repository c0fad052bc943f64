#include "app/Options.h"

#include "graph/Resource.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <charconv>
#include <cmath>
#include <sstream>

namespace inkgraph {
namespace {

constexpr int kMaxImageSide = 16384;
constexpr double kMinFovDegrees = 0.01;
constexpr double kMaxFovDegrees = 179.0;
const std::vector<std::string> kOutputExtensions = {".png", ".exr", ".tif", ".tiff", ".jpg", ".jpeg"};

std::string lowercaseExtension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

double parseNumber(const std::string& flag, const std::string& text) {
    double value = 0.0;
    const char* begin = text.data();
    const char* end = begin + text.size();
    auto [stop, error] = std::from_chars(begin, end, value);
    if (error != std::errc() || stop != end || !std::isfinite(value))
        throw UsageError(flag + ": '" + text + "' is not a finite number");
    return value;
}

std::vector<std::string> splitList(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream stream(text);
    while (std::getline(stream, part, separator)) parts.push_back(part);
    if (!text.empty() && text.back() == separator) parts.push_back("");
    return parts;
}

glm::dvec3 parseVector(const std::string& flag, const std::string& text) {
    const std::vector<std::string> parts = splitList(text, ',');
    if (parts.size() != 3) throw UsageError(flag + ": expected X,Y,Z (three comma-separated numbers), got '" + text + "'");
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

void parseSize(const std::string& text, int& width, int& height) {
    const auto cross = text.find('x');
    if (cross == std::string::npos) throw UsageError("--size: expected WxH such as 1024x768, got '" + text + "'");
    const double w = parseNumber("--size", text.substr(0, cross));
    const double h = parseNumber("--size", text.substr(cross + 1));
    if (w != std::floor(w) || h != std::floor(h) || w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide)
        throw UsageError("--size: width and height must be whole numbers from 1 to " + std::to_string(kMaxImageSide) +
                         ", got '" + text + "'");
    width = static_cast<int>(w);
    height = static_cast<int>(h);
}

std::string joined(const std::vector<std::string>& items) {
    std::string text;
    for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
    return text.empty() ? "(none in this version)" : text;
}

} // namespace

const std::vector<std::string>& knownLineTypes() {
    static const std::vector<std::string> kLineTypes = {
        "outline", "silhouette", "normal-edge", "depth-edge",     "crease",
        "border",  "suggestive", "suggestive-object", "contour", "mesh-silhouette"};
    return kLineTypes;
}

bool isImageSpaceLineType(const std::string& type) {
    return type == "contour" || type == "suggestive" || type == "depth-edge" || type == "normal-edge";
}

bool isObjectSpaceLineType(const std::string& type) { return type == "suggestive-object"; }

bool isMeshEdgeLineType(const std::string& type) {
    return type == "mesh-silhouette" || type == "crease" || type == "border";
}

namespace {

const std::vector<std::pair<std::string, ShadingMode>> kShadingModes = {
    {"none", ShadingMode::None},       {"flat", ShadingMode::Flat}, {"gouraud", ShadingMode::Gouraud},
    {"lambert", ShadingMode::Lambert}, {"phong", ShadingMode::Phong}, {"cel", ShadingMode::Cel},
    {"comic", ShadingMode::Comic},
};
const std::vector<std::pair<std::string, FaceOrientationMethod>> kOrientationMethods = {
    {"standard", FaceOrientationMethod::Standard},
    {"during-triangles", FaceOrientationMethod::DuringTriangles},
    {"during-vertices", FaceOrientationMethod::DuringVertices},
    {"after-vertices", FaceOrientationMethod::AfterVertices},
};
constexpr double kMaxShininess = 1e6;
constexpr double kMaxLineWidthPixels = 256.0;
constexpr double kMinClipDistance = 1e-30;
constexpr double kMaxClipDistance = 1e30;
constexpr double kMaxClipRatio = 1e30;
constexpr int kMaxMemoryLimitMib = 1 << 24; // 16 TiB

template <typename Value>
Value parseChoice(const std::string& flag, const std::string& text,
                  const std::vector<std::pair<std::string, Value>>& choices) {
    std::string names;
    for (const auto& [name, value] : choices) {
        if (name == text) return value;
        names += (names.empty() ? "" : ", ") + name;
    }
    throw UsageError(flag + ": unknown value '" + text + "' (available: " + names + ")");
}

int parseWholeNumber(const std::string& flag, const std::string& text, int low, int high) {
    const double value = parseNumber(flag, text);
    if (value != std::floor(value) || value < low || value > high)
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

/** "--outline-width" -> {"outline", "width"} when the type is known; nullopt otherwise. */
std::optional<std::pair<std::string, std::string>> lineStyleFlag(const std::string& argument) {
    for (const std::string& type : knownLineTypes())
        for (const char* property : {"width", "color"})
            if (argument == "--" + type + "-" + property) return std::make_pair(type, std::string(property));
    return std::nullopt;
}

/** Line flags that would change nothing about the requested line types are refused, like the shading flags. */
void checkLineFlags(const RenderOptions& options, const std::vector<std::string>& given) {
    auto wasGiven = [&](const char* flag) { return std::find(given.begin(), given.end(), flag) != given.end(); };
    auto drawn = [&](const char* type) {
        return std::find(options.lines.begin(), options.lines.end(), type) != options.lines.end();
    };
    auto require = [&](const char* flag, std::initializer_list<const char*> types) {
        if (!wasGiven(flag)) return;
        std::string names;
        for (const char* type : types) {
            if (drawn(type)) return;
            names += std::string(names.empty() ? "" : ", ") + type;
        }
        throw UsageError(std::string(flag) + " has no effect: none of the line types it applies to (" + names +
                         ") is in --lines");
    };
    require("--crease-angle", {"crease", "normal-edge"});
    require("--depth-jump", {"contour", "suggestive", "suggestive-object", "depth-edge", "normal-edge"});
    require("--suggestive-threshold", {"suggestive", "suggestive-object"});
    require("--suggestive-fade", {"suggestive", "suggestive-object"});
    require("--suggestive-stencil", {"suggestive"});
    require("--supersample", {"contour", "suggestive", "suggestive-object", "depth-edge", "normal-edge",
                              "mesh-silhouette", "crease", "border"});
    if (std::size_t(options.width) * options.supersample > std::size_t(kMaxImageSide) ||
        std::size_t(options.height) * options.supersample > std::size_t(kMaxImageSide))
        throw UsageError("--supersample: " + std::to_string(options.supersample) + " x --size " +
                         std::to_string(options.width) + "x" + std::to_string(options.height) +
                         " exceeds the largest buffer side, " + std::to_string(kMaxImageSide));
}

/** Flags that only mean something with some shading modes are refused elsewhere, so a typo'd mode is not silently
 *  rendered without the look the user asked for. */
void checkShadingFlags(const RenderOptions& options, const std::vector<std::string>& given) {
    auto wasGiven = [&](const char* flag) { return std::find(given.begin(), given.end(), flag) != given.end(); };
    const std::string mode = shadingModeName(options.shading);
    auto refuse = [&](const char* flag, const char* appliesTo) {
        throw UsageError(std::string(flag) + " has no effect with --shading " + mode + " (it applies to " +
                         appliesTo + ")");
    };
    const bool specular = options.shading == ShadingMode::Phong || options.shading == ShadingMode::Comic;
    if (wasGiven("--shininess") && !specular) refuse("--shininess", "phong and comic");
    if (wasGiven("--bands") && options.shading != ShadingMode::Cel) refuse("--bands", "cel");
    if (wasGiven("--shademap") && !usesShadeMap(options.shading)) refuse("--shademap", "cel and comic");
    if (wasGiven("--bands") && wasGiven("--shademap"))
        throw UsageError("--bands and --shademap both choose the cel shade map: give one");
    for (const char* flag : {"--view-vector", "--face-orientation", "--front-rule"})
        if (wasGiven(flag) && options.shading != ShadingMode::Comic) refuse(flag, "comic");
    const bool vertexMethod = options.faceOrientation == FaceOrientationMethod::DuringVertices ||
                              options.faceOrientation == FaceOrientationMethod::AfterVertices;
    if (wasGiven("--front-rule") && !vertexMethod)
        throw UsageError("--front-rule applies to --face-orientation during-vertices and after-vertices, not '" +
                         faceOrientationMethodName(options.faceOrientation) + "'");
}

/** What parsing gathers beside the options: the flags given, and the line types a style flag names. */
struct ParseState {
    RenderOptions options;
    std::vector<std::string> givenFlags;
    std::vector<std::pair<std::string, std::string>> styledLineTypes; // flag, line type
};

/** Applies arguments[i] to `state`, with its value (i then points at the value). Returns false at --help, where
 *  parsing stops. */
bool parseArgument(const std::vector<std::string>& arguments, std::size_t& i, ParseState& state) {
    RenderOptions& options = state.options;
    std::vector<std::string>& givenFlags = state.givenFlags;
    std::vector<std::pair<std::string, std::string>>& styledLineTypes = state.styledLineTypes;
    const std::string& argument = arguments[i];
    if (!argument.empty() && argument[0] == '-') givenFlags.push_back(argument);
    auto value = [&]() -> const std::string& {
        if (i + 1 >= arguments.size()) throw UsageError(argument + ": missing value");
        if (arguments[i + 1].empty()) throw UsageError(argument + ": empty value");
        return arguments[++i];
    };
    if (argument == "--help" || argument == "-h") {
        options.help = true;
        return false;
    }
    if (argument == "-o" || argument == "--output") {
        options.outputPath = value();
        const std::string extension = lowercaseExtension(options.outputPath);
        if (std::find(kOutputExtensions.begin(), kOutputExtensions.end(), extension) == kOutputExtensions.end())
            throw UsageError("-o: '" + options.outputPath +
                             "' has no picture extension I write (use .png, .exr, "
                             ".tif or .jpg)");
    } else if (argument == "--size") {
        parseSize(value(), options.width, options.height);
    } else if (argument == "--eye") {
        options.eye = parsePoint(argument, value());
    } else if (argument == "--target") {
        options.target = parsePoint(argument, value());
    } else if (argument == "--up") {
        options.up = parseDirection(argument, value());
    } else if (argument == "--fov") {
        const double fov = parseNumber(argument, value());
        if (!(fov >= kMinFovDegrees && fov <= kMaxFovDegrees))
            throw UsageError("--fov: degrees must lie in [0.01, 179], got " + arguments[i]);
        options.fovYDegrees = fov;
    } else if (argument == "--clip") {
        const std::vector<std::string> parts = splitList(value(), ',');
        if (parts.size() != 2)
            throw UsageError("--clip: expected NEAR,FAR (two comma-separated distances), got '" + arguments[i] + "'");
        const glm::dvec2 clip(parseNumber(argument, parts[0]), parseNumber(argument, parts[1]));
        if (!(clip.x > 0.0 && clip.x < clip.y))
            throw UsageError("--clip: expected 0 < NEAR < FAR, got '" + arguments[i] + "'");
        // The shaders get the planes, and reversed-z depth (about NEAR / distance), as float32, where 1e-38 is
        // already subnormal and flushed to zero: every depth then reads as the far plane, a blank picture. Within
        // these bounds every depth stays a normal float32 (tests/pipeline/ExtremesGLTest.cpp renders 1e-6,1e6 like
        // the fitted range).
        if (clip.x < kMinClipDistance || clip.y > kMaxClipDistance || clip.y / clip.x > kMaxClipRatio)
            throw UsageError("--clip: NEAR and FAR must lie in [1e-30, 1e30] with FAR/NEAR at most 1e30 (depth is "
                             "float32), got '" + arguments[i] + "'");
        options.clipRange = clip;
    } else if (argument == "--light") {
        options.towardLight = parseDirection(argument, value());
    } else if (argument == "--shading") {
        options.shading = parseChoice(argument, value(), kShadingModes);
    } else if (argument == "--shininess") {
        options.shininess = parseNumber(argument, value());
        if (options.shininess < 0.0 || options.shininess > kMaxShininess)
            throw UsageError("--shininess: expected a number from 0 to 1e6, got '" + arguments[i] + "'");
    } else if (argument == "--bands") {
        options.bands = parseWholeNumber(argument, value(), 2, 256);
    } else if (argument == "--shademap") {
        options.shadeMapPath = value();
    } else if (argument == "--view-vector") {
        options.viewVector = parseChoice<ViewVectorMode>(
            argument, value(), {{"exact", ViewVectorMode::Exact}, {"constant", ViewVectorMode::Constant}});
    } else if (argument == "--face-orientation") {
        options.faceOrientation = parseChoice(argument, value(), kOrientationMethods);
    } else if (argument == "--front-rule") {
        options.frontRule = parseWholeNumber(argument, value(), 1, 3);
    } else if (auto styleFlag = lineStyleFlag(argument)) {
        LineStyle& style = options.lineStyles[styleFlag->first];
        if (styleFlag->second == "color") {
            style.color = parseColor(argument, value());
        } else {
            style.widthPixels = parseNumber(argument, value());
            if (!(style.widthPixels > 0.0 && style.widthPixels <= kMaxLineWidthPixels))
                throw UsageError(argument + ": pixels must be above 0 and at most 256, got '" + arguments[i] + "'");
        }
        styledLineTypes.emplace_back(argument, styleFlag->first);
    } else if (argument == "--silhouette-object-width") {
        options.silhouetteObjectWidth = parseNumber(argument, value());
        if (!(*options.silhouetteObjectWidth > 0.0))
            throw UsageError("--silhouette-object-width: model units must be above 0, got '" + arguments[i] + "'");
        styledLineTypes.emplace_back(argument, "silhouette");
    } else if (argument == "--lines") {
        const std::string& list = value();
        options.lines.clear();
        if (list == "none") return true;
        for (const std::string& type : splitList(list, ',')) {
            const auto& known = knownLineTypes();
            if (std::find(known.begin(), known.end(), type) == known.end())
                throw UsageError("--lines: unknown line type '" + type + "' (available: " + joined(known) +
                                 "; or 'none')");
            if (std::find(options.lines.begin(), options.lines.end(), type) != options.lines.end())
                throw UsageError("--lines: '" + type + "' is listed twice");
            options.lines.push_back(type);
        }
    } else if (argument == "--crease-angle") {
        options.creaseAngleDegrees = parseNumber(argument, value());
        if (!(options.creaseAngleDegrees > 0.0 && options.creaseAngleDegrees < 180.0))
            throw UsageError("--crease-angle: degrees must lie above 0 and below 180, got '" + arguments[i] + "'");
    } else if (argument == "--depth-jump") {
        options.depthJump = parseNumber(argument, value());
        if (!(options.depthJump > 0.0 && options.depthJump <= 100.0))
            throw UsageError("--depth-jump: expected a relative depth step above 0 up to 100, got '" + arguments[i] +
                             "'");
    } else if (argument == "--suggestive-threshold" || argument == "--suggestive-fade") {
        const double strength = parseNumber(argument, value());
        if (!(strength >= 0.0 && strength <= 1e6))
            throw UsageError(argument + ": expected a number from 0 to 1e6, got '" + arguments[i] + "'");
        (argument == "--suggestive-threshold" ? options.suggestiveThreshold : options.suggestiveFade) = strength;
    } else if (argument == "--supersample") {
        options.supersample = parseWholeNumber(argument, value(), 1, 8);
    } else if (argument == "--suggestive-stencil") {
        const std::string stencil = value();
        if (stencil != "3" && stencil != "5")
            throw UsageError("--suggestive-stencil: expected 3 or 5, got '" + stencil + "'");
        options.suggestiveStencil = stencil == "3" ? 3 : 5;
    } else if (argument == "--gbuffer-precision") {
        const std::string precision = value();
        if (precision == "float")
            options.gbufferPrecision = GBufferPrecision::Float32;
        else if (precision == "half")
            options.gbufferPrecision = GBufferPrecision::Float16;
        else
            throw UsageError("--gbuffer-precision: expected float or half, got '" + precision + "'");
    } else if (argument == "--background") {
        const glm::dvec3 color = parseVector(argument, value());
        for (int c = 0; c < 3; ++c)
            if (color[c] < 0.0 || color[c] > 1.0)
                throw UsageError("--background: channels must lie in [0, 1], got '" + arguments[i] + "'");
        options.background = color;
    } else if (argument == "--request") {
        for (const std::string& resource : splitList(value(), ',')) {
            const ResourceName name = ResourceName::split(resource);
            if (name.pass.empty() || name.field.empty())
                throw UsageError("--request: '" + resource +
                                 "' is not a resource name like 'gbuffer.normal' "
                                 "or 'gbuffer.*'");
            options.extraOutputs.push_back(resource);
        }
    } else if (argument == "--dump") {
        options.dumpDirectory = value();
    } else if (argument == "--stats") {
        options.statsPath = value();
    } else if (argument == "--graphviz") {
        options.graphvizPath = value();
    } else if (argument == "--contact-sheet") {
        options.contactSheetPath = value();
        if (lowercaseExtension(options.contactSheetPath) != ".png")
            throw UsageError("--contact-sheet: '" + options.contactSheetPath + "' must be a .png file");
    } else if (argument == "--svg") {
        options.svgPath = value();
        if (lowercaseExtension(options.svgPath) != ".svg")
            throw UsageError("--svg: '" + options.svgPath + "' must be a .svg file");
    } else if (argument == "--svg-tolerance") {
        options.svgTolerance = parseNumber(argument, value());
        if (options.svgTolerance < 0.0 || options.svgTolerance > 100.0)
            throw UsageError("--svg-tolerance: expected output pixels from 0 to 100, got '" + arguments[i] + "'");
    } else if (argument == "--list") {
        options.listPath = value();
    } else if (argument == "--shard") {
        options.shard = parseShard(argument, value());
    } else if (argument == "--print-plan") {
        options.printPlan = true;
    } else if (argument == "--egl-platform") {
        options.eglPlatform = value();
        if (options.eglPlatform != "auto" && options.eglPlatform != "device" && options.eglPlatform != "surfaceless")
            throw UsageError("--egl-platform: '" + options.eglPlatform + "' is not one of auto, device, surfaceless");
    } else if (argument == "--memory-limit") {
        options.memoryLimitBytes = std::size_t(parseWholeNumber(argument, value(), 64, kMaxMemoryLimitMib)) << 20;
    } else if (argument == "--style") {
        options.stylePath = value(); // its settings were put first by expandStyleFile()
    } else if (argument == "-q" || argument == "--quiet") {
        options.quiet = true;
    } else if (!argument.empty() && argument[0] == '-') {
        throw UsageError("unknown option '" + argument + "'");
    } else {
        if (options.modelPaths.empty()) options.modelPath = argument;
        options.modelPaths.push_back(argument);
    }
    return true;
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
    };
    return kFlags;
}

bool rendersImages(const RenderOptions& options) {
    return !options.outputPath.empty() || !options.dumpDirectory.empty() || !options.contactSheetPath.empty() ||
           !options.svgPath.empty();
}

std::string shadingModeName(ShadingMode mode) {
    for (const auto& [name, value] : kShadingModes)
        if (value == mode) return name;
    return "?";
}

bool usesShadeMap(ShadingMode mode) { return mode == ShadingMode::Cel || mode == ShadingMode::Comic; }

RenderOptions parseRenderOptions(const std::vector<std::string>& arguments) {
    return parseRenderOptions(arguments, {});
}

RenderOptions parseRenderOptions(const std::vector<std::string>& arguments, const std::vector<std::string>& origins) {
    if (!origins.empty() && origins.size() != arguments.size())
        throw std::invalid_argument("parseRenderOptions(): " + std::to_string(origins.size()) + " origins for " +
                                    std::to_string(arguments.size()) + " arguments");
    ParseState state;
    RenderOptions& options = state.options;
    for (const std::string& type : knownLineTypes()) options.lineStyles[type] = LineStyle{};
    for (std::size_t i = 0; i < arguments.size(); ++i) {
        const std::size_t flagIndex = i;
        try {
            if (!parseArgument(arguments, i, state)) return options;
        } catch (const UsageError& error) {
            if (origins.empty() || origins[flagIndex].empty()) throw;
            throw UsageError(origins[flagIndex] + ": " + error.what());
        }
    }
    if (options.modelPaths.empty() && options.listPath.empty())
        throw UsageError("missing MODEL (a .gltf, .glb, .obj or .stl file, or --list FILE)");
    checkShadingFlags(options, state.givenFlags);
    checkLineFlags(options, state.givenFlags);
    for (const auto& [flag, type] : state.styledLineTypes)
        if (std::find(options.lines.begin(), options.lines.end(), type) == options.lines.end())
            throw UsageError(flag + ": the '" + type + "' line type is not drawn (add it to --lines)");
    if (options.outputPath.empty() && !options.printPlan && options.dumpDirectory.empty() &&
        options.graphvizPath.empty() && options.contactSheetPath.empty() && options.svgPath.empty())
        throw UsageError("missing -o OUT.png (or --print-plan / --graphviz to only show the plan)");
    if (options.eye && options.target && *options.eye == *options.target)
        throw UsageError("--eye and --target must differ");
    const bool renders = rendersImages(options);
    const std::vector<std::string>& given = state.givenFlags;
    if (std::find(given.begin(), given.end(), "--svg-tolerance") != given.end() && options.svgPath.empty())
        throw UsageError("--svg-tolerance: applies to --svg, which is not given");
    if (!options.svgPath.empty() && options.lines.empty())
        throw UsageError("--svg: no line types to write (add --lines)");
    if (!options.statsPath.empty() && !renders)
        throw UsageError("--stats needs -o or --dump: with --print-plan alone nothing is rendered or timed");
    return options;
}

std::string renderHelp() {
    return R"(Usage: inkgraph render MODEL... -o OUT.png [options]

Renders one still of each MODEL (.gltf, .glb, .obj, .stl) with no window or display (EGL).

Output
  -o, --output FILE      the final picture: .png, .exr, .tif or .jpg
  --size WxH             image size in pixels (default 1024x1024, at most 16384 a side)
  --dump DIR             also write every buffer the plan computed, and manifest.json. What is computed follows
                         from the request: shading draws the meshes itself; add --request 'gbuffer.*' for
                         normal.exr, view.exr, w.exr (float32 RGBA, alpha = coverage), ndotv.exr, depth.exr
                         (float32), coverage.png, basecolor.png. Also shading.png, final.png, lines-<type>.png.
                         An earlier dump in DIR is replaced once everything is written; DIR must be new, empty, or
                         hold exactly an earlier dump
  --request LIST         compute and keep extra graph outputs, comma-separated: 'gbuffer.wVec', or 'gbuffer.*'
                         for all of them (requesting is what makes a pass compute a buffer; dumping never does)
  --stats FILE.json      timings per pass, culled passes with reasons, scene and GL facts
  --print-plan           print the compiled render plan (without -o, print it and stop: no GL needed)
  --graphviz FILE.dot    write the plan as a Graphviz graph (culled passes dashed)
  --contact-sheet FILE.png
                         every buffer the plan computed (normal, view, w, n.v, depth, each line layer, shading,
                         final) side by side in one labelled picture
  --svg FILE.svg         the line layers as vector paths, one group (an Inkscape layer) per line type, traced
                         from the one-pixel line skeletons and simplified, in the lines' widths and colours
  --svg-tolerance PX     --svg: how far a simplified path may leave the traced pixels, in output pixels
                         (default 0.5; 0 keeps every pixel)
  -q, --quiet            no progress lines on stderr

Camera (right-handed world, OpenGL lookAt/perspective; default: the glTF camera, else auto-framed)
  --eye X,Y,Z            camera position, in world units (coordinates within +-1e15)
  --target X,Y,Z         point looked at (default: the model's bounding-sphere centre; within +-1e15)
  --up X,Y,Z             up direction (default: the glTF camera's, else 0,1,0); auto-framing looks from the
                         front, slightly above, as this up defines it
  --fov DEG              vertical field of view in degrees, 0.01 to 179 (default 35)
  --clip NEAR,FAR        near and far clip distances along the view axis, 0 < NEAR < FAR, both in [1e-30, 1e30],
                         FAR/NEAR at most 1e30 (default: fitted to the bounding sphere, with far/near at most 1e4);
                         depth is reversed-Z float, so ratios up to 1e6 and beyond keep about 1e-7 of the distance
                         apart

Look
  --style FILE           settings from a style file, one NAME = VALUE per line (# comments): any flag of this
                         section and of Lines, --size and --fov, without the dashes; e.g. "shading = comic",
                         "lines = contour, suggestive". Flags on the command line win over the file's
  --shading MODE         cel (default) | comic | flat | gouraud | lambert | phong | none
                           cel: 1-D shade map indexed by the half-Lambert (n.l + 1)/2; default: seed 003's five
                                bands {0, .25, .5, .75, 1} x the material colour
                           comic: 2-D shade map indexed by diffuse max(n.l, 0) (across) and specular
                                max(r.v, 0)^shininess (up), seed 000
                           flat, gouraud, lambert: ambient + diffuse per face, per vertex, per pixel
                           phong: ambient + diffuse + white specular per pixel
  --shininess N          specular exponent for phong and comic, 0 to 1e6 (default 32)
  --bands N              cel: N even bands, 2 to 256
  --shademap FILE        cel: a one-row image; comic: a 2-D image (left dark -> right lit, bottom no highlight
                         -> top full highlight); 8-bit, at most 4096 a side; multiplied with the material colour
  --view-vector V        comic: exact (default, per pixel) | constant (seed 000's V_c toward the bounding-sphere
                         centre; falls back to exact when the eye is inside or within 2 radii of the sphere)
  --face-orientation M   comic: standard (default: the GPU culls and lights per pixel) | during-triangles |
                         during-vertices | after-vertices (seed 000's CPU marking with per-vertex lighting;
                         --stats reports front shares, holes and milliseconds)
  --front-rule R         during-vertices, after-vertices: a triangle is front when 3 (R=1), 2 (R=2) or 1 (R=3,
                         default) of its vertices are front
  --light X,Y,Z          world direction toward the light (default: the glTF directional light, else from
                         the upper left behind the camera)
  --background R,G,B     paper colour, channels in [0,1] (default 1,1,1)

Lines (any subset; only the passes the listed types need run: see --stats "culled")
  --lines LIST           comma-separated line types, or none (default none), composited in this order:
                           outline: Lander's back faces drawn as thick wireframe behind the fill (seed 000)
                           silhouette: the inflated hull (seed 003), offset along position-welded smooth
                                normals so hard edges do not crack it
                           normal-edge: creases where neighbouring G-buffer normals differ by more than
                                --crease-angle (Saito and Takahashi)
                           depth-edge: jumps in linear depth larger than --depth-jump x the depth
                           crease: mesh edges whose faces meet at more than --crease-angle (object space)
                           border: open (and non-manifold) mesh edges (object space)
                           suggestive: suggestive contours (DeCarlo et al.): D_w(n.v) = 0 with D_w D_w(n.v) > 0,
                                in the float G-buffer with v = c - p, so the lines are where kappa_r = 0
                           suggestive-object: the same lines found on the mesh (object space): the zero set of
                                kappa_r from per-vertex curvature (Rusinkiewicz 2004) and rtsc's per-view test,
                                projected, hidden by the G-buffer depth (within --depth-jump), sub-pixel exact
                           contour: where n.v changes sign, and where the model ends (against the background or
                                in front of a farther surface), as a one-pixel skeleton
                           mesh-silhouette: mesh edges between a front and a back face (exact perspective test)
                         each is written to lines-<type>.png by --dump
  --TYPE-width PX        line width in pixels, above 0 up to 256 (default 2), constant across distance, field
                         of view and resolution (for outline: the width showing outside the silhouette)
  --TYPE-color R,G,B[,A] line colour, channels in [0,1] (default 0,0,0)
  --silhouette-object-width D
                         offset the hull by D model units instead (the width then shrinks with distance)
  --crease-angle DEG     crease, normal-edge: the angle above which an edge is a crease (default 30)
  --depth-jump R         contour, suggestive, depth-edge, normal-edge: neighbouring pixels whose depths differ
                         by more than R x the nearer depth are different surfaces (default 0.05);
                         suggestive-object: a line point more than R x the depth behind the visible surface is
                         hidden
  --suggestive-threshold T, --suggestive-fade F
                         suggestive, suggestive-object: keep lines whose strength q (rtsc's
                         fs^2 tan(theta) D_w kappa_r, fs = 5% of the bounding radius) exceeds T (default 0.01),
                         drawn with alpha (q - T) / (q - T + F) (default F = 0.03; 0 draws every kept line in
                         full)
  --suggestive-stencil N suggestive: 3 (default) or 5-point central differences; 5 is fourth order, more exact on
                         clean data, slower, and needs two pixels of one surface on each side
  --supersample S        find the G-buffer, mesh-edge and object-space lines at S x the size (1 to 8,
                         default 1) and area-downsample only the final line images: smoother, better-placed
                         lines, S^2 the work. Outline and silhouette are drawn by GL at the output size.
  --gbuffer-precision P  float (default) | half: store the G-buffer's normal, view, w, n.v and radial fields as
                         16-bit floats (depth stays 32-bit). Half the memory; the suggestive contours get noisy
                         (docs/accuracy.md measures it). Also applies to --request 'gbuffer.*'
  Outline and silhouette draw nothing when the eye is inside the model (they would flood the picture).

Batch (several models in one process: one GL context, each shader program compiled once)
  MODEL...               several models render one after the other; every output path must then hold {name}
                         (the model's file name without extension) or {index} (its list position from 1,
                         zero-padded), e.g. -o 'out/{name}.png' --stats 'out/{name}.json'
  --list FILE            more models, one path per line (blank lines and # comments skipped; relative paths
                         from the current folder); '-' reads standard input
  --shard K/N            render only the models at list positions p (from 0) with p mod N = K, 0 <= K < N: one
                         task of an array job (Slurm: --shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT)
  Each model gets a progress line. A model that cannot be read is reported and the others go on; the run then
  ends with exit 3. Any other error stops the batch; models already done keep their files.

System
  --egl-platform P       auto | device | surfaceless (default auto: device first, then surfaceless)
  --memory-limit MIB     the most memory the process may take for one still, 64 and up (default: half this
                         machine's memory, at least 1024). Checked before allocating: the model load from the
                         file's size and declared counts (exit 3), then the whole run's peak from the plan (the
                         process, the scene, every buffer at --size and --supersample, read-backs, encoding; exit
                         2), naming the flags that need the memory. --stats reports the estimate
                         (estimated_peak_mib) and the measured peak (peak_rss_mib); docs/batch.md sizes a task

Exit codes: 0 done, 2 bad command line, 3 unreadable or invalid model, 4 no OpenGL/EGL,
5 an output could not be written, 1 anything else.
)";
}

std::string mainHelp() {
    return R"(inkgraph - headless anime- and comic-style renderer

Usage:
  inkgraph render MODEL... -o OUT.png [options]
                                               render a still of each model (see: inkgraph help render)
  inkgraph --version                           print the version
  inkgraph --help                              this text
)";
}

} // namespace inkgraph
