// postfx/Strokes on small synthetic skeletons; no GL. Expected strokes come from the shapes drawn: how many there
// are, which pixels each holds, their lengths, and which ones the length rule and the hysteresis keep.
#include "postfx/Strokes.h"

#include "tests/support/ThrowMessage.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::invalidArgumentMessage;

/** A skeleton with one point per set pixel at its centre, of the given strength. */
LineSkeleton skeletonOf(const cv::Mat& mask, float strength = 1.0f) {
    LineSkeleton skeleton = skeletonFromMask(mask);
    for (LinePoint& point : skeleton.points) point.strength = strength;
    return skeleton;
}

cv::Mat blank(int size = 64) { return cv::Mat::zeros(size, size, CV_8UC1); }

void drawLine(cv::Mat& mask, cv::Point a, cv::Point b) { cv::line(mask, a, b, 255, 1, cv::LINE_8); }

std::size_t keptOfLayer(const Strokes& strokes, int layer) {
    std::size_t count = 0;
    for (const Stroke& stroke : strokes.strokes) count += stroke.kept && stroke.layer == layer;
    return count;
}

TEST(StrokesTest, AStraightLineIsOneStrokeOfItsLength) {
    cv::Mat mask = blank();
    drawLine(mask, {5, 10}, {45, 10});
    const LineSkeleton skeleton = skeletonOf(mask);
    const Strokes strokes = chainStrokes({{&skeleton}});
    ASSERT_EQ(strokes.strokes.size(), 1u);
    EXPECT_NEAR(strokes.strokes[0].lengthPixels, 40.0, 1e-9);
    EXPECT_EQ(strokes.strokes[0].points.size(), 41u);
    EXPECT_FALSE(strokes.strokes[0].closed);
    EXPECT_TRUE(strokes.strokes[0].kept);
    EXPECT_FLOAT_EQ(strokes.strokes[0].meanStrength, 1.0f);
}

TEST(StrokesTest, ACrossingIsTwoStraightStrokesNotFourBranches) {
    // An X of two lines through (30, 30): tracing gives four branches at the junction; the straightest pairs run on.
    cv::Mat mask = blank();
    drawLine(mask, {10, 30}, {50, 30});
    drawLine(mask, {30, 10}, {30, 50});
    const LineSkeleton skeleton = skeletonOf(mask);
    const Strokes strokes = chainStrokes({{&skeleton}});
    ASSERT_EQ(strokes.strokes.size(), 2u);
    EXPECT_EQ(strokes.junctionJoins, 2u);
    for (const Stroke& stroke : strokes.strokes) {
        EXPECT_NEAR(stroke.lengthPixels, 40.0, 1e-9);
        const cv::Point2f first = stroke.points.front().position, last = stroke.points.back().position;
        // Each runs straight: one coordinate constant.
        EXPECT_TRUE(first.x == last.x || first.y == last.y) << first << " " << last;
    }
}

TEST(StrokesTest, ATJunctionKeepsTheStraightRunAndEndsTheStem) {
    cv::Mat mask = blank();
    drawLine(mask, {10, 20}, {50, 20});
    drawLine(mask, {30, 21}, {30, 40});
    const LineSkeleton skeleton = skeletonOf(mask);
    const Strokes strokes = chainStrokes({{&skeleton}});
    ASSERT_EQ(strokes.strokes.size(), 2u);
    std::vector<double> lengths{strokes.strokes[0].lengthPixels, strokes.strokes[1].lengthPixels};
    std::sort(lengths.begin(), lengths.end());
    EXPECT_NEAR(lengths[0], 20.0, 1e-9); // the stem, from the junction pixel down
    EXPECT_NEAR(lengths[1], 40.0, 1e-9);
}

TEST(StrokesTest, ACircleIsOneClosedStroke) {
    cv::Mat mask = blank();
    cv::circle(mask, {32, 32}, 20, 255, 1, cv::LINE_8);
    const LineSkeleton skeleton = skeletonOf(mask);
    const Strokes strokes = chainStrokes({{&skeleton}});
    ASSERT_EQ(strokes.strokes.size(), 1u);
    EXPECT_TRUE(strokes.strokes[0].closed);
    // A digital circle's 8-connected length is between its circumference and 8/(2 pi) x more.
    EXPECT_GT(strokes.strokes[0].lengthPixels, 2.0 * std::numbers::pi * 20.0 * 0.95);
    EXPECT_LT(strokes.strokes[0].lengthPixels, 2.0 * std::numbers::pi * 20.0 * 1.15);
}

