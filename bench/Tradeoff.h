#pragma once
/** @file The speed/accuracy trade, swept (issue 5; docs/accuracy.md): each line method renders through the CLI's
 *  own graph (the same flags, passes and kernels), warm, and its lines are scored against analytic ground truth
 *  (tests/support/AnalyticLines.h) with postfx/LineMetrics.h. The shading approximations (constant view vector,
 *  CPU face orientation) are scored by their shade-band boundaries against the exact mode's.
 *
 *  Scenes: a torus R = 1, r = 0.4 (512 x 256 segments, 262,144 triangles unless a row says otherwise) seen from 30
 *  degrees above its plane at distance 5, and unit UV spheres at distance 4 of 32 to 512 segments; field of view 35
 *  degrees. */

#include "postfx/LineMetrics.h"

#include <opencv2/core.hpp>

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

namespace inkgraph::bench {

/** One method at one setting: its median cost and its accuracy. */
struct TradeoffRow {
    std::string method;  ///< the series: "contour", "suggestive", "suggestive-object", "mesh-silhouette", "comic"
    std::string setting; ///< what varies, e.g. "1024 S2 half 5-point T0.01"; " gpu": --post-stage gpu
    std::string scene;   ///< "torus 262k", "sphere 128"
    int size = 0;        ///< output side in pixels
    int supersample = 1;
    std::size_t triangles = 0;
    /** Median over the repetitions of the whole graph's execute() (G-buffer or shading, readback, kernel, stroke,
     *  composite), warm: programs built and meshes uploaded once, as in a batch. */
    double frameMilliseconds = 0.0;
    double methodMilliseconds = 0.0; ///< median of the method's own passes (G-buffer + its line layer, or shade)
    double setupMilliseconds = 0.0;  ///< one-off derived data of the first frame (object-space curvature), else 0
    LineAccuracy accuracy;           ///< at TradeoffConfig::tolerancePixels
    double f1AtTwoPixels = 0.0;      ///< F1 at 2 px, for methods whose lines are offset by design
};

struct TradeoffConfig {
    bool quick = false;           ///< small sizes and few settings: for the test that runs the sweep end to end
    int repetitions = 5;          ///< timed runs per row after one warm-up; the median is reported
    double tolerancePixels = 1.0; ///< k of precision, recall and F1
    /** Run only the rows of this method ("contour": the torus's contour rows, CPU and GPU); empty: every row. */
    std::string onlyMethod;
};

/** Runs every row; `progress` gets one line per row. Needs a GL context (it creates the shared one). */
std::vector<TradeoffRow> runTradeoffSweep(const TradeoffConfig& config, std::ostream& progress);

/** One line per row with a header; numbers in full precision. */
std::string tradeoffCsv(const std::vector<TradeoffRow>& rows);
/** A markdown table: method, setting, scene, ms (frame, method, setup), P, R, F1 at k, F1 at 2 px, p95 and max
 *  distances both ways. */
std::string tradeoffMarkdown(const std::vector<TradeoffRow>& rows, double tolerancePixels);
/** Milliseconds (log scale) against F1, one colour per method, each point labelled with its setting: CV_8UC3. */
cv::Mat tradeoffPlot(const std::vector<TradeoffRow>& rows, double tolerancePixels);

} // namespace inkgraph::bench
