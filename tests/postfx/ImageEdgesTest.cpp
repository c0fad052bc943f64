// postfx/ImageEdges on synthetic buffers built inline; no GL.
#include "postfx/ImageEdges.h"
#include "tests/postfx/LineTestImages.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace inkgraph {
namespace {

using test::filled;
using test::markedPixels;

constexpr double degrees = std::numbers::pi / 180.0;

cv::Vec4f normalAt(double angleAroundY) {
    return {static_cast<float>(std::sin(angleAroundY)), 0.0f, static_cast<float>(std::cos(angleAroundY)), 1.0f};
}

/** Two half-planes meeting at the seam between column `lastLeftColumn` and the next. */
cv::Mat normalsWithSeam(int cols, int rows, int lastLeftColumn, const cv::Vec4f& left, const cv::Vec4f& right) {
    cv::Mat normal(rows, cols, CV_32FC4);
    for (int row = 0; row < rows; ++row)
        for (int col = 0; col < cols; ++col) normal.at<cv::Vec4f>(row, col) = col <= lastLeftColumn ? left : right;
    return normal;
}

TEST(DepthEdges, StepIsJudgedRelativeToDepth) {
    auto step = [](float left, float right) {
        return filled(40, 12, [=](int col, int) { return col < 25 ? left : right; });
    };
    for (const float scale : {1.0f, 1000.0f, 1e-3f}) {
        const LineSkeleton skeleton = extractDepthEdges(step(2.0f * scale, 3.0f * scale), {});
        ASSERT_EQ(skeleton.points.size(), 12u) << "scale " << scale;
        for (const LinePoint& point : skeleton.points) EXPECT_EQ(point.position.x, 24.5f);
        for (const cv::Point& pixel : markedPixels(skeleton.mask)) EXPECT_EQ(pixel.x, 24) << "the nearer side";
        EXPECT_TRUE(extractDepthEdges(step(2.0f * scale, 2.08f * scale), {}).points.empty()) << "scale " << scale;
    }
    DepthEdgeSettings strict;
    strict.relativeJump = 0.03f;
    EXPECT_EQ(extractDepthEdges(step(2.0f, 2.08f), strict).points.size(), 12u) << "4% is above 3%";
}

TEST(DepthEdges, StepIsFoundInEveryColumnAndRow) {
    for (const int firstFar : {1, 16, 17, 32, 33, 39}) {
        const LineSkeleton skeleton =
            extractDepthEdges(filled(40, 3, [=](int col, int) { return col < firstFar ? 1.0f : 2.0f; }), {});
        ASSERT_EQ(skeleton.points.size(), 3u) << "step before column " << firstFar;
        for (const cv::Point& pixel : markedPixels(skeleton.mask)) EXPECT_EQ(pixel.x, firstFar - 1);
    }
    for (const int firstFar : {1, 20, 39}) {
        const LineSkeleton skeleton =
            extractDepthEdges(filled(18, 40, [=](int, int row) { return row < firstFar ? 2.0f : 1.0f; }), {});
        ASSERT_EQ(skeleton.points.size(), 18u) << "step before row " << firstFar;
        for (const cv::Point& pixel : markedPixels(skeleton.mask))
            EXPECT_EQ(pixel.y, firstFar) << "the lower rows are nearer";
    }
}

TEST(DepthEdges, BackgroundBoundaryMarksOnlyTheModel) {
    // A square of columns 8..15 and rows 6..13 on the background.
    const cv::Mat depth =
        filled(24, 20, [](int col, int row) { return col >= 8 && col <= 15 && row >= 6 && row <= 13 ? 4.0f : 0.0f; });
    const LineSkeleton skeleton = extractDepthEdges(depth, {});
    const std::vector<cv::Point> pixels = markedPixels(skeleton.mask);
    EXPECT_EQ(pixels.size(), 28u) << "the square's outer ring";
    for (const cv::Point& pixel : pixels) {
        EXPECT_GT(depth.at<float>(pixel), 0.0f) << pixel;
        EXPECT_TRUE(pixel.x == 8 || pixel.x == 15 || pixel.y == 6 || pixel.y == 13) << pixel;
    }
    ASSERT_EQ(skeleton.points.size(), 32u) << "one per model-background pair";
    for (const LinePoint& point : skeleton.points) {
        const bool onVerticalSide = (point.position.x == 7.5f || point.position.x == 15.5f) &&
                                    point.position.y >= 6.0f && point.position.y <= 13.0f;
        const bool onHorizontalSide = (point.position.y == 5.5f || point.position.y == 13.5f) &&
                                      point.position.x >= 8.0f && point.position.x <= 15.0f;
        EXPECT_TRUE(onVerticalSide || onHorizontalSide) << point.position;
    }
}

TEST(DepthEdges, GrazingPlaneHasNone) {
    // 4 units per pixel, but at most 4% of the depth: a steep plane, not an edge.
    const cv::Mat depth = filled(64, 8, [](int col, int) { return 100.0f + 4.0f * static_cast<float>(col); });
    EXPECT_TRUE(extractDepthEdges(depth, {}).points.empty());
    // At 3% the near end (4 / (100 + 4x) > 0.03 for x < 8.3) breaks: each pair marks its nearer pixel.
    DepthEdgeSettings strict;
    strict.relativeJump = 0.03f;
    const LineSkeleton skeleton = extractDepthEdges(depth, strict);
    for (const cv::Point& pixel : markedPixels(skeleton.mask)) EXPECT_LE(pixel.x, 8) << pixel;
    EXPECT_EQ(cv::countNonZero(skeleton.mask), 9 * 8);
}

TEST(DepthEdges, RejectsWrongInputs) {
    EXPECT_THROW(extractDepthEdges(cv::Mat(), {}), std::invalid_argument);
    EXPECT_THROW(extractDepthEdges(cv::Mat(4, 4, CV_32FC3), {}), std::invalid_argument);
    DepthEdgeSettings negative;
    negative.relativeJump = -0.5f;
    try {
        extractDepthEdges(cv::Mat(4, 4, CV_32FC1, cv::Scalar(1.0)), negative);
        FAIL() << "a negative jump was accepted";
    } catch (const std::invalid_argument& error) {
        EXPECT_NE(std::string(error.what()).find("extractDepthEdges(): 'settings.relativeJump'"), std::string::npos)
            << error.what();
    }
}

TEST(NormalEdges, SeamAbove30DegreesIsOnePixelWide) {
    const cv::Mat depth(10, 40, CV_32FC1, cv::Scalar(3.0));
    const LineSkeleton crease =
        extractNormalEdges(normalsWithSeam(40, 10, 19, normalAt(0.0), normalAt(45.0 * degrees)), depth, {});
    ASSERT_EQ(crease.points.size(), 10u);
    for (const LinePoint& point : crease.points) EXPECT_EQ(point.position.x, 19.5f) << "the midpoint of the pair";
    for (const cv::Point& pixel : markedPixels(crease.mask)) EXPECT_EQ(pixel.x, 19) << "the left pixel";
    EXPECT_EQ(cv::countNonZero(crease.mask), 10);

    const LineSkeleton gentle =
        extractNormalEdges(normalsWithSeam(40, 10, 19, normalAt(0.0), normalAt(20.0 * degrees)), depth, {});
    EXPECT_TRUE(gentle.points.empty()) << "20 degrees is below the 30-degree default";
    NormalEdgeSettings sharp;
    sharp.creaseAngleDegrees = 15.0f;
    EXPECT_EQ(extractNormalEdges(normalsWithSeam(40, 10, 19, normalAt(0.0), normalAt(20.0 * degrees)), depth, sharp)
                  .points.size(),
              10u);
}

TEST(NormalEdges, SeamIsFoundInEveryColumn) {
    const cv::Mat depth(3, 40, CV_32FC1, cv::Scalar(3.0));
    for (const int lastLeftColumn : {0, 15, 16, 31, 32, 38}) {
        const LineSkeleton skeleton = extractNormalEdges(
            normalsWithSeam(40, 3, lastLeftColumn, normalAt(0.0), normalAt(45.0 * degrees)), depth, {});
        ASSERT_EQ(skeleton.points.size(), 3u) << "seam after column " << lastLeftColumn;
        for (const cv::Point& pixel : markedPixels(skeleton.mask)) EXPECT_EQ(pixel.x, lastLeftColumn);
    }
}

TEST(NormalEdges, HorizontalSeamMarksTheUpperPixel) {
    cv::Mat normal(12, 30, CV_32FC4);
    for (int row = 0; row < 12; ++row)
        for (int col = 0; col < 30; ++col)
            normal.at<cv::Vec4f>(row, col) = row <= 6 ? normalAt(10.0 * degrees) : normalAt(-40.0 * degrees);
    const LineSkeleton skeleton = extractNormalEdges(normal, cv::Mat(12, 30, CV_32FC1, cv::Scalar(3.0)), {});
    ASSERT_EQ(skeleton.points.size(), 30u);
    for (const LinePoint& point : skeleton.points) EXPECT_EQ(point.position.y, 6.5f);
    for (const cv::Point& pixel : markedPixels(skeleton.mask)) EXPECT_EQ(pixel.y, 6);
}

TEST(NormalEdges, ConstantNormalHasNone) {
    const cv::Mat normal(20, 50, CV_32FC4, cv::Scalar(0.6, -0.48, 0.64, 1.0));
    EXPECT_TRUE(extractNormalEdges(normal, cv::Mat(20, 50, CV_32FC1, cv::Scalar(7.0)), {}).points.empty());
}

TEST(NormalEdges, NothingAcrossADepthBreak) {
    const cv::Mat normal = normalsWithSeam(40, 10, 19, normalAt(0.0), normalAt(45.0 * degrees));
    const cv::Mat depth = filled(40, 10, [](int col, int) { return col <= 19 ? 1.0f : 2.0f; });
    EXPECT_TRUE(extractNormalEdges(normal, depth, {}).points.empty()) << "a depth edge, not a crease";
    EXPECT_EQ(extractDepthEdges(depth, {}).points.size(), 10u) << "which extractDepthEdges finds";
    // Nor against the background, whose normal is zero.
    const cv::Mat withBackground = filled(40, 10, [](int col, int) { return col <= 19 ? 1.0f : 0.0f; });
    cv::Mat normalWithBackground = normalsWithSeam(40, 10, 19, normalAt(0.0), cv::Vec4f(0.0f, 0.0f, 0.0f, 0.0f));
    EXPECT_TRUE(extractNormalEdges(normalWithBackground, withBackground, {}).points.empty());
}

TEST(NormalEdges, SmallCreaseAnglesAreResolved) {
    // Near 1 degree, 1 - a . b is ~1.5e-4 and loses digits in float; |a x b| keeps its relative precision.
    const cv::Mat depth(4, 24, CV_32FC1, cv::Scalar(2.0));
    NormalEdgeSettings oneDegree;
    oneDegree.creaseAngleDegrees = 1.0f;
    const double base = 20.0 * degrees;
    EXPECT_EQ(
        extractNormalEdges(normalsWithSeam(24, 4, 9, normalAt(base), normalAt(base + 1.5 * degrees)), depth, oneDegree)
            .points.size(),
        4u);
    EXPECT_TRUE(
        extractNormalEdges(normalsWithSeam(24, 4, 9, normalAt(base), normalAt(base + 0.5 * degrees)), depth, oneDegree)
            .points.empty());
}

TEST(NormalEdges, ZeroCreaseAngleMarksEveryChangeOfDirection) {
    NormalEdgeSettings zero;
    zero.creaseAngleDegrees = 0.0f;
    const cv::Mat depth(3, 20, CV_32FC1, cv::Scalar(1.0));
    const cv::Vec4f towards(0.0f, 0.0f, 1.0f, 1.0f);
    const cv::Vec4f away(0.0f, 0.0f, -1.0f, 1.0f);
    EXPECT_EQ(extractNormalEdges(normalsWithSeam(20, 3, 9, towards, away), depth, zero).points.size(), 3u)
        << "opposite normals: 180 degrees apart, though their cross product is zero";
    EXPECT_EQ(extractNormalEdges(normalsWithSeam(20, 3, 9, normalAt(0.0), normalAt(0.1 * degrees)), depth, zero)
                  .points.size(),
              3u);
    EXPECT_TRUE(
        extractNormalEdges(normalsWithSeam(20, 3, 9, normalAt(0.3), normalAt(0.3)), depth, zero).points.empty());
    NormalEdgeSettings straight;
    straight.creaseAngleDegrees = 180.0f;
    EXPECT_TRUE(extractNormalEdges(normalsWithSeam(20, 3, 9, towards, away), depth, straight).points.empty())
        << "nothing is more than 180 degrees apart";
}

TEST(NormalEdges, AgreesWithAtan2OnRandomNormals) {
    // Two rows of random unit normals: every pair is classified by the kernel and by atan2 in double.
    constexpr int cols = 70;
    std::mt19937 random(12345);
    std::normal_distribution<double> gaussian;
    cv::Mat normal(2, cols, CV_32FC4);
    std::vector<cv::Vec3d> exact(2 * cols);
    for (int index = 0; index < 2 * cols; ++index) {
        cv::Vec3d direction(gaussian(random), gaussian(random), gaussian(random));
        direction /= cv::norm(direction);
        const cv::Vec4f stored(static_cast<float>(direction[0]), static_cast<float>(direction[1]),
                               static_cast<float>(direction[2]), 1.0f);
        normal.at<cv::Vec4f>(index / cols, index % cols) = stored;
        exact[index] = cv::Vec3d(stored[0], stored[1], stored[2]);
    }
    for (const float creaseDegrees : {30.0f, 90.0f, 150.0f}) {
        NormalEdgeSettings settings;
        settings.creaseAngleDegrees = creaseDegrees;
        const LineSkeleton skeleton = extractNormalEdges(normal, cv::Mat(2, cols, CV_32FC1, cv::Scalar(1.0)), settings);
        std::set<std::pair<float, float>> found;
        for (const LinePoint& point : skeleton.points) found.insert({point.position.x, point.position.y});
        int compared = 0;
        auto check = [&](int a, int b) {
            const double angle = std::atan2(cv::norm(exact[a].cross(exact[b])), exact[a].dot(exact[b]));
            if (std::abs(angle - creaseDegrees * degrees) < 1e-4) return; // too close to call in float
            const std::pair<float, float> midpoint{0.5f * static_cast<float>(a % cols + b % cols),
                                                   0.5f * static_cast<float>(a / cols + b / cols)};
            EXPECT_EQ(found.count(midpoint), angle > creaseDegrees * degrees ? 1u : 0u)
                << "pair " << a << "-" << b << " at " << angle / degrees << " degrees, crease " << creaseDegrees;
            ++compared;
        };
        for (int col = 0; col < cols; ++col) {
            if (col + 1 < cols) check(col, col + 1);
            if (col + 1 < cols) check(cols + col, cols + col + 1);
            check(col, cols + col);
        }
        EXPECT_GT(compared, 200);
    }
}

TEST(NormalEdges, RejectsWrongInputs) {
    const cv::Mat normal(6, 6, CV_32FC4, cv::Scalar(0.0, 0.0, 1.0, 1.0));
    const cv::Mat depth(6, 6, CV_32FC1, cv::Scalar(1.0));
    EXPECT_THROW(extractNormalEdges(cv::Mat(6, 6, CV_32FC3), depth, {}), std::invalid_argument);
    EXPECT_THROW(extractNormalEdges(cv::Mat(), depth, {}), std::invalid_argument);
    try {
        extractNormalEdges(normal, cv::Mat(6, 7, CV_32FC1, cv::Scalar(1.0)), {});
        FAIL() << "a depth of another size was accepted";
    } catch (const std::invalid_argument& error) {
        EXPECT_STREQ(error.what(), "extractNormalEdges(): 'depth' must be CV_32FC1 of the size of 'normal'");
    }
    for (const float angle : {-1.0f, 181.0f, std::numeric_limits<float>::quiet_NaN()}) {
        NormalEdgeSettings settings;
        settings.creaseAngleDegrees = angle;
        EXPECT_THROW(extractNormalEdges(normal, depth, settings), std::invalid_argument) << angle;
    }
    NormalEdgeSettings negativeJump;
    negativeJump.depthJump = -0.01f;
    EXPECT_THROW(extractNormalEdges(normal, depth, negativeJump), std::invalid_argument);
}

} // namespace
} // namespace inkgraph