TEST(StrokesTest, AGapInOneLayerIsBridgedAndDrawn) {
    cv::Mat mask = blank();
    drawLine(mask, {5, 10}, {24, 10});
    drawLine(mask, {27, 10}, {45, 10}); // a two-pixel hole at x = 25, 26
    const LineSkeleton skeleton = skeletonOf(mask);
    StrokeSettings settings;
    settings.joinRadiusPixels = 3.5;
    const Strokes strokes = chainStrokes({{&skeleton}}, settings);
    ASSERT_EQ(strokes.strokes.size(), 1u);
    EXPECT_EQ(strokes.gapJoins, 1u);
    EXPECT_NEAR(strokes.strokes[0].lengthPixels, 40.0, 1e-9);
    const LineSkeleton drawn = keptSkeleton(strokes, {{&skeleton}}, 0);
    EXPECT_EQ(drawn.mask.at<uchar>(10, 25), 255);
    EXPECT_EQ(drawn.mask.at<uchar>(10, 26), 255);
    // A gap across the line's direction is not bridged: two parallel lines stay two strokes.
    cv::Mat parallel = blank();
    drawLine(parallel, {5, 10}, {45, 10});
    drawLine(parallel, {5, 12}, {45, 12});
    const LineSkeleton two = skeletonOf(parallel);
    EXPECT_EQ(chainStrokes({{&two}}, settings).strokes.size(), 2u);
}

TEST(StrokesTest, ALineRunsOnAcrossTypesAndItsShortPieceIsKept) {
    // A 40-pixel contour continued by a 4-pixel crease: one chain of 45 px; the crease piece alone would be short.
    cv::Mat contourMask = blank(), creaseMask = blank();
    drawLine(contourMask, {5, 10}, {45, 10});
    drawLine(creaseMask, {46, 10}, {50, 10});
    const LineSkeleton contour = skeletonOf(contourMask), crease = skeletonOf(creaseMask);
    StrokeLayer contourLayer{&contour}, creaseLayer{&crease};
    creaseLayer.minLengthPixels = 20.0;
    const Strokes strokes = chainStrokes({contourLayer, creaseLayer});
    ASSERT_EQ(strokes.strokes.size(), 2u);
    EXPECT_EQ(strokes.crossTypeJoins, 1u);
    EXPECT_EQ(strokes.chains.size(), 1u);
    EXPECT_NEAR(strokes.chains[0].lengthPixels, 45.0, 1e-9);
    EXPECT_EQ(keptOfLayer(strokes, 1), 1u);
    // Alone, at right angles to nothing it continues, the same crease piece is dropped.
    cv::Mat apart = blank();
    drawLine(apart, {30, 40}, {34, 40});
    const LineSkeleton alone = skeletonOf(apart);
    creaseLayer.skeleton = &alone;
    const Strokes separate = chainStrokes({contourLayer, creaseLayer});
    EXPECT_EQ(keptOfLayer(separate, 1), 0u);
    EXPECT_EQ(separate.droppedShort(), 1u);
}

TEST(StrokesTest, AFragmentBetweenRunsOfAnotherTypeIsDrawnAsItsNeighbour) {
    // contour, two pixels of crease, contour again: one contour stroke, no two-pixel crease path.
    cv::Mat contourMask = blank(), creaseMask = blank();
    drawLine(contourMask, {5, 10}, {25, 10});
    drawLine(creaseMask, {26, 10}, {27, 10});
    drawLine(contourMask, {28, 10}, {50, 10});
    const LineSkeleton contour = skeletonOf(contourMask), crease = skeletonOf(creaseMask);
    const std::vector<StrokeLayer> layers{{&contour}, {&crease}};
    const Strokes strokes = chainStrokes(layers);
    ASSERT_EQ(strokes.strokes.size(), 1u);
    EXPECT_EQ(strokes.absorbedFragments, 1u);
    EXPECT_EQ(strokes.strokes[0].layer, 0);
    EXPECT_NEAR(strokes.strokes[0].lengthPixels, 45.0, 1e-9);
    const LineSkeleton drawn = keptSkeleton(strokes, layers, 0);
    EXPECT_EQ(drawn.mask.at<uchar>(10, 26), 255) << "the absorbed pixels are drawn as contour";
    EXPECT_EQ(cv::countNonZero(keptSkeleton(strokes, layers, 1).mask), 0);
}

