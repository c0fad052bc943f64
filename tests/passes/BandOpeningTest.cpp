// bandOpeningPixels() and openedBand() (passes/LineMaskTarget.h): the stroke stage opens a band of one width by a
// square a reference pixel wide at the band's size, never wider than half the band. No GL.
#include "passes/LineMaskTarget.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace inkgraph {
namespace {

TEST(BandOpening, IsAPixelAtTheReferenceSizeAndAtMostHalfTheBand) {
    EXPECT_EQ(bandOpeningPixels(2.0f, 512), 1);
    EXPECT_EQ(bandOpeningPixels(2.0f, 1024), 1);
    EXPECT_EQ(bandOpeningPixels(2.0f, 2047), 1);
    EXPECT_EQ(bandOpeningPixels(2.0f, 2048), 2); // a 4-pixel band
    EXPECT_EQ(bandOpeningPixels(3.0f, 2048), 2); // 6 pixels
    EXPECT_EQ(bandOpeningPixels(2.0f, 4096), 4); // 8 pixels
    // A 1-pixel line's band is 2 pixels at 2048 rows, where a square of 2 would break its diagonal stretches.
    EXPECT_EQ(bandOpeningPixels(1.0f, 2048), 1);
    EXPECT_EQ(bandOpeningPixels(1.0f, 4096), 2);
    EXPECT_EQ(bandOpeningPixels(0.5f, 4096), 1);
}

/** A frame `rows` square with a band `bandPixels` wide along a circle and a sliver one pixel wide across it. */
cv::Mat ringWithSliver(int rows, int bandPixels) {
    cv::Mat mask = cv::Mat::zeros(rows, rows, CV_8UC1);
    const cv::Point centre(rows / 2, rows / 2);
    cv::circle(mask, centre, rows / 4 + bandPixels / 2, 255, bandPixels, cv::LINE_8);
    cv::line(mask, {rows / 2, rows / 8}, {rows / 2 + rows / 3, rows / 8 + rows / 5}, 255, 1, cv::LINE_8);
    return mask;
}

TEST(BandOpening, DropsSliversAndKeepsTheBand) {
    // 2048 rows, a 2-pixel line: a 4-pixel band, opened by 2 x 2.
    const cv::Mat band = ringWithSliver(2048, 4);
    const cv::Mat opened = openedBand(band, 2.0f);
    cv::Mat ring = cv::Mat::zeros(band.size(), CV_8UC1);
    cv::circle(ring, {1024, 1024}, 512 + 2, 255, 4, cv::LINE_8);
    const cv::Mat sliver = band & ~ring;
    ASSERT_GT(cv::countNonZero(sliver), 500);
    EXPECT_EQ(cv::countNonZero(opened & sliver), 0) << "the one-pixel sliver is under a pixel at 1024 rows";
    // The ring's rasterised rim may lose a stair-step pixel; its width stays: nothing inside it goes.
    cv::Mat core = cv::Mat::zeros(band.size(), CV_8UC1);
    cv::circle(core, {1024, 1024}, 512 + 2, 255, 2, cv::LINE_8);
    EXPECT_EQ(cv::countNonZero(core & ~opened), 0);
    EXPECT_GE(cv::countNonZero(opened & ring), cv::countNonZero(ring) * 95 / 100);
    EXPECT_EQ(cv::countNonZero(opened & ~band), 0) << "an opening keeps a subset: nothing moves";

    // Where the model hides most of a band, what shows can narrow to a pixel for a few rows between full stretches:
    // that remnant stays, so the line is not cut there.
    cv::Mat waisted = cv::Mat::zeros(2048, 2048, CV_8UC1);
    waisted(cv::Rect(500, 100, 4, 200)).setTo(255);
    waisted(cv::Rect(500, 200, 4, 3)).setTo(0);
    waisted(cv::Rect(501, 200, 1, 3)).setTo(255);
    const cv::Mat waistOpened = openedBand(waisted, 2.0f);
    EXPECT_EQ(cv::countNonZero(waistOpened(cv::Rect(501, 200, 1, 3))), 3);
    EXPECT_EQ(cv::countNonZero(waistOpened != waisted), 0);

    // Up to 1024 rows nothing is opened: the band is returned as it is.
    const cv::Mat small = ringWithSliver(1024, 2);
    EXPECT_EQ(cv::countNonZero(openedBand(small, 2.0f) != small), 0);
}

} // namespace
} // namespace inkgraph
