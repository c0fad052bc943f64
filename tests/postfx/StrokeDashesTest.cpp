// postfx/StrokeDashes on strokes of known shape; no GL. Expected dashes follow from the pattern along the arc length:
// where each begins and ends (exactly: the cut points are placed on the pattern's boundaries), how many there are,
// the pattern running on through corners and round a closed stroke's seam, and the raster and the SVG polylines made
// from the same dashes.
#include "postfx/StrokeDashes.h"

#include "tests/support/ThrowMessage.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::invalidArgumentMessage;

/** A kept stroke through `corners`, with a point every pixel along each side (and at each corner), on layer 0. */
Stroke strokeThrough(const std::vector<cv::Point2f>& corners, bool closed) {
    Stroke stroke;
    stroke.kept = true;
    stroke.closed = closed;
    const std::size_t sides = closed ? corners.size() : corners.size() - 1;
    for (std::size_t side = 0; side < sides; ++side) {
        const cv::Point2f a = corners[side], b = corners[(side + 1) % corners.size()];
        const int steps = int(std::lround(cv::norm(b - a)));
        for (int step = 0; step < steps; ++step) {
            LinePoint point;
            point.position = a + (b - a) * (float(step) / float(steps));
            stroke.points.push_back(point);
            stroke.pixels.emplace_back(int(std::lround(point.position.x)), int(std::lround(point.position.y)));
        }
    }
    if (!closed) {
        LinePoint last;
        last.position = corners.back();
        stroke.points.push_back(last);
        stroke.pixels.emplace_back(int(std::lround(last.position.x)), int(std::lround(last.position.y)));
    }
    double length = 0.0;
    for (std::size_t index = 1; index < stroke.points.size(); ++index)
        length += cv::norm(stroke.points[index].position - stroke.points[index - 1].position);
    if (closed) length += cv::norm(stroke.points.front().position - stroke.points.back().position);
    stroke.lengthPixels = length;
    return stroke;
}

double polylineLength(const std::vector<LinePoint>& points) {
    double length = 0.0;
    for (std::size_t index = 1; index < points.size(); ++index)
        length += cv::norm(points[index].position - points[index - 1].position);
    return length;
}

TEST(StrokeDashesTest, AStraightStrokeIsCutIntoDashesOfTheExactLengths) {
    Strokes strokes;
    strokes.strokes.push_back(strokeThrough({{10.0f, 20.0f}, {110.0f, 20.0f}}, false)); // 100 px
    EXPECT_EQ(dashStrokes(strokes, 0, {6.0, 4.0}), 10u);
    ASSERT_EQ(strokes.strokes.size(), 10u);
    for (std::size_t index = 0; index < strokes.strokes.size(); ++index) {
        SCOPED_TRACE(index);
        const Stroke& dash = strokes.strokes[index];
        EXPECT_TRUE(dash.kept);
        EXPECT_FALSE(dash.closed);
        EXPECT_EQ(dash.layer, 0);
        EXPECT_EQ(dash.points.size(), dash.pixels.size());
        // Dash k covers [10k, 10k + 6] along the stroke: exact, not to the nearest point.
        EXPECT_NEAR(dash.points.front().position.x, 10.0 + 10.0 * double(index), 1e-4);
        EXPECT_NEAR(dash.points.back().position.x, 16.0 + 10.0 * double(index), 1e-4);
        EXPECT_NEAR(dash.lengthPixels, 6.0, 1e-4);
        if (index > 0) { // the gap before it: 4 px
            EXPECT_NEAR(dash.points.front().position.x - strokes.strokes[index - 1].points.back().position.x, 4.0,
                        1e-4);
        }
    }
}

