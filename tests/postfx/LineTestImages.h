#pragma once
/** @file Small synthetic images and queries shared by the line-kernel tests. */

#include <opencv2/core.hpp>

#include <functional>
#include <vector>

namespace inkgraph::test {

/** A CV_32FC1 image of `cols` x `rows` with value(col, row) in each pixel. */
inline cv::Mat filled(int cols, int rows, const std::function<float(int col, int row)>& value) {
    cv::Mat image(rows, cols, CV_32FC1);
    for (int row = 0; row < rows; ++row)
        for (int col = 0; col < cols; ++col) image.at<float>(row, col) = value(col, row);
    return image;
}

/** The non-zero pixels of a skeleton mask. */
inline std::vector<cv::Point> markedPixels(const cv::Mat& mask) {
    std::vector<cv::Point> pixels;
    cv::findNonZero(mask, pixels);
    return pixels;
}

} // namespace inkgraph::test
