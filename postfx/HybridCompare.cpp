#include "postfx/HybridCompare.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace inkgraph {

namespace {

constexpr int kTile = 8;
constexpr double kC1 = (0.01 * 255.0) * (0.01 * 255.0);
constexpr double kC2 = (0.03 * 255.0) * (0.03 * 255.0);

void requireRgb8(const cv::Mat& image, const char* name) {
    if (image.empty() || image.type() != CV_8UC3)
        throw std::invalid_argument(std::string("rgbHybridCompare(): '") + name +
                                    "' must be a non-empty CV_8UC3 image (RGB)");
}

/** A channel value as the crate stores it: clamped to [0, 255], then truncated. */
uchar toByte(float value) { return static_cast<uchar>(std::clamp(value, 0.0f, 255.0f)); }

/** ITU-T T.871's Y'CbCr, in float and in the crate's order of operations, so the truncation lands where its does. */
void splitToYuv(const cv::Mat& rgb, cv::Mat& y, cv::Mat& u, cv::Mat& v) {
    y.create(rgb.size(), CV_8UC1);
    u.create(rgb.size(), CV_8UC1);
    v.create(rgb.size(), CV_8UC1);
    for (int row = 0; row < rgb.rows; ++row) {
        const cv::Vec3b* in = rgb.ptr<cv::Vec3b>(row);
        uchar* outY = y.ptr<uchar>(row);
        uchar* outU = u.ptr<uchar>(row);
        uchar* outV = v.ptr<uchar>(row);
        for (int col = 0; col < rgb.cols; ++col) {
            const float r = in[col][0], g = in[col][1], b = in[col][2];
            outY[col] = toByte(0.0f + 0.299f * r + 0.587f * g + 0.114f * b);
            outU[col] = toByte(128.0f - 0.168736f * r - 0.331264f * g + 0.5f * b);
            outV[col] = toByte(128.0f + 0.5f * r - 0.418688f * g - 0.081312f * b);
        }
    }
}

/** SSIM of one tile, with sums (not means) for the second moments, as the crate computes it. */
double tileSsim(const cv::Mat& x, const cv::Mat& y, const cv::Rect& tile) {
    double sumX = 0.0, sumY = 0.0;
    for (int row = tile.y; row < tile.y + tile.height; ++row)
        for (int col = tile.x; col < tile.x + tile.width; ++col) {
            sumX += x.at<uchar>(row, col);
            sumY += y.at<uchar>(row, col);
        }
    const double area = double(tile.area());
    const double meanX = sumX / area, meanY = sumY / area;
    double varianceX = 0.0, varianceY = 0.0, covariance = 0.0;
    for (int row = tile.y; row < tile.y + tile.height; ++row)
        for (int col = tile.x; col < tile.x + tile.width; ++col) {
            const double dx = x.at<uchar>(row, col) - meanX;
            const double dy = y.at<uchar>(row, col) - meanY;
            varianceX += dx * dx;
            varianceY += dy * dy;
            covariance += dx * dy;
        }
    return ((2.0 * meanX * meanY + kC1) * (2.0 * covariance + kC2)) /
           ((meanX * meanX + meanY * meanY + kC1) * (varianceX + varianceY + kC2));
}

/** Per pixel, its tile's SSIM as float (the crate keeps its similarity images in f32). */
cv::Mat tiledSsim(const cv::Mat& x, const cv::Mat& y) {
    cv::Mat result(x.size(), CV_32FC1);
    for (int top = 0; top < x.rows; top += kTile)
        for (int left = 0; left < x.cols; left += kTile) {
            const cv::Rect tile(left, top, std::min(kTile, x.cols - left), std::min(kTile, x.rows - top));
            result(tile).setTo(cv::Scalar(double(float(tileSsim(x, y, tile)))));
        }
    return result;
}

float channelSimilarity(uchar a, uchar b) {
    const float normalized = float(int(a) - int(b)) / 255.0f;
    return 1.0f - std::fabs(normalized);
}

} // namespace

HybridSimilarity rgbHybridCompare(const cv::Mat& first, const cv::Mat& second) {
    requireRgb8(first, "first");
    requireRgb8(second, "second");
    if (first.size() != second.size())
        throw std::invalid_argument("rgbHybridCompare(): 'first' is " + std::to_string(first.cols) + "x" +
                                    std::to_string(first.rows) + " but 'second' is " + std::to_string(second.cols) +
                                    "x" + std::to_string(second.rows));
    cv::Mat y1, u1, v1, y2, u2, v2;
    splitToYuv(first, y1, u1, v1);
    splitToYuv(second, y2, u2, v2);
    const cv::Mat structure = tiledSsim(y1, y2);

    HybridSimilarity result;
    result.differences.create(first.size(), CV_32FC3);
    double sum = 0.0; // in f64 over f32 terms, row by row, as the crate sums
    for (int row = 0; row < first.rows; ++row) {
        const float* ssim = structure.ptr<float>(row);
        cv::Vec3f* out = result.differences.ptr<cv::Vec3f>(row);
        for (int col = 0; col < first.cols; ++col) {
            const float s = std::clamp(ssim[col], 0.0f, 1.0f);
            const float u = std::clamp(channelSimilarity(u1.at<uchar>(row, col), u2.at<uchar>(row, col)), 0.0f, 1.0f);
            const float v = std::clamp(channelSimilarity(v1.at<uchar>(row, col), v2.at<uchar>(row, col)), 0.0f, 1.0f);
            const float colour = std::clamp(std::sqrt(u * u + v * v), 0.0f, 1.0f);
            sum += double(std::min(s, colour));
            out[col] = cv::Vec3f(1.0f - s, 1.0f - u, 1.0f - v);
        }
    }
    result.score = sum / double(first.total());
    return result;
}

} // namespace inkgraph
