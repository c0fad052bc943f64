// postfx/LineTracing on small synthetic masks; no GL. Expected vertices come from the drawn shapes (pixel centres at
// integers) and from the analytic lines they were drawn from.
#include "postfx/LineTracing.h"

#include "tests/support/ThrowMessage.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

cv::Mat blank(int cols, int rows) { return cv::Mat::zeros(rows, cols, CV_8UC1); }

void set(cv::Mat& mask, int col, int row) { mask.at<uchar>(row, col) = 255; }

double distanceToSegment(const cv::Point2d& p, const cv::Point2d& a, const cv::Point2d& b) {
    const cv::Point2d ab = b - a;
    const double lengthSquared = ab.dot(ab);
    const double t = lengthSquared == 0.0 ? 0.0 : std::clamp((p - a).dot(ab) / lengthSquared, 0.0, 1.0);
    const cv::Point2d offset = p - (a + t * ab);
    return std::hypot(offset.x, offset.y);
}

/** Distance from `p` to the nearest segment (or dot) of any polyline, the closing segment of closed ones included. */
double distanceToPolylines(const cv::Point2d& p, const std::vector<Polyline>& polylines) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Polyline& polyline : polylines) {
        const std::size_t count = polyline.points.size();
        if (count == 1) nearest = std::min(nearest, distanceToSegment(p, polyline.points[0], polyline.points[0]));
        const std::size_t segmentCount = polyline.closed ? count : count - 1;
        for (std::size_t index = 0; count >= 2 && index < segmentCount; ++index)
            nearest =
                std::min(nearest, distanceToSegment(p, polyline.points[index], polyline.points[(index + 1) % count]));
    }
    return nearest;
}

std::vector<cv::Point> onPixels(const cv::Mat& mask) {
    std::vector<cv::Point> pixels;
    cv::findNonZero(mask, pixels);
    return pixels;
}

/** The two promises of traceSkeleton() on a mask with no sub-pixel points: every on-pixel centre within
 *  tolerance + 0.5 of the traced lines (it lies on them before simplification, RDP moves them at most the
 *  tolerance; the 0.5 is the brief's slack), and every vertex within 1 px of an on-pixel centre. */
void expectCoversMask(const cv::Mat& mask, const std::vector<Polyline>& polylines, double tolerance) {
    const std::vector<cv::Point> pixels = onPixels(mask);
    for (const cv::Point& pixel : pixels)
        EXPECT_LE(distanceToPolylines(cv::Point2d(pixel), polylines), tolerance + 0.5) << "pixel " << pixel;
    for (const Polyline& polyline : polylines)
        for (const cv::Point2f& vertex : polyline.points) {
            double nearest = std::numeric_limits<double>::infinity();
            for (const cv::Point& pixel : pixels)
                nearest = std::min(nearest, std::hypot(double(vertex.x) - pixel.x, double(vertex.y) - pixel.y));
            EXPECT_LE(nearest, 1.0) << "vertex " << vertex;
        }
}

bool hasVertex(const Polyline& polyline, cv::Point2f vertex) {
    return std::find(polyline.points.begin(), polyline.points.end(), vertex) != polyline.points.end();
}

using test::invalidArgumentMessage;

TEST(LineTracingTest, StraightLineOf200PixelsSimplifiesToItsTwoEnds) {
    cv::Mat mask = blank(240, 40);
    for (int col = 10; col < 210; ++col) set(mask, col, 20);
    const std::vector<Polyline> polylines = traceSkeleton({mask, {}});
    ASSERT_EQ(polylines.size(), 1u);
    EXPECT_FALSE(polylines[0].closed);
    ASSERT_EQ(polylines[0].points.size(), 2u);
    // Chains start at their raster-first end.
    EXPECT_EQ(polylines[0].points[0], cv::Point2f(10, 20));
    EXPECT_EQ(polylines[0].points[1], cv::Point2f(209, 20));
}

TEST(LineTracingTest, DiagonalBresenhamLineIsOneSegment) {
    // A LINE_8 raster of a slanted segment: its pixels lie within 0.5 px of the line, so with the default
    // tolerance RDP keeps only the ends.
    cv::Mat mask = blank(160, 100);
    cv::line(mask, {5, 5}, {150, 90}, 255, 1, cv::LINE_8);
    const std::vector<Polyline> polylines = traceSkeleton({mask, {}});
    ASSERT_EQ(polylines.size(), 1u);
    ASSERT_EQ(polylines[0].points.size(), 2u);
    EXPECT_EQ(polylines[0].points[0], cv::Point2f(5, 5));
    EXPECT_EQ(polylines[0].points[1], cv::Point2f(150, 90));
    expectCoversMask(mask, polylines, 0.5);
}