TEST(StrokesTest, AnOverlappingLineOfALaterTypeGivesWay) {
    // An outline band's middle line and a contour one pixel beside it along 40 px; a second contour stroke runs
    // off where the outline does not go.
    cv::Mat outlineMask = blank(), contourMask = blank();
    drawLine(outlineMask, {5, 20}, {45, 20});
    drawLine(contourMask, {5, 21}, {45, 21});
    drawLine(contourMask, {20, 30}, {40, 50});
    const LineSkeleton outline = skeletonOf(outlineMask), contour = skeletonOf(contourMask);
    std::vector<StrokeLayer> layers{{&outline}, {&contour}};
    layers[1].minLengthPixels = 8.0;
    Strokes strokes = chainStrokes(layers);
    mergeOverlaps(strokes, layers, {1.0, 1.0});
    EXPECT_EQ(strokes.overlapsMerged, 1u);
    const LineSkeleton drawnContour = keptSkeleton(strokes, layers, 1);
    EXPECT_EQ(drawnContour.mask.at<uchar>(21, 25), 0) << "drawn once, by the outline";
    EXPECT_EQ(drawnContour.mask.at<uchar>(40, 30), 255) << "the contour's own stroke stays";
    EXPECT_EQ(keptSkeleton(strokes, layers, 0).mask.at<uchar>(20, 25), 255);
    // Apart by more than the two half widths, both are drawn.
    cv::Mat farContour = blank();
    drawLine(farContour, {5, 24}, {45, 24});
    const LineSkeleton apart = skeletonOf(farContour);
    layers[1].skeleton = &apart;
    Strokes separate = chainStrokes(layers);
    mergeOverlaps(separate, layers, {1.0, 1.0});
    EXPECT_EQ(separate.overlapsMerged, 0u);
    EXPECT_EQ(keptSkeleton(separate, layers, 1).mask.at<uchar>(24, 25), 255);
}

TEST(StrokesTest, TheLengthRuleDropsSpecksAndKeepsLines) {
    cv::Mat mask = blank();
    drawLine(mask, {5, 10}, {45, 10});
    mask.at<uchar>(30, 30) = 255;       // a speck
    drawLine(mask, {5, 50}, {8, 50});   // 3 px
    drawLine(mask, {20, 50}, {33, 50}); // 13 px
    const LineSkeleton skeleton = skeletonOf(mask);
    StrokeLayer layer{&skeleton};
    layer.minLengthPixels = 10.0;
    const Strokes strokes = chainStrokes({layer});
    EXPECT_EQ(strokes.strokes.size(), 4u);
    EXPECT_EQ(strokes.keptStrokes(), 2u);
    EXPECT_EQ(strokes.droppedShort(), 2u);
    const LineSkeleton drawn = keptSkeleton(strokes, {layer}, 0);
    EXPECT_EQ(drawn.mask.at<uchar>(30, 30), 0);
    EXPECT_EQ(drawn.mask.at<uchar>(50, 6), 0);
    EXPECT_EQ(drawn.mask.at<uchar>(50, 25), 255);
    EXPECT_EQ(drawn.mask.at<uchar>(10, 25), 255);
}

/** The same straight line on a picture 1024, 2048 and 4096 rows high (extent E px at 1024, its samples one a pixel):
 *  the length rule keeps it at every size or at none. Measured from its first sample to its last, the line is E - 1 px
 *  long at 1024 and 2E - 1 at 2048, so under the span alone (0.01 x the height) a line of 11 px at 1024 (span 10,
 *  under 10.24) was dropped there and kept at 2048 (span 21, over 20.48), as ticks of the torus knot were. */
