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
    static const std::vector<std::string> kLineTypes;
    return kLineTypes;
}

std::string shadingModeName(ShadingMode mode) {
    switch (mode) {
    case ShadingMode::None: return "none";
    case ShadingMode::Lambert: return "lambert";
    }
    return "?";
}

RenderOptions parseRenderOptions(const std::vector<std::string>& arguments) {
    RenderOptions options;
    for (std::size_t i = 0; i < arguments.size(); ++i) {
        const std::string& argument = arguments[i];
        auto value = [&]() -> const std::string& {
            if (i + 1 >= arguments.size()) throw UsageError(argument + ": missing value");
            if (arguments[i + 1].empty()) throw UsageError(argument + ": empty value");
            return arguments[++i];
        };
        if (argument == "--help" || argument == "-h") {
            options.help = true;
            return options;
        }
        if (argument == "-o" || argument == "--output") {
            options.outputPath = value();
            std::string extension = std::filesystem::path(options.outputPath).extension().string();
            std::transform(extension.begin(), extension.end(), extension.begin(),
                           [](unsigned char c) { return char(std::tolower(c)); });
            if (std::find(kOutputExtensions.begin(), kOutputExtensions.end(), extension) == kOutputExtensions.end())
                throw UsageError("-o: '" + options.outputPath + "' has no picture extension I write (use .png, .exr, "
                                 ".tif or .jpg)");
        } else if (argument == "--size") {
            parseSize(value(), options.width, options.height);
        } else if (argument == "--eye") {
            options.eye = parseVector(argument, value());
        } else if (argument == "--target") {
            options.target = parseVector(argument, value());
        } else if (argument == "--up") {
            options.up = parseVector(argument, value());
            if (glm::length(*options.up) == 0.0) throw UsageError("--up: the up vector must not be zero");
        } else if (argument == "--fov") {
            const double fov = parseNumber(argument, value());
            if (!(fov >= kMinFovDegrees && fov <= kMaxFovDegrees))
                throw UsageError("--fov: degrees must lie in [0.01, 179], got " + arguments[i]);
            options.fovYDegrees = fov;
        } else if (argument == "--light") {
            const glm::dvec3 light = parseVector(argument, value());
            if (glm::length(light) == 0.0) throw UsageError("--light: the direction must not be zero");
            options.towardLight = glm::normalize(light);
        } else if (argument == "--shading") {
            const std::string& mode = value();
            if (mode == "none") options.shading = ShadingMode::None;
            else if (mode == "lambert") options.shading = ShadingMode::Lambert;
            else throw UsageError("--shading: unknown mode '" + mode + "' (available: none, lambert)");
        } else if (argument == "--lines") {
            const std::string& list = value();
            options.lines.clear();
            if (list == "none") continue;
            for (const std::string& type : splitList(list, ',')) {
                const auto& known = knownLineTypes();
                if (std::find(known.begin(), known.end(), type) == known.end())
                    throw UsageError("--lines: unknown line type '" + type + "' (available: " + joined(known) +
                                     "; or 'none')");
                options.lines.push_back(type);
            }
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
                    throw UsageError("--request: '" + resource + "' is not a resource name like 'gbuffer.normal' "
                                     "or 'gbuffer.*'");
                options.extraOutputs.push_back(resource);
            }
        } else if (argument == "--dump") {
            options.dumpDirectory = value();
        } else if (argument == "--stats") {
            options.statsPath = value();
        } else if (argument == "--graphviz") {
            options.graphvizPath = value();
        } else if (argument == "--print-plan") {
            options.printPlan = true;
        } else if (argument == "--egl-platform") {
            options.eglPlatform = value();
            if (options.eglPlatform != "auto" && options.eglPlatform != "device" && options.eglPlatform != "surfaceless")
                throw UsageError("--egl-platform: '" + options.eglPlatform + "' is not one of auto, device, surfaceless");
        } else if (argument == "-q" || argument == "--quiet") {
            options.quiet = true;
        } else if (!argument.empty() && argument[0] == '-') {
            throw UsageError("unknown option '" + argument + "'");
        } else if (options.modelPath.empty()) {
            options.modelPath = argument;
        } else {
            throw UsageError("unexpected argument '" + argument + "' (one MODEL per run; the model is '" +
                             options.modelPath + "')");
        }
    }
    if (options.modelPath.empty()) throw UsageError("missing MODEL (a .gltf, .glb, .obj or .stl file)");
    if (options.outputPath.empty() && !options.printPlan && options.dumpDirectory.empty() &&
        options.graphvizPath.empty())
        throw UsageError("missing -o OUT.png (or --print-plan / --graphviz to only show the plan)");
    if (options.eye && options.target && *options.eye == *options.target)
        throw UsageError("--eye and --target must differ");
    const bool renders = !options.outputPath.empty() || !options.dumpDirectory.empty();
    if (!options.statsPath.empty() && !renders)
        throw UsageError("--stats needs -o or --dump: with --print-plan alone nothing is rendered or timed");
    return options;
}

std::string renderHelp() {
    return R"(Usage: inkgraph render MODEL -o OUT.png [options]

Renders one still of MODEL (.gltf, .glb, .obj, .stl) with no window or display (EGL).

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
  -q, --quiet            no progress lines on stderr

Camera (right-handed world, OpenGL lookAt/perspective; default: the glTF camera, else auto-framed)
  --eye X,Y,Z            camera position
  --target X,Y,Z         point looked at (default: the model's bounding-sphere centre)
  --up X,Y,Z             up direction (default: the glTF camera's, else 0,1,0); auto-framing looks from the
                         front, slightly above, as this up defines it
  --fov DEG              vertical field of view in degrees, 0.01 to 179 (default 35)

Look
  --shading MODE         none | lambert (default lambert)
  --light X,Y,Z          world direction toward the light (default: the glTF directional light, else from
                         the upper left behind the camera)
  --lines LIST           comma-separated line types, or none (default none)
  --background R,G,B     paper colour, channels in [0,1] (default 1,1,1)

System
  --egl-platform P       auto | device | surfaceless (default auto: device first, then surfaceless)

Exit codes: 0 done, 2 bad command line, 3 unreadable or invalid model, 4 no OpenGL/EGL,
5 an output could not be written, 1 anything else.
)";
}

std::string mainHelp() {
    return R"(inkgraph - headless anime- and comic-style renderer

Usage:
  inkgraph render MODEL -o OUT.png [options]   render one still (see: inkgraph help render)
  inkgraph --version                           print the version
  inkgraph --help                              this text
)";
}

} // namespace inkgraph
