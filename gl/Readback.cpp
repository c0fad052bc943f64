#include "gl/Readback.h"

#include <algorithm>
#include <stdexcept>

namespace inkgraph {

int cvTypeOf(Format format) {
    switch (format) {
    case Format::RGBA32F: return CV_32FC4;
    case Format::R32F: return CV_32FC1;
    case Format::RGBA8: return CV_8UC4;
    case Format::R8: return CV_8UC1;
    case Format::RGBA16F: return CV_32FC4;
    case Format::R16F: return CV_32FC1;
    }
    throw std::logic_error("cvTypeOf(): unknown format");
}

namespace {

// Transfers go in bands of rows: one glGetTextureImage call takes a GLsizei byte count, which overflows at 2 GiB,
// and bands let each row land directly at its flipped place without a second full-size copy.
constexpr std::size_t kBandBytes = std::size_t(64) << 20;

int rowsPerBand(const cv::Mat& image) {
    const std::size_t rowBytes = std::size_t(image.cols) * image.elemSize();
    return int(std::max<std::size_t>(1, kBandBytes / rowBytes));
}

void throwOnGlError(const char* function, const GlTexture& texture) {
    if (const GLenum error = glGetError(); error != GL_NO_ERROR)
        throw std::runtime_error(std::string(function) + ": GL error " + glErrorName(error) + " on texture '" +
                                 texture.label() + "'");
}

} // namespace

cv::Mat readTexture(const GlTexture& texture) {
    const GlFormat glFormat = glFormatOf(texture.format());
    cv::Mat topDown(texture.height(), texture.width(), cvTypeOf(texture.format()));
    const int band = rowsPerBand(topDown);
    cv::Mat bottomUpBand(band, topDown.cols, topDown.type());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    for (int glRow = 0; glRow < texture.height(); glRow += band) {
        const int rows = std::min(band, texture.height() - glRow);
        glGetTextureSubImage(texture.id(), 0, 0, glRow, 0, texture.width(), rows, 1, glFormat.pixelFormat,
                             glFormat.pixelType, GLsizei(std::size_t(rows) * bottomUpBand.step[0]), bottomUpBand.data);
        throwOnGlError("readTexture()", texture);
        // GL row glRow + i is image row (height - 1 - glRow - i).
        for (int i = 0; i < rows; ++i) bottomUpBand.row(i).copyTo(topDown.row(texture.height() - 1 - glRow - i));
    }
    return topDown;
}

void uploadImage(GlTexture& texture, const cv::Mat& image) {
    if (image.cols != texture.width() || image.rows != texture.height() || image.type() != cvTypeOf(texture.format()))
        throw std::invalid_argument("uploadImage(): image of " + std::to_string(image.cols) + "x" +
                                    std::to_string(image.rows) + " does not match texture '" + texture.label() + "'");
    const GlFormat glFormat = glFormatOf(texture.format());
    const int band = rowsPerBand(image);
    cv::Mat bottomUpBand(band, image.cols, image.type());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int glRow = 0; glRow < texture.height(); glRow += band) {
        const int rows = std::min(band, texture.height() - glRow);
        for (int i = 0; i < rows; ++i) image.row(texture.height() - 1 - glRow - i).copyTo(bottomUpBand.row(i));
        glTextureSubImage2D(texture.id(), 0, 0, glRow, texture.width(), rows, glFormat.pixelFormat, glFormat.pixelType,
                            bottomUpBand.data);
        throwOnGlError("uploadImage()", texture);
    }
}

} // namespace inkgraph
