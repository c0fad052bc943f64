// postfx/Contour on synthetic buffers built inline; no GL.
#include "postfx/Contour.h"
#include "tests/postfx/LineTestImages.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::filled;
using test::markedPixels;

bool sameSkeleton(const LineSkeleton& a, const LineSkeleton& b) {
    if (a.points.size() != b.points.size() || cv::countNonZero(a.mask != b.mask) != 0) return false;
    for (size_t index = 0; index < a.points.size(); ++index)
        if (a.points[index].position != b.points[index].position ||
            a.points[index].strength != b.points[index].strength)
            return false;
    return true;
}

/** The image of a sphere seen head-on: a disc of radius `radius` around `centre`, n.v = sqrt(1 - (r / radius)^2),
 *  depth nearer in the middle, background 0. */
struct SphereImage {
    cv::Point2d centre{100.3, 99.6};
    double radius = 80.0;
    cv::Mat nDotV;
    cv::Mat depth;

    SphereImage() {
        const int size = 201;
        nDotV = cv::Mat::zeros(size, size, CV_32FC1);
        depth = cv::Mat::zeros(size, size, CV_32FC1);
        for (int row = 0; row < size; ++row)
            for (int col = 0; col < size; ++col) {
                const double r = std::hypot(col - centre.x, row - centre.y) / radius;
                if (r >= 1.0) continue;
                const double facing = std::sqrt(1.0 - r * r);
                nDotV.at<float>(row, col) = static_cast<float>(facing);
                depth.at<float>(row, col) = static_cast<float>(5.0 - facing);
            }
    }
    double offCircle(cv::Point2d point) const {
        return std::abs(std::hypot(point.x - centre.x, point.y - centre.y) - radius);
    }
};

TEST(Contours, ConstantFrontFacingSurfaceHasNone) {
    const cv::Mat nDotV(32, 40, CV_32FC1, cv::Scalar(0.5));
    const cv::Mat depth(32, 40, CV_32FC1, cv::Scalar(2.0));
    const LineSkeleton skeleton = extractContours(nDotV, depth, {});
    ASSERT_EQ(skeleton.mask.type(), CV_8UC1);
    ASSERT_EQ(skeleton.mask.size(), nDotV.size());
    EXPECT_EQ(cv::countNonZero(skeleton.mask), 0);
    EXPECT_TRUE(skeleton.points.empty());
}

TEST(Contours, SphereGivesAFullRingOnItsSilhouette) {
    const SphereImage sphere;
    const LineSkeleton skeleton = extractContours(sphere.nDotV, sphere.depth, {});
    const std::vector<cv::Point> pixels = markedPixels(skeleton.mask);
    ASSERT_FALSE(pixels.empty());
    for (const cv::Point& pixel : pixels) {
        EXPECT_LE(sphere.offCircle(pixel), 1.0) << "pixel " << pixel;
        EXPECT_GT(sphere.depth.at<float>(pixel), 0.0f) << "background marked at " << pixel;
    }
    constexpr int angleBins = 360;
    std::vector<int> pointsPerBin(angleBins, 0);
    for (const LinePoint& point : skeleton.points) {
        ASSERT_TRUE(std::isfinite(point.position.x) && std::isfinite(point.position.y));
        EXPECT_LE(sphere.offCircle(point.position), 0.75) << "point " << point.position;
        EXPECT_EQ(point.strength, 1.0f);
        const double angle = std::atan2(point.position.y - sphere.centre.y, point.position.x - sphere.centre.x);
        const int bin = static_cast<int>(std::floor((angle + std::numbers::pi) / (2.0 * std::numbers::pi) * angleBins));
        ++pointsPerBin[std::min(bin, angleBins - 1)];
    }
    for (int bin = 0; bin < angleBins; ++bin)
        EXPECT_GT(pointsPerBin[bin], 0) << "no point between " << bin << " and " << bin + 1 << " degrees";
}

TEST(Contours, SignChangeIsPlacedAtTheLinearZeroCrossing) {
    const cv::Mat depth(16, 24, CV_32FC1, cv::Scalar(1.0));
    // n.v crosses zero at x = 10.3 in every row: the point lies there, the pixel with the smaller |n.v| is marked.
    const LineSkeleton acrossColumns = extractContours(
        filled(24, 16, [](int col, int) { return 0.05f * (static_cast<float>(col) - 10.3f); }), depth, {});
    ASSERT_EQ(acrossColumns.points.size(), 16u);
    for (const LinePoint& point : acrossColumns.points) {
        EXPECT_NEAR(point.position.x, 10.3f, 1e-3f);
        EXPECT_EQ(point.position.y, std::round(point.position.y));
    }
    for (const cv::Point& pixel : markedPixels(acrossColumns.mask))
        EXPECT_EQ(pixel.x, 10) << "|n.v| is 0.015 at x = 10 and 0.035 at x = 11";
    EXPECT_EQ(cv::countNonZero(acrossColumns.mask), 16);

    // Decreasing the other way and nearer to 11: the right-hand pixel is marked.
    const LineSkeleton otherSide = extractContours(
        filled(24, 16, [](int col, int) { return 0.05f * (10.7f - static_cast<float>(col)); }), depth, {});
    ASSERT_EQ(otherSide.points.size(), 16u);
    for (const LinePoint& point : otherSide.points) EXPECT_NEAR(point.position.x, 10.7f, 1e-3f);
    for (const cv::Point& pixel : markedPixels(otherSide.mask)) EXPECT_EQ(pixel.x, 11);

    // Across rows (the vertical pairs): zero at y = 7.6.
    const LineSkeleton acrossRows = extractContours(
        filled(24, 16, [](int, int row) { return 0.2f * (static_cast<float>(row) - 7.6f); }), depth, {});
    ASSERT_EQ(acrossRows.points.size(), 24u);
    for (const LinePoint& point : acrossRows.points) EXPECT_NEAR(point.position.y, 7.6f, 1e-3f);
    for (const cv::Point& pixel : markedPixels(acrossRows.mask)) EXPECT_EQ(pixel.y, 8);
}

