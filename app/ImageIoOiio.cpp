// The OpenImageIO side of app/ImageIoModule.h, built as the module libinkgraph_imageio.so.
#include "app/ImageIoModule.h"

#include <OpenImageIO/imageio.h>

#include <vector>

namespace inkgraph {
namespace {

OIIO::TypeDesc oiioTypeOf(int depth) {
    switch (depth) {
    case CV_8U: return OIIO::TypeDesc::UINT8;
    case CV_32F: return OIIO::TypeDesc::FLOAT;
    default: return OIIO::TypeDesc::UNKNOWN;
    }
}

bool writeWithOiio(const std::string& formatPath, const std::string& temporaryPath, const cv::Mat& image,
                   std::string& error) {
    const OIIO::TypeDesc type = oiioTypeOf(image.depth());
    if (image.empty() || type == OIIO::TypeDesc::UNKNOWN) {
        error = "only non-empty 8-bit or float32 images are written";
        return false;
    }
    // The writer is chosen by the final name's extension; the temporary name keeps the same extension anyway.
    auto output = OIIO::ImageOutput::create(formatPath);
    if (!output) {
        error = "no image format for this extension (" + OIIO::geterror() + ")";
        return false;
    }
    cv::Mat contiguous = image.isContinuous() ? image : image.clone();
    // JPEG has no alpha: our pictures are opaque, so the alpha channel is simply left out.
    if (contiguous.channels() == 4 && !output->supports("alpha")) {
        cv::Mat rgb;
        std::vector<cv::Mat> channels;
        cv::split(contiguous, channels);
        channels.pop_back();
        cv::merge(channels, rgb);
        contiguous = rgb;
    }
    OIIO::ImageSpec spec(contiguous.cols, contiguous.rows, contiguous.channels(), type);
    if (contiguous.channels() == 4) spec.alpha_channel = 3;
    // 8-bit images are display colour (sRGB); float images are linear data (normals, depths). Alpha is coverage,
    // never premultiplied, so OIIO must not (un)premultiply it.
    spec.attribute("oiio:ColorSpace", type == OIIO::TypeDesc::UINT8 ? "sRGB" : "Linear");
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (type == OIIO::TypeDesc::UINT8) spec.attribute("png:compressionLevel", 3); // faster than 6, about as small
    if (!output->open(temporaryPath, spec) || !output->write_image(type, contiguous.data) || !output->close()) {
        error = output->geterror();
        return false;
    }
    return true;
}

bool readWithOiio(const std::string& path, cv::Mat& image, std::string& error) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto input = OIIO::ImageInput::open(path, &config);
    if (!input) {
        error = OIIO::geterror();
        return false;
    }
    const OIIO::ImageSpec& spec = input->spec();
    if (spec.nchannels < 1 || spec.nchannels > 4) {
        error = "it has " + std::to_string(spec.nchannels) + " channels; 1 to 4 are supported";
        return false;
    }
    const bool eightBit = spec.format == OIIO::TypeDesc::UINT8;
    image.create(spec.height, spec.width, CV_MAKETYPE(eightBit ? CV_8U : CV_32F, spec.nchannels));
    if (!input->read_image(0, 0, 0, spec.nchannels, eightBit ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT,
                           image.data)) {
        error = input->geterror();
        return false;
    }
    return true;
}

bool hasOiioWriter(const std::string& path) { return OIIO::ImageOutput::create(path) != nullptr; }

bool pixelTypeWithOiio(const std::string& path, std::string& type, std::string& error) {
    auto input = OIIO::ImageInput::open(path);
    if (!input) {
        error = OIIO::geterror();
        return false;
    }
    type = input->spec().format.c_str();
    return true;
}

const ImageIoFunctions kFunctions = {kImageIoVersion, writeWithOiio, readWithOiio, hasOiioWriter, pixelTypeWithOiio};

} // namespace
} // namespace inkgraph

extern "C" __attribute__((visibility("default"))) const inkgraph::ImageIoFunctions* inkgraph_image_io_functions() {
    return &inkgraph::kFunctions;
}
