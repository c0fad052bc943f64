#include "postfx/Composite.h"
#include "postfx/SizeText.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include <opencv2/core/utility.hpp>

#include <stdexcept>
#include <vector>
#include <string>

namespace inkgraph {
namespace {

bool isUnitColor(const cv::Vec4f& color) {
    for (int channel = 0; channel < 4; ++channel)
        if (!(color[channel] >= 0.0f && color[channel] <= 1.0f)) return false;
    return true;
}

cv::Vec4b toBytes(const cv::Vec4f& color) {
    return {cv::saturate_cast<uchar>(color[0] * 255.0f + 0.5f), cv::saturate_cast<uchar>(color[1] * 255.0f + 0.5f),
            cv::saturate_cast<uchar>(color[2] * 255.0f + 0.5f), cv::saturate_cast<uchar>(color[3] * 255.0f + 0.5f)};
}

/** "over" in 8 bits with rounding: top x alpha + bottom x (255 - alpha), alpha in 0..255. */
uchar over(int top, int bottom, int alpha) {
    return static_cast<uchar>((top * alpha + bottom * (255 - alpha) + 127) / 255);
}

} // namespace

cv::Mat compositeFinal(const CompositeInputs& inputs) {
    if (inputs.size.width <= 0 || inputs.size.height <= 0)
        throw std::invalid_argument("compositeFinal(): output size must be positive");
    if (!isUnitColor(inputs.paper))
        throw std::invalid_argument("compositeFinal(): 'paper' channels must lie in [0, 1]");
    if (!inputs.shading.empty() && (inputs.shading.type() != CV_8UC4 || inputs.shading.size() != inputs.size))
        throw std::invalid_argument("compositeFinal(): 'shading' must be CV_8UC4 of " + sizeText(inputs.size));
    for (const LineLayer& layer : inputs.lines) {
        if (layer.mask.type() != CV_8UC1 || layer.mask.size() != inputs.size)
            throw std::invalid_argument("compositeFinal(): line layer '" + layer.name + "' must be CV_8UC1 of " +
                                        sizeText(inputs.size));
        if (!isUnitColor(layer.color))
            throw std::invalid_argument("compositeFinal(): line layer '" + layer.name +
                                        "' colour channels must lie in [0, 1]");
    }

    const cv::Vec4b paper = toBytes(inputs.paper);
    // Not filled with the paper first: each row writes every pixel once (the paper where the shading is empty).
    cv::Mat result(inputs.size, CV_8UC4);
    std::vector<cv::Vec4b> lineColors;
    for (const LineLayer& layer : inputs.lines) lineColors.push_back(toBytes(layer.color));
    // Rows are independent; opaque and empty pixels (most of a frame) skip the blend.
    cv::parallel_for_(cv::Range(0, result.rows), [&](const cv::Range& rows) {
        // Locals, not the captured references: the byte stores below may alias anything, so the compiler would
        // reload the width and the paper from memory on every pixel.
        const int cols = result.cols;
        const cv::Vec4b paperPixel = paper;
        for (int row = rows.start; row < rows.end; ++row) {
            auto* out = result.ptr<cv::Vec4b>(row);
            if (inputs.shading.empty()) {
                std::fill(out, out + cols, paperPixel);
            } else {
                const auto* shading = inputs.shading.ptr<cv::Vec4b>(row);
                for (int col = 0; col < cols; ++col) {
                    const int alpha = shading[col][3];
                    if (alpha == 0) {
                        out[col] = paperPixel;
                        continue;
                    }
                    if (alpha == 255) {
                        out[col] = shading[col];
                        continue;
                    }
                    // Premultiplied: a blended surface over nothing holds colour x alpha (the shade pass blends so).
                    for (int channel = 0; channel < 3; ++channel)
                        out[col][channel] = static_cast<uchar>(
                            std::min(255, shading[col][channel] + (paperPixel[channel] * (255 - alpha) + 127) / 255));
                    out[col][3] = static_cast<uchar>(alpha + (paperPixel[3] * (255 - alpha) + 127) / 255);
                }
            }
            for (std::size_t layer = 0; layer < inputs.lines.size(); ++layer) {
                const uchar* mask = inputs.lines[layer].mask.ptr<uchar>(row);
                const cv::Vec4b color = lineColors[layer];
                for (int col = 0; col < cols; ++col) {
                    // Eight mask bytes at a time: line masks are mostly empty.
                    if (col + 8 <= cols) {
                        std::uint64_t word;
                        std::memcpy(&word, mask + col, sizeof word);
                        if (word == 0) {
                            col += 7;
                            continue;
                        }
                    }
                    if (mask[col] == 0) continue;
                    const int alpha = (mask[col] * color[3] + 127) / 255;
                    for (int channel = 0; channel < 3; ++channel)
                        out[col][channel] = over(color[channel], out[col][channel], alpha);
                    out[col][3] = static_cast<uchar>(alpha + (out[col][3] * (255 - alpha) + 127) / 255);
                }
            }
        }
    });
    return result;
}

cv::Mat straightAlphaOf(const cv::Mat& premultiplied) {
    if (premultiplied.type() != CV_8UC4) return premultiplied;
    cv::Mat straight = premultiplied.clone();
    straight.forEach<cv::Vec4b>([](cv::Vec4b& pixel, const int*) {
        const int alpha = pixel[3];
        if (alpha == 0 || alpha == 255) return;
        for (int channel = 0; channel < 3; ++channel)
            pixel[channel] = static_cast<uchar>(std::min(255, (pixel[channel] * 255 + alpha / 2) / alpha));
    });
    return straight;
}

} // namespace inkgraph
