// Shade maps on the CPU: band levels and borders, the default comic map, and the checks on images read from files.
// No GL.
#include "passes/shade/ShadeMap.h"

#include "tests/support/ThrowMessage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

/** Linear value of an 8-bit sRGB code (the inverse of the encode the maps use). */
double decodeSrgb(int code) {
    const double encoded = code / 255.0;
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

/** The texel a shader picks for coordinate u in [0, 1]: i = min(floor(u N), N - 1). */
int texelIndex(double u, int count) { return std::min(int(std::floor(u * count)), count - 1); }

using test::invalidArgumentMessage;

TEST(ShadeMap, FiveBandsAreSeed003Levels) {
    const ShadeMap map = makeBandShadeMap(5);
    ASSERT_EQ(map.texels.type(), CV_8UC4);
    ASSERT_EQ(map.texels.size(), cv::Size(5, 1));
    EXPECT_TRUE(map.isOneDimensional());
    EXPECT_EQ(map.source, "builtin:bands-5");
    const double levels[] = {0.0, 0.25, 0.5, 0.75, 1.0};
    for (int i = 0; i < 5; ++i) {
        const cv::Vec4b texel = map.texels.at<cv::Vec4b>(0, i);
        EXPECT_EQ(texel[0], texel[1]);
        EXPECT_EQ(texel[0], texel[2]);
        EXPECT_EQ(texel[3], 255);
        // Stored as sRGB codes of linear levels: rounding moves a level by at most half a code step, under 0.005
        // linear up to 1 (a step is 0.0096 linear at the top of the range).
        EXPECT_NEAR(decodeSrgb(texel[0]), levels[i], 0.005) << "band " << i;
    }
    // The usual sRGB codes of the levels.
    EXPECT_EQ(map.texels.at<cv::Vec4b>(0, 0)[0], 0);
    EXPECT_EQ(map.texels.at<cv::Vec4b>(0, 1)[0], 137);
    EXPECT_EQ(map.texels.at<cv::Vec4b>(0, 2)[0], 188);
    EXPECT_EQ(map.texels.at<cv::Vec4b>(0, 3)[0], 225);
    EXPECT_EQ(map.texels.at<cv::Vec4b>(0, 4)[0], 255);
}

TEST(ShadeMap, FiveBandBordersSitAtQuarterFifths) {
    // Qu, Chen & Zwicker's eq. 4: level 0 below q = .2, .25 up to .4, .5 up to .6, .75 up to .8, 1 above. The same
    // texel rule as the shader, on both sides of every border.
    const int bands = makeBandShadeMap(5).texels.cols;
    const double borders[] = {0.2, 0.4, 0.6, 0.8};
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(texelIndex(borders[k] - 1e-6, bands), k) << "below border " << borders[k];
        EXPECT_EQ(texelIndex(borders[k] + 1e-6, bands), k + 1) << "above border " << borders[k];
    }
    EXPECT_EQ(texelIndex(0.0, bands), 0);
    EXPECT_EQ(texelIndex(1.0, bands), 4) << "q = 1 (n = l) must stay on the last texel, never wrap";
    // The closed form of docs/shading.md agrees away from the borders.
    for (double q = 0.01; q < 1.0; q += 0.02) {
        const double closedForm = std::clamp(std::ceil(5.0 * q - 1.0) / 4.0, 0.0, 1.0);
        EXPECT_DOUBLE_EQ(texelIndex(q, bands) / 4.0, closedForm) << "q = " << q;
    }
}

TEST(ShadeMap, BandLevelsForOtherCounts) {
    const ShadeMap two = makeBandShadeMap(2);
    EXPECT_EQ(two.texels.cols, 2);
    EXPECT_EQ(two.texels.at<cv::Vec4b>(0, 0)[0], 0);
    EXPECT_EQ(two.texels.at<cv::Vec4b>(0, 1)[0], 255);
    const ShadeMap three = makeBandShadeMap(3);
    EXPECT_NEAR(decodeSrgb(three.texels.at<cv::Vec4b>(0, 1)[0]), 0.5, 0.005);
    const ShadeMap most = makeBandShadeMap(256);
    ASSERT_EQ(most.texels.cols, 256);
    for (int i = 1; i < 256; ++i)
        EXPECT_GE(most.texels.at<cv::Vec4b>(0, i)[0], most.texels.at<cv::Vec4b>(0, i - 1)[0]) << "monotonic at " << i;
    EXPECT_EQ(most.texels.at<cv::Vec4b>(0, 255)[0], 255);
}

TEST(ShadeMap, BandCountOutsideTwoTo256IsRejected) {
    EXPECT_EQ(invalidArgumentMessage([] { makeBandShadeMap(1); }),
              "makeBandShadeMap(): bands must be between 2 and 256, got 1");
    EXPECT_EQ(invalidArgumentMessage([] { makeBandShadeMap(257); }),
              "makeBandShadeMap(): bands must be between 2 and 256, got 257");
    EXPECT_EQ(invalidArgumentMessage([] { makeBandShadeMap(0); }),
              "makeBandShadeMap(): bands must be between 2 and 256, got 0");
}

