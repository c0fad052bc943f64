// postfx/LineMetrics on hand-made lines whose scores are known exactly; no GL.
#include "postfx/LineMetrics.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

/** Points every `spacing` px along y = `y` from x0 to x1 inclusive. */
std::vector<cv::Point2d> pointsAlong(double x0, double x1, double y, double spacing) {
    std::vector<cv::Point2d> points;
    const int count = int(std::lround((x1 - x0) / spacing));
    for (int index = 0; index <= count; ++index) points.emplace_back(x0 + index * spacing, y);
    return points;
}

LinePolyline horizontalLine(double x0, double x1, double y) { return {{{x0, y}, {x1, y}}, false}; }

TEST(LineMetrics, IdenticalLinesScorePerfectly) {
    // The truth is sampled at the midpoints of 0.25 px pieces; points every 0.125 px hold every sample and vertex.
    const std::vector<LinePolyline> truth{horizontalLine(10.0, 110.0, 20.0)};
    const std::vector<cv::Point2d> predicted = pointsAlong(10.0, 110.0, 20.0, 0.125);
    const LineAccuracy accuracy = scoreLinePoints(predicted, truth, 1.0);
    EXPECT_EQ(accuracy.precision, 1.0);
    EXPECT_EQ(accuracy.recall, 1.0);
    EXPECT_EQ(accuracy.f1, 1.0);
    EXPECT_EQ(accuracy.predictedCount, predicted.size());
    EXPECT_EQ(accuracy.spuriousCount, 0u);
    EXPECT_NEAR(accuracy.truthLength, 100.0, 1e-12);
    EXPECT_NEAR(accuracy.truthLengthWithinTolerance, 100.0, 1e-9);
    EXPECT_EQ(accuracy.truthSampleCount, 400u + 2u); // 400 pieces and the two vertices
    EXPECT_LT(accuracy.hausdorff, 1e-12);
    EXPECT_LT(accuracy.chamferMean, 1e-12);
    EXPECT_LT(accuracy.predictedToTruthP95, 1e-12);
    EXPECT_LT(accuracy.truthToPredictedP95, 1e-12);

    // A closed polygon, scored on its own vertices, and the same masks.
    LinePolyline square{{{5, 5}, {25, 5}, {25, 25}, {5, 25}}, true};
    std::vector<cv::Point2d> squarePoints;
    for (int side = 0; side < 4; ++side)
        for (int step = 0; step < 160; ++step) {
            const cv::Point2d a = square.points[std::size_t(side)], b = square.points[std::size_t(side + 1) % 4];
            squarePoints.push_back(a + (step / 160.0) * (b - a));
        }
    const LineAccuracy squareAccuracy = scoreLinePoints(squarePoints, {square}, 0.5);
    EXPECT_NEAR(squareAccuracy.truthLength, 80.0, 1e-12);
    EXPECT_EQ(squareAccuracy.f1, 1.0);
    EXPECT_LT(squareAccuracy.predictedToTruthMax, 1e-12);

    cv::Mat mask = cv::Mat::zeros(40, 40, CV_8UC1);
    cv::rectangle(mask, {5, 5}, {25, 25}, cv::Scalar(255), 1);
    const LineAccuracy maskAccuracy = scoreLineMasks(mask, mask, 0.0);
    EXPECT_EQ(maskAccuracy.f1, 1.0);
    EXPECT_EQ(maskAccuracy.hausdorff, 0.0);
}

TEST(LineMetrics, ShiftedLineScoresByTolerance) {
    const std::vector<LinePolyline> truth{horizontalLine(10.0, 110.0, 20.0)};
    const std::vector<cv::Point2d> predicted = pointsAlong(10.0, 110.0, 20.6, 0.125);
    const LineAccuracy loose = scoreLinePoints(predicted, truth, 1.0);
    EXPECT_EQ(loose.precision, 1.0);
    EXPECT_EQ(loose.recall, 1.0);
    EXPECT_EQ(loose.f1, 1.0);
    EXPECT_NEAR(loose.predictedToTruthP95, 0.6, 1e-12);
    EXPECT_NEAR(loose.truthToPredictedP95, 0.6, 1e-12);
    EXPECT_NEAR(loose.hausdorff, 0.6, 1e-12);
    EXPECT_NEAR(loose.chamferMean, 0.6, 1e-12);
    const LineAccuracy tight = scoreLinePoints(predicted, truth, 0.5);
    EXPECT_EQ(tight.precision, 0.0);
    EXPECT_EQ(tight.recall, 0.0);
    EXPECT_EQ(tight.f1, 0.0);
    EXPECT_EQ(tight.spuriousCount, predicted.size());
}

