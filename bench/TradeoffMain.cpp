// inkgraph_tradeoff: the speed/accuracy sweep of bench/Tradeoff.h, written as a CSV, a markdown table and a plot.
#include "render/BackgroundThreads.h"
#include "render/ImageFiles.h"
#include "bench/Tradeoff.h"

#include <opencv2/imgproc.hpp>

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

namespace {

constexpr const char* kHelp = R"(Usage: inkgraph_tradeoff --out DIR [--quick] [--repetitions N] [--tolerance PX]

Renders every line method of inkgraph at a range of settings (resolution, supersampling, float16 against float32
G-buffers, 3- against 5-point differences, thresholds, image- against object-space suggestive contours, comic
shading's view-vector and face-orientation modes), times each warm (median of N runs after a warm-up) and scores its
lines against analytic ground truth: precision, recall and F1 within PX pixels (default 1), 95th-percentile and
largest distances. Writes DIR/tradeoff.csv, DIR/tradeoff.md and DIR/tradeoff.png (milliseconds against F1).

  --out DIR          where the three files go (created if missing; files there of the same names are replaced)
  --quick            small images and few settings (about a minute): a smoke run
  --repetitions N    timed runs per setting, 1 to 100 (default 5)
  --tolerance PX     the F1 tolerance in output pixels, above 0 up to 10 (default 1)
  --only contour     only the torus's contour rows (CPU and --post-stage gpu), to regenerate those

Run it on a quiet machine; LP_NUM_THREADS sets llvmpipe's threads. docs/accuracy.md explains the results.
)";

int usage(const std::string& message) {
    std::cerr << "inkgraph_tradeoff: " << message << "\n(see: inkgraph_tradeoff --help)\n";
    return 2;
}

} // namespace

int main(int argc, char** argv) {
    inkgraph::bench::TradeoffConfig config;
    std::filesystem::path out;
    for (int i = 1; i < argc; ++i) {
        const std::string argument = argv[i];
        const bool hasValue = i + 1 < argc;
        if (argument == "--help" || argument == "-h") {
            std::cout << kHelp;
            return 0;
        } else if (argument == "--quick") {
            config.quick = true;
        } else if (argument == "--only" && hasValue) {
            config.onlyMethod = argv[++i];
            if (config.onlyMethod != "contour")
                return usage("--only: the one method that can run alone is 'contour', got '" + config.onlyMethod + "'");
        } else if (argument == "--out" && hasValue) {
            out = argv[++i];
        } else if (argument == "--repetitions" && hasValue) {
            char* end = nullptr;
            const long repetitions = std::strtol(argv[++i], &end, 10);
            if (*end != '\0' || repetitions < 1 || repetitions > 100)
                return usage("--repetitions: expected a whole number from 1 to 100, got '" + std::string(argv[i]) +
                             "'");
            config.repetitions = int(repetitions);
        } else if (argument == "--tolerance" && hasValue) {
            char* end = nullptr;
            const double tolerance = std::strtod(argv[++i], &end);
            if (*end != '\0' || !(tolerance > 0.0 && tolerance <= 10.0))
                return usage("--tolerance: expected pixels above 0 up to 10, got '" + std::string(argv[i]) + "'");
            config.tolerancePixels = tolerance;
        } else if (argument == "--out" || argument == "--repetitions" || argument == "--tolerance") {
            return usage(argument + " needs a value");
        } else {
            return usage("unknown argument '" + argument + "'");
        }
    }
    if (out.empty()) return usage("--out DIR is required");
    int exitCode = 0;
    try {
        std::filesystem::create_directories(out);
        const auto rows = inkgraph::bench::runTradeoffSweep(config, std::cout);
        inkgraph::writeTextFile(out / "tradeoff.csv", inkgraph::bench::tradeoffCsv(rows));
        inkgraph::writeTextFile(out / "tradeoff.md", inkgraph::bench::tradeoffMarkdown(rows, config.tolerancePixels));
        cv::Mat rgba;
        cv::cvtColor(inkgraph::bench::tradeoffPlot(rows, config.tolerancePixels), rgba, cv::COLOR_BGR2RGBA);
        inkgraph::writeImage(out / "tradeoff.png", rgba);
        std::cout << "wrote " << (out / "tradeoff.csv").string() << ", tradeoff.md, tradeoff.png\n";
    } catch (const std::exception& error) {
        std::cerr << "inkgraph_tradeoff: " << error.what() << "\n";
        exitCode = 1;
    }
    // The end every inkgraph process shares (render/BackgroundThreads.h).
    inkgraph::finishProcess();
    return exitCode;
}
