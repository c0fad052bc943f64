#pragma once
/** @file Pictures for the conformance suite's comparisons: any 8-bit PNG as CV_8UC3 in RGB order, as the Rust crate
 *  image-compare's `into_rgb8()` makes it (grey replicated, alpha dropped, not blended), and the crate's
 *  visualisation of a comparison. */

#include "postfx/HybridCompare.h"
#include "render/ImageFiles.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace inkgraph::test {

inline cv::Mat readRgb8(const std::filesystem::path& path) {
    const cv::Mat image = readImage(path);
    if (image.depth() != CV_8U) throw std::runtime_error("readRgb8(): '" + path.string() + "' is not an 8-bit picture");
    cv::Mat rgb;
    if (image.channels() == 3) return image;
    if (image.channels() == 1) {
        cv::merge(std::vector<cv::Mat>{image, image, image}, rgb);
        return rgb;
    }
    if (image.channels() == 4) {
        rgb.create(image.size(), CV_8UC3);
        const int fromTo[] = {0, 0, 1, 1, 2, 2};
        cv::mixChannels(&image, 1, &rgb, 1, fromTo, 3);
        return rgb;
    }
    throw std::runtime_error("readRgb8(): '" + path.string() + "' has 2 channels (grey and alpha)");
}

/** The crate's `to_color_map()` of HybridSimilarity::differences: each channel clamped to [0, 1], times 255,
 *  truncated to 8 bits. */
inline cv::Mat differencePicture(const HybridSimilarity& similarity) {
    cv::Mat picture(similarity.differences.size(), CV_8UC3);
    for (int row = 0; row < picture.rows; ++row)
        for (int col = 0; col < picture.cols; ++col) {
            const cv::Vec3f& d = similarity.differences.at<cv::Vec3f>(row, col);
            for (int c = 0; c < 3; ++c)
                picture.at<cv::Vec3b>(row, col)[c] = uchar(std::min(std::max(d[c], 0.0f), 1.0f) * 255.0f);
        }
    return picture;
}

} // namespace inkgraph::test
