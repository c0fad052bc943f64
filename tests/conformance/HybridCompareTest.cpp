/** @file rgbHybridCompare() (postfx/HybridCompare.h) against the Rust crate image-compare 0.4.1: the scores its own
 *  tests publish for its sample pictures (image-compare/hybrid_rgb.feature, the pictures beside it, MIT licence),
 *  its difference picture of two images, and closed-form scores of small images. */

#include "postfx/HybridCompare.h"
#include "tests/conformance/ConformanceImages.h"
#include "tests/support/ThrowMessage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

namespace fs = std::filesystem;

fs::path crateData() { return fs::path(INKGRAPH_SOURCE_ROOT) / "tests" / "conformance" / "image-compare"; }

struct PublishedScore {
    const char* picture;
    double score;
};

// tests/features/hybrid_rgb.feature of image-compare 0.4.1 (commit 3f62bbc), each picture compared with
// pad_gaprao.png; the crate asserts them with ==.
const PublishedScore kPublished[] = {
    {"pad_gaprao.png", 1.0},
    {"pad_gaprao_lighter.png", 0.9514066504143178},
    {"pad_gaprao_noise.png", 0.13009783371684705},
    {"pad_gaprao_gray_inverted.png", 3.2566565189821024e-5},
    {"pad_gaprao_color_filters.png", 0.9876923700357477},
};

TEST(HybridCompare, ScoresTheCratesPublishedPicturesAsItDoes) {
    const cv::Mat original = test::readRgb8(crateData() / "pad_gaprao.png");
    for (const PublishedScore& expected : kPublished) {
        const cv::Mat other = test::readRgb8(crateData() / expected.picture);
        // The same operations in the same order, in f32 where the crate uses f32 and f64 where it uses f64 (its
        // SSIM and its sum), without fused multiply-adds (postfx/CMakeLists.txt): the same double, bit for bit.
        EXPECT_EQ(rgbHybridCompare(original, other).score, expected.score) << expected.picture;
    }
}

TEST(HybridCompare, DrawsTheCratesDifferencePicture) {
    // The crate's test: its colour map of colored_primitives.png against colored_primitives_swapped.png (RGBA
    // pictures taken as RGB, alpha dropped) equals colored_primitives_hybrid_compare_rgb.png, every byte.
    const auto similarity = rgbHybridCompare(test::readRgb8(crateData() / "colored_primitives.png"),
                                             test::readRgb8(crateData() / "colored_primitives_swapped.png"));
    const cv::Mat expected = test::readRgb8(crateData() / "colored_primitives_hybrid_compare_rgb.png");
    const cv::Mat actual = test::differencePicture(similarity);
    ASSERT_EQ(actual.size(), expected.size());
    EXPECT_EQ(cv::norm(actual, expected, cv::NORM_INF), 0.0);
    EXPECT_GT(cv::norm(actual, cv::NORM_INF), 0.0); // the pictures do differ
}

cv::Mat flat(int width, int height, cv::Vec3b rgb) { return cv::Mat(height, width, CV_8UC3, cv::Scalar(rgb)); }

constexpr double kC1 = (0.01 * 255.0) * (0.01 * 255.0);
constexpr double kC2 = (0.03 * 255.0) * (0.03 * 255.0);

TEST(HybridCompare, IdenticalPicturesScoreOneAtAnySize) {
    cv::Mat image(9, 10, CV_8UC3); // tiles cut by both borders
    cv::randu(image, cv::Scalar::all(0), cv::Scalar::all(256));
    const auto similarity = rgbHybridCompare(image, image.clone());
    EXPECT_EQ(similarity.score, 1.0);
    EXPECT_EQ(cv::norm(similarity.differences, cv::NORM_INF), 0.0);
}

