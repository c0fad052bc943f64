// inkgraph_line_cleanliness: how clean one model's lines are in one look (issue 19), and how still they hold across
// sizes and small turns (issue 39), measured by running an inkgraph binary (any build: the same tool measures the one
// before a change and the one after) and reading its dumps.
#include "render/BackgroundThreads.h"
#include "render/ImageFiles.h"
#include "bench/LineCleanlinessMetrics.h"
#include "tests/support/SvgPaths.h"

#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using inkgraph::bench::PinholeView;
using inkgraph::bench::PointSetAgreement;

constexpr const char* kHelp =
    R"(Usage: inkgraph_line_cleanliness --inkgraph BIN --model FILE --work DIR [--look NAME] [--json FILE]
                                 [--columns TYPE,...] [--depth-tolerance R] [--disagreement DIR] [--header]
                                 [-- RENDER FLAGS...]

Renders FILE with the inkgraph binary BIN (its environment is passed on: LD_LIBRARY_PATH, INKGRAPH_SHADER_DIR, ...)
nine times, with RENDER FLAGS (the look, e.g. --shading comic --lines outline,contour,suggestive,crease) added:
  view A  --orbit 0,14.04 (the default view) at 1024x1024, with --dump, --svg and --stats;
  view A  at 512x512 and at 2048x2048, with --dump;
  views   --orbit 1,14.04, -1,14.04, 5,14.04, -5,14.04, 0.1,14.04 and -0.1,14.04 (1, 5 and 0.1 degrees either
          way around the up axis, the same distance) at 1024x1024, with --dump.
and measures (bench/README.md defines each number):
  ink share       pixels where the largest line layer is >= 128, on the model (coverage > 0) / model pixels,
                  and off the model / model pixels;
  SVG paths       <path> count, share shorter than 3 output pixels, median length;
  F1 size         per line type and size pair, view A's skeleton at the smaller size against the one at twice the
                  size mapped to the smaller size's pixels, within 1.5 of those pixels: 512/1024 and 1024/2048;
  F1 view         per line type and turn, A's 1024 skeleton reprojected into the turned view through A's depth
                  against that view's, and the turned view's into A against A's (points that leave the frame or are
                  hidden there are left out), within 1.5 px: +1, -1, +5, -5, +0.1 and -0.1 degrees. A tenth of a
                  degree moves the model under a pixel, so what changes there is flicker, not lines moving.
The table cell per type is "F1 512/1024, F1 1024/2048 / F1 view +-1, F1 view +-5, F1 view +-0.1", each view number
the smaller of the two turns; the JSON has every comparison and the minima.
Writes the renders under DIR, the numbers as JSON to FILE (default DIR/line-cleanliness.json), and prints one
markdown table row (with --header, the header first).

  --look NAME          the look's name in the table (default: the render flags as written, or 'default')
  --columns LIST       the line types given a table column, in order (default outline,silhouette,contour,
                       suggestive,crease); every drawn type is in the JSON
  --depth-tolerance R  F1 view: a reprojected point is visible when within R x the depth there (default 0.03)
  --disagreement DIR   also write, per type, where two skeletons disagree: TYPE-1024-2048.png (the 2048 skeleton
                       mapped into 1024 pixels) and TYPE-turn+1.png, TYPE-turn-1.png, TYPE-turn+0.1.png,
                       TYPE-turn-0.1.png (the turned view's skeleton
                       reprojected into view A, both judged there, so a point may read otherwise than in the F1,
                       which judges A's points in the turned view): view A's 1024 points black where matched
                       within 1.5 px, red where not; the other's grey where matched, blue where not
)";

constexpr double kTolerancePixels = 1.5;
constexpr int kInkThreshold = 128;
constexpr double kShortPathPixels = 3.0;
constexpr const char* kElevation = "14.04";