TEST(LineMetrics, RecallCountsTheTruthsLength) {
    // Half of a 1000 px line found: within k = 1 px the found half reaches 1 px past its end, so R = 501 / 1000.
    const std::vector<LinePolyline> truth{horizontalLine(0.0, 1000.0, 50.0)};
    const LineAccuracy accuracy = scoreLinePoints(pointsAlong(0.0, 500.0, 50.0, 0.5), truth, 1.0);
    EXPECT_EQ(accuracy.precision, 1.0);
    EXPECT_NEAR(accuracy.recall, 0.5, 0.005);
    EXPECT_NEAR(accuracy.truthLengthWithinTolerance, 501.0, 0.25);
    EXPECT_NEAR(accuracy.f1, 2.0 * 0.5 / 1.5, 0.005);
    EXPECT_NEAR(accuracy.truthToPredictedMax, 500.0, 1e-9); // the far end
    // The truth weighs by length, not by vertex: the same line split into 1000 vertices on its first half only.
    LinePolyline uneven{pointsAlong(0.0, 500.0, 50.0, 0.5), false};
    uneven.points.emplace_back(1000.0, 50.0);
    const LineAccuracy unevenAccuracy = scoreLinePoints(pointsAlong(0.0, 500.0, 50.0, 0.5), {uneven}, 1.0);
    EXPECT_NEAR(unevenAccuracy.recall, accuracy.recall, 1e-3);
}

TEST(LineMetrics, SpuriousSegmentLowersPrecisionByItsShare) {
    const std::vector<LinePolyline> truth{horizontalLine(0.0, 100.0, 10.0)};
    std::vector<cv::Point2d> predicted = pointsAlong(0.0, 100.0, 10.0, 0.5);      // 201 on the line
    const std::vector<cv::Point2d> spurious = pointsAlong(20.0, 69.5, 30.0, 0.5); // 100, 20 px away
    predicted.insert(predicted.end(), spurious.begin(), spurious.end());
    const LineAccuracy accuracy = scoreLinePoints(predicted, truth, 1.0);
    EXPECT_EQ(accuracy.spuriousCount, 100u);
    EXPECT_DOUBLE_EQ(accuracy.precision, 201.0 / 301.0);
    EXPECT_EQ(accuracy.recall, 1.0);
    EXPECT_NEAR(accuracy.predictedToTruthMax, 20.0, 1e-12);
    EXPECT_NEAR(accuracy.hausdorff, 20.0, 1e-12);
    // 100 of 301 at 20 px: the 95th percentile is 20, the mean 2000 / 301.
    EXPECT_NEAR(accuracy.predictedToTruthP95, 20.0, 1e-12);
    EXPECT_NEAR(accuracy.predictedToTruthMean, 2000.0 / 301.0, 1e-9);
}

