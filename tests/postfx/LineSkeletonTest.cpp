// postfx/LineSkeleton on synthetic skeletons; no GL. Expected coverages come from the documented disc formula
// clamp(radius + 0.5 - distance, 0, 1) x strength, evaluated here independently per pixel.
#include "postfx/LineSkeleton.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

float discCoverage(float radius, float distance) { return std::clamp(radius + 0.5f - distance, 0.0f, 1.0f); }

LineSkeleton emptySkeleton(int cols, int rows) { return {cv::Mat::zeros(rows, cols, CV_8UC1), {}}; }

/** One point per data row at x = `outputX` in output pixels: output pixel u covers data pixels u s .. u s + s - 1,
 *  whose centres average at u s + (s - 1) / 2. */
LineSkeleton verticalLine(int outputSize, int supersample, float outputX) {
    const int size = outputSize * supersample;
    LineSkeleton skeleton = emptySkeleton(size, size);
    const float dataX = outputX * static_cast<float>(supersample) + 0.5f * static_cast<float>(supersample - 1);
    for (int row = 0; row < size; ++row) {
        skeleton.points.push_back({{dataX, static_cast<float>(row)}, 1.0f});
        skeleton.mask.at<uchar>(row, static_cast<int>(std::lround(dataX))) = 255;
    }
    return skeleton;
}

/** Sum and centroid of one row's coverage, in output pixels. */
struct CrossSection {
    double sum = 0.0;
    double centre = 0.0;
};

CrossSection crossSection(const cv::Mat& lines, int row) {
    CrossSection section;
    double weighted = 0.0;
    for (int col = 0; col < lines.cols; ++col) {
        const double coverage = lines.at<uchar>(row, col) / 255.0;
        section.sum += coverage;
        weighted += coverage * col;
    }
    section.centre = weighted / section.sum;
    return section;
}

cv::Point2d centroid(const cv::Mat& lines) {
    double sum = 0.0;
    cv::Point2d weighted(0.0, 0.0);
    for (int row = 0; row < lines.rows; ++row)
        for (int col = 0; col < lines.cols; ++col) {
            const double coverage = lines.at<uchar>(row, col) / 255.0;
            sum += coverage;
            weighted += coverage * cv::Point2d(col, row);
        }
    return weighted / sum;
}

TEST(LineSkeleton, FromMaskTakesEveryNonZeroPixelAtItsCentre) {
    cv::Mat mask = cv::Mat::zeros(3, 20, CV_8UC1);
    mask.at<uchar>(0, 3) = 51;   // faded: strength 0.2
    mask.at<uchar>(1, 17) = 255; // past the first eight-pixel word
    mask.at<uchar>(2, 19) = 255; // the last pixel
    const LineSkeleton skeleton = skeletonFromMask(mask);
    ASSERT_EQ(skeleton.mask.type(), CV_8UC1);
    ASSERT_EQ(skeleton.mask.size(), mask.size());
    EXPECT_EQ(cv::countNonZero(skeleton.mask), 3);
    EXPECT_EQ(skeleton.mask.at<uchar>(0, 3), 255) << "the skeleton mask is binary";
    ASSERT_EQ(skeleton.points.size(), 3u);
    EXPECT_EQ(skeleton.points[0].position, cv::Point2f(3.0f, 0.0f));
    EXPECT_FLOAT_EQ(skeleton.points[0].strength, 0.2f);
    EXPECT_EQ(skeleton.points[1].position, cv::Point2f(17.0f, 1.0f));
    EXPECT_FLOAT_EQ(skeleton.points[1].strength, 1.0f);
    EXPECT_EQ(skeleton.points[2].position, cv::Point2f(19.0f, 2.0f));
}

TEST(LineSkeleton, FromMaskRejectsWrongMasks) {
    EXPECT_THROW(skeletonFromMask(cv::Mat()), std::invalid_argument);
    EXPECT_THROW(skeletonFromMask(cv::Mat::zeros(4, 4, CV_32FC1)), std::invalid_argument);
    try {
        skeletonFromMask(cv::Mat::zeros(4, 4, CV_8UC3));
        FAIL() << "a 3-channel mask was accepted";
    } catch (const std::invalid_argument& error) {
        EXPECT_NE(std::string(error.what()).find("skeletonFromMask(): 'mask'"), std::string::npos) << error.what();
    }
}