/** The turned views of the F1 view numbers: azimuth in tenths of a degree from view A's 0, and the name of each. */
struct Turn {
    int tenths;
    const char* name; ///< the JSON key and render name: "+1", "-1", ...
};
constexpr Turn kTurns[] = {{10, "+1"}, {-10, "-1"}, {50, "+5"}, {-50, "-5"}, {1, "+0.1"}, {-1, "-0.1"}};

struct Options {
    fs::path inkgraph;
    fs::path model;
    fs::path work;
    fs::path json;
    std::string look;
    std::vector<std::string> columns{"outline", "silhouette", "contour", "suggestive", "crease"};
    double depthTolerance = 0.03;
    fs::path disagreement; ///< empty: no pictures
    bool header = false;
    std::vector<std::string> renderFlags;
};

class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

std::vector<std::string> splitList(const std::string& list) {
    std::vector<std::string> items;
    std::stringstream stream(list);
    for (std::string item; std::getline(stream, item, ',');)
        if (!item.empty()) items.push_back(item);
    return items;
}

Options parseOptions(int argc, char** argv) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string argument = argv[i];
        if (argument == "--") {
            options.renderFlags.assign(argv + i + 1, argv + argc);
            break;
        }
        if (argument == "--header") {
            options.header = true;
            continue;
        }
        if (i + 1 >= argc) throw UsageError("unknown argument or missing value: '" + argument + "'");
        const std::string value = argv[++i];
        if (argument == "--inkgraph") {
            options.inkgraph = value;
        } else if (argument == "--model") {
            options.model = value;
        } else if (argument == "--work") {
            options.work = value;
        } else if (argument == "--json") {
            options.json = value;
        } else if (argument == "--look") {
            options.look = value;
        } else if (argument == "--disagreement") {
            options.disagreement = value;
        } else if (argument == "--columns") {
            options.columns = splitList(value);
        } else if (argument == "--depth-tolerance") {
            char* end = nullptr;
            options.depthTolerance = std::strtod(value.c_str(), &end);
            if (*end != '\0' || !(options.depthTolerance > 0.0 && options.depthTolerance < 1.0))
                throw UsageError("--depth-tolerance: expected a ratio above 0 and below 1, got '" + value + "'");
        } else {
            throw UsageError("unknown argument '" + argument + "'");
        }
    }
    if (options.inkgraph.empty() || options.model.empty() || options.work.empty())
        throw UsageError("--inkgraph, --model and --work are required");
    if (options.json.empty()) options.json = options.work / "line-cleanliness.json";
    if (options.look.empty()) {
        for (const std::string& flag : options.renderFlags) options.look += (options.look.empty() ? "" : " ") + flag;
        if (options.look.empty()) options.look = "default";
    }
    return options;
}

/** Runs `arguments` (argv[0] is the program) with this process's environment and waits; throws unless it exits 0. */
void runProgram(const std::vector<std::string>& arguments) {
    std::string shown;
    for (const std::string& argument : arguments) shown += (shown.empty() ? "" : " ") + argument;
    std::vector<char*> argv;
    for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
    argv.push_back(nullptr);
    std::cout.flush();
    const pid_t child = fork();
    if (child < 0) throw std::runtime_error("runProgram(): fork failed: " + std::string(std::strerror(errno)));
    if (child == 0) {
        execv(argv[0], argv.data());
        std::fprintf(stderr, "runProgram(): cannot run '%s': %s\n", argv[0], std::strerror(errno));
        _exit(127);
    }
    int status = 0;
    while (waitpid(child, &status, 0) < 0)
        if (errno != EINTR)
            throw std::runtime_error("runProgram(): waitpid failed: " + std::string(std::strerror(errno)));
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw std::runtime_error("runProgram(): '" + shown + "' failed (" +
                                 (WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                                    : "killed by signal " + std::to_string(WTERMSIG(status))) +
                                 ")");
}

