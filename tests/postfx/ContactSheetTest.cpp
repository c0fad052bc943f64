// postfx/ContactSheet on synthetic buffers; no GL.
#include "postfx/ContactSheet.h"

#include "tests/support/ThrowMessage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using Layout = ContactSheetLayout;

const cv::Vec4b kWhite{255, 255, 255, 255};
const cv::Vec4b kBlack{0, 0, 0, 255};
const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

cv::Vec4b grey(int value) { return {uchar(value), uchar(value), uchar(value), 255}; }

/** The tile of a buffer shown at its own size (no scaling), so each pixel is the mapping of one value. */
cv::Mat tileAtOwnSize(const cv::Mat& image, TileContent content) { return tileImage(image, content, image.size()); }

using test::invalidArgumentMessage;

bool startsWith(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

int countDifferentPixels(const cv::Mat& a, const cv::Mat& b) {
    cv::Mat difference;
    cv::absdiff(a, b, difference);
    return cv::countNonZero(difference.reshape(1));
}

// --- tileImage(): each content's colours -------------------------------------------------------------------------

TEST(ContactSheetTile, ColorShowsCoverageOverTheChecker) {
    cv::Mat color(16, 16, CV_8UC4, cv::Scalar(0, 0, 0, 0)); // transparent everywhere but the pixels set below
    color.at<cv::Vec4b>(1, 1) = {10, 20, 30, 255};          // covered: the colour itself
    color.at<cv::Vec4b>(2, 2) = {0, 0, 0, 128};             // half covered black over the light square
    const cv::Mat tile = tileAtOwnSize(color, TileContent::Color);
    ASSERT_EQ(tile.type(), CV_8UC4);
    ASSERT_EQ(tile.size(), cv::Size(16, 16));
    EXPECT_EQ(tile.at<cv::Vec4b>(1, 1), cv::Vec4b(10, 20, 30, 255));
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 0), TilePalette::kCheckerLight) << "square (0,0) is light";
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 8), TilePalette::kCheckerDark) << "the next square is dark";
    EXPECT_EQ(tile.at<cv::Vec4b>(8, 0), TilePalette::kCheckerDark);
    EXPECT_EQ(tile.at<cv::Vec4b>(8, 8), TilePalette::kCheckerLight);
    EXPECT_EQ(tile.at<cv::Vec4b>(2, 2), grey(127)) << "255 x (1 - 128/255), as compositeFinal() blends";
}

TEST(ContactSheetTile, ColorWithThreeChannelsIsOpaque) {
    const cv::Mat color(4, 4, CV_8UC3, cv::Scalar(200, 100, 50));
    const cv::Mat tile = tileAtOwnSize(color, TileContent::Color);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 0), cv::Vec4b(200, 100, 50, 255)) << "channels stay in RGB order";
    EXPECT_EQ(tile.at<cv::Vec4b>(3, 3), cv::Vec4b(200, 100, 50, 255));
}

TEST(ContactSheetTile, ColorOfTransparentPixelsDoesNotBleedWhenShrunk) {
    // Left column transparent red, right column opaque blue: the average is half blue over the checker, no red.
    cv::Mat color(2, 2, CV_8UC4);
    color.col(0).setTo(cv::Scalar(255, 0, 0, 0));
    color.col(1).setTo(cv::Scalar(0, 0, 255, 255));
    const cv::Vec4b pixel = tileImage(color, TileContent::Color, {1, 1}).at<cv::Vec4b>(0, 0);
    EXPECT_EQ(pixel[0], pixel[1]) << "red would show if colours were averaged before the alpha";
    EXPECT_NEAR(pixel[0], 127.5, 1.0);
    EXPECT_EQ(pixel[2], 255);
}

TEST(ContactSheetTile, LinesAreDarkOnWhite) {
    cv::Mat lines(1, 3, CV_8UC1);
    lines.at<uchar>(0, 0) = 255; // a full line: black
    lines.at<uchar>(0, 1) = 0;   // no line: white
    lines.at<uchar>(0, 2) = 64;  // a quarter: light grey
    const cv::Mat tile = tileAtOwnSize(lines, TileContent::Lines);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 0), kBlack);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 1), kWhite);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 2), grey(191));
}

TEST(ContactSheetTile, MaskIsGreyAsItIs) {
    cv::Mat mask(1, 3, CV_8UC1);
    mask.at<uchar>(0, 0) = 0;
    mask.at<uchar>(0, 1) = 255;
    mask.at<uchar>(0, 2) = 100;
    const cv::Mat tile = tileAtOwnSize(mask, TileContent::Mask);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 0), kBlack);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 1), kWhite);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 2), grey(100));
}