TEST(ShadeMap, DefaultComicMapHasTwoTonesAndAHighlight) {
    const ShadeMap map = makeDefaultComicShadeMap();
    ASSERT_EQ(map.texels.type(), CV_8UC4);
    EXPECT_FALSE(map.isOneDimensional());
    EXPECT_EQ(map.source, "builtin:comic");
    const int rows = map.texels.rows;
    const int cols = map.texels.cols;
    // Bottom row (t = 0): dark left, lit right; top row (t = 1): the highlight everywhere.
    const uchar shadow = map.texels.at<cv::Vec4b>(rows - 1, 0)[0];
    const uchar lit = map.texels.at<cv::Vec4b>(rows - 1, cols - 1)[0];
    const uchar highlight = map.texels.at<cv::Vec4b>(0, cols - 1)[0];
    EXPECT_LT(shadow, lit);
    EXPECT_LT(lit, highlight);
    EXPECT_EQ(highlight, 255);
    // Grey only, opaque, and exactly three tones.
    std::set<int> tones;
    for (int row = 0; row < rows; ++row) {
        for (int col = 0; col < cols; ++col) {
            const cv::Vec4b texel = map.texels.at<cv::Vec4b>(row, col);
            EXPECT_EQ(texel[0], texel[1]);
            EXPECT_EQ(texel[0], texel[2]);
            EXPECT_EQ(texel[3], 255);
            tones.insert(texel[0]);
        }
    }
    EXPECT_EQ(tones.size(), 3u);
    // The documented borders: s = 0.25 between the tones, t = 0.5 below the highlight.
    EXPECT_EQ(map.texels.at<cv::Vec4b>(rows - 1, texelIndex(0.25 - 1e-6, cols))[0], shadow);
    EXPECT_EQ(map.texels.at<cv::Vec4b>(rows - 1, texelIndex(0.25 + 1e-6, cols))[0], lit);
    EXPECT_EQ(map.texels.at<cv::Vec4b>(rows - 1 - texelIndex(0.5 - 1e-6, rows), cols - 1)[0], lit);
    EXPECT_EQ(map.texels.at<cv::Vec4b>(rows - 1 - texelIndex(0.5 + 1e-6, rows), cols - 1)[0], highlight);
}

TEST(ShadeMap, GreyImagesBecomeRgb) {
    cv::Mat grey(1, 3, CV_8UC1);
    grey.at<uchar>(0, 0) = 10;
    grey.at<uchar>(0, 1) = 128;
    grey.at<uchar>(0, 2) = 250;
    const ShadeMap map = shadeMapFromImage(grey, "ramp.png", true);
    ASSERT_EQ(map.texels.type(), CV_8UC4);
    ASSERT_EQ(map.texels.size(), cv::Size(3, 1));
    EXPECT_EQ(map.source, "ramp.png");
    EXPECT_EQ(map.texels.at<cv::Vec4b>(0, 0), cv::Vec4b(10, 10, 10, 255));
    EXPECT_EQ(map.texels.at<cv::Vec4b>(0, 1), cv::Vec4b(128, 128, 128, 255));
    EXPECT_EQ(map.texels.at<cv::Vec4b>(0, 2), cv::Vec4b(250, 250, 250, 255));

    cv::Mat greyAlpha(2, 1, CV_8UC2, cv::Scalar(77, 3));
    EXPECT_EQ(shadeMapFromImage(greyAlpha, "ga.png", false).texels.at<cv::Vec4b>(1, 0), cv::Vec4b(77, 77, 77, 255));
}

TEST(ShadeMap, ColourImagesKeepTheirChannelsAndDropAlpha) {
    cv::Mat rgb(2, 2, CV_8UC3, cv::Scalar(1, 2, 3));
    rgb.at<cv::Vec3b>(1, 0) = cv::Vec3b(200, 100, 50);
    const ShadeMap fromRgb = shadeMapFromImage(rgb, "rgb.png", false);
    EXPECT_FALSE(fromRgb.isOneDimensional());
    EXPECT_EQ(fromRgb.texels.at<cv::Vec4b>(0, 0), cv::Vec4b(1, 2, 3, 255));
    EXPECT_EQ(fromRgb.texels.at<cv::Vec4b>(1, 0), cv::Vec4b(200, 100, 50, 255)) << "rows keep their order";

    cv::Mat rgba(1, 2, CV_8UC4, cv::Scalar(9, 8, 7, 0));
    EXPECT_EQ(shadeMapFromImage(rgba, "rgba.png", true).texels.at<cv::Vec4b>(0, 1), cv::Vec4b(9, 8, 7, 255));

    // A view into a larger image (not continuous) converts the same.
    cv::Mat big(4, 4, CV_8UC3, cv::Scalar(5, 6, 7));
    const ShadeMap fromRoi = shadeMapFromImage(big(cv::Rect(1, 1, 2, 2)), "roi", false);
    EXPECT_EQ(fromRoi.texels.size(), cv::Size(2, 2));
    EXPECT_EQ(fromRoi.texels.at<cv::Vec4b>(1, 1), cv::Vec4b(5, 6, 7, 255));
}