nlohmann::json readJson(const fs::path& path) {
    std::ifstream stream(path);
    if (!stream) throw std::runtime_error("readJson(): cannot open '" + path.string() + "'");
    try {
        return nlohmann::json::parse(stream);
    } catch (const std::exception& error) {
        throw std::runtime_error("readJson(): '" + path.string() + "': " + error.what());
    }
}

std::string readText(const fs::path& path) {
    std::ifstream stream(path, std::ios::binary);
    if (!stream) throw std::runtime_error("readText(): cannot open '" + path.string() + "'");
    std::stringstream text;
    text << stream.rdbuf();
    return text.str();
}

/** One channel of a dumped image, of the expected depth (CV_8U for PNGs, CV_32F for EXRs). */
cv::Mat readChannel(const fs::path& path, int expectedDepth) {
    cv::Mat image = inkgraph::readImage(path);
    if (image.depth() != expectedDepth)
        throw std::runtime_error("readChannel(): '" + path.string() + "' is not of the expected pixel type");
    if (image.channels() > 1) cv::extractChannel(image, image, 0);
    return image;
}

cv::Matx44d matrixFromJson(const nlohmann::json& rows, const std::string& where) {
    if (!rows.is_array() || rows.size() != 4) throw std::runtime_error("matrixFromJson(): " + where + " is not 4x4");
    cv::Matx44d matrix;
    for (int row = 0; row < 4; ++row) {
        if (!rows[row].is_array() || rows[row].size() != 4)
            throw std::runtime_error("matrixFromJson(): " + where + " is not 4x4");
        for (int column = 0; column < 4; ++column) matrix(row, column) = rows[row][column].get<double>();
    }
    return matrix;
}

/** The camera of a dump: manifest.json's view and projection matrices (rows as written) and size. --stats holds
 *  only the camera source and the clip planes, so the manifest is the one place the whole camera is written. */
PinholeView cameraOfDump(const nlohmann::json& manifest, const fs::path& where) {
    const std::string name = "'" + (where / "manifest.json").string() + "'";
    if (!manifest.contains("camera") || !manifest["camera"].contains("view_matrix") ||
        !manifest["camera"].contains("projection_matrix") || !manifest.contains("size"))
        throw std::runtime_error("cameraOfDump(): " + name + " lacks camera.view_matrix, projection_matrix or size");
    PinholeView view;
    view.view = matrixFromJson(manifest["camera"]["view_matrix"], name + " camera.view_matrix");
    view.projection = matrixFromJson(manifest["camera"]["projection_matrix"], name + " camera.projection_matrix");
    view.size = cv::Size(manifest["size"][0].get<int>(), manifest["size"][1].get<int>());
    return view;
}

double eyeDistance(const nlohmann::json& manifest) {
    const auto& camera = manifest["camera"];
    double squared = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
        const double difference = camera["eye"][axis].get<double>() - camera["target"][axis].get<double>();
        squared += difference * difference;
    }
    return std::sqrt(squared);
}

/** The line types the render drew, in composite order, from the manifest's look. */
std::vector<std::string> drawnLineTypes(const nlohmann::json& manifest) {
    std::vector<std::string> types;
    if (manifest.contains("look") && manifest["look"].contains("lines"))
        for (const auto& line : manifest["look"]["lines"]) types.push_back(line["type"].get<std::string>());
    return types;
}

struct Render {
    fs::path dump;
    nlohmann::json manifest;
};

Render render(const Options& options, const std::string& name, int size, const std::string& orbit,
              const std::string& request, bool withSvgAndStats) {
    Render result;
    result.dump = options.work / (name + "-dump");
    std::vector<std::string> arguments{options.inkgraph.string(),
                                       "render",
                                       options.model.string(),
                                       "-q",
                                       "-o",
                                       (options.work / (name + ".png")).string(),
                                       "--size",
                                       std::to_string(size) + "x" + std::to_string(size),
                                       "--orbit",
                                       orbit,
                                       "--dump",
                                       result.dump.string()};
    if (!request.empty()) arguments.insert(arguments.end(), {"--request", request});
    if (withSvgAndStats)
        arguments.insert(arguments.end(), {"--svg", (options.work / (name + ".svg")).string(), "--stats",
                                           (options.work / (name + "-stats.json")).string()});
    arguments.insert(arguments.end(), options.renderFlags.begin(), options.renderFlags.end());
    runProgram(arguments);
    result.manifest = readJson(result.dump / "manifest.json");
    return result;
}

