// Material boundaries on synthetic id images: exact positions, nothing against the background, nothing inside one
// material, and bad input refused.
#include "postfx/MaterialBoundaries.h"

#include <gtest/gtest.h>

#include <cmath>

namespace inkgraph {
namespace {

/** Ids: 0 (background) in the outer frame, `left` on columns [2, split), `right` on [split, cols - 2). */
cv::Mat twoMaterials(int rows, int cols, int split, float left, float right) {
    cv::Mat ids = cv::Mat::zeros(rows, cols, CV_32FC1);
    for (int row = 2; row < rows - 2; ++row)
        for (int col = 2; col < cols - 2; ++col) ids.at<float>(row, col) = col < split ? left : right;
    return ids;
}

TEST(MaterialBoundaries, ADifferentMaterialGivesOneLineOnTheSharedPixelEdge) {
    const cv::Mat ids = twoMaterials(20, 30, 13, 1.0f, 2.0f);
    const LineSkeleton skeleton = extractMaterialBoundaries(ids);
    // One point per covered row, on the edge between columns 12 and 13: x = 12.5 in pixel-centre coordinates.
    ASSERT_EQ(skeleton.points.size(), 16u);
    for (const LinePoint& point : skeleton.points) {
        EXPECT_FLOAT_EQ(point.position.x, 12.5f);
        EXPECT_GE(point.position.y, 2.0f);
        EXPECT_LE(point.position.y, 17.0f);
        EXPECT_EQ(point.strength, 1.0f);
    }
    EXPECT_EQ(cv::countNonZero(skeleton.mask), 16);
    EXPECT_EQ(cv::countNonZero(skeleton.mask.col(12)), 16);
}

TEST(MaterialBoundaries, OneMaterialAndTheBackgroundGiveNothing) {
    const LineSkeleton same = extractMaterialBoundaries(twoMaterials(20, 30, 13, 3.0f, 3.0f));
    EXPECT_TRUE(same.points.empty());
    EXPECT_EQ(cv::countNonZero(same.mask), 0);
    EXPECT_TRUE(extractMaterialBoundaries(cv::Mat::zeros(8, 8, CV_32FC1)).points.empty());
}

TEST(MaterialBoundaries, HorizontalBoundariesLieBetweenRows) {
    cv::Mat ids = cv::Mat::zeros(10, 10, CV_32FC1);
    ids.rowRange(0, 4).setTo(5.0f);
    ids.rowRange(4, 10).setTo(6.0f);
    const LineSkeleton skeleton = extractMaterialBoundaries(ids);
    ASSERT_EQ(skeleton.points.size(), 10u);
    for (const LinePoint& point : skeleton.points) EXPECT_FLOAT_EQ(point.position.y, 3.5f);
}

TEST(MaterialBoundaries, RefusesWhatIsNotAnIdImage) {
    EXPECT_THROW(extractMaterialBoundaries(cv::Mat()), std::invalid_argument);
    EXPECT_THROW(extractMaterialBoundaries(cv::Mat::zeros(4, 4, CV_8UC1)), std::invalid_argument);
}

} // namespace
} // namespace inkgraph