TEST(HybridCompare, BlackAgainstWhiteIsTheSsimOfTheirMeans) {
    // Luma 0 against 255 (T.871 gives white exactly 255, both chroma 128): no variance, so SSIM is
    // C1 / (255^2 + C1) in every tile; the chroma agree, and the minimum is the SSIM.
    const double ssim = kC1 / (255.0 * 255.0 + kC1);
    EXPECT_NEAR(rgbHybridCompare(flat(16, 16, {0, 0, 0}), flat(16, 16, {255, 255, 255})).score, ssim, 1e-9);
}

TEST(HybridCompare, APixelChangesOnlyItsOwnTile) {
    // 16 x 8 black; one white pixel in the left 8 x 8 tile. That tile: means 0 and 255/64, the second's variance
    // summed over the tile 255^2 (1 - 1/64), no covariance; the right tile is identical.
    cv::Mat changed = flat(16, 8, {0, 0, 0});
    changed.at<cv::Vec3b>(3, 5) = cv::Vec3b(255, 255, 255);
    const double mean = 255.0 / 64.0;
    const double variance = 255.0 * 255.0 * (1.0 - 1.0 / 64.0);
    const double left = (kC1 * kC2) / ((mean * mean + kC1) * (variance + kC2));
    const auto similarity = rgbHybridCompare(flat(16, 8, {0, 0, 0}), changed);
    EXPECT_NEAR(similarity.score, (left + 1.0) / 2.0, 1e-7);
    for (int row = 0; row < 8; ++row)
        for (int col = 0; col < 16; ++col) {
            const cv::Vec3f d = similarity.differences.at<cv::Vec3f>(row, col);
            EXPECT_NEAR(d[0], col < 8 ? 1.0 - left : 0.0, 1e-6) << row << "," << col;
            EXPECT_EQ(d[1], 0.0f); // white's and black's chroma are both 128
            EXPECT_EQ(d[2], 0.0f);
        }
}

TEST(HybridCompare, ColourCountsOnlyWhereBothChromaChannelsDifferALot) {
    // Flat red against flat blue: no structure, so SSIM compares the luma means only, and the chroma differ by
    // 171 and 148 of 255, enough for sqrt(u^2 + v^2) to fall below the SSIM and decide.
    const cv::Mat a = flat(8, 8, {255, 0, 0}), b = flat(8, 8, {0, 0, 255});
    const auto similarity = rgbHybridCompare(a, b);
    // T.871 in float, truncated: red (76, 84, 255), blue (29, 255, 107).
    const double ssim = (2.0 * 76.0 * 29.0 + kC1) / (76.0 * 76.0 + 29.0 * 29.0 + kC1);
    const double u = 1.0 - (255.0 - 84.0) / 255.0, v = 1.0 - (255.0 - 107.0) / 255.0;
    const double colour = std::sqrt(u * u + v * v);
    ASSERT_LT(colour, ssim);
    EXPECT_NEAR(similarity.score, colour, 1e-6);
    const cv::Vec3f d = similarity.differences.at<cv::Vec3f>(0, 0);
    EXPECT_NEAR(d[0], 1.0 - ssim, 1e-6);
    EXPECT_NEAR(d[1], 1.0 - u, 1e-6);
    EXPECT_NEAR(d[2], 1.0 - v, 1e-6);
}

TEST(HybridCompare, RefusesWhatItCannotCompare) {
    const cv::Mat rgb = flat(4, 4, {1, 2, 3});
    EXPECT_EQ(test::invalidArgumentMessage([&] { rgbHybridCompare(cv::Mat(), rgb); }),
              "rgbHybridCompare(): 'first' must be a non-empty CV_8UC3 image (RGB)");
    EXPECT_EQ(test::invalidArgumentMessage([&] { rgbHybridCompare(rgb, cv::Mat(4, 4, CV_8UC4)); }),
              "rgbHybridCompare(): 'second' must be a non-empty CV_8UC3 image (RGB)");
    EXPECT_EQ(test::invalidArgumentMessage([&] {
                  rgbHybridCompare(rgb, flat(5, 4, {1, 2, 3}));
              }),
              "rgbHybridCompare(): 'first' is 4x4 but 'second' is 5x4");
}

} // namespace
} // namespace inkgraph