TEST(StrokesTest, TheLengthRuleJudgesALineAlikeAtEverySize) {
    EXPECT_DOUBLE_EQ(strokeLengthLimitPixels(0.01, 512.0), 5.12);
    EXPECT_DOUBLE_EQ(strokeLengthLimitPixels(0.01, 1024.0), 10.24);
    EXPECT_DOUBLE_EQ(strokeLengthLimitPixels(0.01, 2048.0), 21.48);
    EXPECT_DOUBLE_EQ(strokeLengthLimitPixels(0.01, 4096.0), 43.96);
    EXPECT_EQ(strokeLengthLimitPixels(0.0, 4096.0), 0.0); // 0 keeps a pixel alone at every size
    for (const int extentAt1024 : {9, 10, 11, 12, 13, 14}) {
        std::vector<bool> kept;
        for (const int times : {1, 2, 4}) {
            cv::Mat mask = blank(80);
            const int pixels = extentAt1024 * times;
            drawLine(mask, {5, 10}, {5 + pixels - 1, 10});
            const LineSkeleton skeleton = skeletonOf(mask);
            StrokeLayer layer{&skeleton};
            layer.minLengthPixels = strokeLengthLimitPixels(0.01, 1024.0 * times);
            const Strokes strokes = chainStrokes({layer});
            ASSERT_EQ(strokes.strokes.size(), 1u);
            kept.push_back(strokes.strokes[0].kept);
        }
        SCOPED_TRACE("a line of " + std::to_string(extentAt1024) + " px at 1024 rows");
        EXPECT_EQ(kept[0], extentAt1024 >= 12); // span 11 >= 10.24; 10 < 10.24
        EXPECT_EQ(kept[1], kept[0]) << "2048 rows";
        EXPECT_EQ(kept[2], kept[0]) << "4096 rows";
    }
    EXPECT_NE(invalidArgumentMessage([] {
                  strokeLengthLimitPixels(-0.01, 1024.0);
              }).find("strokeLengthLimitPixels(): 'share'"),
              std::string::npos);
    EXPECT_NE(invalidArgumentMessage([] { strokeLengthLimitPixels(0.01, 0.0); }).find("'heightPixels'"),
              std::string::npos);
    EXPECT_NE(invalidArgumentMessage([] { strokeLengthLimitPixels(std::nan(""), 1024.0); }).find("'share'"),
              std::string::npos);
}

TEST(StrokesTest, TheJoinRadiusBridgesAGapAlikeAtEverySize) {
    // Two ends' samples lie a pixel further apart than the gap between the lines they draw, at every size; the radius
    // takes that pixel back above 1024 rows (strokeSpanBiasPixels()), so a gap of one pixel of a 1024-row picture
    // is bridged and one of 1.5 is not, at 2048 and 4096 rows as at 1024.
    EXPECT_DOUBLE_EQ(strokeSpanBiasPixels(512.0), 0.0);
    EXPECT_DOUBLE_EQ(strokeSpanBiasPixels(1024.0), 0.0);
    EXPECT_DOUBLE_EQ(strokeSpanBiasPixels(2048.0), 1.0);
    EXPECT_DOUBLE_EQ(strokeSettingsFor(512.0, 1).joinRadiusPixels, 2.0);
    EXPECT_DOUBLE_EQ(strokeSettingsFor(1024.0, 1).joinRadiusPixels, 2.0);
    EXPECT_DOUBLE_EQ(strokeSettingsFor(2048.0, 1).joinRadiusPixels, 3.0);
    EXPECT_DOUBLE_EQ(strokeSettingsFor(4096.0, 1).joinRadiusPixels, 5.0);
    EXPECT_DOUBLE_EQ(strokeSettingsFor(1024.0, 2).joinRadiusPixels, 3.0); // data rows 2048, as at 2048 rows
    EXPECT_DOUBLE_EQ(strokeSettingsFor(512.0, 2).joinRadiusPixels, 4.0);  // data rows 1024: as before
    EXPECT_DOUBLE_EQ(strokeSettingsFor(2048.0, 1).directionPixels, 8.0);  // lengths along a line keep the scaling
    EXPECT_DOUBLE_EQ(strokeSettingsFor(2048.0, 1).absorbPixels, 8.0);
    for (const double gapAt1024 : {0.5, 1.0, 1.5, 2.0}) {
        for (const int times : {1, 2, 4}) {
            const double gap = gapAt1024 * times;
            if (gap != std::floor(gap) || gap < 1.0) continue; // whole empty pixels only
            cv::Mat mask = blank(128);
            const int lineLength = 12 * times;
            drawLine(mask, {2, 20}, {2 + lineLength - 1, 20});
            const int secondStart = 2 + lineLength + int(gap);
            drawLine(mask, {secondStart, 20}, {secondStart + lineLength - 1, 20});
            const LineSkeleton skeleton = skeletonOf(mask);
            const Strokes strokes = chainStrokes({StrokeLayer{&skeleton}}, strokeSettingsFor(1024.0 * times, 1));
            SCOPED_TRACE("a gap of " + std::to_string(gapAt1024) + " px at 1024 rows, at " +
                         std::to_string(1024 * times) + " rows");
            EXPECT_EQ(strokes.gapJoins, gapAt1024 <= 1.0 ? 1u : 0u);
            EXPECT_EQ(strokes.chains.size(), gapAt1024 <= 1.0 ? 1u : 2u);
        }
    }
    EXPECT_NE(invalidArgumentMessage([] { strokeSettingsFor(0.0, 1); }).find("strokeSettingsFor(): 'outputRows'"),
              std::string::npos);
    EXPECT_NE(invalidArgumentMessage([] { strokeSettingsFor(1024.0, 0); }).find("'supersample'"), std::string::npos);
    EXPECT_NE(invalidArgumentMessage([] { strokeSpanBiasPixels(std::nan("")); }).find("'heightPixels'"),
              std::string::npos);
}

