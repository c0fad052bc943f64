#pragma once
/** @file The final picture from its layers. Pure function over cv::Mat: no GL, no I/O, inputs never mutated. */

#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace inkgraph {

/** One line type's mask and how to draw it. */
struct LineLayer {
    std::string name;                        ///< the line type, for error messages ("silhouette")
    cv::Mat mask;                            ///< CV_8UC1 coverage, 255 = line
    cv::Vec4f color{0.0f, 0.0f, 0.0f, 1.0f}; ///< display RGBA in [0,1]; alpha scales the mask
};

struct CompositeInputs {
    cv::Size size;                           ///< output size; every given layer must match it
    cv::Vec4f paper{1.0f, 1.0f, 1.0f, 1.0f}; ///< display RGBA in [0,1] behind everything
    cv::Mat shading;              ///< CV_8UC4 sRGB colour premultiplied by the coverage in alpha, or empty for none
    std::vector<LineLayer> lines; ///< drawn over the shading in this order
};

/** CV_8UC4, row 0 at the top: the shading over the paper (premultiplied: shading + paper x (1 - alpha)), then each
 *  line layer over that with alpha = mask x colour alpha. Without shading the picture starts from the paper alone.
 *  Throws std::invalid_argument naming the layer when a type, size or colour is wrong. */
cv::Mat compositeFinal(const CompositeInputs& inputs);

/** A CV_8UC4 premultiplied colour image (the shading) with straight alpha, as image files hold it: each colour
 *  channel divided by alpha, rounded; pixels with alpha 0 or 255 unchanged. Other types are returned as they are. */
cv::Mat straightAlphaOf(const cv::Mat& premultiplied);

} // namespace inkgraph
