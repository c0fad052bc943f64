#pragma once
/** @file The "hybrid" RGB image similarity of the Rust crate image-compare (ChrisRega/image-compare 0.4.1,
 *  `rgb_hybrid_compare`), written anew from its definition: structure by SSIM on luma, colour by the absolute
 *  difference of the chroma channels, the worse of the two per pixel, averaged. The MToon conformance suite scores
 *  renders against reference pictures with it (tests/conformance/README.md). Pure cv::Mat: no GL. */

#include <opencv2/core.hpp>

namespace inkgraph {

struct HybridSimilarity {
    /** Mean over the pixels of each pixel's similarity: 1 for identical images, toward 0 for unrelated ones. */
    double score = 0.0;
    /** CV_32FC3, row 0 at the top, per pixel (1 - luma SSIM, 1 - U similarity, 1 - V similarity) in R, G, B, each
     *  clamped to [0, 1] first: black where the images agree, red where structure differs, green, blue and cyan
     *  where colour does (the crate's visualisation). */
    cv::Mat differences;
};

/** Compares two CV_8UC3 images of one size, channels in RGB order. Each pixel goes to Y'CbCr after ITU-T T.871
 *  in float, each channel clamped to [0, 255] and truncated to 8 bits, as the crate does. Y is compared by SSIM
 *  (C1 = (0.01 * 255)^2, C2 = (0.03 * 255)^2) over the 8 x 8 tiles from the top-left corner (the last row and
 *  column of tiles cut by the border), each pixel taking its tile's value; note that the crate's "variances" and
 *  "covariance" are sums over the tile, not means, which this keeps, since its published scores depend on it. U and
 *  V are compared per pixel, 1 - |a - b| / 255. A pixel's similarity is min(SSIM, sqrt(u^2 + v^2)), every term
 *  clamped to [0, 1]: colour lowers it only where u^2 + v^2 < 1, e.g. both chroma channels off by more than 29% of
 *  their range, so the score is mostly luma structure. Throws
 *  std::invalid_argument naming 'first' or 'second' for an empty image or another type, and for images of
 *  different sizes. */
HybridSimilarity rgbHybridCompare(const cv::Mat& first, const cv::Mat& second);

} // namespace inkgraph