TEST(StrokesTest, ALayerSampledAt1024RowsIsJudgedAsAt1024WhereverItIsDrawn) {
    // A skeleton found on a field of 1024 rows and chained at 2048 (the suggestive contours' one sampling,
    // StrokeLayer::scale 2) has its samples two data pixels apart: its span needs no bias, and each of its ends adds
    // half a data pixel to the join radius, so the length rule and the joins decide as a 1024-row picture does.
    EXPECT_DOUBLE_EQ(strokeSpanBiasPixels(2048.0, 2.0), 0.0);
    EXPECT_DOUBLE_EQ(strokeSpanBiasPixels(4096.0, 2.0), 2.0);
    EXPECT_DOUBLE_EQ(strokeSpanBiasPixels(4096.0, 4.0), 0.0);
    EXPECT_DOUBLE_EQ(strokeSpanBiasPixels(1024.0, 2.0), 0.0) << "never below 0";
    EXPECT_DOUBLE_EQ(strokeLengthLimitPixels(0.01, 2048.0, 2.0), 20.48);
    EXPECT_DOUBLE_EQ(strokeJoinAllowancePixels(2048.0, 1.0), 0.0);
    EXPECT_DOUBLE_EQ(strokeJoinAllowancePixels(2048.0, 2.0), 0.5);
    EXPECT_DOUBLE_EQ(strokeJoinAllowancePixels(4096.0, 4.0), 1.5);
    EXPECT_DOUBLE_EQ(strokeJoinAllowancePixels(1024.0, 2.0), 0.0) << "no bias to take back at 1024 data rows";
    for (const int times : {2, 4}) {
        const double rows = 1024.0 * times;
        for (const int extentAt1024 : {9, 10, 11, 12, 13, 14}) {
            cv::Mat coarse = blank(40);
            drawLine(coarse, {2, 10}, {2 + extentAt1024 - 1, 10});
            const LineSkeleton skeleton = skeletonOf(coarse);
            StrokeLayer layer{&skeleton};
            layer.scale = times;
            layer.minLengthPixels = strokeLengthLimitPixels(0.01, rows, times);
            const Strokes strokes = chainStrokes({layer});
            ASSERT_EQ(strokes.strokes.size(), 1u);
            EXPECT_EQ(strokes.strokes[0].kept, extentAt1024 >= 12)
                << "a line of " << extentAt1024 << " px at 1024 rows, drawn at " << rows;
        }
        for (const int gapAt1024 : {1, 2}) {
            cv::Mat coarse = blank(40);
            drawLine(coarse, {2, 10}, {13, 10});
            drawLine(coarse, {14 + gapAt1024, 10}, {25 + gapAt1024, 10});
            const LineSkeleton skeleton = skeletonOf(coarse);
            StrokeLayer layer{&skeleton};
            layer.scale = times;
            layer.joinAllowancePixels = strokeJoinAllowancePixels(rows, times);
            const Strokes strokes = chainStrokes({layer}, strokeSettingsFor(rows, 1));
            EXPECT_EQ(strokes.gapJoins, gapAt1024 == 1 ? 1u : 0u)
                << "a gap of " << gapAt1024 << " px at 1024 rows, drawn at " << rows;
        }
    }
    cv::Mat mask = blank(8);
    drawLine(mask, {1, 1}, {5, 1});
    const LineSkeleton skeleton = skeletonOf(mask);
    StrokeLayer bad{&skeleton};
    bad.joinAllowancePixels = -1.0;
    EXPECT_NE(invalidArgumentMessage([&] { chainStrokes({bad}); }).find("'joinAllowancePixels'"), std::string::npos);
    EXPECT_NE(invalidArgumentMessage([] { strokeSpanBiasPixels(2048.0, 0.0); }).find("'samplePixels'"),
              std::string::npos);
}