TEST(Contours, SignChangeIsFoundInEveryColumn) {
    // The kernel scans blocks of columns and a tail; a crossing is found wherever it lies, the last pair included.
    const cv::Mat depth(3, 40, CV_32FC1, cv::Scalar(1.0));
    for (const float crossing : {0.3f, 7.6f, 15.3f, 16.3f, 31.3f, 32.4f, 35.3f, 38.3f}) {
        const LineSkeleton skeleton =
            extractContours(filled(40, 3, [=](int col, int) { return crossing - static_cast<float>(col); }), depth, {});
        ASSERT_EQ(skeleton.points.size(), 3u) << "crossing at " << crossing;
        for (const LinePoint& point : skeleton.points) EXPECT_NEAR(point.position.x, crossing, 1e-4f);
        for (const cv::Point& pixel : markedPixels(skeleton.mask))
            EXPECT_EQ(pixel.x, static_cast<int>(std::lround(crossing))) << "crossing at " << crossing;
    }
    // And across rows, down to the last row and the last column.
    const cv::Mat tallDepth(40, 18, CV_32FC1, cv::Scalar(1.0));
    for (const float crossing : {0.4f, 17.6f, 38.4f}) {
        const LineSkeleton skeleton = extractContours(
            filled(18, 40, [=](int, int row) { return crossing - static_cast<float>(row); }), tallDepth, {});
        ASSERT_EQ(skeleton.points.size(), 18u) << "crossing at " << crossing;
        for (const LinePoint& point : skeleton.points) EXPECT_NEAR(point.position.y, crossing, 1e-4f);
    }
}

TEST(Contours, ZeroCountsAsFrontFacing) {
    const cv::Mat depth(4, 24, CV_32FC1, cv::Scalar(1.0));
    const LineSkeleton skeleton =
        extractContours(filled(24, 4, [](int col, int) { return static_cast<float>(col - 10); }), depth, {});
    // -1 | 0 changes sign (the point on the zero pixel); 0 | 1 does not.
    ASSERT_EQ(skeleton.points.size(), 4u);
    for (const LinePoint& point : skeleton.points) EXPECT_EQ(point.position.x, 10.0f);
    for (const cv::Point& pixel : markedPixels(skeleton.mask)) EXPECT_EQ(pixel.x, 10);
}

TEST(Contours, TouchingZeroIsNoContour) {
    // n.v = |x - 10| dips to 0 but never turns away: nothing changes sign.
    const cv::Mat depth(4, 24, CV_32FC1, cv::Scalar(1.0));
    EXPECT_TRUE(
        extractContours(filled(24, 4, [](int col, int) { return static_cast<float>(std::abs(col - 10)); }), depth, {})
            .points.empty());
}

TEST(Contours, DepthStepMarksTheNearerSideAboveARelativeThreshold) {
    const cv::Mat nDotV(16, 40, CV_32FC1, cv::Scalar(0.8));
    auto step = [](float left, float right) {
        return filled(40, 16, [=](int col, int) { return col < 21 ? left : right; });
    };
    auto expectEdgeAt = [&](const LineSkeleton& skeleton, int markedColumn, const std::string& what) {
        ASSERT_EQ(skeleton.points.size(), 16u) << what;
        for (const LinePoint& point : skeleton.points)
            EXPECT_EQ(point.position.x, 20.5f) << what << ": the midpoint of the pair";
        for (const cv::Point& pixel : markedPixels(skeleton.mask)) EXPECT_EQ(pixel.x, markedColumn) << what;
        EXPECT_EQ(cv::countNonZero(skeleton.mask), 16) << what;
    };
    expectEdgeAt(extractContours(nDotV, step(2.0f, 3.0f), {}), 20, "nearer on the left");
    expectEdgeAt(extractContours(nDotV, step(3.0f, 2.0f), {}), 21, "nearer on the right");
    expectEdgeAt(extractContours(nDotV, step(2000.0f, 3000.0f), {}), 20, "the same step in other units");
    EXPECT_TRUE(extractContours(nDotV, step(2.0f, 2.08f), {}).points.empty()) << "4% is below the 5% default";
    EXPECT_TRUE(extractContours(nDotV, step(2000.0f, 2080.0f), {}).points.empty()) << "4% in other units";
    ContourSettings loose;
    loose.depthJump = 0.6f;
    EXPECT_TRUE(extractContours(nDotV, step(2.0f, 3.0f), loose).points.empty()) << "50% is below 60%";
}

