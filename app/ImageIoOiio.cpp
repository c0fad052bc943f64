// The OpenImageIO side of app/ImageIoModule.h, built as the module libinkgraph_imageio.so.
#include "app/ImageIoModule.h"

#include <OpenImageIO/imageio.h>

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
    OIIO::ImageSpec spec(image.cols, image.rows, image.channels(), type);
    if (image.channels() == 4) spec.alpha_channel = 3;
    if (type == OIIO::TypeDesc::UINT8) spec.attribute("png:compressionLevel", 3); // 2x faster than 6, ~same size
    const cv::Mat contiguous = image.isContinuous() ? image : image.clone();
    if (!output->open(temporaryPath, spec) || !output->write_image(type, contiguous.data) || !output->close()) {
        error = output->geterror();
        return false;
    }
    return true;
}

bool readWithOiio(const std::string& path, cv::Mat& image, std::string& error) {
    auto input = OIIO::ImageInput::open(path);
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

const ImageIoFunctions kFunctions = {kImageIoVersion, writeWithOiio, readWithOiio, hasOiioWriter};

} // namespace
} // namespace inkgraph

extern "C" __attribute__((visibility("default"))) const inkgraph::ImageIoFunctions* inkgraph_image_io_functions() {
    return &inkgraph::kFunctions;
}