TEST(StrokesTest, StrokesNearARulesLimitAreCountedPerLayer) {
    // Layer 0 is drawn from 10 pixels and seeds at 0.5; layer 1 has no length rule and always seeds.
    const LineSkeleton unused;
    StrokeLayer ruled{&unused};
    ruled.minLengthPixels = 10.0;
    ruled.seedStrength = 0.5f;
    const StrokeLayer free{&unused};
    Strokes strokes;
    for (const double length : {9.5, 12.0, 10.05, 10.9}) strokes.chains.push_back(StrokeChain{length});
    auto add = [&](int layer, std::size_t chain, float peak) {
        Stroke stroke;
        stroke.layer = layer;
        stroke.chain = chain;
        stroke.peakStrength = peak;
        strokes.strokes.push_back(stroke);
    };
    add(0, 0, 0.52f); // 5% short of the length, 4% over the seed: near both
    add(0, 1, 0.3f);  // 20% over the length, 40% under the seed: near neither
    add(0, 2, 0.56f); // 0.5% over the length, 12% over the seed: near the length
    add(0, 3, 0.5f);  // 9% over the length; its chain also holds layer 1, which always seeds: near the length only
    add(1, 3, 0.0f);
    const StrokesNearLimits near = strokesNearLimits(strokes, {ruled, free}, 0.1);
    EXPECT_EQ(near.length, (std::vector<std::size_t>{3, 0}));
    EXPECT_EQ(near.seed, (std::vector<std::size_t>{1, 0}));
    EXPECT_EQ(strokesNearLimits(strokes, {ruled, free}, 0.0).length, (std::vector<std::size_t>{0, 0}));
    EXPECT_THROW(strokesNearLimits(strokes, {ruled, free}, 1.0), std::invalid_argument);
    EXPECT_THROW(strokesNearLimits(strokes, {ruled}, 0.1), std::invalid_argument);
}

TEST(StrokesTest, HysteresisKeepsWeakLinesThatContinueStrongOnes) {
    // Layer 0: a weak line (0.2) whose right half is strong (0.8); and a separate weak line.
    cv::Mat mask = blank();
    drawLine(mask, {5, 10}, {45, 10});
    drawLine(mask, {5, 30}, {45, 30});
    LineSkeleton skeleton = skeletonOf(mask, 0.2f);
    for (LinePoint& point : skeleton.points)
        if (point.position.y == 10.0f && point.position.x > 25.0f) point.strength = 0.8f;
    StrokeLayer layer{&skeleton};
    layer.seedStrength = 0.5f;
    const Strokes strokes = chainStrokes({layer});
    ASSERT_EQ(strokes.strokes.size(), 2u);
    EXPECT_EQ(strokes.keptStrokes(), 1u);
    EXPECT_EQ(strokes.droppedWeak(), 1u);
    const LineSkeleton drawn = keptSkeleton(strokes, {layer}, 0);
    EXPECT_EQ(drawn.mask.at<uchar>(10, 6), 255) << "the weak half of the seeded line is drawn";
    EXPECT_EQ(drawn.mask.at<uchar>(30, 25), 0) << "the unseeded line is not";
}

TEST(StrokesTest, EverythingKeptGivesTheSkeletonAsFound) {
    cv::Mat mask = blank();
    cv::circle(mask, {32, 32}, 12, 255, 1, cv::LINE_8);
    drawLine(mask, {2, 2}, {60, 8});
    const LineSkeleton skeleton = skeletonOf(mask, 0.7f);
    const Strokes strokes = chainStrokes({{&skeleton}});
    const LineSkeleton drawn = keptSkeleton(strokes, {{&skeleton}}, 0);
    EXPECT_EQ(cv::countNonZero(drawn.mask != skeleton.mask), 0);
    EXPECT_EQ(drawn.points.size(), skeleton.points.size());
    EXPECT_EQ(cv::countNonZero(strokeLines(drawn, 2.0f, 1) != strokeLines(skeleton, 2.0f, 1)), 0);
}

TEST(StrokesTest, PointsBetweenPixelsStayWithThePixelTheyMarked) {
    // A kernel marks one pixel of a pair and places its point at the crossing, which may round to the other pixel
    // (off the mask): the point is drawn with its marked pixel.
    cv::Mat mask = blank();
    drawLine(mask, {5, 10}, {45, 10});
    LineSkeleton skeleton = skeletonOf(mask);
    for (LinePoint& point : skeleton.points) point.position.y += 0.7f; // rounds to row 11, which is off
    const Strokes strokes = chainStrokes({{&skeleton}});
    ASSERT_EQ(strokes.strokes.size(), 1u);
    EXPECT_FLOAT_EQ(strokes.strokes[0].peakStrength, 1.0f);
    const LineSkeleton drawn = keptSkeleton(strokes, {{&skeleton}}, 0);
    EXPECT_EQ(drawn.points.size(), skeleton.points.size());
    EXPECT_EQ(drawn.mask.at<uchar>(10, 20), 255);
}