TEST(ContactSheetTile, UnitVectorIsHalfPlusHalfAndBackgroundIsNeutral) {
    cv::Mat normal(1, 4, CV_32FC4);
    normal.at<cv::Vec4f>(0, 0) = {0.0f, 0.0f, 1.0f, 1.0f};  // facing the camera: the familiar normal-map blue
    normal.at<cv::Vec4f>(0, 1) = {-1.0f, 1.0f, 0.0f, 1.0f}; // left and up
    normal.at<cv::Vec4f>(0, 2) = {0.0f, 0.0f, 1.0f, 0.0f};  // not covered: background, whatever the vector
    normal.at<cv::Vec4f>(0, 3) = {2.0f, -3.0f, 0.0f, 1.0f}; // out of range: clamped
    const cv::Mat tile = tileAtOwnSize(normal, TileContent::UnitVector);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 0), cv::Vec4b(128, 128, 255, 255));
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 1), cv::Vec4b(0, 255, 128, 255));
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 2), TilePalette::kVectorBackground);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 3), cv::Vec4b(255, 0, 128, 255));
}

TEST(ContactSheetTile, UnitVectorWithThreeChannelsAndHalfFloats) {
    cv::Mat view(1, 2, CV_32FC3);
    view.at<cv::Vec3f>(0, 0) = {0.0f, 0.0f, 1.0f};
    view.at<cv::Vec3f>(0, 1) = {0.0f, 0.0f, 0.0f}; // no alpha: shown as a vector (w is 0 where n faces the eye)
    cv::Mat half;
    view.convertTo(half, CV_16F);
    for (const cv::Mat& image : {view, half}) {
        const cv::Mat tile = tileAtOwnSize(image, TileContent::UnitVector);
        EXPECT_EQ(tile.at<cv::Vec4b>(0, 0), cv::Vec4b(128, 128, 255, 255));
        EXPECT_EQ(tile.at<cv::Vec4b>(0, 1), grey(128));
    }
}

TEST(ContactSheetTile, SignedScalarIsBlueWhiteRedOnAFixedScale) {
    const cv::Mat nDotV = (cv::Mat_<float>(1, 6) << -1.0f, 0.0f, 1.0f, -0.5f, 0.5f, 3.0f);
    const cv::Mat tile = tileAtOwnSize(nDotV, TileContent::SignedScalar);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 0), cv::Vec4b(0, 0, 255, 255)) << "-1: blue";
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 1), cv::Vec4b(255, 255, 255, 255)) << "0: white";
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 2), cv::Vec4b(255, 0, 0, 255)) << "+1: red";
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 3), cv::Vec4b(128, 128, 255, 255));
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 4), cv::Vec4b(255, 128, 128, 255));
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 5), cv::Vec4b(255, 0, 0, 255)) << "clamped, not rescaled";
    // The scale is fixed: the same value gives the same colour whatever else is in the buffer.
    const cv::Mat narrow = (cv::Mat_<float>(1, 2) << -0.5f, 0.0f);
    EXPECT_EQ(tileAtOwnSize(narrow, TileContent::SignedScalar).at<cv::Vec4b>(0, 0), cv::Vec4b(128, 128, 255, 255));
}

TEST(ContactSheetTile, DepthNearestBrightestBackgroundFlat) {
    const cv::Mat depth = (cv::Mat_<float>(1, 5) << 0.0f, 2.0f, 4.0f, 6.0f, 0.0f);
    const cv::Mat tile = tileAtOwnSize(depth, TileContent::Depth);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 1), grey(TilePalette::kDepthNear)) << "nearest covered pixel: brightest";
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 2), grey(160)) << "halfway: (255 + 64) / 2 = 159.5";
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 3), grey(TilePalette::kDepthFar)) << "farthest covered pixel";
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 0), TilePalette::kDepthBackground);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 4), TilePalette::kDepthBackground);
}

TEST(ContactSheetTile, DepthIgnoresBadValuesWhenNormalisingAndShowsThem) {
    const cv::Mat depth = (cv::Mat_<float>(1, 5) << 10.0f, 20.0f, kNaN, kInf, -1.0f);
    const cv::Mat tile = tileAtOwnSize(depth, TileContent::Depth);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 0), grey(TilePalette::kDepthNear));
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 1), grey(TilePalette::kDepthFar)) << "the range is 10..20, not up to Inf";
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 2), TilePalette::kBad);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 3), TilePalette::kBad);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 4), TilePalette::kBad) << "negative depth is a convention mix-up";
    // One covered depth: all of it nearest.
    const cv::Mat single = (cv::Mat_<float>(1, 2) << 0.0f, 3.0f);
    EXPECT_EQ(tileAtOwnSize(single, TileContent::Depth).at<cv::Vec4b>(0, 1), grey(TilePalette::kDepthNear));
}

