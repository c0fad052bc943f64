#include "tests/support/ImageCompare.h"

#include "render/ImageFiles.h"

#include <opencv2/imgproc.hpp>

#include <cstdlib>
#include <sstream>

namespace inkgraph::test {

std::filesystem::path testOutputDirectory(const std::string& testName) {
    // tests/sanitizers/check-exit-threads.sh reruns tests while ctest runs them too: its own root keeps them apart.
    const char* root = std::getenv("INKGRAPH_TEST_OUTPUT_ROOT");
    const std::filesystem::path base =
        root != nullptr && *root != '\0' ? std::filesystem::path(root) : std::filesystem::path(INKGRAPH_BINARY_ROOT);
    return base / "test-output" / testName;
}

std::filesystem::path sourceRoot() { return INKGRAPH_SOURCE_ROOT_DIR; }

bool updatingGoldens() {
    const char* value = std::getenv("INKGRAPH_UPDATE_GOLDEN");
    return value != nullptr && std::string(value) == "1";
}

cv::Mat coverageEdges(const cv::Mat& coverage) {
    cv::Mat grown, shrunk;
    const cv::Mat kernel = cv::Mat::ones(3, 3, CV_8U);
    cv::dilate(coverage, grown, kernel);
    cv::erode(coverage, shrunk, kernel);
    return grown != shrunk;
}

::testing::AssertionResult imagesNear(const cv::Mat& actual, const cv::Mat& expected, ImageTolerance tolerance,
                                      const std::string& testName, const std::string& resourceName,
                                      const cv::Mat& outlierZone) {
    if (actual.size() != expected.size() || actual.channels() != expected.channels())
        return ::testing::AssertionFailure() << resourceName << ": size or channels differ: actual " << actual.cols
                                             << "x" << actual.rows << "x" << actual.channels() << ", expected "
                                             << expected.cols << "x" << expected.rows << "x" << expected.channels();
    cv::Mat actualFloat, expectedFloat, difference;
    actual.convertTo(actualFloat, CV_32F);
    expected.convertTo(expectedFloat, CV_32F);
    cv::absdiff(actualFloat, expectedFloat, difference);
    double maxAbs = 0.0;
    cv::minMaxLoc(difference.reshape(1), nullptr, &maxAbs);
    // A pixel is an outlier when any of its channels is beyond maxAbs.
    cv::Mat perPixelMax;
    cv::reduce(difference.reshape(1, static_cast<int>(difference.total())), perPixelMax, 1, cv::REDUCE_MAX);
    const cv::Mat outlierMask = cv::Mat(perPixelMax > tolerance.maxAbs).reshape(1, difference.rows);
    const double outliers = cv::countNonZero(outlierMask) / double(difference.total());
    int outliersOffEdge = 0;
    if (!outlierZone.empty()) outliersOffEdge = cv::countNonZero(outlierMask & ~outlierZone);
    const cv::Scalar channelMeans = cv::mean(difference);
    double meanAbs = 0.0;
    for (int c = 0; c < difference.channels(); ++c) meanAbs += channelMeans[c] / difference.channels();
    // NaN anywhere fails too: comparisons with NaN are false, so test for "within" rather than "beyond".
    const bool withinMax = outliers <= tolerance.outlierFraction && outliersOffEdge == 0;
    const bool withinMean = meanAbs <= tolerance.meanAbs;
    const bool finite = cv::checkRange(actualFloat);
    if (withinMax && withinMean && finite) return ::testing::AssertionSuccess();

    const std::filesystem::path directory = testOutputDirectory(testName);
    std::filesystem::create_directories(directory);
    writeImage(directory / (resourceName + ".actual.exr"), actualFloat);
    writeImage(directory / (resourceName + ".diff.exr"), difference);
    return ::testing::AssertionFailure() << resourceName << ": max |diff| " << maxAbs << ", " << outliers * 100.0
                                         << "% of pixels beyond " << tolerance.maxAbs << " (allowed "
                                         << tolerance.outlierFraction * 100.0 << "%, " << outliersOffEdge
                                         << " outside the allowed zone), mean |diff| " << meanAbs << " (allowed "
                                         << tolerance.meanAbs << ")" << (finite ? "" : ", NaN or Inf in actual")
                                         << "; wrote " << directory.string();
}

} // namespace inkgraph::test
