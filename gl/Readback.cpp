#include "gl/Readback.h"

#include <stdexcept>

namespace inkgraph {

int cvTypeOf(Format format) {
    switch (format) {
    case Format::RGBA32F: return CV_32FC4;
    case Format::R32F: return CV_32FC1;
    case Format::RGBA8: return CV_8UC4;
    case Format::R8: return CV_8UC1;
    }
    throw std::logic_error("cvTypeOf(): unknown format");
}

cv::Mat readTexture(const GlTexture& texture) {
    const GlFormat glFormat = glFormatOf(texture.format());
    cv::Mat bottomUp(texture.height(), texture.width(), cvTypeOf(texture.format()));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(texture.id(), 0, glFormat.pixelFormat, glFormat.pixelType,
                      static_cast<GLsizei>(bottomUp.total() * bottomUp.elemSize()), bottomUp.data);
    cv::Mat topDown;
    cv::flip(bottomUp, topDown, 0);
    return topDown;
}

void uploadImage(GlTexture& texture, const cv::Mat& image) {
    if (image.cols != texture.width() || image.rows != texture.height() || image.type() != cvTypeOf(texture.format()))
        throw std::invalid_argument("uploadImage(): image of " + std::to_string(image.cols) + "x" +
                                    std::to_string(image.rows) + " does not match texture '" + texture.label() + "'");
    cv::Mat bottomUp;
    cv::flip(image, bottomUp, 0);
    const GlFormat glFormat = glFormatOf(texture.format());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(texture.id(), 0, 0, 0, texture.width(), texture.height(), glFormat.pixelFormat,
                        glFormat.pixelType, bottomUp.data);
}

} // namespace inkgraph
