#include "postfx/Composite.h"

#include <stdexcept>
#include <string>

namespace inkgraph {

cv::Mat compositeFinal(const CompositeInputs& inputs) {
    if (inputs.size.width <= 0 || inputs.size.height <= 0)
        throw std::invalid_argument("compositeFinal(): output size must be positive");
    for (int channel = 0; channel < 4; ++channel)
        if (!(inputs.paper[channel] >= 0.0f && inputs.paper[channel] <= 1.0f))
            throw std::invalid_argument("compositeFinal(): 'paper' channels must lie in [0, 1]");
    const cv::Vec4b paper(cv::saturate_cast<uchar>(inputs.paper[0] * 255.0f + 0.5f),
                          cv::saturate_cast<uchar>(inputs.paper[1] * 255.0f + 0.5f),
                          cv::saturate_cast<uchar>(inputs.paper[2] * 255.0f + 0.5f),
                          cv::saturate_cast<uchar>(inputs.paper[3] * 255.0f + 0.5f));
    cv::Mat result(inputs.size, CV_8UC4, cv::Scalar(paper[0], paper[1], paper[2], paper[3]));
    if (inputs.shading.empty()) return result;

    if (inputs.shading.type() != CV_8UC4 || inputs.shading.size() != inputs.size)
        throw std::invalid_argument("compositeFinal(): 'shading' must be CV_8UC4 of " +
                                    std::to_string(inputs.size.width) + "x" + std::to_string(inputs.size.height));
    for (int row = 0; row < result.rows; ++row) {
        const auto* shading = inputs.shading.ptr<cv::Vec4b>(row);
        auto* out = result.ptr<cv::Vec4b>(row);
        for (int col = 0; col < result.cols; ++col) {
            const int alpha = shading[col][3];
            for (int channel = 0; channel < 3; ++channel)
                out[col][channel] = static_cast<uchar>((shading[col][channel] * alpha + paper[channel] * (255 - alpha) + 127) / 255);
            out[col][3] = static_cast<uchar>(alpha + (paper[3] * (255 - alpha) + 127) / 255);
        }
    }
    return result;
}

} // namespace inkgraph