TEST(ShadeMap, BadImagesAreRejectedNamingTheSource) {
    EXPECT_EQ(invalidArgumentMessage([] { shadeMapFromImage(cv::Mat(), "empty.png", false); }),
              "shadeMapFromImage(): 'empty.png' is empty");
    EXPECT_EQ(invalidArgumentMessage([] { shadeMapFromImage(cv::Mat(2, 8, CV_8UC3), "two-rows.png", true); }),
              "shadeMapFromImage(): 'two-rows.png' has 2 rows; a 1-D shade map must be a single row");
    EXPECT_EQ(invalidArgumentMessage([] { shadeMapFromImage(cv::Mat(1, 4097, CV_8UC1), "wide.png", true); }),
              "shadeMapFromImage(): 'wide.png' is 4097x1 (at most 4096 a side)");
    EXPECT_EQ(invalidArgumentMessage([] { shadeMapFromImage(cv::Mat(4097, 1, CV_8UC1), "tall.png", false); }),
              "shadeMapFromImage(): 'tall.png' is 1x4097 (at most 4096 a side)");
    EXPECT_EQ(invalidArgumentMessage([] { shadeMapFromImage(cv::Mat(1, 4, CV_32FC3), "float.exr", true); }),
              "shadeMapFromImage(): 'float.exr' is not an 8-bit image (a shade map holds 8-bit sRGB colours)");
    EXPECT_EQ(invalidArgumentMessage([] { shadeMapFromImage(cv::Mat(1, 4, CV_8UC(5)), "five.tif", true); }),
              "shadeMapFromImage(): 'five.tif' has 5 channels (1 to 4 are allowed)");
    // The largest allowed maps pass.
    EXPECT_NO_THROW(shadeMapFromImage(cv::Mat(1, 4096, CV_8UC1, cv::Scalar(0)), "max.png", true));
    EXPECT_NO_THROW(shadeMapFromImage(cv::Mat(4096, 2, CV_8UC1, cv::Scalar(0)), "max.png", false));
}

TEST(SpecularRowBands, BordersMoveToTheDistanceDomainExactly) {
    // 8 rows, bottom 5 one tone, top 3 another: one border at t = 5/8, between bottom rows 4 and 5.
    ShadeMap map{cv::Mat(8, 4, CV_8UC4, cv::Scalar(50, 50, 50, 255)), "test"};
    map.texels.rowRange(0, 3).setTo(cv::Scalar(250, 250, 250, 255));
    const SpecularRowBands bands = specularRowBands(map, 32.0);
    ASSERT_EQ(bands.firstRow, (std::vector<int>{0, 5}));
    ASSERT_EQ(bands.maxHalfSquaredDistance.size(), 1u);
    // At the border t = (1 - x)^32 = 5/8 exactly.
    EXPECT_NEAR(std::pow(1.0 - bands.maxHalfSquaredDistance[0], 32.0), 5.0 / 8.0, 1e-12);
    // Shininess 1e6: the border lies 4.7e-7 from r = v, still a positive, representable distance.
    const SpecularRowBands sharp = specularRowBands(map, 1e6);
    EXPECT_NEAR(sharp.maxHalfSquaredDistance[0], -std::log(5.0 / 8.0) / 1e6, 1e-12);
    EXPECT_GT(sharp.maxHalfSquaredDistance[0], 0.0);
    // Shininess 0: t = 1 wherever lit, so every x passes every border.
    EXPECT_GT(specularRowBands(map, 0.0).maxHalfSquaredDistance[0], 2.0);
}

TEST(SpecularRowBands, EveryDistinctRowIsABand) {
    const ShadeMap comic = makeDefaultComicShadeMap();
    const SpecularRowBands bands = specularRowBands(comic, 16.0);
    ASSERT_EQ(bands.firstRow.size(), 2u) << "tones below and a highlight above t = 0.5";
    EXPECT_EQ(bands.firstRow[1], comic.texels.rows / 2);
    // A gradient map has a band per row; the borders decrease (higher t needs r closer to v).
    ShadeMap gradient{cv::Mat(16, 2, CV_8UC4), "gradient"};
    for (int row = 0; row < 16; ++row) gradient.texels.row(row).setTo(cv::Scalar(row * 10, 0, 0, 255));
    const SpecularRowBands many = specularRowBands(gradient, 8.0);
    ASSERT_EQ(many.firstRow.size(), 16u);
    for (std::size_t i = 1; i < many.maxHalfSquaredDistance.size(); ++i)
        EXPECT_LT(many.maxHalfSquaredDistance[i], many.maxHalfSquaredDistance[i - 1]);
    EXPECT_EQ(specularRowBands(makeBandShadeMap(4), 8.0).firstRow.size(), 1u) << "one row, one band";
    EXPECT_THROW(specularRowBands(gradient, -1.0), std::invalid_argument);
}

} // namespace
} // namespace inkgraph