TEST(LineMetrics, EmptyCasesAreDefined) {
    const std::vector<LinePolyline> truth{horizontalLine(0.0, 10.0, 0.0)};
    const std::vector<cv::Point2d> predicted = pointsAlong(0.0, 10.0, 0.0, 1.0);
    const double infinity = std::numeric_limits<double>::infinity();

    const LineAccuracy neither = scoreLinePoints({}, {}, 1.0);
    EXPECT_EQ(neither.precision, 1.0);
    EXPECT_EQ(neither.recall, 1.0);
    EXPECT_EQ(neither.f1, 1.0);
    EXPECT_EQ(neither.hausdorff, 0.0);
    EXPECT_EQ(neither.chamferMean, 0.0);
    // Polylines with no points are no truth.
    EXPECT_EQ(scoreLinePoints({}, {LinePolyline{}}, 1.0).f1, 1.0);

    const LineAccuracy onlyPredicted = scoreLinePoints(predicted, {}, 1.0);
    EXPECT_EQ(onlyPredicted.precision, 0.0);
    EXPECT_EQ(onlyPredicted.recall, 1.0);
    EXPECT_EQ(onlyPredicted.f1, 0.0);
    EXPECT_EQ(onlyPredicted.spuriousCount, predicted.size());
    EXPECT_EQ(onlyPredicted.predictedToTruthMax, infinity);
    EXPECT_EQ(onlyPredicted.truthToPredictedMax, 0.0);
    EXPECT_EQ(onlyPredicted.hausdorff, infinity);
    EXPECT_EQ(onlyPredicted.chamferMean, infinity);

    const LineAccuracy onlyTruth = scoreLinePoints({}, truth, 1.0);
    EXPECT_EQ(onlyTruth.precision, 1.0);
    EXPECT_EQ(onlyTruth.recall, 0.0);
    EXPECT_EQ(onlyTruth.f1, 0.0);
    EXPECT_EQ(onlyTruth.truthLength, 10.0);
    EXPECT_EQ(onlyTruth.truthToPredictedMax, infinity);
    EXPECT_EQ(onlyTruth.truthToPredictedMean, infinity);
    EXPECT_EQ(onlyTruth.predictedToTruthMax, 0.0);
    EXPECT_EQ(onlyTruth.hausdorff, infinity);

    // Truth of isolated points (length 0): recall by count.
    const std::vector<LinePolyline> dots{{{{0.0, 0.0}}, false}, {{{50.0, 0.0}}, false}};
    const LineAccuracy dotAccuracy = scoreLinePoints({{0.3, 0.0}}, dots, 1.0);
    EXPECT_EQ(dotAccuracy.truthLength, 0.0);
    EXPECT_EQ(dotAccuracy.precision, 1.0);
    EXPECT_EQ(dotAccuracy.recall, 0.5);

    // The same rules for masks.
    const cv::Mat blank = cv::Mat::zeros(20, 20, CV_8UC1);
    cv::Mat line = blank.clone();
    cv::line(line, {2, 10}, {17, 10}, cv::Scalar(255));
    EXPECT_EQ(scoreLineMasks(blank, blank, 1.0).f1, 1.0);
    const LineAccuracy maskOnlyPredicted = scoreLineMasks(line, blank, 1.0);
    EXPECT_EQ(maskOnlyPredicted.precision, 0.0);
    EXPECT_EQ(maskOnlyPredicted.recall, 1.0);
    EXPECT_EQ(maskOnlyPredicted.spuriousCount, 16u);
    const LineAccuracy maskOnlyTruth = scoreLineMasks(blank, line, 1.0);
    EXPECT_EQ(maskOnlyTruth.precision, 1.0);
    EXPECT_EQ(maskOnlyTruth.recall, 0.0);
    EXPECT_EQ(maskOnlyTruth.hausdorff, infinity);
}

TEST(LineMetrics, GridSearchMatchesBruteForce) {
    // Random zig-zag truth with vertices < 0.25 px apart (so its samples are its vertices and segment midpoints) and
    // random points, some far outside the truth's box: every distance equals the brute-force one.
    std::mt19937 random(7);
    std::uniform_real_distribution<double> coordinate(-40.0, 240.0);
    std::uniform_real_distribution<double> step(-0.17, 0.17);
    std::vector<LinePolyline> truth;
    for (int line = 0; line < 6; ++line) {
        LinePolyline polyline;
        cv::Point2d p(coordinate(random) * 0.5 + 50.0, coordinate(random) * 0.5 + 50.0);
        for (int index = 0; index < 300; ++index) {
            polyline.points.push_back(p);
            p += cv::Point2d(std::abs(step(random)) * 0.7 + 0.01, step(random));
        }
        truth.push_back(polyline);
    }
    std::vector<cv::Point2d> predicted;
    for (int index = 0; index < 500; ++index) predicted.emplace_back(coordinate(random), coordinate(random));
    predicted.emplace_back(5000.0, -3000.0);

    auto segmentDistance = [](const cv::Point2d& p, const cv::Point2d& a, const cv::Point2d& b) {
        const cv::Point2d along = b - a;
        const double t = std::clamp((p - a).dot(along) / along.dot(along), 0.0, 1.0);
        return cv::norm(p - (a + t * along));
    };
    double worstPredicted = 0.0, sumPredicted = 0.0;
    for (const cv::Point2d& p : predicted) {
        double best = std::numeric_limits<double>::infinity();
        for (const LinePolyline& polyline : truth)
            for (std::size_t index = 0; index + 1 < polyline.points.size(); ++index)
                best = std::min(best, segmentDistance(p, polyline.points[index], polyline.points[index + 1]));
        worstPredicted = std::max(worstPredicted, best);
        sumPredicted += best;
    }
    double worstTruth = 0.0;
    for (const LinePolyline& polyline : truth)
        for (std::size_t index = 0; index < polyline.points.size(); ++index) {
            std::vector<cv::Point2d> samples{polyline.points[index]};
            if (index + 1 < polyline.points.size())
                samples.push_back(0.5 * (polyline.points[index] + polyline.points[index + 1]));
            for (const cv::Point2d& q : samples) {
                double best = std::numeric_limits<double>::infinity();
                for (const cv::Point2d& p : predicted) best = std::min(best, cv::norm(p - q));
                worstTruth = std::max(worstTruth, best);
            }
        }
    const LineAccuracy accuracy = scoreLinePoints(predicted, truth, 2.0);
    EXPECT_NEAR(accuracy.predictedToTruthMax, worstPredicted, 1e-9);
    EXPECT_NEAR(accuracy.predictedToTruthMean, sumPredicted / double(predicted.size()), 1e-9);
    EXPECT_NEAR(accuracy.truthToPredictedMax, worstTruth, 1e-9);
}