TEST(ContactSheetTile, DataNormalisesEachChannelOverItsFiniteRange) {
    const cv::Mat scalar = (cv::Mat_<float>(1, 5) << 10.0f, 20.0f, 30.0f, kNaN, -kInf);
    const cv::Mat tile = tileAtOwnSize(scalar, TileContent::Data);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 0), kBlack);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 1), grey(128));
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 2), kWhite);
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 3), TilePalette::kBad) << "NaN: magenta";
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 4), TilePalette::kBad) << "-Inf: magenta";

    cv::Mat radial(1, 2, CV_32FC4);
    radial.at<cv::Vec4f>(0, 0) = {-5.0f, 100.0f, 7.0f, 1e30f}; // the 4th channel is not shown
    radial.at<cv::Vec4f>(0, 1) = {5.0f, 0.0f, 7.0f, -1e30f};
    const cv::Mat radialTile = tileAtOwnSize(radial, TileContent::Data);
    EXPECT_EQ(radialTile.at<cv::Vec4b>(0, 0), cv::Vec4b(0, 255, TilePalette::kDataFlat, 255))
        << "each channel on its own range; a flat channel is mid grey";
    EXPECT_EQ(radialTile.at<cv::Vec4b>(0, 1), cv::Vec4b(255, 0, TilePalette::kDataFlat, 255));

    cv::Mat twoChannels(1, 2, CV_32FC2);
    twoChannels.at<cv::Vec2f>(0, 0) = {0.0f, 1.0f};
    twoChannels.at<cv::Vec2f>(0, 1) = {1.0f, 0.0f};
    EXPECT_EQ(tileAtOwnSize(twoChannels, TileContent::Data).at<cv::Vec4b>(0, 0), cv::Vec4b(0, 255, 0, 255))
        << "two channels: red and green, blue 0";
}

TEST(ContactSheetTile, NonFiniteIsMagentaForEveryFloatContent) {
    cv::Mat vector(1, 2, CV_32FC4, cv::Scalar(0, 0, 1, 1));
    vector.at<cv::Vec4f>(0, 1)[0] = kNaN;
    EXPECT_EQ(tileAtOwnSize(vector, TileContent::UnitVector).at<cv::Vec4b>(0, 1), TilePalette::kBad);
    const cv::Mat nDotV = (cv::Mat_<float>(1, 2) << 0.5f, kInf);
    EXPECT_EQ(tileAtOwnSize(nDotV, TileContent::SignedScalar).at<cv::Vec4b>(0, 1), TilePalette::kBad);
}

TEST(ContactSheetTile, OneNaNStaysVisibleWhenShrunk) {
    cv::Mat data(64, 64, CV_32FC1);
    for (int row = 0; row < 64; ++row)
        for (int col = 0; col < 64; ++col) data.at<float>(row, col) = static_cast<float>(row + col);
    data.at<float>(37, 10) = kNaN; // one bad pixel of 4096, in picture pixel (9, 2) at a quarter of the size
    const cv::Mat tile = tileImage(data, TileContent::Data, {16, 16});
    cv::Mat isBad;
    cv::inRange(tile, cv::Scalar(255, 0, 255, 255), cv::Scalar(255, 0, 255, 255), isBad);
    EXPECT_EQ(cv::countNonZero(isBad), 1);
    EXPECT_EQ(tile.at<cv::Vec4b>(9, 2), TilePalette::kBad);
}

// --- tileImage(): scaling -------------------------------------------------------------------------------------

TEST(ContactSheetTile, KeepsTheAspectAndLetterboxes) {
    const cv::Mat wide(32, 64, CV_8UC1, cv::Scalar(255)); // 2:1 into a square: 32x16 in the middle
    const cv::Mat tile = tileImage(wide, TileContent::Mask, {32, 32});
    ASSERT_EQ(tile.size(), cv::Size(32, 32));
    ASSERT_EQ(tile.type(), CV_8UC4);
    for (int row = 0; row < 32; ++row) {
        const bool picture = row >= 8 && row < 24;
        for (int col = 0; col < 32; ++col)
            ASSERT_EQ(tile.at<cv::Vec4b>(row, col), picture ? kWhite : TilePalette::kLetterbox)
                << "row " << row << " col " << col;
    }
    const cv::Mat tall(40, 10, CV_8UC1, cv::Scalar(0)); // 1:4 into 20x20: 5x20, columns 7..11
    const cv::Mat tallTile = tileImage(tall, TileContent::Mask, {20, 20});
    EXPECT_EQ(tallTile.at<cv::Vec4b>(0, 6), TilePalette::kLetterbox);
    EXPECT_EQ(tallTile.at<cv::Vec4b>(0, 7), kBlack);
    EXPECT_EQ(tallTile.at<cv::Vec4b>(19, 11), kBlack);
    EXPECT_EQ(tallTile.at<cv::Vec4b>(19, 12), TilePalette::kLetterbox);
}