TEST(StrokeLines, SinglePointIsTheAntiAliasedDisc) {
    // Narrow discs are stamped pixel by pixel, wide ones by runs per row: the same formula either way.
    for (const cv::Point2f centre : {cv::Point2f(20.0f, 20.0f), cv::Point2f(20.3f, 19.6f)}) {
        for (const float width : {1.0f, 2.0f, 3.0f, 30.0f, 35.5f}) {
            LineSkeleton skeleton = emptySkeleton(41, 41);
            skeleton.points.push_back({centre, 1.0f});
            const cv::Mat lines = strokeLines(skeleton, width, 1);
            ASSERT_EQ(lines.type(), CV_8UC1);
            ASSERT_EQ(lines.size(), cv::Size(41, 41));
            for (int row = 0; row < 41; ++row)
                for (int col = 0; col < 41; ++col) {
                    const float distance = std::hypot(col - centre.x, row - centre.y);
                    const float expected = 255.0f * discCoverage(0.5f * width, distance);
                    EXPECT_NEAR(lines.at<uchar>(row, col), expected, 0.51)
                        << "pixel (" << col << ", " << row << "), width " << width << ", centre " << centre;
                }
        }
    }
}

TEST(StrokeLines, SubPixelPositionMovesTheCentroid) {
    auto strokedCentroid = [](cv::Point2f position) {
        LineSkeleton skeleton = emptySkeleton(21, 21);
        skeleton.points.push_back({position, 1.0f});
        return centroid(strokeLines(skeleton, 2.0f, 1));
    };
    const cv::Point2d atCentre = strokedCentroid({10.0f, 10.0f});
    EXPECT_NEAR(atCentre.x, 10.0, 1e-6);
    EXPECT_NEAR(atCentre.y, 10.0, 1e-6);
    const cv::Point2d shifted = strokedCentroid({10.3f, 9.6f});
    EXPECT_NEAR(shifted.x - atCentre.x, 0.3, 0.05);
    EXPECT_NEAR(shifted.y - atCentre.y, -0.4, 0.05);
}

TEST(StrokeLines, LineWidthIsInOutputPixelsAtEverySupersample) {
    for (const int supersample : {1, 2, 4}) {
        for (const float width : {1.0f, 2.0f, 5.0f}) {
            const cv::Mat lines = strokeLines(verticalLine(48, supersample, 20.3f), width, supersample);
            ASSERT_EQ(lines.size(), cv::Size(48, 48));
            const CrossSection section = crossSection(lines, 24);
            EXPECT_NEAR(section.sum, width, 0.1) << "width " << width << " at supersample " << supersample;
            EXPECT_NEAR(section.centre, 20.3, 0.05) << "width " << width << " at supersample " << supersample;
        }
    }
}

TEST(StrokeLines, WideLineHasTheAnalyticCrossSection) {
    // 128 points of a 40-pixel disc each: at this density strokeLines draws by nearest point rather than per-point
    // stamping; the expected values are the same either way.
    LineSkeleton skeleton = verticalLine(64, 1, 31.3f);
    // A faded point before each full one, in the same pixel: the maximum is still the full disc.
    const std::vector<LinePoint> fullPoints = skeleton.points;
    skeleton.points.clear();
    for (const LinePoint& point : fullPoints) {
        skeleton.points.push_back({point.position + cv::Point2f(-0.1f, 0.0f), 0.3f});
        skeleton.points.push_back(point);
    }
    const cv::Mat lines = strokeLines(skeleton, 40.0f, 1);
    for (const int row : {0, 20, 63})
        for (int col = 0; col < 64; ++col)
            EXPECT_NEAR(lines.at<uchar>(row, col), 255.0f * discCoverage(20.0f, std::abs(col - 31.3f)), 0.51)
                << "pixel (" << col << ", " << row << ")";
    EXPECT_NEAR(crossSection(lines, 32).sum, 40.0, 0.1);
}

TEST(StrokeLines, StrengthScalesCoverage) {
    for (const float width : {3.0f, 30.0f}) {
        LineSkeleton full = emptySkeleton(41, 41);
        full.points.push_back({{20.2f, 19.9f}, 1.0f});
        LineSkeleton half = full;
        half.points[0].strength = 0.5f;
        const cv::Mat fullLines = strokeLines(full, width, 1);
        const cv::Mat halfLines = strokeLines(half, width, 1);
        EXPECT_EQ(halfLines.at<uchar>(20, 20), 128) << "full coverage at half strength, width " << width;
        for (int row = 0; row < 41; ++row)
            for (int col = 0; col < 41; ++col)
                EXPECT_NEAR(halfLines.at<uchar>(row, col), 0.5 * fullLines.at<uchar>(row, col), 1.0)
                    << "pixel (" << col << ", " << row << "), width " << width;
    }
}

