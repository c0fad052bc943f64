// The speed/accuracy sweep end to end (bench/Tradeoff.h, --quick: 128-256 px, few settings): every row renders
// through the CLI's graph and is scored against analytic lines. Asserts accuracies, not times.
#include "bench/Tradeoff.h"
#include "tests/support/GlTestContext.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <algorithm>
#include <sstream>
#include <string>

namespace inkgraph::bench {
namespace {

const TradeoffRow& rowOf(const std::vector<TradeoffRow>& rows, const std::string& method, const std::string& setting) {
    const auto found = std::find_if(rows.begin(), rows.end(), [&](const TradeoffRow& row) {
        return row.method == method && row.setting == setting;
    });
    if (found == rows.end()) throw std::runtime_error("no row '" + method + " | " + setting + "'");
    return *found;
}

class TradeoffSweep : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        test::sharedGlContext();
        TradeoffConfig config;
        config.quick = true;
        config.repetitions = 1;
        std::ostringstream progress;
        rows = new std::vector<TradeoffRow>(runTradeoffSweep(config, progress));
        std::cout << progress.str();
    }
    static void TearDownTestSuite() {
        delete rows;
        rows = nullptr;
    }
    static std::vector<TradeoffRow>* rows;
};
std::vector<TradeoffRow>* TradeoffSweep::rows = nullptr;

TEST_F(TradeoffSweep, EveryRowIsTimedAndScored) {
    ASSERT_GE(rows->size(), 20u);
    for (const TradeoffRow& row : *rows) {
        EXPECT_GT(row.frameMilliseconds, 0.0) << row.method << " " << row.setting;
        EXPECT_GT(row.methodMilliseconds, 0.0) << row.method << " " << row.setting;
        EXPECT_LE(row.methodMilliseconds, row.frameMilliseconds * 1.0001) << row.method << " " << row.setting;
        EXPECT_GE(row.accuracy.f1, 0.0);
        EXPECT_LE(row.accuracy.f1, 1.0);
        EXPECT_GT(row.accuracy.predictedCount, 0u) << row.method << " " << row.setting << " found no line";
    }
}

TEST_F(TradeoffSweep, AccuraciesMatchWhatTheKernelTestsMeasure) {
    // The GL pipeline keeps the kernels' accuracy (tests/postfx measured F1 1.0 for contours, 0.99 for suggestive
    // contours on ray-cast buffers at 512^2); a wrong camera, a half-pixel shift or a y flip drops F1 toward 0.
    EXPECT_GE(rowOf(*rows, "contour", "256 S1 float").accuracy.f1, 0.98);
    EXPECT_GE(rowOf(*rows, "contour", "256 S2 float").accuracy.f1, 0.98);
    // --post-stage gpu finds the same points within 1e-3 px: the same scores.
    for (const std::string setting : {"128 S1 float", "256 S1 float", "256 S2 float"}) {
        const TradeoffRow& cpu = rowOf(*rows, "contour", setting);
        const TradeoffRow& gpu = rowOf(*rows, "contour", setting + " gpu");
        EXPECT_EQ(gpu.accuracy.predictedCount, cpu.accuracy.predictedCount) << setting;
        EXPECT_NEAR(gpu.accuracy.f1, cpu.accuracy.f1, 1e-9) << setting;
        EXPECT_NEAR(gpu.accuracy.predictedToTruthP95, cpu.accuracy.predictedToTruthP95, 1e-3) << setting;
    }
    EXPECT_GE(rowOf(*rows, "contour (sphere)", "256 128 segments").accuracy.f1, 0.98);
    EXPECT_GE(rowOf(*rows, "mesh-silhouette", "256 128 segments").accuracy.f1, 0.98);
    // A 32-segment sphere lies inside its circle by up to R(1 - cos(pi/32)) ~ 0.25 px here: still mostly within 1 px.
    EXPECT_GE(rowOf(*rows, "mesh-silhouette", "256 32 segments").accuracy.f1, 0.85);

    const TradeoffRow& suggestive = rowOf(*rows, "suggestive", "256 S1 float 3-point T0.01");
    const TradeoffRow& supersampled = rowOf(*rows, "suggestive", "256 S2 float 3-point T0.01");
    EXPECT_GE(suggestive.accuracy.precision, 0.97);
    EXPECT_GE(suggestive.accuracy.f1, 0.9);
    // Supersampling finds the lines closer to the silhouette, where one pixel of surface is too little at 1x.
    EXPECT_GT(supersampled.accuracy.recall, suggestive.accuracy.recall);
    // float16 buffers cost accuracy, never gain it (to within the rounding of one row).
    EXPECT_LE(rowOf(*rows, "suggestive", "256 S1 half 3-point T0.01").accuracy.f1, suggestive.accuracy.f1 + 0.005);

    // Object space on a mesh as fine as the image-space row's: as close to the analytic lines, in other ways (it
    // follows the mesh's curvature estimate, not the G-buffer), and its curvature is derived once, on the first frame.
    const TradeoffRow& object = rowOf(*rows, "suggestive-object", "256 S1 T0.01 66k tris");
    EXPECT_GE(object.accuracy.f1, 0.95);
    EXPECT_GT(object.setupMilliseconds, 0.0);
    EXPECT_EQ(suggestive.setupMilliseconds, 0.0);

    // Comic shading: the exact mode is the reference (F1 1); the constant view vector moves the highlight bands.
    EXPECT_DOUBLE_EQ(rowOf(*rows, "comic", "exact view, standard").accuracy.f1, 1.0);
    EXPECT_LT(rowOf(*rows, "comic", "constant view, standard").accuracy.f1, 0.95);
}

TEST_F(TradeoffSweep, WritesOneCsvLineAndOneTableRowPerRow) {
    const std::string csv = tradeoffCsv(*rows);
    EXPECT_EQ(std::size_t(std::count(csv.begin(), csv.end(), '\n')), rows->size() + 1);
    EXPECT_EQ(csv.rfind("method,setting,scene,size,supersample,triangles,frame_ms,", 0), 0u);
    const std::string table = tradeoffMarkdown(*rows, 1.0);
    EXPECT_EQ(std::size_t(std::count(table.begin(), table.end(), '\n')), rows->size() + 2);
    const cv::Mat plot = tradeoffPlot(*rows, 1.0);
    EXPECT_EQ(plot.type(), CV_8UC3);
    // Axes, grids, points and labels: a few percent of the pixels are not paper white.
    cv::Mat white;
    cv::inRange(plot, cv::Scalar(255, 255, 255), cv::Scalar(255, 255, 255), white);
    const double drawn = 1.0 - double(cv::countNonZero(white)) / double(plot.total());
    EXPECT_GT(drawn, 0.02);
}

} // namespace
} // namespace inkgraph::bench
