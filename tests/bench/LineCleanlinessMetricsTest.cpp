// The line-cleanliness measures (bench/LineCleanlinessMetrics.h) on inputs whose answers are known by hand.
#include "bench/LineCleanlinessMetrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace inkgraph::bench {
namespace {

TEST(InkShare, CountsInkOnAndOffTheModelAtTheThreshold) {
    cv::Mat coverage = cv::Mat::zeros(4, 4, CV_8UC1);
    coverage(cv::Rect(0, 0, 2, 4)).setTo(255); // 8 model pixels: the left half
    cv::Mat first = cv::Mat::zeros(4, 4, CV_8UC1);
    cv::Mat second = cv::Mat::zeros(4, 4, CV_8UC1);
    first.at<std::uint8_t>(0, 0) = 128;  // ink, on the model
    first.at<std::uint8_t>(1, 0) = 127;  // just below the threshold: not ink
    second.at<std::uint8_t>(1, 0) = 200; // but the other layer inks it
    second.at<std::uint8_t>(0, 3) = 255; // ink off the model
    const InkShare share = measureInkShare(coverage, {first, second});
    EXPECT_EQ(share.modelPixels, 8u);
    EXPECT_EQ(share.inkInsideModel, 2u);
    EXPECT_EQ(share.inkOutsideModel, 1u);
    EXPECT_DOUBLE_EQ(share.insideShare, 0.25);
    EXPECT_DOUBLE_EQ(share.outsideShare, 0.125);
}

TEST(InkShare, NoModelAndNoLayersGiveZeroShares) {
    const InkShare share = measureInkShare(cv::Mat::zeros(3, 3, CV_8UC1), {});
    EXPECT_EQ(share.modelPixels, 0u);
    EXPECT_EQ(share.insideShare, 0.0);
}

TEST(InkShare, RefusesMismatchedLayersAndBadThresholds) {
    const cv::Mat coverage = cv::Mat::zeros(4, 4, CV_8UC1);
    EXPECT_THROW(measureInkShare(coverage, {cv::Mat::zeros(4, 5, CV_8UC1)}), std::invalid_argument);
    EXPECT_THROW(measureInkShare(coverage, {cv::Mat::zeros(4, 4, CV_32FC1)}), std::invalid_argument);
    EXPECT_THROW(measureInkShare(coverage, {}, 0), std::invalid_argument);
    EXPECT_THROW(measureInkShare(cv::Mat(), {}), std::invalid_argument);
}

TEST(PathLength, SumsSegmentsAndTheClosingOne) {
    EXPECT_DOUBLE_EQ(pathLength({{0, 0}, {3, 4}}, false), 5.0);
    EXPECT_DOUBLE_EQ(pathLength({{2.5, 2.5}, {2.5, 2.5}}, false), 0.0); // "M x y L x y" at one place
    EXPECT_DOUBLE_EQ(pathLength({{1, 1}}, false), 0.0);
    EXPECT_DOUBLE_EQ(pathLength({{0, 0}, {2, 0}, {2, 2}, {0, 2}}, false), 6.0);
    EXPECT_DOUBLE_EQ(pathLength({{0, 0}, {2, 0}, {2, 2}, {0, 2}}, true), 8.0);
    EXPECT_THROW(pathLength({}, false), std::invalid_argument);
}

TEST(PathLengths, ShortShareIsStrictlyBelowTheThresholdAndTheMedianIsTheMiddle) {
    const PathLengthSummary odd = summarisePathLengths({10.0, 0.0, 3.0, 2.99, 1.0});
    EXPECT_EQ(odd.pathCount, 5u);
    EXPECT_EQ(odd.shortPathCount, 3u); // 0, 1, 2.99; 3 is not shorter than 3
    EXPECT_DOUBLE_EQ(odd.shortShare, 0.6);
    EXPECT_DOUBLE_EQ(odd.medianLength, 2.99);
    const PathLengthSummary even = summarisePathLengths({4.0, 1.0, 2.0, 8.0});
    EXPECT_DOUBLE_EQ(even.medianLength, 3.0);
    const PathLengthSummary none = summarisePathLengths({});
    EXPECT_EQ(none.pathCount, 0u);
    EXPECT_EQ(none.shortShare, 0.0);
    EXPECT_EQ(none.medianLength, 0.0);
    EXPECT_THROW(summarisePathLengths({-1.0}), std::invalid_argument);
    EXPECT_THROW(summarisePathLengths({1.0}, 0.0), std::invalid_argument);
}

TEST(SkeletonPoints, AThreePixelBarThinsToItsMiddleRowAndFaintPixelsAreNoInk) {
    cv::Mat layer = cv::Mat::zeros(9, 20, CV_8UC1);
    layer(cv::Rect(2, 3, 16, 3)).setTo(255); // rows 3 to 5
    layer.row(7).setTo(127);                 // anti-aliased fringe below the ink threshold
    const std::vector<cv::Point2d> points = skeletonPoints(layer);
    ASSERT_FALSE(points.empty());
    for (const cv::Point2d& point : points) {
        EXPECT_EQ(point.y, 4.0);
        EXPECT_GE(point.x, 2.0);
        EXPECT_LE(point.x, 17.0);
    }
    EXPECT_GE(points.size(), 12u); // Zhang-Suen may shorten each end by about half the width
    EXPECT_TRUE(skeletonPoints(cv::Mat::zeros(5, 5, CV_8UC1)).empty());
    EXPECT_THROW(skeletonPoints(cv::Mat::zeros(5, 5, CV_32FC1)), std::invalid_argument);
}

TEST(ToSmallerImage, KeepsPixelCentresAtIntegers) {
    const auto mapped = toSmallerImage({{0, 0}, {1, 1}, {2047, 6}}, 2.0);
    EXPECT_DOUBLE_EQ(mapped[0].x, -0.25);
    EXPECT_DOUBLE_EQ(mapped[1].x, 0.25);
    EXPECT_DOUBLE_EQ(mapped[2].x, 1023.25);
    EXPECT_DOUBLE_EQ(mapped[2].y, 2.75);
    EXPECT_THROW(toSmallerImage({}, 0.0), std::invalid_argument);
}

TEST(CountWithin, IsExactAtTheTolerance) {
    const std::vector<cv::Point2d> reference{{10, 10}};
    EXPECT_EQ(countWithin({{11.5, 10}, {11.51, 10}, {10, 8.5}, {11, 11}}, reference, 1.5), 3u);
    EXPECT_EQ(countWithin({{10, 10}}, reference, 0.0), 1u);
    EXPECT_EQ(countWithin({{10, 10}}, {}, 1.5), 0u);
    // Far points and negative coordinates land in other grid cells, not in a wrapped one.
    EXPECT_EQ(countWithin({{-10, 10}, {1e6, 10}, {-1, -1}}, {{-0.5, -0.5}}, 1.5), 1u);
    EXPECT_THROW(countWithin({{NAN, 0}}, reference, 1.5), std::invalid_argument);
    EXPECT_THROW(countWithin({}, reference, -1.0), std::invalid_argument);
}

TEST(PointSetAgreement, ScoresEachSetAgainstTheOther) {
    std::vector<cv::Point2d> line;
    for (int x = 0; x < 10; ++x) line.emplace_back(x, 5);
    EXPECT_DOUBLE_EQ(comparePointSets(line, line, 1.5).f1, 1.0);

    std::vector<cv::Point2d> shiftedByOne = line;
    for (auto& point : shiftedByOne) point.y += 1.0;
    EXPECT_DOUBLE_EQ(comparePointSets(line, shiftedByOne, 1.5).f1, 1.0);
    std::vector<cv::Point2d> shiftedByTwo = line;
    for (auto& point : shiftedByTwo) point.y += 2.0;
    EXPECT_DOUBLE_EQ(comparePointSets(line, shiftedByTwo, 1.5).f1, 0.0);

    // The second set has the line plus 10 stray points: precision 1, recall 10 / 20, F1 2/3.
    std::vector<cv::Point2d> withStrays = line;
    for (int x = 0; x < 10; ++x) withStrays.emplace_back(x, 50);
    const PointSetAgreement partial = comparePointSets(line, withStrays, 1.5);
    EXPECT_DOUBLE_EQ(partial.precision, 1.0);
    EXPECT_DOUBLE_EQ(partial.recall, 0.5);
    EXPECT_NEAR(partial.f1, 2.0 / 3.0, 1e-12);
}

TEST(PointSetAgreement, EmptyCasesFollowLineMetrics) {
    EXPECT_DOUBLE_EQ(agreementFromCounts(0, 0, 0, 0).f1, 1.0);
    const PointSetAgreement firstEmpty = agreementFromCounts(0, 0, 5, 0);
    EXPECT_DOUBLE_EQ(firstEmpty.precision, 1.0);
    EXPECT_DOUBLE_EQ(firstEmpty.recall, 0.0);
    EXPECT_DOUBLE_EQ(firstEmpty.f1, 0.0);
    const PointSetAgreement secondEmpty = agreementFromCounts(5, 0, 0, 0);
    EXPECT_DOUBLE_EQ(secondEmpty.precision, 0.0);
    EXPECT_DOUBLE_EQ(secondEmpty.recall, 1.0);
    EXPECT_DOUBLE_EQ(secondEmpty.f1, 0.0);
    EXPECT_THROW(agreementFromCounts(1, 2, 0, 0), std::invalid_argument);
}

TEST(CompareAcrossSizes, MapsTheLargerSkeletonOntoTheSmallerGridWithTheToleranceInSmallerPixels) {
    // A horizontal line at row 5 of the smaller image, drawn at twice the size on row 11 (rows 10 and 11 cover the
    // smaller row 5; the thinned line may take either): row 11 maps to (11 + 0.5) / 2 - 0.5 = 5.25, x 0..19 to
    // -0.25..9.25.
    std::vector<cv::Point2d> smaller;
    std::vector<cv::Point2d> larger;
    for (int x = 0; x < 10; ++x) smaller.emplace_back(x, 5);
    for (int x = 0; x < 20; ++x) larger.emplace_back(x, 11);
    const PointSetAgreement same = compareAcrossSizes(smaller, larger, 2.0, 1.5);
    EXPECT_EQ(same.firstCount, 10u); // precision is the smaller image's share
    EXPECT_EQ(same.secondCount, 20u);
    EXPECT_DOUBLE_EQ(same.f1, 1.0);

    // The tolerance is in smaller pixels: (21, 13) maps to (10.25, 6.25), exactly 1.5 from (10.25, 4.75) (3 apart in
    // the larger image's pixels).
    EXPECT_DOUBLE_EQ(compareAcrossSizes({{10.25, 4.75}}, {{21, 13}}, 2.0, 1.5).f1, 1.0);
    EXPECT_DOUBLE_EQ(compareAcrossSizes({{10.25, 4.74}}, {{21, 13}}, 2.0, 1.5).f1, 0.0);

    // The line drawn two smaller rows lower at the larger size (row 15 -> 7.25): 2.25 px apart, nothing agrees.
    std::vector<cv::Point2d> lower;
    for (int x = 0; x < 20; ++x) lower.emplace_back(x, 15);
    EXPECT_DOUBLE_EQ(compareAcrossSizes(smaller, lower, 2.0, 1.5).f1, 0.0);
    // The larger line's right half missing: its points all agree (recall 1), the smaller's only up to x = 5.
    const std::vector<cv::Point2d> half(larger.begin(), larger.begin() + 10); // x 0..9 -> -0.25..4.25
    const PointSetAgreement partial = compareAcrossSizes(smaller, half, 2.0, 1.5);
    EXPECT_EQ(partial.firstWithin, 6u); // x = 0..5: 5 is within 1.5 of (4.25, 5.25) (distance 0.79)
    EXPECT_EQ(partial.secondWithin, 10u);
    EXPECT_THROW(compareAcrossSizes(smaller, larger, 0.0, 1.5), std::invalid_argument);
    EXPECT_THROW(compareAcrossSizes(smaller, larger, 2.0, -1.0), std::invalid_argument);
}

TEST(SmallestF1, IsTheWorstComparison) {
    EXPECT_DOUBLE_EQ(
        smallestF1({agreementFromCounts(4, 4, 4, 4), agreementFromCounts(4, 2, 4, 4), agreementFromCounts(0, 0, 0, 0)}),
        2.0 * 0.5 / 1.5);
    EXPECT_DOUBLE_EQ(smallestF1({agreementFromCounts(0, 0, 3, 0)}), 0.0);
    EXPECT_THROW(smallestF1({}), std::invalid_argument);
}

/** OpenGL's gluPerspective for a square image, fov 90 degrees: x_ndc = x / -z. */
cv::Matx44d squarePerspective(double near, double far) {
    return cv::Matx44d(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -(far + near) / (far - near), -2 * far * near / (far - near), 0, 0,
                       -1, 0);
}

PinholeView viewAt(double eyeX, cv::Size size) {
    PinholeView view;
    view.view = cv::Matx44d(1, 0, 0, -eyeX, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1); // looking down -z from (eyeX, 0, 0)
    view.projection = squarePerspective(0.1, 100.0);
    view.size = size;
    return view;
}

TEST(Reprojection, ASideStepShiftsAPlaneByFocalTimesStepOverDepth) {
    // A plane at depth 10 fills both views; focal length in pixels is width / 2 = 50 at fov 90. Moving the eye by
    // +0.4 in x moves every point by -50 * 0.4 / 10 = -2 px.
    const cv::Size size(100, 100);
    const cv::Mat depth(size, CV_32FC1, cv::Scalar(10.0f));
    const Reprojection moved =
        reprojectPoints({{50, 50}, {20, 70}}, depth, viewAt(0.0, size), depth, viewAt(0.4, size));
    ASSERT_EQ(moved.points.size(), 2u);
    EXPECT_NEAR(moved.points[0].x, 48.0, 1e-9);
    EXPECT_NEAR(moved.points[0].y, 50.0, 1e-9);
    EXPECT_NEAR(moved.points[1].x, 18.0, 1e-9);
    EXPECT_NEAR(moved.points[1].y, 70.0, 1e-9);

    const Reprojection same = reprojectPoints({{3, 97}}, depth, viewAt(0.0, size), depth, viewAt(0.0, size));
    ASSERT_EQ(same.points.size(), 1u);
    EXPECT_NEAR(same.points[0].x, 3.0, 1e-9);
    EXPECT_NEAR(same.points[0].y, 97.0, 1e-9);
}

TEST(Reprojection, DropsPointsWithoutDepthOutsideTheFrameOrHidden) {
    const cv::Size size(100, 100);
    cv::Mat sourceDepth(size, CV_32FC1, cv::Scalar(10.0f));
    sourceDepth(cv::Rect(0, 0, 10, 10)).setTo(0.0f); // off the model
    // Off the model by one pixel: takes the surface within the search radius.
    cv::Mat targetDepth(size, CV_32FC1, cv::Scalar(10.0f));
    targetDepth(cv::Rect(60, 0, 40, 100)).setTo(5.0f); // something nearer covers the right of the target
    const Reprojection result = reprojectPoints({{2, 2}, {11, 11}, {1, 50}, {80, 50}}, sourceDepth, viewAt(0.0, size),
                                                targetDepth, viewAt(0.4, size));
    EXPECT_EQ(result.withoutDepth, 1u);   // (2, 2): no model pixel within 2 px
    EXPECT_EQ(result.outsideFrame, 1u);   // (1, 50) lands at x = -1
    EXPECT_EQ(result.hiddenInTarget, 1u); // (80, 50) lands at 78, where the target sees depth 5
    ASSERT_EQ(result.points.size(), 1u);  // (11, 11), next to the hole, takes depth 10
    EXPECT_NEAR(result.points[0].x, 9.0, 1e-9);

    EXPECT_THROW(reprojectPoints({}, cv::Mat(size, CV_8UC1), viewAt(0, size), targetDepth, viewAt(0, size)),
                 std::invalid_argument);
    EXPECT_THROW(reprojectPoints({}, sourceDepth, viewAt(0, size), targetDepth, viewAt(0, size), 0.0),
                 std::invalid_argument);
}

TEST(CompareAcrossViews, ReprojectsBothWaysAndLeavesOutWhatLeavesTheFrame) {
    // A plane at depth 10 in both views; the second view's eye is 0.4 to the right, so a point moves by -2 px.
    const cv::Size size(100, 100);
    const cv::Mat depth(size, CV_32FC1, cv::Scalar(10.0f));
    std::vector<cv::Point2d> first;
    for (int y = 10; y < 90; ++y) first.emplace_back(50, y);
    first.emplace_back(1, 50); // lands at x = -1 in the second view: left out, not counted as a miss
    const auto line = [](double x) {
        std::vector<cv::Point2d> points;
        for (int y = 10; y < 90; ++y) points.emplace_back(x, y);
        return points;
    };
    const ViewAgreement exact =
        compareAcrossViews(first, depth, viewAt(0.0, size), line(48), depth, viewAt(0.4, size), 1.5);
    EXPECT_EQ(exact.firstInSecond.outsideFrame, 1u);
    EXPECT_EQ(exact.agreement.firstCount, 80u);
    EXPECT_EQ(exact.agreement.secondCount, 80u);
    EXPECT_DOUBLE_EQ(exact.agreement.f1, 1.0);
    ASSERT_EQ(exact.secondInFirst.points.size(), 80u);
    EXPECT_NEAR(exact.secondInFirst.points[0].x, 50.0, 1e-9);

    // The second view's line one pixel off where the first's lands (47 against 48): within 1.5 both ways.
    EXPECT_DOUBLE_EQ(
        compareAcrossViews(first, depth, viewAt(0.0, size), line(47), depth, viewAt(0.4, size), 1.5).agreement.f1, 1.0);
    // Two pixels off (46): A's points land at 48, B's at 48 against A's 50, nothing within 1.5 either way.
    const ViewAgreement apart =
        compareAcrossViews(first, depth, viewAt(0.0, size), line(46), depth, viewAt(0.4, size), 1.5);
    EXPECT_EQ(apart.agreement.firstWithin, 0u);
    EXPECT_EQ(apart.agreement.secondWithin, 0u);
    EXPECT_DOUBLE_EQ(apart.agreement.f1, 0.0);
    // At a tolerance of 2 the same two lines agree.
    EXPECT_DOUBLE_EQ(
        compareAcrossViews(first, depth, viewAt(0.0, size), line(46), depth, viewAt(0.4, size), 2.0).agreement.f1, 1.0);
    // The second view drew only half the line (rows 10..49): recall (B's share) is 1, precision (A's share) 41 / 80.
    std::vector<cv::Point2d> halfLine = line(48);
    halfLine.resize(40); // rows 10..49
    const ViewAgreement half =
        compareAcrossViews(first, depth, viewAt(0.0, size), halfLine, depth, viewAt(0.4, size), 1.5);
    EXPECT_EQ(half.agreement.firstWithin, 41u); // rows 10..50: 50 is 1 from row 49, 51 is 2
    EXPECT_DOUBLE_EQ(half.agreement.recall, 1.0);
    EXPECT_THROW(compareAcrossViews(first, depth, viewAt(0.0, size), line(48), depth, viewAt(0.4, size), -1.0),
                 std::invalid_argument);
}

TEST(DisagreementPicture, ColoursEachPointByWhetherTheOtherSetHasOneNear) {
    // first: (2, 2) matched by (3, 2), (8, 1) alone; second: (3, 2) matched, (5, 6) alone, (20, 20) outside.
    const std::vector<cv::Point2d> first{{2.0, 2.0}, {8.2, 0.9}};
    const std::vector<cv::Point2d> second{{3.0, 2.0}, {5.0, 6.4}, {20.0, 20.0}};
    const cv::Mat picture = disagreementPicture(cv::Size(10, 8), first, second, 1.5);
    ASSERT_EQ(picture.type(), CV_8UC4);
    ASSERT_EQ(picture.size(), cv::Size(10, 8));
    EXPECT_EQ(picture.at<cv::Vec4b>(2, 2), cv::Vec4b(0, 0, 0, 255));       // first, matched: black
    EXPECT_EQ(picture.at<cv::Vec4b>(1, 8), cv::Vec4b(255, 0, 0, 255));     // first, alone: red
    EXPECT_EQ(picture.at<cv::Vec4b>(2, 3), cv::Vec4b(150, 150, 150, 255)); // second, matched: grey
    EXPECT_EQ(picture.at<cv::Vec4b>(6, 5), cv::Vec4b(0, 0, 255, 255));     // second, alone: blue
    // Paper everywhere else: black and grey differ from white in three channels, red and blue in two.
    EXPECT_EQ(cv::countNonZero(picture.reshape(1) != 255), 3 + 2 + 3 + 2);
    // A first point over a second one is drawn last.
    const cv::Mat overlap = disagreementPicture(cv::Size(4, 4), {{1.0, 1.0}}, {{1.0, 1.0}}, 0.5);
    EXPECT_EQ(overlap.at<cv::Vec4b>(1, 1), cv::Vec4b(0, 0, 0, 255));
    EXPECT_THROW(disagreementPicture(cv::Size(0, 4), first, second, 1.5), std::invalid_argument);
    EXPECT_THROW(disagreementPicture(cv::Size(4, 4), first, second, -1.0), std::invalid_argument);
}

} // namespace
} // namespace inkgraph::bench
