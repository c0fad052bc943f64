// The formats written through the OpenImageIO module (render/ImageIoOiio.cpp): TIFF and EXR come back as written (a
// TIFF written through OpenImageIO 2.4's memory proxy with the colour space attribute lost its image directory), and
// their bytes depend on the pixels only, never on when they were written (a fixed time stamp), so a data set's
// checksums hold across runs.
#include "render/ImageFiles.h"
#include "tests/support/TestFolder.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

namespace inkgraph {
namespace {

using ImageIoFiles = test::TestFolder;

std::string bytesOf(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

TEST_F(ImageIoFiles, TiffAndExrRoundTripAndCarryAFixedTimeStamp) {
    cv::Mat rgba(23, 31, CV_8UC4);
    cv::Mat depth(23, 31, CV_32FC1);
    for (int row = 0; row < rgba.rows; ++row)
        for (int col = 0; col < rgba.cols; ++col) {
            rgba.at<cv::Vec4b>(row, col) = cv::Vec4b(uchar(row * 9), uchar(col * 7), uchar((row * col) % 256), 255);
            depth.at<float>(row, col) = 0.25f * float(row) + 1e-3f * float(col);
        }
    writeImage(directory / "a.tif", rgba);
    writeImage(directory / "a.exr", depth);
    const cv::Mat tiffBack = readImage(directory / "a.tif");
    ASSERT_EQ(tiffBack.type(), CV_8UC4);
    EXPECT_EQ(cv::norm(tiffBack, rgba, cv::NORM_INF), 0.0);
    const cv::Mat exrBack = readImage(directory / "a.exr");
    ASSERT_EQ(exrBack.type(), CV_32FC1);
    EXPECT_EQ(cv::norm(exrBack, depth, cv::NORM_INF), 0.0);
    // Written again (the clock has moved on by then, if only by microseconds; the stamp is in seconds, so this alone
    // would rarely catch a clock stamp), the bytes are the same, and the stamp in them is the fixed one.
    writeImage(directory / "b.tif", rgba);
    writeImage(directory / "b.exr", depth);
    EXPECT_EQ(bytesOf(directory / "a.tif"), bytesOf(directory / "b.tif"));
    EXPECT_EQ(bytesOf(directory / "a.exr"), bytesOf(directory / "b.exr"));
    EXPECT_NE(bytesOf(directory / "a.tif").find("2000:01:01 00:00:00"), std::string::npos);
    EXPECT_NE(bytesOf(directory / "a.exr").find("2000:01:01 00:00:00"), std::string::npos);
}

} // namespace
} // namespace inkgraph
