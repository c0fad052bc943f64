#include "render/PngFiles.h"

#include "codecs/PngCodec.h"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

/** Rows of a cv::Mat of the layout's size and depth, allocated once the header has been judged against `maxPixels`. */
PngRowProvider rowsInto(cv::Mat& pixels, std::size_t maxPixels) {
    return [&pixels, maxPixels](const PngLayout& layout) {
        if (std::size_t(layout.width) * std::size_t(layout.height) > maxPixels)
            throw std::runtime_error("it declares " + std::to_string(layout.width) + "x" +
                                     std::to_string(layout.height) + " pixels, more than the " +
                                     std::to_string(maxPixels) + " allowed here");
        pixels.create(int(layout.height), int(layout.width),
                      CV_MAKETYPE(layout.bitDepth == 16 ? CV_16U : CV_8U, layout.channels));
        std::vector<unsigned char*> rows(layout.height);
        for (int row = 0; row < pixels.rows; ++row) rows[std::size_t(row)] = pixels.ptr(row);
        return rows;
    };
}

/** As OpenImageIO gave them: samples other than 8-bit as float, 65535 as 1. */
cv::Mat asOpenImageIoGaveIt(const cv::Mat& pixels) {
    if (pixels.depth() == CV_8U) return pixels;
    cv::Mat scaled(pixels.size(), CV_MAKETYPE(CV_32F, pixels.channels()));
    for (int row = 0; row < pixels.rows; ++row) {
        const auto* in = pixels.ptr<std::uint16_t>(row);
        float* out = scaled.ptr<float>(row);
        for (int i = 0; i < pixels.cols * pixels.channels(); ++i) out[i] = float(in[i]) / 65535.0f;
    }
    return scaled;
}

} // namespace

std::vector<unsigned char> encodePng(const cv::Mat& image) {
    if (image.empty() || image.depth() != CV_8U || image.channels() > 4)
        throw std::runtime_error(
            "only non-empty 8-bit images of 1 to 4 channels are written as PNG (float images go to .exr or .tif)");
    std::vector<const unsigned char*> rows(std::size_t(image.rows));
    for (int row = 0; row < image.rows; ++row) rows[std::size_t(row)] = image.ptr(row);
    return encodePngRows(std::uint32_t(image.cols), std::uint32_t(image.rows), image.channels(), rows.data());
}

cv::Mat decodePng(const unsigned char* bytes, std::size_t byteCount, std::size_t maxPixels) {
    cv::Mat pixels;
    decodePngBytes(bytes, byteCount, PngExpansion::AsStored, rowsInto(pixels, maxPixels));
    return asOpenImageIoGaveIt(pixels);
}

cv::Mat readPngFile(const std::filesystem::path& path, std::size_t maxPixels) {
    struct CloseFile {
        void operator()(std::FILE* file) const { std::fclose(file); }
    };
    const std::unique_ptr<std::FILE, CloseFile> file(std::fopen(path.c_str(), "rb"));
    if (!file) throw std::runtime_error(std::string("cannot open it: ") + std::strerror(errno));
    cv::Mat pixels;
    decodePngStream(file.get(), PngExpansion::AsStored, rowsInto(pixels, maxPixels));
    return asOpenImageIoGaveIt(pixels);
}

} // namespace inkgraph