TEST(StrokeDashesTest, ThePatternRunsOnThroughPointsAndCorners) {
    // An L: 13 px down, then 17 px right (30 px). Dashes 6 on, 4 off: [0, 6], [10, 16] round the corner at 13, [20,
    // 26].
    Strokes strokes;
    strokes.strokes.push_back(strokeThrough({{5.0f, 5.0f}, {5.0f, 18.0f}, {22.0f, 18.0f}}, false));
    EXPECT_EQ(dashStrokes(strokes, 0, {6.0, 4.0}), 3u);
    ASSERT_EQ(strokes.strokes.size(), 3u);
    for (const Stroke& dash : strokes.strokes) {
        EXPECT_NEAR(dash.lengthPixels, 6.0, 1e-4);
        EXPECT_NEAR(polylineLength(dash.points), 6.0, 1e-4);
    }
    EXPECT_NEAR(strokes.strokes[1].points.front().position.y, 15.0, 1e-4); // s = 10: 10 px down
    EXPECT_NEAR(strokes.strokes[1].points.back().position.x, 8.0, 1e-4);   // s = 16: 3 px past the corner
    EXPECT_NEAR(strokes.strokes[2].points.front().position.x, 12.0, 1e-4); // s = 20
    EXPECT_NEAR(strokes.strokes[2].points.back().position.x, 18.0, 1e-4);  // s = 26
    // The corner point is in the middle dash, between its cut ends.
    bool corner = false;
    for (const LinePoint& point : strokes.strokes[1].points)
        corner = corner || (point.position == cv::Point2f(5.0f, 18.0f));
    EXPECT_TRUE(corner);
}

TEST(StrokeDashesTest, AClosedStrokesLastDashRunsOnIntoTheFirstAcrossTheSeam) {
    // A square of side 23 (92 px round), dashes 6 on, 4 off from its first corner: [0, 6] ... [80, 86], and the tenth,
    // [90, 92], reaches the seam while drawn and runs on into the first: 9 dashes, one of them 8 px.
    Strokes strokes;
    strokes.strokes.push_back(strokeThrough({{10.0f, 10.0f}, {33.0f, 10.0f}, {33.0f, 33.0f}, {10.0f, 33.0f}}, true));
    ASSERT_NEAR(strokes.strokes[0].lengthPixels, 92.0, 1e-9);
    EXPECT_EQ(dashStrokes(strokes, 0, {6.0, 4.0}), 9u);
    ASSERT_EQ(strokes.strokes.size(), 9u);
    EXPECT_NEAR(strokes.strokes[0].lengthPixels, 8.0, 1e-4);
    EXPECT_NEAR(strokes.strokes[0].points.front().position.y, 12.0, 1e-4); // s = 90: up the left side, 2 px short
    EXPECT_NEAR(strokes.strokes[0].points.back().position.x, 16.0, 1e-4);  // s = 6
    double total = 0.0;
    for (std::size_t index = 1; index < strokes.strokes.size(); ++index) {
        EXPECT_NEAR(strokes.strokes[index].lengthPixels, 6.0, 1e-4);
        EXPECT_FALSE(strokes.strokes[index].closed);
        total += strokes.strokes[index].lengthPixels;
    }
    EXPECT_NEAR(total + strokes.strokes[0].lengthPixels, 8 * 6.0 + 8.0, 1e-3);

    // A period that divides the length: ten dashes of 7, the last ending 3 px before the seam.
    Strokes even;
    even.strokes.push_back(strokeThrough({{10.0f, 10.0f}, {35.0f, 10.0f}, {35.0f, 35.0f}, {10.0f, 35.0f}}, true));
    EXPECT_EQ(dashStrokes(even, 0, {7.0, 3.0}), 10u);
    for (const Stroke& dash : even.strokes) EXPECT_NEAR(dash.lengthPixels, 7.0, 1e-4);
}

