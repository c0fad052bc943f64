#pragma once
/** @file The final picture from its layers. Pure function over cv::Mat: no GL, no I/O, inputs never mutated. */

#include <opencv2/core.hpp>

namespace inkgraph {

struct CompositeInputs {
    cv::Size size;                       ///< output size; every given layer must match it
    cv::Vec4f paper{1.0f, 1.0f, 1.0f, 1.0f}; ///< display RGBA in [0,1] behind everything
    cv::Mat shading;                     ///< CV_8UC4 sRGB colour with coverage in alpha, or empty for none
};

/** CV_8UC4, row 0 at the top: the shading over the paper ("over" with the shading's alpha). Without shading the
 *  picture is the paper alone. Throws std::invalid_argument naming the layer when a type or size is wrong. */
cv::Mat compositeFinal(const CompositeInputs& inputs);

} // namespace inkgraph