TEST(ContactSheetTile, EnlargingRepeatsPixels) {
    cv::Mat mask(2, 2, CV_8UC1, cv::Scalar(0));
    mask.at<uchar>(0, 1) = 255;
    const cv::Mat tile = tileImage(mask, TileContent::Mask, {8, 8});
    for (int row = 0; row < 8; ++row)
        for (int col = 0; col < 8; ++col)
            ASSERT_EQ(tile.at<cv::Vec4b>(row, col), row < 4 && col >= 4 ? kWhite : kBlack) << row << "," << col;
}

TEST(ContactSheetTile, OnePixelLineSurvivesShrinkingFourTimes) {
    cv::Mat lines(64, 64, CV_8UC1, cv::Scalar(0));
    lines.col(10).setTo(255);                                      // vertical, in picture column 2
    for (int i = 0; i < 64; ++i) lines.at<uchar>(i, 63 - i) = 255; // anti-diagonal
    const cv::Mat tile = tileImage(lines, TileContent::Lines, {16, 16});
    for (int row = 0; row < 16; ++row) {
        const cv::Vec4b vertical = tile.at<cv::Vec4b>(row, 2);
        EXPECT_LT(vertical[0], 255) << "row " << row << ": the vertical line is gone";
        EXPECT_GT(vertical[0], 0) << "a quarter-covered pixel is grey, not black";
        EXPECT_LT(tile.at<cv::Vec4b>(row, 15 - row)[0], 255) << "row " << row << ": the diagonal is gone";
    }
    EXPECT_EQ(tile.at<cv::Vec4b>(0, 0), kWhite);
    EXPECT_EQ(tile.at<cv::Vec4b>(5, 2), grey(191)) << "4 of 16 pixels covered";
}

// --- composeContactSheet() ------------------------------------------------------------------------------------

ContactTile solidTile(const std::string& label, cv::Scalar rgba, cv::Size size = {64, 32}) {
    return {label, "rgba8 " + std::to_string(size.width) + "x" + std::to_string(size.height),
            cv::Mat(size, CV_8UC4, rgba), TileContent::Color};
}

std::vector<ContactTile> solidTiles(int count) {
    std::vector<ContactTile> tiles;
    for (int i = 0; i < count; ++i) tiles.push_back(solidTile("tile" + std::to_string(i), {0, 128, 0, 255}));
    return tiles;
}

/** Top-left corner of cell `index` by the documented layout, for a 64x32 (2:1) first tile. */
cv::Point cellCorner(int index, int columns, const Layout& layout) {
    const int tileHeight = layout.tileWidth / 2;
    const int title = layout.title.empty() ? 0 : Layout::kTitleBarHeight;
    return {Layout::kSpacing + (index % columns) * (layout.tileWidth + Layout::kSpacing),
            title + Layout::kSpacing + (index / columns) * (tileHeight + Layout::kCaptionHeight + Layout::kSpacing)};
}

TEST(ContactSheet, SizeFollowsTilesColumnsAndTileWidth) {
    Layout layout;
    layout.tileWidth = 64; // tiles are 64x32: each picture is 64x32
    const auto expected = [](int columns, int rows, int tileWidth, int tileHeight, bool title) {
        return cv::Size(Layout::kSpacing + columns * (tileWidth + Layout::kSpacing),
                        (title ? Layout::kTitleBarHeight : 0) + Layout::kSpacing +
                            rows * (tileHeight + Layout::kCaptionHeight + Layout::kSpacing));
    };
    // Automatic: 5 tiles -> ceil(sqrt(5)) = 3 columns, 2 rows.
    EXPECT_EQ(composeContactSheet(solidTiles(5), layout).size(), expected(3, 2, 64, 32, false));
    EXPECT_EQ(composeContactSheet(solidTiles(4), layout).size(), expected(2, 2, 64, 32, false));
    EXPECT_EQ(composeContactSheet(solidTiles(1), layout).size(), expected(1, 1, 64, 32, false));
    layout.columns = 2;
    EXPECT_EQ(composeContactSheet(solidTiles(5), layout).size(), expected(2, 3, 64, 32, false));
    layout.columns = 10; // more columns than tiles: only as many as the tiles
    EXPECT_EQ(composeContactSheet(solidTiles(3), layout).size(), expected(3, 1, 64, 32, false));
    layout.columns = 1;
    layout.tileWidth = 100; // 100 x 32/64 = 50
    layout.title = "bunny, cel";
    EXPECT_EQ(composeContactSheet(solidTiles(3), layout).size(), expected(1, 3, 100, 50, true));
    EXPECT_EQ(contactSheetSize(3, {64, 32}, layout), expected(1, 3, 100, 50, true));
    // The first tile's aspect sets the picture height: 33x100 at width 32 -> round(96.97) = 97.
    layout.tileWidth = 32;
    layout.title.clear();
    std::vector<ContactTile> tall = {solidTile("tall", {0, 0, 0, 255}, {33, 100}), solidTile("wide", {0, 0, 0, 255})};
    EXPECT_EQ(composeContactSheet(tall, layout).size(), expected(1, 2, 32, 97, false));
    // A picture over kMaxTileAspect times as tall as wide gets a cell that tall, letterboxed: the contact sheet of
    // a 16x512 still's ten buffers was 24748 pixels tall, refused after the whole render.
    layout = Layout();
    std::vector<ContactTile> portrait;
    for (int i = 0; i < 10; ++i) portrait.push_back(solidTile("portrait", {0, 0, 0, 255}, {16, 512}));
    EXPECT_EQ(contactSheetSize(10, {16, 512}, layout), expected(4, 3, 256, 1024, false));
    const cv::Mat sheet = composeContactSheet(portrait, layout);
    EXPECT_EQ(sheet.size(), expected(4, 3, 256, 1024, false));
    const cv::Point cell(Layout::kSpacing, Layout::kSpacing);
    EXPECT_EQ(sheet.at<cv::Vec4b>(cell + cv::Point(128, 512)), cv::Vec4b(0, 0, 0, 255)) << "the picture, centred";
    EXPECT_EQ(sheet.at<cv::Vec4b>(cell + cv::Point(4, 512)), TilePalette::kLetterbox) << "letterboxed beside it";
}