TEST(StrokesTest, ALayerAtALowerResolutionJoinsInDataPixels) {
    // Layer 1 at half the resolution continues layer 0's line: (col + 0.5) x 2 - 0.5 in data pixels.
    cv::Mat fine = cv::Mat::zeros(64, 64, CV_8UC1), coarse = cv::Mat::zeros(32, 32, CV_8UC1);
    drawLine(fine, {4, 21}, {30, 21});
    drawLine(coarse, {16, 10}, {28, 10}); // data x 32.5 .. 56.5 at y 20.5
    const LineSkeleton a = skeletonOf(fine), b = skeletonOf(coarse);
    StrokeLayer coarseLayer{&b};
    coarseLayer.scale = 2;
    StrokeSettings settings;
    settings.joinRadiusPixels = 3.0;
    const Strokes strokes = chainStrokes({{&a}, coarseLayer}, settings);
    EXPECT_EQ(strokes.crossTypeJoins, 1u);
    EXPECT_EQ(strokes.chains.size(), 1u);
    const LineSkeleton drawn = keptSkeleton(strokes, {{&a}, coarseLayer}, 1);
    EXPECT_EQ(drawn.mask.size(), cv::Size(64, 64));
    EXPECT_FLOAT_EQ(drawn.points.front().position.x, 32.5f);
}

TEST(StrokesTest, ALayerAtALowerResolutionIsDrawnWhole) {
    // Traced every two data pixels and stamped with discs of a data pixel's radius (2 px wide at the data size), a
    // coarse layer's line would be beaded: half ink between two points. Its points are filled in a data pixel apart.
    cv::Mat coarse = cv::Mat::zeros(32, 32, CV_8UC1);
    drawLine(coarse, {4, 10}, {24, 10}); // data x 8.5 .. 48.5 at y 20.5
    const LineSkeleton line = skeletonOf(coarse, 0.8f);
    StrokeLayer layer{&line};
    layer.scale = 2;
    const Strokes strokes = chainStrokes({layer});
    const LineSkeleton drawn = keptSkeleton(strokes, {layer}, 0);
    ASSERT_GE(drawn.points.size(), 40u) << "21 traced points and 20 between them";
    for (std::size_t index = 1; index < drawn.points.size(); ++index)
        EXPECT_LE(cv::norm(drawn.points[index].position - drawn.points[index - 1].position), 1.0 + 1e-5) << index;
    // Along the line, the ink is even: no column between two traced points lighter than one on a point.
    const cv::Mat ink = strokeLines(drawn, 2.0f, 1);
    int lightest = 255, darkest = 0;
    for (int col = 10; col <= 46; ++col) {
        const int column = std::max(ink.at<uchar>(20, col), ink.at<uchar>(21, col));
        lightest = std::min(lightest, column);
        darkest = std::max(darkest, column);
    }
    EXPECT_LE(darkest - lightest, 3);
    EXPECT_GE(lightest, int(0.75 * 0.8 * 255));
}