TEST(Contours, DeterministicAndFiniteWhereInputsAreNot) {
    const SphereImage sphere;
    EXPECT_TRUE(
        sameSkeleton(extractContours(sphere.nDotV, sphere.depth, {}), extractContours(sphere.nDotV, sphere.depth, {})));

    // NaN and infinite n.v on the surface, NaN depth: no NaN point comes out, and a NaN depth counts as background.
    cv::Mat nDotV = filled(24, 8, [](int col, int) { return 0.1f * (static_cast<float>(col) - 10.3f); });
    cv::Mat depth(8, 24, CV_32FC1, cv::Scalar(1.0));
    nDotV.at<float>(2, 10) = std::numeric_limits<float>::quiet_NaN();
    nDotV.at<float>(3, 10) = -std::numeric_limits<float>::infinity();
    nDotV.at<float>(3, 11) = std::numeric_limits<float>::infinity();
    depth.at<float>(5, 4) = std::numeric_limits<float>::quiet_NaN();
    const LineSkeleton skeleton = extractContours(nDotV, depth, {});
    for (const LinePoint& point : skeleton.points)
        EXPECT_TRUE(std::isfinite(point.position.x) && std::isfinite(point.position.y)) << point.position;
    EXPECT_EQ(skeleton.mask.at<uchar>(5, 4), 0) << "a NaN depth is background, never marked";
    EXPECT_EQ(skeleton.mask.at<uchar>(5, 3), 255) << "its neighbours end the surface";
}

TEST(Contours, RejectsWrongInputs) {
    const cv::Mat nDotV(8, 8, CV_32FC1, cv::Scalar(0.5));
    const cv::Mat depth(8, 8, CV_32FC1, cv::Scalar(1.0));
    try {
        extractContours(nDotV, cv::Mat(8, 9, CV_32FC1, cv::Scalar(1.0)), {});
        FAIL() << "a depth of another size was accepted";
    } catch (const std::invalid_argument& error) {
        EXPECT_STREQ(error.what(), "extractContours(): 'depth' must be CV_32FC1 of the size of 'nDotV'");
    }
    EXPECT_THROW(extractContours(cv::Mat(8, 8, CV_64FC1, cv::Scalar(0.5)), depth, {}), std::invalid_argument);
    EXPECT_THROW(extractContours(cv::Mat(), cv::Mat(), {}), std::invalid_argument);
    EXPECT_THROW(extractContours(nDotV, cv::Mat(8, 8, CV_8UC1, cv::Scalar(1)), {}), std::invalid_argument);
    ContourSettings negative;
    negative.depthJump = -0.1f;
    EXPECT_THROW(extractContours(nDotV, depth, negative), std::invalid_argument);
    ContourSettings notANumber;
    notANumber.depthJump = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(extractContours(nDotV, depth, notANumber), std::invalid_argument);
}

TEST(AppendDepthBreaks, AddsToAnExistingSkeleton) {
    const cv::Mat depth = filled(20, 6, [](int col, int) { return col < 5 ? 0.0f : 2.0f; });
    LineSkeleton skeleton{cv::Mat::zeros(6, 20, CV_8UC1), {{{15.0f, 2.0f}, 0.5f}}};
    skeleton.mask.at<uchar>(2, 15) = 255;
    appendDepthBreaks(depth, 0.05f, skeleton);
    ASSERT_EQ(skeleton.points.size(), 7u);
    EXPECT_EQ(skeleton.points[0].position, cv::Point2f(15.0f, 2.0f)) << "what was there stays first";
    for (size_t index = 1; index < skeleton.points.size(); ++index) EXPECT_EQ(skeleton.points[index].position.x, 4.5f);
    EXPECT_EQ(skeleton.mask.at<uchar>(2, 15), 255);
    EXPECT_EQ(cv::countNonZero(skeleton.mask.col(5)), 6) << "the model's first column, next to the background";
    EXPECT_EQ(cv::countNonZero(skeleton.mask), 7);

    LineSkeleton fresh; // an empty mask is allocated
    appendDepthBreaks(depth, 0.05f, fresh);
    EXPECT_EQ(fresh.points.size(), 6u);
    LineSkeleton wrongSize{cv::Mat::zeros(5, 20, CV_8UC1), {}};
    EXPECT_THROW(appendDepthBreaks(depth, 0.05f, wrongSize), std::invalid_argument);
    EXPECT_THROW(appendDepthBreaks(depth, -1.0f, fresh), std::invalid_argument);
}

} // namespace
} // namespace inkgraph