TEST(LineMetrics, ThinningLeavesOnePixelAlongTheMiddle) {
    cv::Mat bar = cv::Mat::zeros(60, 120, CV_8UC1);
    bar(cv::Rect(10, 28, 100, 5)).setTo(255); // rows 28..32, middle row 30
    const cv::Mat skeleton = thinLines(bar);
    ASSERT_EQ(skeleton.type(), CV_8UC1);
    ASSERT_EQ(skeleton.size(), bar.size());
    // Every column away from the ends holds exactly one pixel, on the middle row.
    for (int col = 14; col < 106; ++col) {
        EXPECT_EQ(cv::countNonZero(skeleton.col(col)), 1) << "column " << col;
        EXPECT_EQ(skeleton.at<uchar>(30, col), 255) << "column " << col;
    }
    // Nothing outside the bar; each end shortens by about half the width (measured: 95 of 100 left).
    EXPECT_EQ(cv::countNonZero(skeleton & ~bar), 0);
    EXPECT_GE(cv::countNonZero(skeleton), 94);
    EXPECT_LE(cv::countNonZero(skeleton), 100);

    // A one-pixel line stays (8-connected lines are already thin), and a thick ring thins to within a pixel of its
    // middle circle.
    cv::Mat line = cv::Mat::zeros(60, 120, CV_8UC1);
    cv::line(line, {5, 5}, {100, 50}, cv::Scalar(255), 1, cv::LINE_8);
    EXPECT_EQ(cv::countNonZero(thinLines(line) != line), 0);
    cv::Mat ring = cv::Mat::zeros(101, 101, CV_8UC1);
    cv::circle(ring, {50, 50}, 35, cv::Scalar(255), 5);
    std::vector<cv::Point> ringPixels;
    cv::findNonZero(thinLines(ring), ringPixels);
    ASSERT_GT(ringPixels.size(), 150u);
    for (const cv::Point& pixel : ringPixels) EXPECT_NEAR(std::hypot(pixel.x - 50, pixel.y - 50), 35.0, 1.0);
    // One pixel wide: no 2 x 2 block is left, and there are fewer pixels than a 4-connected circle's 8 r = 280
    // (measured 248: Zhang-Suen keeps some staircase corners an 8-connected circle, ~5.7 r, would not).
    cv::Mat thinRing = thinLines(ring);
    for (int row = 0; row + 1 < thinRing.rows; ++row)
        for (int col = 0; col + 1 < thinRing.cols; ++col)
            ASSERT_LT(cv::countNonZero(thinRing(cv::Rect(col, row, 2, 2))), 4) << col << "," << row;
    EXPECT_LT(ringPixels.size(), 8u * 35u);
}