TEST(StrokesTest, LineWeightTapersEndsAndThinsFarLines) {
    cv::Mat mask = blank();
    drawLine(mask, {4, 10}, {44, 10});
    drawLine(mask, {4, 40}, {44, 40});
    const LineSkeleton skeleton = skeletonOf(mask);
    Strokes strokes = chainStrokes({{&skeleton}});
    cv::Mat depth(64, 64, CV_32FC1, cv::Scalar(0.0f));
    depth.rowRange(0, 20).setTo(2.0f);  // the upper line is near
    depth.rowRange(30, 50).setTo(4.0f); // the lower far
    LineWeightSettings weight;
    weight.nearDepth = 2.0;
    weight.farDepth = 4.0;
    weight.farWidth = 0.5;
    weight.taperPixels = 10.0;
    weight.taperStart = 0.2;
    weighStrokes(strokes, weight, depth, depth.size());
    for (const Stroke& stroke : strokes.strokes) {
        const float scale = stroke.points.front().position.y < 20.0f ? 1.0f : 0.5f;
        EXPECT_NEAR(stroke.points.front().width, 0.2f * scale, 1e-6);
        EXPECT_NEAR(stroke.points.back().width, 0.2f * scale, 1e-6);
        EXPECT_NEAR(stroke.points[5].width, (0.2f + 0.8f * 0.5f) * scale, 1e-6); // halfway up the taper
        EXPECT_NEAR(stroke.points[20].width, scale, 1e-6);
    }
    // The polylines carry the widths of the vertices they keep. A straight line needs only its ends, but its width
    // needs the taper's knees too (where it reaches full width, 10 px from each end): drawn 4 px wide, the outline
    // between the ends alone would cut 1.6 px into the line's middle (the --svg of a short tapered stroke was as
    // thin as its ends).
    std::vector<std::vector<float>> widths;
    const std::vector<Polyline> polylines = strokePolylines(strokes, 0, 0.5, &widths, 4.0);
    ASSERT_EQ(polylines.size(), 2u);
    ASSERT_EQ(widths.size(), 2u);
    for (std::size_t line = 0; line < 2; ++line) {
        ASSERT_EQ(widths[line].size(), polylines[line].points.size());
        ASSERT_EQ(polylines[line].points.size(), 4u);
        const float scale = polylines[line].points.front().y < 20.0f ? 1.0f : 0.5f;
        EXPECT_NEAR(widths[line][0], 0.2f * scale, 1e-6);
        EXPECT_NEAR(widths[line][1], scale, 1e-6);
        EXPECT_NEAR(widths[line][2], scale, 1e-6);
        EXPECT_NEAR(widths[line][3], 0.2f * scale, 1e-6);
        EXPECT_NEAR(std::abs(polylines[line].points[1].x - polylines[line].points[0].x), 10.0f, 1e-4);
        EXPECT_NEAR(std::abs(polylines[line].points[3].x - polylines[line].points[2].x), 10.0f, 1e-4);
    }
    // A tolerance as wide as the line would keep no width at all: an eighth of the width bounds it (--svg-tolerance 2
    // on a 4 px line drew it 0.8 px wide all along).
    EXPECT_EQ(strokePolylines(strokes, 0, 2.0, &widths, 4.0)[0].points.size(), 4u);
    // Without widths the line is its two ends.
    EXPECT_EQ(strokePolylines(strokes, 0, 0.5)[0].points.size(), 2u);
}

TEST(StrokesTest, AStrokesOpacityIsTheMeanStrengthOfItsPoints) {
    // Two lines of one layer, one full and one faded to 0.4 (a suggestive contour's --suggestive-fade): --svg draws
    // each path at its stroke's opacity, as the picture draws each point at its strength.
    cv::Mat full = blank(), faded = blank();
    drawLine(full, {4, 10}, {44, 10});
    drawLine(faded, {4, 40}, {44, 40});
    LineSkeleton skeleton = skeletonOf(full);
    const LineSkeleton weak = skeletonOf(faded, 0.4f);
    skeleton.points.insert(skeleton.points.end(), weak.points.begin(), weak.points.end());
    skeleton.mask |= weak.mask;
    const Strokes strokes = chainStrokes({{&skeleton}});
    const std::vector<Polyline> polylines = strokePolylines(strokes, 0, 0.5);
    const std::vector<float> opacities = strokeOpacities(strokes, 0);
    ASSERT_EQ(polylines.size(), 2u);
    ASSERT_EQ(opacities.size(), 2u);
    for (std::size_t line = 0; line < 2; ++line)
        EXPECT_NEAR(opacities[line], polylines[line].points.front().y < 20.0f ? 1.0f : 0.4f, 1e-6) << line;
    EXPECT_TRUE(strokeOpacities(strokes, 1).empty()) << "no strokes of another layer";
}

TEST(StrokesTest, RefusesBadInputNamingIt) {
    const LineSkeleton empty;
    EXPECT_NE(invalidArgumentMessage([&] { chainStrokes({{&empty}}); }).find("chainStrokes(): 'layers' [0]"),
              std::string::npos);
    cv::Mat mask = blank();
    const LineSkeleton skeleton = skeletonOf(mask);
    StrokeLayer layer{&skeleton};
    layer.seedStrength = 2.0f;
    EXPECT_NE(invalidArgumentMessage([&] { chainStrokes({layer}); }).find("'seedStrength'"), std::string::npos);
    StrokeSettings settings;
    settings.joinAngleDegrees = 270.0;
    EXPECT_NE(
        invalidArgumentMessage([&] { chainStrokes({{&skeleton}}, settings); }).find("'settings.joinAngleDegrees'"),
        std::string::npos);
    const LineSkeleton small = skeletonOf(blank(32));
    EXPECT_NE(invalidArgumentMessage([&] {
                  chainStrokes({{&skeleton}, {&small}});
              }).find("data size"),
              std::string::npos);
}

} // namespace
} // namespace inkgraph