TEST(ContactSheet, IsOpaqueRgbaOnThePaper) {
    Layout layout;
    layout.tileWidth = 64;
    layout.paper = {200, 100, 50, 0}; // alpha ignored
    const cv::Mat sheet = composeContactSheet({solidTile("", {0, 0, 0, 0})}, layout);
    ASSERT_EQ(sheet.type(), CV_8UC4);
    std::vector<cv::Mat> channels;
    cv::split(sheet, channels);
    EXPECT_EQ(cv::countNonZero(channels[3] != 255), 0);
    EXPECT_EQ(sheet.at<cv::Vec4b>(0, 0), cv::Vec4b(200, 100, 50, 255)) << "the margin is paper, in RGBA order";
    EXPECT_EQ(sheet.at<cv::Vec4b>(sheet.rows - 1, sheet.cols - 1), cv::Vec4b(200, 100, 50, 255));
}

TEST(ContactSheet, TilesAreInTheGivenOrder) {
    Layout layout;
    layout.tileWidth = 64;
    layout.columns = 2;
    const std::vector<ContactTile> tiles = {solidTile("red", {255, 0, 0, 255}), solidTile("blue", {0, 0, 255, 255}),
                                            solidTile("green", {0, 255, 0, 255})};
    const cv::Mat sheet = composeContactSheet(tiles, layout);
    const cv::Point middle(32, 16);
    EXPECT_EQ(sheet.at<cv::Vec4b>(cellCorner(0, 2, layout) + middle), cv::Vec4b(255, 0, 0, 255));
    EXPECT_EQ(sheet.at<cv::Vec4b>(cellCorner(1, 2, layout) + middle), cv::Vec4b(0, 0, 255, 255));
    EXPECT_EQ(sheet.at<cv::Vec4b>(cellCorner(2, 2, layout) + middle), cv::Vec4b(0, 255, 0, 255))
        << "the third tile starts the second row";
    // The whole picture of the first tile is in its cell, corners included.
    EXPECT_EQ(sheet.at<cv::Vec4b>(cellCorner(0, 2, layout)), cv::Vec4b(255, 0, 0, 255));
    EXPECT_EQ(sheet.at<cv::Vec4b>(cellCorner(0, 2, layout) + cv::Point(63, 31)), cv::Vec4b(255, 0, 0, 255));
    EXPECT_EQ(sheet.at<cv::Vec4b>(cellCorner(0, 2, layout) + cv::Point(64, 31)), layout.paper);
}

TEST(ContactSheet, OtherAspectsAreLetterboxedInTheCell) {
    Layout layout;
    layout.tileWidth = 64;
    layout.columns = 2;
    // First tile 2:1 sets 64x32 cells; the second, 1:1, is 32x32 in the middle of its cell.
    const std::vector<ContactTile> tiles = {solidTile("wide", {255, 0, 0, 255}),
                                            solidTile("square", {0, 0, 255, 255}, {16, 16})};
    const cv::Mat sheet = composeContactSheet(tiles, layout);
    const cv::Point cell = cellCorner(1, 2, layout);
    EXPECT_EQ(sheet.at<cv::Vec4b>(cell + cv::Point(15, 16)), TilePalette::kLetterbox);
    EXPECT_EQ(sheet.at<cv::Vec4b>(cell + cv::Point(16, 16)), cv::Vec4b(0, 0, 255, 255));
    EXPECT_EQ(sheet.at<cv::Vec4b>(cell + cv::Point(47, 16)), cv::Vec4b(0, 0, 255, 255));
    EXPECT_EQ(sheet.at<cv::Vec4b>(cell + cv::Point(48, 16)), TilePalette::kLetterbox);
}