TEST(LineMetrics, MasksAreThinnedBeforeScoring) {
    cv::Mat truth = cv::Mat::zeros(100, 200, CV_8UC1);
    cv::line(truth, {10, 50}, {190, 50}, cv::Scalar(255));
    cv::Mat thick = cv::Mat::zeros(100, 200, CV_8UC1);
    thick(cv::Rect(10, 48, 181, 5)).setTo(255); // rows 48..52 around the truth's row 50
    const LineAccuracy accuracy = scoreLineMasks(thick, truth, 1.0);
    // Thinned to the middle row: every skeleton pixel on the truth; the ends shorten by about 2 px each.
    EXPECT_EQ(accuracy.precision, 1.0);
    EXPECT_GT(accuracy.recall, 0.97);
    EXPECT_LE(accuracy.predictedCount, 181u);
    EXPECT_EQ(accuracy.truthSampleCount, 181u);
    EXPECT_EQ(accuracy.predictedToTruthMax, 0.0);
    // Without thinning 2 of the 5 rows would lie 2 px off: precision 3/5 at k = 1.
    const cv::Mat thinTruth = thinLines(truth);
    EXPECT_EQ(cv::countNonZero(thinTruth != truth), 0);

    // Distances come from the exact transform: a line 3 rows down is 3 px away, one 2 columns right of a vertical
    // line 2 px.
    cv::Mat shifted = cv::Mat::zeros(100, 200, CV_8UC1);
    cv::line(shifted, {10, 53}, {190, 53}, cv::Scalar(255));
    const LineAccuracy shiftedAccuracy = scoreLineMasks(shifted, truth, 2.5);
    EXPECT_EQ(shiftedAccuracy.precision, 0.0);
    EXPECT_NEAR(shiftedAccuracy.predictedToTruthP95, 3.0, 1e-5);
    EXPECT_EQ(scoreLineMasks(shifted, truth, 3.0).f1, 1.0);
}

TEST(LineMetrics, OutputPixelPositionsUndoTheSupersample) {
    LineSkeleton skeleton;
    skeleton.points = {{{1.5f, 3.5f}, 1.0f}, {{0.0f, 0.0f}, 0.5f}};
    const std::vector<cv::Point2d> output = outputPixelPositions(skeleton, 2);
    ASSERT_EQ(output.size(), 2u);
    EXPECT_EQ(output[0], cv::Point2d(0.5, 1.5));
    EXPECT_EQ(output[1], cv::Point2d(-0.25, -0.25)); // data pixel 0 of 2 lies left of the output pixel's centre
    EXPECT_EQ(outputPixelPositions(skeleton)[0], cv::Point2d(1.5, 3.5));
}

TEST(LineMetrics, RejectsWrongInputsNamingThem) {
    auto expectRejected = [](const std::function<void()>& call, const std::string& function,
                             const std::string& argument) {
        try {
            call();
            ADD_FAILURE() << function << " accepted a wrong '" << argument << "'";
        } catch (const std::invalid_argument& error) {
            const std::string message = error.what();
            EXPECT_EQ(message.rfind(function, 0), 0u) << message;
            EXPECT_NE(message.find("'" + argument + "'"), std::string::npos) << message;
        }
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<LinePolyline> truth{horizontalLine(0.0, 10.0, 0.0)};
    expectRejected([&] { scoreLinePoints({}, truth, -1.0); }, "scoreLinePoints()", "tolerancePixels");
    expectRejected([&] { scoreLinePoints({}, truth, nan); }, "scoreLinePoints()", "tolerancePixels");
    expectRejected([&] { scoreLinePoints({{nan, 1.0}}, truth, 1.0); }, "scoreLinePoints()", "predicted");
    expectRejected([&] { scoreLinePoints({}, {horizontalLine(0.0, INFINITY, 0.0)}, 1.0); }, "scoreLinePoints()",
                   "truth");
    const cv::Mat mask = cv::Mat::zeros(8, 8, CV_8UC1);
    expectRejected([&] { scoreLineMasks(cv::Mat(8, 8, CV_32FC1), mask, 1.0); }, "scoreLineMasks()", "predicted");
    expectRejected([&] { scoreLineMasks(mask, cv::Mat(), 1.0); }, "scoreLineMasks()", "truth");
    expectRejected([&] { scoreLineMasks(mask, cv::Mat::zeros(8, 9, CV_8UC1), 1.0); }, "scoreLineMasks()", "truth");
    expectRejected([&] { scoreLineMasks(mask, mask, INFINITY); }, "scoreLineMasks()", "tolerancePixels");
    expectRejected([&] { thinLines(cv::Mat(8, 8, CV_8UC3)); }, "thinLines()", "mask");
    expectRejected([&] { outputPixelPositions(LineSkeleton{}, 0); }, "outputPixelPositions()", "supersample");
}

} // namespace
} // namespace inkgraph
