#pragma once
/** @file Image comparison for golden tests (Magnum's CompareImageToFile{max, mean}): per-case thresholds, each with a
 *  comment at the call site saying why. On failure the actual image and the absolute difference are written to
 *  <build>/test-output/<test>/<resource>.actual.exr and .diff.exr for inspection. */

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <filesystem>
#include <string>

namespace inkgraph::test {

struct ImageTolerance {
    double maxAbs = 0.0;  ///< largest allowed |actual - expected| over every pixel and channel
    double meanAbs = 0.0; ///< largest allowed mean of |actual - expected|
    /** Share of pixels allowed to exceed maxAbs: silhouette pixels whose coverage flips on a rasterisation tie
     *  differ by whole normals, and say nothing about the pass being right. */
    double outlierFraction = 0.0;
};

/** Pixels within one pixel of a coverage boundary (CV_8UC1, 255 there): where outliers may fall. */
cv::Mat coverageEdges(const cv::Mat& coverage);

/** Compares two images of the same size and channel count (8-bit values are compared on the 0..255 scale).
 *  With `outlierZone` (CV_8UC1), every pixel beyond maxAbs must lie inside it. */
::testing::AssertionResult imagesNear(const cv::Mat& actual, const cv::Mat& expected, ImageTolerance tolerance,
                                      const std::string& testName, const std::string& resourceName,
                                      const cv::Mat& outlierZone = cv::Mat());

/** Folder the failing comparisons write to: <build>/test-output/<test>, or under $INKGRAPH_TEST_OUTPUT_ROOT where
 *  that is set. */
std::filesystem::path testOutputDirectory(const std::string& testName);

/** Repo root, for models/ and tests/golden/. */
std::filesystem::path sourceRoot();

/** True when INKGRAPH_UPDATE_GOLDEN=1: golden tests then write their goldens instead of comparing. Never in CI. */
bool updatingGoldens();

} // namespace inkgraph::test
