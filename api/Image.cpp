#include "api/Internal.h"

#include "render/ImageFiles.h"

#include <cstring>
#include <stdexcept>

namespace inkgraph::api {

Image imageOf(const cv::Mat& mat) {
    Image image;
    image.width = mat.cols;
    image.height = mat.rows;
    image.channels = mat.channels();
    if (mat.depth() == CV_8U)
        image.type = Image::Type::UInt8;
    else if (mat.depth() == CV_32F)
        image.type = Image::Type::Float32;
    else
        throw std::logic_error("imageOf(): a buffer of OpenCV depth " + std::to_string(mat.depth()) +
                               " (8-bit and float32 only)");
    if (image.channels != 1 && image.channels != 4)
        throw std::logic_error("imageOf(): a buffer of " + std::to_string(image.channels) + " channels (1 or 4 only)");
    const std::size_t rowBytes = std::size_t(mat.cols) * mat.elemSize();
    image.bytes.resize(rowBytes * std::size_t(mat.rows));
    for (int row = 0; row < mat.rows; ++row) std::memcpy(image.bytes.data() + row * rowBytes, mat.ptr(row), rowBytes);
    return image;
}

cv::Mat matOf(const Image& image) {
    if (image.width < 1 || image.height < 1 || (image.channels != 1 && image.channels != 4))
        throw UsageError("an image of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                         " pixels and " + std::to_string(image.channels) + " channels (at least 1x1, 1 or 4 channels)");
    const std::size_t expected =
        std::size_t(image.width) * std::size_t(image.height) * std::size_t(image.channels) * image.bytesPerChannel();
    if (image.bytes.size() != expected)
        throw UsageError("the image holds " + std::to_string(image.bytes.size()) + " bytes; " +
                         std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
                         std::to_string(image.channels) + " pixels need " + std::to_string(expected));
    const int type = CV_MAKETYPE(image.type == Image::Type::Float32 ? CV_32F : CV_8U, image.channels);
    // cv::Mat's constructor over external data takes a non-const pointer; the image is only read.
    return cv::Mat(image.height, image.width, type, const_cast<std::uint8_t*>(image.bytes.data()));
}

const float* Image::floats() const {
    if (type != Type::Float32)
        throw Error(Error::Kind::Usage, "Image::floats(): the image holds 8-bit pixels; read them from bytes");
    return reinterpret_cast<const float*>(bytes.data());
}

void Image::write(const std::string& path) const {
    translated("Image::write()", [&] { writeImage(path, matOf(*this)); });
}

} // namespace inkgraph::api