TEST(LineTracingTest, LShapeKeepsItsCorner) {
    cv::Mat mask = blank(50, 50);
    for (int row = 5; row <= 40; ++row) set(mask, 8, row);  // down
    for (int col = 8; col <= 45; ++col) set(mask, col, 40); // then right
    const std::vector<Polyline> polylines = traceSkeleton({mask, {}});
    ASSERT_EQ(polylines.size(), 1u);
    const std::vector<cv::Point2f> expected = {{8, 5}, {8, 40}, {45, 40}};
    EXPECT_EQ(polylines[0].points, expected);
    EXPECT_FALSE(polylines[0].closed);
}

TEST(LineTracingTest, CircleIsOneClosedPolylineOnTheCircle) {
    const cv::Point centre(40, 38);
    const int radius = 25;
    cv::Mat mask = blank(80, 80);
    cv::circle(mask, centre, radius, 255, 1, cv::LINE_8);
    // How far OpenCV's raster circle itself strays from the true one (its inner corner pixels ~1 px).
    double rasterDeviation = 0.0;
    for (const cv::Point& pixel : onPixels(mask))
        rasterDeviation =
            std::max(rasterDeviation, std::abs(std::hypot(pixel.x - centre.x, pixel.y - centre.y) - radius));
    ASSERT_LT(rasterDeviation, 1.1);

    const double tolerance = 0.5;
    const std::vector<Polyline> polylines = traceSkeleton({mask, {}}, {tolerance});
    ASSERT_EQ(polylines.size(), 1u);
    const Polyline& loop = polylines[0];
    EXPECT_TRUE(loop.closed);
    // Far fewer vertices than the ~140 pixels, but a polygon, not a collapsed shape.
    EXPECT_GE(loop.points.size(), 12u);
    EXPECT_LE(loop.points.size(), 60u);
    // Vertices are pixel centres of the raster, and every edge's midpoint stays within the tolerance of it.
    for (std::size_t index = 0; index < loop.points.size(); ++index) {
        const cv::Point2d vertex = loop.points[index];
        const cv::Point2d middle = 0.5 * (vertex + cv::Point2d(loop.points[(index + 1) % loop.points.size()]));
        EXPECT_LE(std::abs(std::hypot(vertex.x - centre.x, vertex.y - centre.y) - radius), rasterDeviation) << vertex;
        EXPECT_LE(std::abs(std::hypot(middle.x - centre.x, middle.y - centre.y) - radius), rasterDeviation + tolerance)
            << middle;
    }
    // The first vertex is not repeated at the end.
    EXPECT_NE(loop.points.front(), loop.points.back());
    expectCoversMask(mask, polylines, tolerance);
}

