#include "passes/shade/ShadeMap.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace inkgraph {
namespace {

/** 8-bit sRGB code of a linear grey level in [0, 1] (the standard piecewise curve, rounded to nearest). */
uchar srgbCode(double linear) {
    const double clamped = std::clamp(linear, 0.0, 1.0);
    const double encoded = clamped <= 0.0031308 ? 12.92 * clamped : 1.055 * std::pow(clamped, 1.0 / 2.4) - 0.055;
    return cv::saturate_cast<uchar>(std::lround(encoded * 255.0));
}

cv::Vec4b grey(double linear) {
    const uchar code = srgbCode(linear);
    return {code, code, code, 255};
}

} // namespace

ShadeMap makeBandShadeMap(int bands) {
    if (bands < 2 || bands > 256)
        throw std::invalid_argument("makeBandShadeMap(): bands must be between 2 and 256, got " +
                                    std::to_string(bands));
    ShadeMap map;
    map.texels.create(1, bands, CV_8UC4);
    // Levels are linear light, stored sRGB-encoded like every 8-bit colour: the shader decodes them before they
    // multiply the (linear) base colour, so level 0.25 darkens the material to a quarter of its linear value.
    for (int i = 0; i < bands; ++i) map.texels.at<cv::Vec4b>(0, i) = grey(double(i) / double(bands - 1));
    map.source = "builtin:bands-" + std::to_string(bands);
    return map;
}

ShadeMap makeDefaultComicShadeMap() {
    // 32 x 32: columns s = max(n.l, 0), rows t = max(r.v, 0)^n (bottom row t = 0). Shadow where s < 0.25 (texels
    // 0..7, n.l below about cos 75.5 deg), lit tone above; the top half (t >= 0.5) is the highlight. Linear levels
    // 0.2 / 0.6 / 1.0: below 1 for the lit tone so the highlight still shows on a multiplied material colour.
    constexpr int kSide = 32;
    constexpr int kShadowColumns = 8;
    constexpr int kHighlightRows = 16;
    ShadeMap map;
    map.texels.create(kSide, kSide, CV_8UC4);
    for (int row = 0; row < kSide; ++row) {
        for (int col = 0; col < kSide; ++col) {
            // Row 0 is the top of the image, i.e. t = 1.
            const bool highlight = row < kHighlightRows;
            const double level = highlight ? 1.0 : (col < kShadowColumns ? 0.2 : 0.6);
            map.texels.at<cv::Vec4b>(row, col) = grey(level);
        }
    }
    map.source = "builtin:comic";
    return map;
}

ShadeMap shadeMapFromImage(const cv::Mat& image, const std::string& source, bool requireOneRow,
                           const std::string& who) {
    const std::string where = who + ": '" + source + "'";
    if (image.empty()) throw std::invalid_argument(where + " is empty");
    if (image.depth() != CV_8U)
        throw std::invalid_argument(where + " is not an 8-bit image (a shade map holds 8-bit sRGB colours)");
    const int channels = image.channels();
    if (channels < 1 || channels > 4)
        throw std::invalid_argument(where + " has " + std::to_string(channels) + " channels (1 to 4 are allowed)");
    if (image.cols > kMaxShadeMapSide || image.rows > kMaxShadeMapSide)
        throw std::invalid_argument(where + " is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                                    " (at most " + std::to_string(kMaxShadeMapSide) + " a side)");
    if (requireOneRow && image.rows != 1)
        throw std::invalid_argument(where + " has " + std::to_string(image.rows) +
                                    " rows; a 1-D shade map must be a single row");

    // Grey (1 channel) and grey + alpha (2) fill r, g and b; rgb (3) and rgba (4) keep their colour. Alpha is
    // ignored: the map is opaque, coverage comes from the geometry.
    ShadeMap map;
    map.texels.create(image.rows, image.cols, CV_8UC4);
    const int colorChannels = channels <= 2 ? 1 : 3;
    for (int row = 0; row < image.rows; ++row) {
        const uchar* in = image.ptr<uchar>(row);
        cv::Vec4b* out = map.texels.ptr<cv::Vec4b>(row);
        for (int col = 0; col < image.cols; ++col) {
            const uchar* pixel = in + std::size_t(col) * std::size_t(channels);
            for (int c = 0; c < 3; ++c) out[col][c] = pixel[colorChannels == 1 ? 0 : c];
            out[col][3] = 255;
        }
    }
    map.source = source;
    return map;
}

SpecularRowBands specularRowBands(const ShadeMap& map, double shininess) {
    if (map.texels.empty() || map.texels.type() != CV_8UC4)
        throw std::invalid_argument("specularRowBands(): '" + map.source + "' is not a CV_8UC4 shade map");
    if (!(shininess >= 0.0) || !std::isfinite(shininess))
        throw std::invalid_argument("specularRowBands(): shininess must be finite and >= 0");
    const int rows = map.texels.rows;
    SpecularRowBands bands;
    bands.firstRow.push_back(0);
    for (int row = 1; row < rows; ++row) {
        // Row `row` from the bottom is image row rows - 1 - row (the image's row 0 is the top, t = 1).
        const cv::Mat below = map.texels.row(rows - row);
        const cv::Mat current = map.texels.row(rows - 1 - row);
        if (cv::norm(below, current, cv::NORM_INF) == 0.0) continue;
        bands.firstRow.push_back(row);
        const double borderT = double(row) / double(rows);
        // t >= borderT <=> r.v >= borderT^(1/n) <=> x = 1 - r.v <= -expm1(log(borderT) / n); n = 0 makes t = 1.
        bands.maxHalfSquaredDistance.push_back(shininess > 0.0 ? -std::expm1(std::log(borderT) / shininess) : 4.0);
    }
    return bands;
}

} // namespace inkgraph