TEST(StrokeDashesTest, OnlyTheLayersKeptStrokesAreCutAndASolidPatternCutsNothing) {
    Strokes strokes;
    strokes.strokes.push_back(strokeThrough({{0.0f, 0.0f}, {50.0f, 0.0f}}, false));
    Stroke other = strokeThrough({{0.0f, 5.0f}, {50.0f, 5.0f}}, false);
    other.layer = 1;
    strokes.strokes.push_back(other);
    Stroke dropped = strokeThrough({{0.0f, 9.0f}, {50.0f, 9.0f}}, false);
    dropped.kept = false;
    strokes.strokes.push_back(dropped);
    Stroke shortOne = strokeThrough({{0.0f, 12.0f}, {5.0f, 12.0f}}, false); // no longer than a dash
    strokes.strokes.push_back(shortOne);

    Strokes solid = strokes;
    EXPECT_EQ(dashStrokes(solid, 0, {6.0, 0.0}), 0u);
    EXPECT_EQ(solid.strokes.size(), 4u);

    // 50 px: [0,6] ... [40,46], and the short stroke drawn whole, one dash more (--stats counted 5 where the picture
    // and the SVG draw 6).
    EXPECT_EQ(dashStrokes(strokes, 0, {6.0, 4.0}), 6u);
    ASSERT_EQ(strokes.strokes.size(), 5u + 3u);
    EXPECT_EQ(strokes.strokes[5].layer, 1);
    EXPECT_NEAR(strokes.strokes[5].lengthPixels, 50.0, 1e-9);
    EXPECT_FALSE(strokes.strokes[6].kept);
    EXPECT_NEAR(strokes.strokes[6].lengthPixels, 50.0, 1e-9);
    EXPECT_NEAR(strokes.strokes[7].lengthPixels, 5.0, 1e-9);
}

TEST(StrokeDashesTest, RefusesABadPattern) {
    Strokes strokes;
    for (const DashPattern pattern : {DashPattern{0.0, 4.0}, DashPattern{-1.0, 4.0}, DashPattern{6.0, -1.0},
                                      DashPattern{NAN, 4.0}, DashPattern{6.0, INFINITY}}) {
        const std::string message = invalidArgumentMessage([&] { dashStrokes(strokes, 0, pattern); });
        EXPECT_NE(message.find("dashStrokes(): 'pattern'"), std::string::npos) << message;
    }
}

TEST(StrokeDashesTest, TheRasterAndThePolylinesDrawTheSameDashes) {
    // A 61-pixel horizontal line chained as a stroke, dashed 6 on, 4 off: the kept skeleton's pixels are the dashes'
    // (x0 + [10k, 10k + 6]), to within the pixel that holds each cut, and strokePolylines() gives the same dashes.
    cv::Mat mask = cv::Mat::zeros(40, 80, CV_8UC1);
    cv::line(mask, {10, 20}, {70, 20}, 255, 1, cv::LINE_8);
    const LineSkeleton skeleton = skeletonFromMask(mask);
    const std::vector<StrokeLayer> layers = {{&skeleton}};
    Strokes strokes = chainStrokes(layers);
    ASSERT_EQ(strokes.strokes.size(), 1u);
    EXPECT_EQ(dashStrokes(strokes, 0, {6.0, 4.0}), 6u);
    const LineSkeleton kept = keptSkeleton(strokes, layers, 0);
    int wrong = 0;
    for (int col = 10; col <= 70; ++col) {
        const double s = col - 10;
        const double phase = std::fmod(s, 10.0);
        if (phase > 0.5 && phase < 5.5) wrong += kept.mask.at<uchar>(20, col) != 255; // inside a dash
        if (phase > 6.5 && phase < 9.5) wrong += kept.mask.at<uchar>(20, col) != 0;   // inside a gap
    }
    EXPECT_EQ(wrong, 0);
    const std::vector<Polyline> polylines = strokePolylines(strokes, 0, 0.25);
    ASSERT_EQ(polylines.size(), 6u);
    for (std::size_t index = 0; index < polylines.size(); ++index) {
        EXPECT_NEAR(polylines[index].points.front().x, 10.0 + 10.0 * double(index), 1e-4);
        EXPECT_NEAR(polylines[index].points.back().x, 16.0 + 10.0 * double(index), 1e-4);
    }
}

} // namespace
} // namespace inkgraph