TEST(StrokeLines, OverlappingDiscsCombineByMaximum) {
    LineSkeleton skeleton = emptySkeleton(9, 3);
    skeleton.points.push_back({{3.0f, 1.0f}, 0.4f});
    skeleton.points.push_back({{5.0f, 1.0f}, 1.0f});
    const cv::Mat lines = strokeLines(skeleton, 2.0f, 1);
    // Pixel 4 lies on both rims: 0.5 x 0.4 and 0.5. The maximum is 0.5; a sum would give 0.7, "over" 0.6.
    EXPECT_NEAR(lines.at<uchar>(1, 4), 128, 1);
    EXPECT_EQ(lines.at<uchar>(1, 3), 102) << "the faded disc alone: 0.4";
}

TEST(StrokeLines, WidthOf256PixelsOnA1024Frame) {
    // A full-height line: 1024 discs 256 pixels across.
    const cv::Mat lines = strokeLines(verticalLine(1024, 1, 500.0f), 256.0f, 1);
    for (const int row : {0, 511, 1023}) {
        EXPECT_EQ(lines.at<uchar>(row, 500 - 127), 255);
        EXPECT_EQ(lines.at<uchar>(row, 500 + 127), 255);
        EXPECT_NEAR(lines.at<uchar>(row, 500 + 128), 128, 1) << "half coverage on the rim";
        EXPECT_EQ(lines.at<uchar>(row, 500 + 129), 0);
        EXPECT_EQ(lines.at<uchar>(row, 500 - 129), 0);
    }
    EXPECT_NEAR(crossSection(lines, 700).sum, 256.0, 0.1);

    // A single point: a disc of radius 128.
    LineSkeleton point = emptySkeleton(1024, 1024);
    point.points.push_back({{300.0f, 700.0f}, 1.0f});
    const cv::Mat disc = strokeLines(point, 256.0f, 1);
    EXPECT_EQ(disc.at<uchar>(700 - 127, 300), 255);
    EXPECT_EQ(disc.at<uchar>(700 + 89, 300 + 89), 255) << "distance 125.9";
    EXPECT_EQ(disc.at<uchar>(700 + 91, 300 + 91), 0) << "distance 128.7";
}

TEST(StrokeLines, PointsOffTheImageDrawOnlyWhatReachesIt) {
    LineSkeleton skeleton = emptySkeleton(16, 16);
    skeleton.points.push_back({{-3.0f, 5.0f}, 1.0f});
    skeleton.points.push_back({{1e20f, -1e20f}, 1.0f});
    const cv::Mat lines = strokeLines(skeleton, 10.0f, 1);
    for (int col = 0; col < 16; ++col)
        EXPECT_NEAR(lines.at<uchar>(5, col), 255.0f * discCoverage(5.0f, col + 3.0f), 0.51) << "column " << col;
}

TEST(StrokeLines, RejectsInvalidArguments) {
    const LineSkeleton skeleton = emptySkeleton(12, 12);
    auto expectRejected = [](const LineSkeleton& input, float width, int supersample, const std::string& name) {
        try {
            strokeLines(input, width, supersample);
            ADD_FAILURE() << "accepted: " << name;
        } catch (const std::invalid_argument& error) {
            EXPECT_NE(std::string(error.what()).find("strokeLines(): '" + name + "'"), std::string::npos)
                << error.what();
        }
    };
    expectRejected(skeleton, std::numeric_limits<float>::quiet_NaN(), 1, "widthPixels");
    expectRejected(skeleton, std::numeric_limits<float>::infinity(), 1, "widthPixels");
    expectRejected(skeleton, 0.0f, 1, "widthPixels");
    expectRejected(skeleton, -2.0f, 1, "widthPixels");
    expectRejected(skeleton, 2.0f, 0, "supersample");
    expectRejected(skeleton, 2.0f, -2, "supersample");
    expectRejected(skeleton, 2.0f, 5, "supersample"); // 12 is not a multiple of 5
    expectRejected({cv::Mat::zeros(12, 12, CV_32FC1), {}}, 2.0f, 1, "skeleton.mask");
    expectRejected({cv::Mat(), {}}, 2.0f, 1, "skeleton.mask");
    LineSkeleton badPoint = skeleton;
    badPoint.points.push_back({{std::numeric_limits<float>::quiet_NaN(), 1.0f}, 1.0f});
    expectRejected(badPoint, 2.0f, 1, "skeleton.points");
    badPoint.points[0] = {{1.0f, 1.0f}, 0.0f};
    expectRejected(badPoint, 2.0f, 1, "skeleton.points");
    badPoint.points[0] = {{1.0f, 1.0f}, 1.5f};
    expectRejected(badPoint, 2.0f, 1, "skeleton.points");
    EXPECT_NO_THROW(strokeLines(skeleton, 2.0f, 4));
}

} // namespace
} // namespace inkgraph
