/** @file The MToon conformance suite (tests/conformance/README.md): every case generate-cases.py writes, rendered by
 *  the executable in the suite's scene and scored with rgbHybridCompare() against three-vrm's reference picture.
 *  Each picture must reach its threshold (thresholds.txt: what the renderer scored when it was set, less a margin),
 *  and the mean the file's mean; the table of scores goes to the test's output and to
 *  <build>/test-output/MToonConformance/scores.md, beside the renders and the difference pictures. */

#include "render/ImageFiles.h"
#include "tests/app/CliTestSupport.h"
#include "tests/conformance/ConformanceImages.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace inkgraph::test {
namespace {

namespace fs = std::filesystem;

const fs::path kSuite = fs::path(INKGRAPH_SOURCE_ROOT) / "tests" / "conformance";
const fs::path kReferences = kSuite / "reference" / "pictures";
const fs::path kCases = INKGRAPH_CONFORMANCE_CASES;
const fs::path kOutput = fs::path(INKGRAPH_BINARY_ROOT) / "test-output" / "MToonConformance";

// The suite's scene (README.md, "The scene"), as the reference page sets it up in three.js.
const std::map<std::string, std::string> kEyes = {{"front", "0,1.4,1.5"}, {"back", "0,1.4,-1.5"}};
// three.js' ambient light (0.3 at intensity 0.5) is irradiance 0.15; MToon's indirect term is irradiance / pi x the
// lit colour, which --ambient states directly.
constexpr const char* kAmbient = "0.0477465,0.0477465,0.0477465";

struct Picture {
    std::string name; ///< "<case>-<view>", the reference's file name without .png
    std::string file;
    std::string view;
    double time = 0.0;
};

std::vector<Picture> readCases() {
    const auto listing = nlohmann::json::parse(readText(kCases / "cases.json"));
    std::vector<Picture> pictures;
    for (const auto& entry : listing.at("cases"))
        for (const auto& view : entry.at("views"))
            pictures.push_back({entry.at("name").get<std::string>() + "-" + view.get<std::string>(),
                                entry.at("file").get<std::string>(), view.get<std::string>(),
                                entry.at("time").get<double>()});
    return pictures;
}

/** thresholds.txt: "<picture> <threshold>" per line, "mean <threshold>" once; # comments. */
std::map<std::string, double> readThresholds() {
    std::ifstream file(kSuite / "thresholds.txt");
    std::map<std::string, double> thresholds;
    std::string line;
    while (std::getline(file, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream fields(line);
        std::string name;
        double threshold = 0.0;
        if (fields >> name >> threshold) thresholds[name] = threshold;
    }
    return thresholds;
}

/** The executable scored: this build's, or INKGRAPH_CONFORMANCE_EXECUTABLE's (another build's, to score a branch
 *  without building this test there). */
std::string executable() {
    const char* other = std::getenv("INKGRAPH_CONFORMANCE_EXECUTABLE");
    return other != nullptr && *other != '\0' ? other : INKGRAPH_EXECUTABLE;
}

struct InkgraphRun {
    int exitCode = -1;
    std::string err;
};

InkgraphRun runInkgraph(const std::string& arguments) {
    const fs::path errFile = kOutput / "stderr.txt";
    const std::string command = "env LP_NUM_THREADS=1 " + shellQuoted(executable()) + " " + arguments +
                                " > /dev/null 2> '" + errFile.string() + "' < /dev/null";
    double peakMib = 0.0;
    const int status = runShell(command, peakMib);
    InkgraphRun run;
    run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    run.err = readText(errFile);
    fs::remove(errFile);
    return run;
}

TEST(MToonConformance, EveryCaseScoresAtLeastItsThreshold) {
    // The references were rendered from exactly these files: a generator changed without new references fails here.
    ASSERT_EQ(readText(kCases / "cases.sha256"), readText(kReferences / "cases.sha256"))
        << "generate-cases.py writes other files than those reference/pictures/ was rendered from: run "
           "tests/conformance/reference/render-references.sh";
    const std::vector<Picture> pictures = readCases();
    const std::map<std::string, double> thresholds = readThresholds();
    fs::remove_all(kOutput);
    fs::create_directories(kOutput / "renders");
    fs::create_directories(kOutput / "differences");

    // The reference's scene: its camera, light and ambient term, 4x multisampling.
    const std::string common = "render --shading mtoon --size 512x512 --target 0,1.4,0 --fov 30 --light 0.3,0.6,0.7 "
                               "--background 1,1,1 --lines none -q --ambient " +
                               std::string(kAmbient) + " --msaa 4";
    std::vector<std::string> notes;

    // One process per view and time: a batch shares the context and the compiled programs.
    std::map<std::pair<std::string, double>, std::vector<const Picture*>> batches;
    for (const Picture& picture : pictures) batches[{picture.view, picture.time}].push_back(&picture);
    for (const auto& [key, members] : batches) {
        const auto& [view, time] = key;
        const fs::path list = kOutput / ("list-" + view + "-" + std::to_string(time) + ".txt");
        {
            std::ofstream out(list);
            for (const Picture* picture : members) out << (kCases / picture->file).string() << "\n";
        }
        std::string arguments = common + " --eye " + kEyes.at(view) + " --list " + shellQuoted(list) + " -o " +
                                shellQuoted(kOutput / "renders" / ("{name}-" + view + ".png"));
        if (time > 0.0) {
            std::ostringstream timeFlag;
            timeFlag << " --time " << time; // MToon's UV animation clock
            arguments += timeFlag.str();
        }
        const InkgraphRun run = runInkgraph(arguments);
        ASSERT_EQ(run.exitCode, 0) << run.err;
    }

    std::ostringstream table;
    // The mean difference beside the score: the score mostly measures luma structure and hardly moves with a flat
    // change of colour (ReferencePicturesTest.cpp), which this shows.
    table << "| picture | score | threshold | mean abs difference (8-bit sRGB) |\n|---|---|---|---|\n";
    double sum = 0.0;
    int belowGoal = 0;
    for (const Picture& picture : pictures) {
        const cv::Mat rendered = readRgb8(kOutput / "renders" / (picture.name + ".png"));
        const cv::Mat reference = readRgb8(kReferences / (picture.name + ".png"));
        const HybridSimilarity similarity = rgbHybridCompare(rendered, reference);
        writeImage(kOutput / "differences" / (picture.name + ".png"), differencePicture(similarity));
        sum += similarity.score;
        belowGoal += similarity.score < 0.95 ? 1 : 0;
        const auto threshold = thresholds.find(picture.name);
        table << "| " << picture.name << " | " << std::fixed << std::setprecision(4) << similarity.score << " | "
              << (threshold == thresholds.end() ? std::string("none") : std::to_string(threshold->second).substr(0, 6))
              << " | " << std::setprecision(2)
              << cv::norm(rendered, reference, cv::NORM_L1) / double(rendered.total() * 3) << " |\n";
        if (threshold == thresholds.end()) {
            ADD_FAILURE() << picture.name << ": no threshold in tests/conformance/thresholds.txt (scored "
                          << similarity.score << ")";
            continue;
        }
        EXPECT_GE(similarity.score, threshold->second)
            << picture.name << ": " << similarity.score << " against three-vrm's picture, below its threshold; see "
            << (kOutput / "renders" / (picture.name + ".png")).string() << " and its difference picture";
    }
    const double mean = sum / double(pictures.size());
    table << "\nmean " << std::fixed << std::setprecision(4) << mean << " over " << pictures.size() << " pictures; "
          << belowGoal << " below the goal of 0.95 (goal: every picture >= 0.95, mean >= 0.99)\n";
    if (executable() != INKGRAPH_EXECUTABLE) notes.push_back("scored " + executable());
    for (const std::string& note : notes) table << "note: " << note << "\n";
    std::cout << table.str();
    std::ofstream(kOutput / "scores.md") << table.str();
    ASSERT_TRUE(thresholds.count("mean")) << "tests/conformance/thresholds.txt has no 'mean' line";
    EXPECT_GE(mean, thresholds.at("mean"));
}

} // namespace
} // namespace inkgraph::test
