#include "api/Internal.h"

#include "render/ImageFiles.h"

#include <cstdint>
#include <stdexcept>

namespace inkgraph::api {
inline namespace INKGRAPH_ABI_NAMESPACE {
namespace {

/** The most bytes an Image may describe (128 TiB): far beyond any memory, and small enough that byteCount() cannot
 *  wrap around (a width and height near INT_MAX would make it a small number that a short buffer then matches). */
constexpr double kMostImageBytes = double(std::uint64_t(1) << 47);

/** UsageError unless the fields describe an image: at least 1x1, 1 or 4 channels, 8-bit or float32, at most
 *  kMostImageBytes. */
void checkShape(int width, int height, int channels, Image::Type type) {
    const std::string shape = "an image of " + std::to_string(width) + "x" + std::to_string(height) + " pixels and " +
                              std::to_string(channels) + " channels";
    if (width < 1 || height < 1 || (channels != 1 && channels != 4))
        throw UsageError(shape + " (at least 1x1, 1 or 4 channels)");
    if (type != Image::Type::UInt8 && type != Image::Type::Float32)
        throw UsageError(shape + " of type " + std::to_string(int(type)) + " (Image::Type::UInt8 or Float32)");
    if (double(width) * double(height) * double(channels) * sizeof(float) > kMostImageBytes)
        throw UsageError(shape + ": more than 2^47 bytes, which no memory holds");
}

} // namespace

Image::Image(int width, int height, int channels, Type type, std::vector<std::uint8_t> bytes)
    : mWidth(width), mHeight(height), mChannels(channels), mType(type) {
    mRowBytes = packedRowBytes();
    translated("Image()", [&] {
        checkShape(width, height, channels, type);
        if (bytes.size() != byteCount())
            throw UsageError("the image holds " + std::to_string(bytes.size()) + " bytes; " + std::to_string(width) +
                             "x" + std::to_string(height) + "x" + std::to_string(channels) + " pixels need " +
                             std::to_string(byteCount()));
    });
    auto owned = std::make_shared<std::vector<std::uint8_t>>(std::move(bytes));
    mData = owned->data();
    mOwner = std::move(owned);
}

Image::Image(int width, int height, int channels, Type type, const std::uint8_t* data, std::size_t rowBytes,
             std::shared_ptr<const void> owner)
    : mWidth(width), mHeight(height), mChannels(channels), mType(type), mRowBytes(rowBytes), mData(data),
      mOwner(std::move(owner)) {}

Image imageOf(const cv::Mat& mat) {
    Image::Type type = Image::Type::UInt8;
    if (mat.depth() == CV_32F)
        type = Image::Type::Float32;
    else if (mat.depth() != CV_8U)
        throw std::logic_error("imageOf(): a buffer of OpenCV depth " + std::to_string(mat.depth()) +
                               " (8-bit and float32 only)");
    if (mat.channels() != 1 && mat.channels() != 4)
        throw std::logic_error("imageOf(): a buffer of " + std::to_string(mat.channels()) + " channels (1 or 4 only)");
    // The image shares the buffer's pixels: OpenCV counts the references, so they live as long as the image.
    auto kept = std::make_shared<cv::Mat>(mat);
    const std::uint8_t* data = kept->ptr();
    const std::size_t rowBytes = kept->step[0];
    const int width = kept->cols;
    const int height = kept->rows;
    const int channels = kept->channels();
    return ImageAccess::view(width, height, channels, type, data, rowBytes, std::move(kept));
}

cv::Mat matOf(const Image& image) {
    checkShape(image.width(), image.height(), image.channels(), image.type());
    const int type = CV_MAKETYPE(image.type() == Image::Type::Float32 ? CV_32F : CV_8U, image.channels());
    // cv::Mat's constructor over external data takes a non-const pointer; the image is only read.
    return cv::Mat(image.height(), image.width(), type, const_cast<std::uint8_t*>(image.data()), image.rowBytes());
}

const float* Image::floats() const {
    if (mType != Type::Float32)
        throw Error(Error::Kind::Usage, "Image::floats(): the image holds 8-bit pixels; read them from data()");
    return reinterpret_cast<const float*>(mData);
}

void Image::write(const std::string& path) const {
    translated("Image::write()", [&] { writeImage(path, matOf(*this)); });
}

} // namespace INKGRAPH_ABI_NAMESPACE
} // namespace inkgraph::api