TEST(ContactSheet, LabelIsDrawnBelowItsTile) {
    Layout layout;
    layout.tileWidth = 64;
    std::vector<ContactTile> tiles = {solidTile("", {255, 0, 0, 255})};
    tiles[0].caption.clear();
    const cv::Mat blank = composeContactSheet(tiles, layout);
    tiles[0].label = "A";
    const cv::Mat labelled = composeContactSheet(tiles, layout);
    tiles[0].label = "B";
    const cv::Mat other = composeContactSheet(tiles, layout);

    const cv::Point cell = cellCorner(0, 1, layout);
    const cv::Rect picture(cell, cv::Size(64, 32));
    const cv::Rect captionArea(cell.x, cell.y + 32, 64, Layout::kCaptionHeight);
    EXPECT_GT(countDifferentPixels(blank(captionArea), labelled(captionArea)), 10) << "the label left no ink";
    EXPECT_GT(countDifferentPixels(labelled(captionArea), other(captionArea)), 10) << "'A' and 'B' look the same";
    EXPECT_EQ(countDifferentPixels(blank(picture), labelled(picture)), 0) << "text drawn over the picture";
    EXPECT_EQ(countDifferentPixels(blank, labelled), countDifferentPixels(blank(captionArea), labelled(captionArea)))
        << "text drawn outside the caption area";
    // The label line is above the caption line: the label's ink lies in the first half of the area.
    cv::Mat labelInk;
    cv::absdiff(blank(captionArea), labelled(captionArea), labelInk);
    const cv::Rect secondLine(0, Layout::kCaptionHeight / 2, 64, Layout::kCaptionHeight / 2);
    EXPECT_EQ(cv::countNonZero(labelInk(secondLine).reshape(1)), 0);
}

TEST(ContactSheet, CaptionIsDrawnOnTheSecondLine) {
    Layout layout;
    layout.tileWidth = 64;
    std::vector<ContactTile> tiles = {solidTile("", {255, 0, 0, 255})};
    tiles[0].caption.clear();
    const cv::Mat blank = composeContactSheet(tiles, layout);
    tiles[0].caption = "r8 4x4";
    const cv::Mat captioned = composeContactSheet(tiles, layout);
    const cv::Point cell = cellCorner(0, 1, layout);
    const cv::Rect firstLine(cell.x, cell.y + 32, 64, Layout::kCaptionHeight / 2);
    const cv::Rect secondLine(cell.x, cell.y + 32 + Layout::kCaptionHeight / 2, 64, Layout::kCaptionHeight / 2);
    EXPECT_EQ(countDifferentPixels(blank(firstLine), captioned(firstLine)), 0);
    EXPECT_GT(countDifferentPixels(blank(secondLine), captioned(secondLine)), 10);
}

TEST(ContactSheet, TextIsInkInRgbaOrder) {
    Layout layout;
    layout.tileWidth = 64;
    layout.paper = {255, 255, 255, 255};
    layout.ink = {255, 0, 0, 255}; // red: in BGR order it would come out blue
    const cv::Mat sheet = composeContactSheet({solidTile("MMMM", {0, 0, 0, 255})}, layout);
    const cv::Point cell = cellCorner(0, 1, layout);
    const cv::Mat area = sheet(cv::Rect(cell.x, cell.y + 32, 64, Layout::kCaptionHeight));
    int redPixels = 0;
    for (int row = 0; row < area.rows; ++row)
        for (int col = 0; col < area.cols; ++col) {
            const cv::Vec4b pixel = area.at<cv::Vec4b>(row, col);
            ASSERT_EQ(pixel[0], 255) << "red ink on white keeps red at 255";
            ASSERT_EQ(pixel[1], pixel[2]);
            ASSERT_EQ(pixel[3], 255) << "anti-aliasing keeps the sheet opaque";
            if (pixel[1] < 128) ++redPixels;
        }
    EXPECT_GT(redPixels, 10);
}

TEST(ContactSheet, LongTextShrinksInsteadOfOverflowing) {
    Layout layout;
    layout.tileWidth = 64;
    layout.columns = 2;
    std::vector<ContactTile> tiles = {solidTile("", {255, 0, 0, 255}), solidTile("", {0, 0, 255, 255})};
    tiles[0].caption.clear();
    tiles[1].caption.clear();
    const cv::Mat blank = composeContactSheet(tiles, layout);
    tiles[0].label = "gbuffer.normal";
    tiles[0].caption = std::string(500, 'W') + " rgba32f 1024x1024"; // cut with "...": far too long for 64 px
    const cv::Mat labelled = composeContactSheet(tiles, layout);
    const cv::Point cell = cellCorner(0, 2, layout);
    const cv::Rect ownArea(cell.x, cell.y + 32, 64, Layout::kCaptionHeight);
    EXPECT_GT(countDifferentPixels(blank(ownArea), labelled(ownArea)), 10);
    EXPECT_EQ(countDifferentPixels(blank, labelled), countDifferentPixels(blank(ownArea), labelled(ownArea)))
        << "text spilled out of its cell";
}