nlohmann::json agreementJson(const PointSetAgreement& agreement) {
    return {{"f1", agreement.f1},
            {"precision", agreement.precision},
            {"recall", agreement.recall},
            {"first_points", agreement.firstCount},
            {"first_within", agreement.firstWithin},
            {"second_points", agreement.secondCount},
            {"second_within", agreement.secondWithin}};
}

std::string fixed(double value, int decimals) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

nlohmann::json droppedJson(const inkgraph::bench::Reprojection& reprojection) {
    return {{"without_depth", reprojection.withoutDepth},
            {"outside_frame", reprojection.outsideFrame},
            {"hidden", reprojection.hiddenInTarget}};
}

/** --orbit's value at `tenths` of a degree of azimuth: "5,14.04", "-0.1,14.04". */
std::string orbitAt(int tenths) {
    const std::string sign = tenths < 0 ? "-" : "";
    const int whole = std::abs(tenths) / 10;
    const int tenth = std::abs(tenths) % 10;
    return sign + std::to_string(whole) + (tenth != 0 ? "." + std::to_string(tenth) : "") + "," + kElevation;
}

int measure(const Options& options) {
    fs::create_directories(options.work);
    // Depth for reprojection and coverage for the ink share: asking for them is what makes the G-buffer keep them.
    const Render viewA = render(options, "a1024", 1024, orbitAt(0), "gbuffer.coverage,gbuffer.depth", true);
    const Render viewA512 = render(options, "a512", 512, orbitAt(0), "", false);
    const Render viewA2048 = render(options, "a2048", 2048, orbitAt(0), "", false);
    std::vector<Render> turned;
    for (const Turn& turn : kTurns)
        turned.push_back(render(options, std::string("turn") + turn.name + "-1024", 1024, orbitAt(turn.tenths),
                                "gbuffer.depth", false));

    const std::vector<std::string> types = drawnLineTypes(viewA.manifest);
    nlohmann::json json;
    json["model"] = options.model.string();
    json["look"] = options.look;
    json["render_flags"] = options.renderFlags;
    json["inkgraph"] = options.inkgraph.string();
    json["line_types"] = types;
    json["tolerance_pixels"] = kTolerancePixels;
    json["view_a_distance"] = eyeDistance(viewA.manifest);
    for (std::size_t index = 0; index < turned.size(); ++index)
        json["turn_distance"][kTurns[index].name] = eyeDistance(turned[index].manifest);

    // Ink share at 1024x1024.
    const cv::Mat coverage = readChannel(viewA.dump / "coverage.png", CV_8U);
    std::map<std::string, cv::Mat> layersA;
    std::vector<cv::Mat> allLayers;
    for (const std::string& type : types) {
        layersA[type] = readChannel(viewA.dump / ("lines-" + type + ".png"), CV_8U);
        allLayers.push_back(layersA[type]);
    }
    const auto ink = inkgraph::bench::measureInkShare(coverage, allLayers, kInkThreshold);
    json["ink"] = {{"model_pixels", ink.modelPixels},
                   {"ink_inside_model", ink.inkInsideModel},
                   {"ink_outside_model", ink.inkOutsideModel},
                   {"inside_share", ink.insideShare},
                   {"outside_share", ink.outsideShare}};

    // SVG paths of view A at 1024x1024.
    const auto document = inkgraph::test::parseSvgPathDocument(readText(options.work / "a1024.svg"));
    std::vector<double> lengths;
    nlohmann::json svgTypes = nlohmann::json::object();
    for (const auto& group : document.groups) {
        std::vector<double> groupLengths;
        for (std::size_t path = 0; path < group.paths.size(); ++path)
            groupLengths.push_back(inkgraph::bench::pathLength(group.paths[path], group.closed[path]));
        const auto summary = inkgraph::bench::summarisePathLengths(groupLengths, kShortPathPixels);
        svgTypes[group.label.empty() ? group.id : group.label] = {{"paths", summary.pathCount},
                                                                  {"short_paths", summary.shortPathCount},
                                                                  {"median_length", summary.medianLength}};
        lengths.insert(lengths.end(), groupLengths.begin(), groupLengths.end());
    }
    const auto paths = inkgraph::bench::summarisePathLengths(lengths, kShortPathPixels);
    json["svg"] = {{"paths", paths.pathCount},
                   {"short_paths", paths.shortPathCount},
                   {"short_share", paths.shortShare},
                   {"median_length", paths.medianLength},
                   {"per_type", svgTypes}};

    // Skeleton stability per line type: across sizes (512/1024, 1024/2048), and across turns of 1 and 5 degrees either
    // way.
    const PinholeView cameraA = cameraOfDump(viewA.manifest, viewA.dump);
    const cv::Mat depthA = readChannel(viewA.dump / "depth.exr", CV_32F);
    std::vector<PinholeView> turnedCameras;
    std::vector<cv::Mat> turnedDepths;
    for (const Render& view : turned) {
        turnedCameras.push_back(cameraOfDump(view.manifest, view.dump));
        turnedDepths.push_back(readChannel(view.dump / "depth.exr", CV_32F));
    }
    // The table cell per type: "512/1024, 1024/2048 / +-1, +-5", or "empty" when the type drew nothing in any of the
    // renders (every F1 is then 1 by definition, which would read as perfect lines).
    std::map<std::string, std::string> cellByType;
    for (const std::string& type : types) {
        const std::string file = "lines-" + type + ".png";
        const auto skeleton = inkgraph::bench::skeletonPoints(layersA[type], kInkThreshold);
        const auto skeleton512 =
            inkgraph::bench::skeletonPoints(readChannel(viewA512.dump / file, CV_8U), kInkThreshold);
        const auto skeleton2048 =
            inkgraph::bench::skeletonPoints(readChannel(viewA2048.dump / file, CV_8U), kInkThreshold);
        const auto size512To1024 = inkgraph::bench::compareAcrossSizes(skeleton512, skeleton, 2.0, kTolerancePixels);
        const auto size1024To2048 = inkgraph::bench::compareAcrossSizes(skeleton, skeleton2048, 2.0, kTolerancePixels);
        const double sizeMin = inkgraph::bench::smallestF1({size512To1024, size1024To2048});
        if (!options.disagreement.empty()) {
            fs::create_directories(options.disagreement);
            inkgraph::writeImage(options.disagreement / (type + "-1024-2048.png"),
                                 inkgraph::bench::disagreementPicture(
                                     layersA[type].size(), skeleton, inkgraph::bench::toSmallerImage(skeleton2048, 2.0),
                                     kTolerancePixels));
        }
        bool anyPoints = !skeleton.empty() || !skeleton512.empty() || !skeleton2048.empty();

        nlohmann::json views = nlohmann::json::object();
        std::map<int, std::vector<PointSetAgreement>> byAngle; // |tenths of a degree| -> both directions
        for (std::size_t index = 0; index < turned.size(); ++index) {
            const auto skeletonTurned =
                inkgraph::bench::skeletonPoints(readChannel(turned[index].dump / file, CV_8U), kInkThreshold);
            anyPoints = anyPoints || !skeletonTurned.empty();
            const auto view =
                inkgraph::bench::compareAcrossViews(skeleton, depthA, cameraA, skeletonTurned, turnedDepths[index],
                                                    turnedCameras[index], kTolerancePixels, options.depthTolerance);
            nlohmann::json entry = agreementJson(view.agreement);
            entry["dropped_a_to_turn"] = droppedJson(view.firstInSecond);
            entry["dropped_turn_to_a"] = droppedJson(view.secondInFirst);
            views[kTurns[index].name] = entry;
            if (!options.disagreement.empty() && std::abs(kTurns[index].tenths) != 50)
                inkgraph::writeImage(options.disagreement / (type + "-turn" + kTurns[index].name + ".png"),
                                     inkgraph::bench::disagreementPicture(layersA[type].size(), skeleton,
                                                                          view.secondInFirst.points, kTolerancePixels));
            byAngle[std::abs(kTurns[index].tenths)].push_back(view.agreement);
        }
        const double view1Min = inkgraph::bench::smallestF1(byAngle.at(10));
        const double view5Min = inkgraph::bench::smallestF1(byAngle.at(50));
        const double viewTenthMin = inkgraph::bench::smallestF1(byAngle.at(1));
        json["types"][type] = {{"f1_size",
                                {{"512_1024", agreementJson(size512To1024)},
                                 {"1024_2048", agreementJson(size1024To2048)},
                                 {"min", sizeMin}}},
                               {"f1_view", views},
                               {"f1_view_min_1deg", view1Min},
                               {"f1_view_min_5deg", view5Min},
                               {"f1_view_min_tenth_deg", viewTenthMin}};
        cellByType[type] = anyPoints
                               ? fixed(size512To1024.f1, 3) + ", " + fixed(size1024To2048.f1, 3) + " / " +
                                     fixed(view1Min, 3) + ", " + fixed(view5Min, 3) + ", " + fixed(viewTenthMin, 3)
                               : std::string("empty");
    }

    inkgraph::writeTextFile(options.json, json.dump(2) + "\n");

    if (options.header) {
        std::string header = "| model | look | ink % | ink outside % | SVG paths | % < 3 px | median path px |";
        std::string rule = "|---|---|---:|---:|---:|---:|---:|";
        for (const std::string& column : options.columns) {
            header += " " + column + " F1 512/1024, 1024/2048 / ±1°, ±5°, ±0.1° |";
            rule += "---|";
        }
        std::cout << header << "\n" << rule << "\n";
    }
    std::string row = "| " + options.model.filename().string() + " | " + options.look + " | " +
                      fixed(100.0 * ink.insideShare, 1) + " | " + fixed(100.0 * ink.outsideShare, 1) + " | " +
                      std::to_string(paths.pathCount) + " | " + fixed(100.0 * paths.shortShare, 1) + " | " +
                      fixed(paths.medianLength, 1) + " |";
    for (const std::string& column : options.columns) {
        const auto found = cellByType.find(column);
        row.append(" ").append(found == cellByType.end() ? "–" : found->second).append(" |");
    }
    std::cout << row << "\n";
    for (const std::string& type : types)
        if (std::find(options.columns.begin(), options.columns.end(), type) == options.columns.end())
            std::cerr << "inkgraph_line_cleanliness: line type '" << type
                      << "' has no table column (see --columns); its numbers are in the JSON\n";
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
        std::cout << kHelp;
        return 0;
    }
    int exitCode = 0;
    try {
        exitCode = measure(parseOptions(argc, argv));
    } catch (const UsageError& error) {
        std::cerr << "inkgraph_line_cleanliness: " << error.what() << "\n(see: inkgraph_line_cleanliness --help)\n";
        exitCode = 2;
    } catch (const std::exception& error) {
        std::cerr << "inkgraph_line_cleanliness: " << error.what() << "\n";
        exitCode = 1;
    }
    // The end every inkgraph process shares (render/BackgroundThreads.h).
    inkgraph::finishProcess();
    return exitCode;
}
