// The OpenImageIO side of render/ImageIoModule.h, built as the module libinkgraph_imageio.so.
#include "render/ImageIoModule.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <memory>
#include <string>

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

/** 8-bit sRGB colour as linear float, for float formats (EXR): readers take EXR values as linear light. */
cv::Mat linearFromSrgb(const cv::Mat& image) {
    float table[256];
    for (int code = 0; code < 256; ++code) {
        const double encoded = code / 255.0;
        table[code] = float(encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4));
    }
    cv::Mat linear(image.size(), CV_MAKETYPE(CV_32F, image.channels()));
    const int colorChannels = image.channels() == 4 ? 3 : image.channels();
    for (int row = 0; row < image.rows; ++row) {
        const uchar* in = image.ptr<uchar>(row);
        float* out = linear.ptr<float>(row);
        for (int i = 0; i < image.cols * image.channels(); ++i)
            out[i] = i % image.channels() < colorChannels ? table[in[i]] : in[i] / 255.0f; // alpha stays linear
    }
    return linear;
}

bool encodeWithOiio(const std::string& formatPath, const cv::Mat& image, std::vector<unsigned char>& bytes,
                    std::string& error) {
    if (image.empty() || oiioTypeOf(image.depth()) == OIIO::TypeDesc::UNKNOWN) {
        error = "only non-empty 8-bit or float32 images are written";
        return false;
    }
    auto output = OIIO::ImageOutput::create(formatPath);
    if (!output) {
        error = "no image format for this extension (" + OIIO::geterror() + ")";
        return false;
    }
    cv::Mat pixels = image.isContinuous() ? image : image.clone();
    // JPEG has no alpha: our pictures are opaque, so the alpha channel is simply left out.
    if (pixels.channels() == 4 && !output->supports("alpha")) {
        std::vector<cv::Mat> channels;
        cv::split(pixels, channels);
        channels.pop_back();
        cv::merge(channels, pixels);
    }
    const bool floatFormat = std::string(output->format_name()) == "openexr";
    if (floatFormat && pixels.depth() == CV_8U) pixels = linearFromSrgb(pixels);
    const OIIO::TypeDesc type = oiioTypeOf(pixels.depth());
    OIIO::ImageSpec spec(pixels.cols, pixels.rows, pixels.channels(), type);
    if (pixels.channels() == 4) spec.alpha_channel = 3;
    // 8-bit images are display colour (sRGB); float images are linear (light, or data such as normals and depths).
    // Alpha is coverage, never premultiplied, so OIIO must not (un)premultiply it.
    const bool tiff = std::string(output->format_name()) == "tiff";
    // OpenImageIO 2.4's TIFF writer puts the colour space into an EXIF directory, which it cannot write through a
    // memory proxy (the file comes out without its image directory: OpenImageIO pull request 4300); TIFF is read as
    // sRGB when 8-bit and linear when float without it.
    if (!tiff) spec.attribute("oiio:ColorSpace", type == OIIO::TypeDesc::UINT8 ? "sRGB" : "Linear");
    spec.attribute("oiio:UnassociatedAlpha", 1);
    // A fixed time stamp: the writers would stamp the current time (EXR's capDate, TIFF's DateTime), and the same
    // still must give the same bytes whenever it is rendered (a data set's checksums, --resume).
    spec.attribute("DateTime", "2000:01:01 00:00:00");
    OIIO::Filesystem::IOVecOutput memory(bytes);
    bytes.clear();
    if (!output->supports("ioproxy") || !output->set_ioproxy(&memory)) {
        error = std::string("the ") + output->format_name() + " writer cannot write to memory";
        return false;
    }
    if (!output->open(formatPath, spec) || !output->write_image(type, pixels.data) || !output->close()) {
        error = output->geterror();
        return false;
    }
    return true;
}

/** Checks what the opened file's header claims before anything of that size is allocated, then reads it. */
bool readOpened(OIIO::ImageInput& input, std::size_t maxPixels, cv::Mat& image, std::string& error) {
    const OIIO::ImageSpec& spec = input.spec();
    if (spec.nchannels < 1 || spec.nchannels > 4) {
        error = "it has " + std::to_string(spec.nchannels) + " channels; 1 to 4 are supported";
        return false;
    }
    // The header's sizes are the file's claim: a few bytes can declare gigapixels, so they are judged before any
    // allocation. A volume (depth > 1) or deep image would not fit the 2-D buffer read_image fills.
    if (spec.width <= 0 || spec.height <= 0) {
        error = "it declares " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " pixels";
        return false;
    }
    if (std::size_t(spec.width) * std::size_t(spec.height) > maxPixels) {
        error = "it declares " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                " pixels, more than the " + std::to_string(maxPixels) + " allowed here";
        return false;
    }
    if (spec.depth != 1 || spec.deep) {
        error = "it is a volume or deep image; only flat 2-D images are read";
        return false;
    }
    const bool eightBit = spec.format == OIIO::TypeDesc::UINT8;
    image.create(spec.height, spec.width, CV_MAKETYPE(eightBit ? CV_8U : CV_32F, spec.nchannels));
    if (!input.read_image(0, 0, 0, spec.nchannels, eightBit ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT,
                          image.data)) {
        error = input.geterror();
        return false;
    }
    return true;
}

bool readWithOiio(const std::string& path, std::size_t maxPixels, cv::Mat& image, std::string& error) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto input = OIIO::ImageInput::open(path, &config);
    if (!input) {
        error = OIIO::geterror();
        return false;
    }
    return readOpened(*input, maxPixels, image, error);
}

bool pixelTypeWithOiio(const std::string& path, std::string& type, std::string& error) {
    auto input = OIIO::ImageInput::open(path);
    if (!input) {
        error = OIIO::geterror();
        return false;
    }
    type = input->spec().format.c_str();
    return true;
}

const char* oiioVersion() {
    // The library's own number (e.g. 20407), not the headers' the module was built with.
    static const std::string kVersion = [] {
        const int number = OIIO::openimageio_version();
        return std::to_string(number / 10000) + "." + std::to_string(number / 100 % 100) + "." +
               std::to_string(number % 100);
    }();
    return kVersion.c_str();
}

const ImageIoFunctions kFunctions = {kImageIoVersion, encodeWithOiio, readWithOiio, pixelTypeWithOiio, oiioVersion};

} // namespace
} // namespace inkgraph

extern "C" __attribute__((visibility("default"))) const inkgraph::ImageIoFunctions* inkgraph_image_io_functions() {
    // OpenImageIO's and OpenEXR's worker pools off: their threads would fan each picture out over every core
    // while inkgraph already writes pictures on several threads (OpenImageIO's own advice for such callers), and a
    // process forked after a write inherited the pools without their threads: its next EXR write waited for them
    // forever. exr_threads -1 is OpenEXR's 0 threads (0 would be the cores'). Once, when the module is first asked.
    static const bool singleThreaded = [] {
        OIIO::attribute("threads", 1);
        OIIO::attribute("exr_threads", -1);
        return true;
    }();
    (void)singleThreaded;
    return &inkgraph::kFunctions;
}