TEST(ContactSheet, TitleIsDrawnInTheTitleBar) {
    Layout layout;
    layout.tileWidth = 64;
    layout.title = "x";
    const cv::Mat shortTitle = composeContactSheet(solidTiles(2), layout);
    layout.title = "bunny_c3d_70k.obj, cel, outline";
    const cv::Mat longTitle = composeContactSheet(solidTiles(2), layout);
    ASSERT_EQ(shortTitle.size(), longTitle.size());
    const cv::Rect bar(0, 0, shortTitle.cols, Layout::kTitleBarHeight);
    EXPECT_GT(countDifferentPixels(shortTitle(bar), longTitle(bar)), 10);
    EXPECT_EQ(countDifferentPixels(shortTitle, longTitle), countDifferentPixels(shortTitle(bar), longTitle(bar)));
}

TEST(ContactSheet, ShowsEveryContentOfARun) {
    // One of each, as the CLI will pass them: all accepted, each cell shows its own mapping.
    const cv::Size size(8, 8);
    const std::vector<ContactTile> tiles = {
        {"final", "rgba8 8x8", cv::Mat(size, CV_8UC4, cv::Scalar(10, 20, 30, 255)), TileContent::Color},
        {"lines-contour", "r8 8x8", cv::Mat(size, CV_8UC1, cv::Scalar(255)), TileContent::Lines},
        {"coverage", "r8 8x8", cv::Mat(size, CV_8UC1, cv::Scalar(255)), TileContent::Mask},
        {"gbuffer.normal", "rgba32f 8x8", cv::Mat(size, CV_32FC4, cv::Scalar(0, 0, 1, 1)), TileContent::UnitVector},
        {"gbuffer.nDotV", "r32f 8x8", cv::Mat(size, CV_32FC1, cv::Scalar(-1)), TileContent::SignedScalar},
        {"gbuffer.depth", "r32f 8x8", cv::Mat(size, CV_32FC1, cv::Scalar(5)), TileContent::Depth},
        {"gbuffer.radial", "rgba32f 8x8", cv::Mat(size, CV_32FC4, cv::Scalar(kNaN)), TileContent::Data},
    };
    Layout layout;
    layout.tileWidth = 32;
    layout.columns = 7;
    const cv::Mat sheet = composeContactSheet(tiles, layout);
    const std::vector<cv::Vec4b> expected = {{10, 20, 30, 255},    kBlack,           kWhite,
                                             {128, 128, 255, 255}, {0, 0, 255, 255}, grey(TilePalette::kDepthNear),
                                             TilePalette::kBad};
    for (int index = 0; index < 7; ++index) {
        const cv::Point corner(Layout::kSpacing + index * (32 + Layout::kSpacing), Layout::kSpacing);
        EXPECT_EQ(sheet.at<cv::Vec4b>(corner + cv::Point(16, 16)), expected[index]) << tiles[index].label;
    }
}

// --- errors -----------------------------------------------------------------------------------------------------

TEST(ContactSheet, RejectsBadLayouts) {
    Layout layout;
    EXPECT_EQ(invalidArgumentMessage([&] { composeContactSheet({}, layout); }), "composeContactSheet(): no tiles");
    layout.tileWidth = 31;
    EXPECT_TRUE(startsWith(invalidArgumentMessage([&] { composeContactSheet(solidTiles(1), layout); }),
                           "composeContactSheet(): 'tileWidth' must be 32 to 4096, got 31"));
    layout.tileWidth = 4097;
    EXPECT_THROW(composeContactSheet(solidTiles(1), layout), std::invalid_argument);
    layout.tileWidth = 32;
    EXPECT_NO_THROW(composeContactSheet(solidTiles(1), layout)) << "32 is allowed";
    layout.columns = -1;
    EXPECT_TRUE(startsWith(invalidArgumentMessage([&] { composeContactSheet(solidTiles(1), layout); }),
                           "composeContactSheet(): 'columns'"));
}

