// Material and object boundaries (one kernel over an id field) on synthetic id images: exact positions, nothing
// against the background, nothing inside one material, and bad input refused naming the field.
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

TEST(MaterialBoundaries, ObjectIdsGiveTheSameLinesAndMessagesNameTheirField) {
    // Object ids (issue 36's object-boundary) go through the same kernel: an L-shaped object 2 inside object 1 gives
    // a vertical run at x = 5.5 (rows 3..6) and a horizontal one at y = 2.5 (columns 6..9); the background none.
    cv::Mat ids = cv::Mat::zeros(10, 12, CV_32FC1);
    ids(cv::Rect(1, 1, 10, 8)).setTo(1.0f);
    ids(cv::Rect(6, 3, 5, 6)).setTo(2.0f);
    const LineSkeleton skeleton = extractIdBoundaries(ids, "objectId");
    std::size_t vertical = 0, horizontal = 0;
    for (const LinePoint& point : skeleton.points) {
        if (point.position.x == 5.5f && point.position.y >= 3.0f && point.position.y <= 8.0f) ++vertical;
        if (point.position.y == 2.5f && point.position.x >= 6.0f && point.position.x <= 10.0f) ++horizontal;
    }
    EXPECT_EQ(vertical, 6u);
    EXPECT_EQ(horizontal, 5u);
    EXPECT_EQ(skeleton.points.size(), 11u) << "nothing where an object meets the background";
    EXPECT_EQ(extractMaterialBoundaries(ids).points.size(), skeleton.points.size());
    try {
        extractIdBoundaries(cv::Mat(), "objectId");
        FAIL() << "an empty image was accepted";
    } catch (const std::invalid_argument& error) {
        EXPECT_STREQ(error.what(), "extractIdBoundaries(): 'objectId' must be a non-empty CV_32FC1 image");
    }
}

} // namespace
} // namespace inkgraph