TEST(LineTracingTest, TJunctionGivesThreeBranchesFromTheJunction) {
    cv::Mat mask = blank(40, 40);
    for (int col = 5; col <= 35; ++col) set(mask, col, 10);
    for (int row = 11; row <= 30; ++row) set(mask, 20, row);
    const std::vector<Polyline> polylines = traceSkeleton({mask, {}});
    ASSERT_EQ(polylines.size(), 3u);
    for (const Polyline& polyline : polylines) {
        EXPECT_FALSE(polyline.closed);
        ASSERT_EQ(polyline.points.size(), 2u);
        EXPECT_TRUE(polyline.points.front() == cv::Point2f(20, 10) || polyline.points.back() == cv::Point2f(20, 10));
    }
    std::vector<cv::Point2f> ends;
    for (const Polyline& polyline : polylines)
        for (const cv::Point2f& point : polyline.points)
            if (point != cv::Point2f(20, 10)) ends.push_back(point);
    std::sort(ends.begin(), ends.end(),
              [](cv::Point2f a, cv::Point2f b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    const std::vector<cv::Point2f> expected = {{5, 10}, {20, 30}, {35, 10}};
    EXPECT_EQ(ends, expected);
}

TEST(LineTracingTest, DiagonalXJunctionGivesFourBranches) {
    cv::Mat mask = blank(40, 40);
    cv::line(mask, {5, 5}, {35, 35}, 255, 1, cv::LINE_8);
    cv::line(mask, {35, 5}, {5, 35}, 255, 1, cv::LINE_8);
    const std::vector<Polyline> polylines = traceSkeleton({mask, {}});
    ASSERT_EQ(polylines.size(), 4u);
    for (const Polyline& polyline : polylines) {
        ASSERT_EQ(polyline.points.size(), 2u);
        EXPECT_TRUE(hasVertex(polyline, {20, 20}));
    }
    expectCoversMask(mask, polylines, 0.5);
}

TEST(LineTracingTest, StaircaseMakesNoSpuriousJunctions) {
    // A 4-connected staircase (every diagonal step through a corner pixel): with diagonal links pruned where a
    // corner pixel joins them, it is one chain, not a run of 3-way junctions.
    cv::Mat mask = blank(30, 30);
    for (int step = 0; step < 10; ++step) {
        set(mask, 5 + step, 5 + step);
        set(mask, 6 + step, 5 + step);
    }
    const std::vector<Polyline> polylines = traceSkeleton({mask, {}}, {0.0});
    ASSERT_EQ(polylines.size(), 1u);
    EXPECT_EQ(polylines[0].points.front(), cv::Point2f(5, 5));
    EXPECT_EQ(polylines[0].points.back(), cv::Point2f(15, 14));
    // With tolerance 0 every pixel is a corner of the staircase and stays.
    EXPECT_EQ(polylines[0].points.size(), 20u);
}

TEST(LineTracingTest, IsolatedPixelsBecomeOnePointPolylines) {
    cv::Mat mask = blank(20, 20);
    set(mask, 3, 4);
    set(mask, 17, 2);
    set(mask, 0, 19); // corners of the image too
    for (int col = 5; col <= 12; ++col) set(mask, col, 10);
    const std::vector<Polyline> polylines = traceSkeleton({mask, {}});
    ASSERT_EQ(polylines.size(), 4u);
    EXPECT_EQ(polylines[0].points.size(), 2u); // chains first
    // Then the dots, in raster order.
    const std::vector<cv::Point2f> dots = {{17, 2}, {3, 4}, {0, 19}};
    for (std::size_t index = 0; index < dots.size(); ++index) {
        const Polyline& dot = polylines[index + 1];
        ASSERT_EQ(dot.points.size(), 1u);
        EXPECT_EQ(dot.points[0], dots[index]);
        EXPECT_FALSE(dot.closed);
    }
}

TEST(LineTracingTest, TwoPixelsAreOneTwoPointPolyline) {
    cv::Mat mask = blank(10, 10);
    set(mask, 4, 4);
    set(mask, 5, 5);
    const std::vector<Polyline> polylines = traceSkeleton({mask, {}});
    ASSERT_EQ(polylines.size(), 1u);
    const std::vector<cv::Point2f> expected = {{4, 4}, {5, 5}};
    EXPECT_EQ(polylines[0].points, expected);
}

TEST(LineTracingTest, SubPixelPointsPlaceTheirPixelAtTheirMean) {
    cv::Mat mask = blank(40, 20);
    LineSkeleton skeleton{mask, {}};
    for (int col = 5; col <= 30; ++col) {
        set(skeleton.mask, col, 10);
        skeleton.points.push_back({{static_cast<float>(col), 10.3f}, 1.0f});
    }
    // An isolated pixel with two samples: placed at their mean.
    set(skeleton.mask, 2, 2);
    skeleton.points.push_back({{2.2f, 1.9f}, 1.0f});
    skeleton.points.push_back({{2.4f, 2.3f}, 0.5f});
    // Ignored: off the image, far off the image, and on an off pixel.
    skeleton.points.push_back({{-3.0f, 10.0f}, 1.0f});
    skeleton.points.push_back({{1e30f, -1e30f}, 1.0f});
    skeleton.points.push_back({{20.0f, 15.0f}, 1.0f});
    // A pixel with no sample stays at its centre.
    set(skeleton.mask, 35, 15);

    const std::vector<Polyline> polylines = traceSkeleton(skeleton, {0.05});
    ASSERT_EQ(polylines.size(), 3u);
    ASSERT_EQ(polylines[0].points.size(), 2u);
    EXPECT_FLOAT_EQ(polylines[0].points[0].x, 5.0f);
    EXPECT_NEAR(polylines[0].points[0].y, 10.3f, 1e-6);
    EXPECT_FLOAT_EQ(polylines[0].points[1].x, 30.0f);
    EXPECT_NEAR(polylines[0].points[1].y, 10.3f, 1e-6);
    ASSERT_EQ(polylines[1].points.size(), 1u);
    EXPECT_NEAR(polylines[1].points[0].x, 2.3f, 1e-6);
    EXPECT_NEAR(polylines[1].points[0].y, 2.1f, 1e-6);
    EXPECT_EQ(polylines[2].points, std::vector<cv::Point2f>{cv::Point2f(35, 15)});
}

TEST(LineTracingTest, SubPixelCircleIsTracedCloserThanPixelCentres) {
    const cv::Point2d centre(32.2, 31.7);
    const double radius = 20.37; // no extreme exactly on a pixel border (x = 52.5 would round into a clump)
    LineSkeleton skeleton{blank(64, 64), {}};
    for (int sample = 0; sample < 2000; ++sample) {
        const double angle = 2.0 * std::numbers::pi * sample / 2000.0;
        const cv::Point2f position(static_cast<float>(centre.x + radius * std::cos(angle)),
                                   static_cast<float>(centre.y + radius * std::sin(angle)));
        skeleton.points.push_back({position, 1.0f});
        set(skeleton.mask, static_cast<int>(std::floor(position.x + 0.5f)),
            static_cast<int>(std::floor(position.y + 0.5f)));
    }
    const double tolerance = 0.1;
    const std::vector<Polyline> polylines = traceSkeleton(skeleton, {tolerance});
    ASSERT_EQ(polylines.size(), 1u);
    EXPECT_TRUE(polylines[0].closed);
    // Each vertex is a mean of samples on a ~1.4 px arc, within its sagitta (~0.012 px) of the circle; pixel
    // centres would be up to 0.5 px off.
    for (const cv::Point2f& vertex : polylines[0].points)
        EXPECT_NEAR(std::hypot(vertex.x - centre.x, vertex.y - centre.y), radius, 0.03) << vertex;
}

TEST(LineTracingTest, SimplifyOpenPolylineKeepsCornersAndDropsWithinTolerance) {
    Polyline zigzag;
    for (int index = 0; index <= 20; ++index)
        zigzag.points.emplace_back(static_cast<float>(index), index % 2 == 0 ? 0.0f : 0.4f);
    zigzag.points.emplace_back(20.0f, 10.0f); // a real corner
    const Polyline simplified = simplifyPolyline(zigzag, 0.5);
    const std::vector<cv::Point2f> expected = {{0, 0}, {20, 0}, {20, 10}};
    EXPECT_EQ(simplified.points, expected);
    // Below the zigzag's amplitude every vertex stays.
    EXPECT_EQ(simplifyPolyline(zigzag, 0.1).points.size(), zigzag.points.size());
}

TEST(LineTracingTest, SimplifyClosedPolylineHandlesTheLoop) {
    // A 10 x 10 square traced from the middle of its top edge, as a loop's raster start often lies.
    Polyline square;
    square.closed = true;
    for (int x = 5; x < 10; ++x) square.points.emplace_back(float(x), 0.0f);
    for (int y = 0; y < 10; ++y) square.points.emplace_back(10.0f, float(y));
    for (int x = 10; x > 0; --x) square.points.emplace_back(float(x), 10.0f);
    for (int y = 10; y > 0; --y) square.points.emplace_back(0.0f, float(y));
    for (int x = 0; x < 5; ++x) square.points.emplace_back(float(x), 0.0f);

    const Polyline kept = simplifyPolyline(square, 0.5, true);
    EXPECT_TRUE(kept.closed);
    const std::vector<cv::Point2f> withStart = {{5, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}};
    EXPECT_EQ(kept.points, withStart);
    const Polyline dropped = simplifyPolyline(square, 0.5, false);
    const std::vector<cv::Point2f> corners = {{10, 0}, {10, 10}, {0, 10}, {0, 0}};
    EXPECT_EQ(dropped.points, corners);
    EXPECT_TRUE(dropped.closed);
}

TEST(LineTracingTest, LoopHangingOffAJunctionIsClosedAtTheJunction) {
    // A 6 x 6 ring of pixels with a tail to the left of its top-left corner.
    cv::Mat mask = blank(30, 30);
    cv::rectangle(mask, cv::Rect(10, 10, 6, 6), 255, 1);
    for (int col = 3; col < 10; ++col) set(mask, col, 10);
    const std::vector<Polyline> polylines = traceSkeleton({mask, {}});
    ASSERT_EQ(polylines.size(), 2u);
    // Raster order of start pixels: the tail's end (3, 10) comes before the junction (10, 10).
    EXPECT_FALSE(polylines[0].closed);
    EXPECT_EQ(polylines[0].points, (std::vector<cv::Point2f>{{3, 10}, {10, 10}}));
    EXPECT_TRUE(polylines[1].closed);
    EXPECT_EQ(polylines[1].points, (std::vector<cv::Point2f>{{10, 10}, {15, 10}, {15, 15}, {10, 15}}));
}

TEST(LineTracingTest, EveryPixelIsCoveredOnAMixedScene) {
    // Lines, a junction, a loop, a thick blob, a 2 x 2 block, a staircase and dots: every pixel within tolerance
    // + 0.5 of the traced lines, every vertex near a pixel.
    cv::Mat mask = blank(96, 96);
    cv::line(mask, {4, 4}, {60, 30}, 255, 1, cv::LINE_8);
    cv::line(mask, {30, 17}, {30, 60}, 255, 1, cv::LINE_8);
    cv::circle(mask, {70, 70}, 15, 255, 1, cv::LINE_8);
    cv::ellipse(mask, {25, 80}, {12, 6}, 30.0, 0.0, 250.0, 255, 1, cv::LINE_8);
    cv::rectangle(mask, cv::Rect(80, 5, 4, 3), 255, cv::FILLED);
    cv::rectangle(mask, cv::Rect(50, 45, 2, 2), 255, cv::FILLED);
    for (int step = 0; step < 6; ++step) {
        set(mask, 5 + step, 40 + step);
        set(mask, 5 + step, 41 + step);
    }
    set(mask, 90, 90);
    set(mask, 0, 0);
    for (const double tolerance : {0.0, 0.5, 1.5}) {
        SCOPED_TRACE(tolerance);
        expectCoversMask(mask, traceSkeleton({mask, {}}, {tolerance}), tolerance);
    }
}

TEST(LineTracingTest, LongSpiralOnALargeMaskIsOneChain) {
    // ~20k pixels in one chain on a 1024 x 1024 mask: exercises long walks and RDP ranges without recursion.
    cv::Mat mask = blank(1024, 1024);
    std::vector<cv::Point> spiral;
    for (double angle = 0.0; angle < 2.0 * std::numbers::pi * 12; angle += 0.002) {
        const double radius = 20.0 + 38.0 * angle / (2.0 * std::numbers::pi);
        spiral.emplace_back(static_cast<int>(std::lround(512 + radius * std::cos(angle))),
                            static_cast<int>(std::lround(512 + radius * std::sin(angle))));
    }
    cv::polylines(mask, spiral, false, 255, 1, cv::LINE_8);
    const std::size_t pixelCount = onPixels(mask).size();
    ASSERT_GT(pixelCount, 20000u);
    const std::vector<Polyline> polylines = traceSkeleton({mask, {}});
    ASSERT_EQ(polylines.size(), 1u);
    EXPECT_FALSE(polylines[0].closed);
    // The raster joins rounded samples, so its pixel centres wobble by up to ~0.7 px and RDP at 0.5 px keeps a
    // vertex every few pixels; still well under one per two pixels.
    EXPECT_LT(polylines[0].points.size(), pixelCount / 2);
    // Its ends are the spiral's, in whichever order raster order gives.
    const cv::Point2f first = polylines[0].points.front(), last = polylines[0].points.back();
    EXPECT_TRUE((first == cv::Point2f(spiral.front()) && last == cv::Point2f(spiral.back())) ||
                (first == cv::Point2f(spiral.back()) && last == cv::Point2f(spiral.front())));
}

TEST(LineTracingTest, ThinningAFivePixelBandGivesItsCentreLine) {
    cv::Mat mask = blank(80, 40);
    mask(cv::Rect(10, 18, 60, 5)).setTo(255); // rows 18..22: centre row 20
    const cv::Mat skeleton = thinToSkeleton(mask);
    ASSERT_EQ(skeleton.type(), CV_8UC1);
    const std::vector<cv::Point> pixels = onPixels(skeleton);
    ASSERT_GE(pixels.size(), 50u); // ends shorten by about half the width
    for (const cv::Point& pixel : pixels) EXPECT_LE(std::abs(pixel.y - 20), 1) << pixel;
    // The long middle is exactly the centre row.
    for (int col = 15; col < 65; ++col) EXPECT_EQ(skeleton.at<uchar>(20, col), 255) << col;
    // Values are 0 or 255 only.
    EXPECT_EQ(cv::countNonZero(skeleton == 255) + cv::countNonZero(skeleton == 0), skeleton.rows * skeleton.cols);

    const std::vector<Polyline> polylines = traceMask(mask);
    ASSERT_EQ(polylines.size(), 1u);
    for (const cv::Point2f& vertex : polylines[0].points) EXPECT_NEAR(vertex.y, 20.0f, 1.0f);
}

TEST(LineTracingTest, ThinningEvenAndSlantedBandsStaysWithinAPixelOfTheCentre) {
    // A 4-px band (centre between two rows) and a 5-px band along a slanted line, drawn anti-aliased and
    // thresholded at 128 as a GL line layer would be.
    cv::Mat even = blank(80, 40);
    even(cv::Rect(10, 10, 60, 4)).setTo(255); // rows 10..13: centre 11.5
    for (const cv::Point& pixel : onPixels(thinToSkeleton(even))) EXPECT_LE(std::abs(pixel.y - 11.5), 1.0) << pixel;

    cv::Mat slanted = blank(120, 120);
    const cv::Point2d a(15, 20), b(105, 95);
    cv::line(slanted, cv::Point(a), cv::Point(b), 255, 5, cv::LINE_AA);
    const cv::Mat skeleton = thinToSkeleton(slanted);
    const std::vector<cv::Point> pixels = onPixels(skeleton);
    ASSERT_GE(pixels.size(), 80u);
    // Along the band, within a pixel of its centre line; in the round caps (2.5 px past each end) the skeleton's end
    // may follow a one-pixel bump of the thresholded rim, as every thinning does.
    const cv::Point2d direction = (b - a) / std::hypot(b.x - a.x, b.y - a.y);
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    for (const cv::Point& pixel : pixels) {
        const double along = (cv::Point2d(pixel) - a).dot(direction);
        EXPECT_LE(distanceToSegment(cv::Point2d(pixel), a, b), along > 2.5 && along < length - 2.5 ? 1.0 : 3.5)
            << pixel;
    }
    // One-pixel wide: no 2 x 2 block of skeleton pixels anywhere.
    for (int row = 0; row + 1 < skeleton.rows; ++row)
        for (int col = 0; col + 1 < skeleton.cols; ++col)
            EXPECT_FALSE(skeleton.at<uchar>(row, col) && skeleton.at<uchar>(row, col + 1) &&
                         skeleton.at<uchar>(row + 1, col) && skeleton.at<uchar>(row + 1, col + 1));
    const std::vector<Polyline> polylines = traceMask(slanted);
    ASSERT_EQ(polylines.size(), 1u);
    for (const cv::Point2f& vertex : polylines[0].points)
        EXPECT_LE(distanceToSegment(cv::Point2d(vertex), a, b), 3.5) << vertex;
    expectCoversMask(skeleton, polylines, 0.5);
}

TEST(LineTracingTest, ThinningAnAnnulusGivesOneClosedLoop) {
    cv::Mat ring = blank(64, 64);
    cv::circle(ring, {32, 32}, 20, 255, 4, cv::LINE_8);
    const std::vector<Polyline> polylines = traceMask(ring);
    ASSERT_EQ(polylines.size(), 1u);
    EXPECT_TRUE(polylines[0].closed);
    for (const cv::Point2f& vertex : polylines[0].points)
        EXPECT_NEAR(std::hypot(vertex.x - 32.0, vertex.y - 32.0), 20.0, 1.5) << vertex;
}

TEST(LineTracingTest, ThinningNeverRemovesAShape) {
    // Zhang-Suen erases a 2 x 2 block; here every shape keeps at least one pixel, and thin lines stay as they are.
    cv::Mat mask = blank(20, 20);
    mask(cv::Rect(2, 2, 2, 2)).setTo(255);
    mask(cv::Rect(10, 10, 3, 3)).setTo(255);
    set(mask, 17, 3);
    for (int col = 2; col < 18; ++col) set(mask, col, 16);
    const cv::Mat skeleton = thinToSkeleton(mask);
    EXPECT_GT(cv::countNonZero(skeleton(cv::Rect(2, 2, 2, 2))), 0);
    EXPECT_GT(cv::countNonZero(skeleton(cv::Rect(10, 10, 3, 3))), 0);
    EXPECT_EQ(skeleton.at<uchar>(11, 11), 255); // peeled from all four sides, the middle stays
    EXPECT_EQ(skeleton.at<uchar>(3, 17), 255);
    for (int col = 2; col < 18; ++col) EXPECT_EQ(skeleton.at<uchar>(16, col), 255) << col;
    // The threshold decides what is set.
    cv::Mat faint = blank(10, 10);
    faint(cv::Rect(2, 5, 6, 1)).setTo(100);
    EXPECT_EQ(cv::countNonZero(thinToSkeleton(faint)), 0);
    EXPECT_EQ(cv::countNonZero(thinToSkeleton(faint, 100)), 6);
}

TEST(LineTracingTest, InputsAreNotModified) {
    cv::Mat mask = blank(30, 30);
    mask(cv::Rect(5, 5, 20, 5)).setTo(200);
    const cv::Mat copy = mask.clone();
    (void)thinToSkeleton(mask);
    (void)traceMask(mask);
    (void)traceSkeleton({mask, {}});
    EXPECT_EQ(cv::countNonZero(mask != copy), 0);
}

TEST(LineTracingTest, BadInputsThrowNamingTheArgument) {
    const cv::Mat good = blank(8, 8);
    const cv::Mat wrongType = cv::Mat::zeros(8, 8, CV_32FC1);
    EXPECT_EQ(invalidArgumentMessage([&] {
                  traceSkeleton({wrongType, {}});
              }).rfind("traceSkeleton(): 'skeleton.mask'", 0),
              0u);
    EXPECT_EQ(invalidArgumentMessage([&] {
                  traceSkeleton({cv::Mat(), {}});
              }).rfind("traceSkeleton(): 'skeleton.mask'", 0),
              0u);
    EXPECT_EQ(invalidArgumentMessage([&] {
                  traceSkeleton({good, {}}, {-0.1});
              }).rfind("traceSkeleton(): 'settings.tolerancePixels'", 0),
              0u);
    EXPECT_EQ(invalidArgumentMessage([&] {
                  traceSkeleton({good, {}}, {std::nan("")});
              }).rfind("traceSkeleton(): 'settings.tolerancePixels'", 0),
              0u);
    LineSkeleton withNaN{good, {{{std::numeric_limits<float>::quiet_NaN(), 1.0f}, 1.0f}}};
    EXPECT_EQ(invalidArgumentMessage([&] { traceSkeleton(withNaN); }).rfind("traceSkeleton(): 'skeleton.points'", 0),
              0u);
    EXPECT_EQ(invalidArgumentMessage([&] { thinToSkeleton(wrongType); }).rfind("thinToSkeleton(): 'mask'", 0), 0u);
    EXPECT_EQ(invalidArgumentMessage([&] { thinToSkeleton(cv::Mat()); }).rfind("thinToSkeleton(): 'mask'", 0), 0u);
    EXPECT_EQ(invalidArgumentMessage([&] { traceMask(cv::Mat::zeros(4, 4, CV_8UC3)); }).rfind("traceMask(): 'mask'", 0),
              0u);
    EXPECT_EQ(invalidArgumentMessage([&] {
                  traceMask(good, {std::numeric_limits<double>::infinity()});
              }).rfind("traceMask(): 'settings.tolerancePixels'", 0),
              0u);
    EXPECT_EQ(invalidArgumentMessage([&] {
                  simplifyPolyline({{{0, 0}, {1, 1}}}, -1.0);
              }).rfind("simplifyPolyline(): 'tolerancePixels'", 0),
              0u);
    EXPECT_EQ(invalidArgumentMessage([&] {
                  simplifyPolyline({{{0, 0}, {INFINITY, 1}}}, 1.0);
              }).rfind("simplifyPolyline(): 'polyline'", 0),
              0u);
    // An all-zero mask is fine: nothing to trace.
    EXPECT_TRUE(traceSkeleton({good, {}}).empty());
    EXPECT_TRUE(traceMask(good).empty());
}

} // namespace
} // namespace inkgraph