TEST(ContactSheet, RejectsSheetsOverTheSizeLimit) {
    Layout layout;
    layout.tileWidth = 4096;
    layout.columns = 4; // 8 + 4 x 4104 = 16424 > 16384
    EXPECT_TRUE(startsWith(invalidArgumentMessage([&] { composeContactSheet(solidTiles(4), layout); }),
                           "composeContactSheet(): the sheet would be 16424x"));
    layout.columns = 3; // 12320 wide: fine in width, and 2 rows of 2048 + 44 are fine in height
    EXPECT_EQ(contactSheetSize(6, {64, 32}, layout), cv::Size(12320, 8 + 2 * (2048 + 36 + 8)));
    // A thin first tile makes every picture as tall as kMaxTileAspect allows: at 4096 wide, 16384 rows.
    Layout thin;
    thin.tileWidth = 4096;
    std::vector<ContactTile> tiles = {solidTile("thin", {0, 0, 0, 255}, {1, 1000})};
    EXPECT_TRUE(startsWith(invalidArgumentMessage([&] { composeContactSheet(tiles, thin); }),
                           "composeContactSheet(): the sheet would be 4112x16436 pixels"));
    EXPECT_THROW(contactSheetSize(1, {1, 1000}, thin), std::invalid_argument);
    thin.tileWidth = 256; // 1024 rows: fits
    EXPECT_EQ(contactSheetSize(1, {1, 1000}, thin), cv::Size(8 + 256 + 8, 8 + 1024 + 36 + 8));
    // Many tiles in automatic columns: 81 tiles -> 9 columns of 4096.
    layout.columns = 0;
    EXPECT_THROW(contactSheetSize(81, {64, 32}, layout), std::invalid_argument);
    EXPECT_THROW(contactSheetSize(0, {64, 32}, layout), std::invalid_argument);
    EXPECT_THROW(contactSheetSize(1, {0, 32}, layout), std::invalid_argument);
}

TEST(ContactSheet, RejectsBadTilesByLabel) {
    Layout layout;
    std::vector<ContactTile> tiles = solidTiles(2);
    tiles[1] = {"gbuffer.normal", "", cv::Mat(), TileContent::UnitVector};
    EXPECT_EQ(invalidArgumentMessage([&] { composeContactSheet(tiles, layout); }),
              "composeContactSheet(): tile 'gbuffer.normal' is empty");
    tiles[1].image = cv::Mat(4, 4, CV_8UC4);
    EXPECT_EQ(invalidArgumentMessage([&] { composeContactSheet(tiles, layout); }),
              "composeContactSheet(): tile 'gbuffer.normal' must be CV_32FC3 or CV_32FC4 (or CV_16F) for "
              "'UnitVector', got CV_8UC4");
    tiles[1] = {"coverage", "", cv::Mat(4, 4, CV_32FC1), TileContent::Mask};
    EXPECT_TRUE(startsWith(invalidArgumentMessage([&] { composeContactSheet(tiles, layout); }),
                           "composeContactSheet(): tile 'coverage' must be CV_8UC1 for 'Mask'"));
    tiles[1] = {"radial", "", cv::Mat(4, 4, CV_8UC4), TileContent::Data};
    EXPECT_THROW(composeContactSheet(tiles, layout), std::invalid_argument);
    tiles[1] = {"final", "", cv::Mat(4, 4, CV_32FC4), TileContent::Color};
    EXPECT_THROW(composeContactSheet(tiles, layout), std::invalid_argument);
    tiles[1] = {"depth", "", cv::Mat(4, 4, CV_32FC2), TileContent::Depth};
    EXPECT_THROW(composeContactSheet(tiles, layout), std::invalid_argument);
}

TEST(ContactSheetTile, RejectsBadInputs) {
    EXPECT_EQ(invalidArgumentMessage([] {
                  tileImage(cv::Mat(), TileContent::Mask, {8, 8});
              }),
              "tileImage(): image is empty");
    EXPECT_EQ(invalidArgumentMessage([] {
                  tileImage(cv::Mat(2, 2, CV_32FC1), TileContent::Lines, {8, 8});
              }),
              "tileImage(): image must be CV_8UC1 for 'Lines', got CV_32FC1");
    EXPECT_TRUE(startsWith(invalidArgumentMessage([] {
                               tileImage(cv::Mat(2, 2, CV_8UC1), TileContent::Mask, {0, 8});
                           }),
                           "tileImage(): size must be 1 to 16384 a side, got 0x8"));
    EXPECT_THROW(tileImage(cv::Mat(2, 2, CV_8UC1), TileContent::Mask, {16385, 8}), std::invalid_argument);
    EXPECT_THROW(tileImage(cv::Mat(2, 2, CV_32FC(5)), TileContent::Data, {8, 8}), std::invalid_argument);
}

TEST(ContactSheetTile, DescribesImagesForCaptions) {
    EXPECT_EQ(describeImage(cv::Mat(32, 64, CV_32FC4)), "rgba32f 64x32");
    EXPECT_EQ(describeImage(cv::Mat(2, 3, CV_8UC1)), "r8 3x2");
    EXPECT_EQ(describeImage(cv::Mat(1, 1, CV_16FC2)), "rg16f 1x1");
    EXPECT_EQ(describeImage(cv::Mat()), "empty");
    EXPECT_STREQ(tileContentName(TileContent::SignedScalar), "SignedScalar");
}

} // namespace
} // namespace inkgraph
