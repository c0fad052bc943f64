#include "codecs/WebpCodec.h"

#include <webp/decode.h>

#include <cstring>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

std::string statusText(VP8StatusCode status) {
    switch (status) {
    case VP8_STATUS_OK: return "ok";
    case VP8_STATUS_OUT_OF_MEMORY: return "out of memory";
    case VP8_STATUS_INVALID_PARAM: return "invalid parameter";
    case VP8_STATUS_BITSTREAM_ERROR: return "bitstream error";
    case VP8_STATUS_UNSUPPORTED_FEATURE: return "unsupported feature";
    case VP8_STATUS_SUSPENDED: return "suspended";
    case VP8_STATUS_USER_ABORT: return "aborted";
    case VP8_STATUS_NOT_ENOUGH_DATA: return "not enough data (truncated)";
    }
    return "status " + std::to_string(int(status));
}

std::runtime_error failure(const char* step, VP8StatusCode status) {
    return std::runtime_error(std::string("libwebp ") + step + ": " + statusText(status));
}

/** libwebp's own buffers for an image of this layout (WebpLayout::decoderBytes). */
std::size_t decoderBytesOf(const WebpLayout& layout) {
    const std::size_t pixels = std::size_t(layout.width) * layout.height;
    const std::size_t rows = std::size_t(layout.width) * 256; // row caches of either decoder, generously
    const std::size_t whole =
        layout.lossless ? pixels * 4 + std::size_t(layout.width) * 17 * 4 : (layout.hasAlpha ? pixels * 2 : 0);
    return whole + rows + (std::size_t(1) << 20);
}

} // namespace

bool looksLikeWebp(const unsigned char* bytes, std::size_t byteCount) {
    return byteCount >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0;
}

void decodeWebpRgba8(const unsigned char* bytes, std::size_t byteCount, const WebpPixelProvider& pixelsFor) {
    WebPDecoderConfig config;
    if (!WebPInitDecoderConfig(&config)) throw std::runtime_error("libwebp: version mismatch with its header");
    const VP8StatusCode header = WebPGetFeatures(bytes, byteCount, &config.input);
    if (header != VP8_STATUS_OK) throw failure("header", header);
    if (config.input.has_animation)
        throw std::runtime_error("an animated WebP, which libwebp's still decoder does not read; export one frame");
    if (config.input.width <= 0 || config.input.height <= 0) throw std::runtime_error("libwebp header: no pixels");
    WebpLayout layout;
    layout.width = std::uint32_t(config.input.width);
    layout.height = std::uint32_t(config.input.height);
    layout.hasAlpha = config.input.has_alpha != 0;
    layout.lossless = config.input.format == 2;
    layout.decoderBytes = decoderBytesOf(layout);
    unsigned char* pixels = pixelsFor(layout);
    config.output.colorspace = MODE_RGBA;
    config.output.is_external_memory = 1;
    config.output.u.RGBA.rgba = pixels;
    config.output.u.RGBA.stride = int(layout.width) * 4;
    config.output.u.RGBA.size = std::size_t(layout.width) * layout.height * 4;
    const VP8StatusCode decode = WebPDecode(bytes, byteCount, &config);
    WebPFreeDecBuffer(&config.output); // frees nothing of the caller's external memory; any buffer of libwebp's own
    if (decode != VP8_STATUS_OK) throw failure("decode", decode);
    if (config.output.width != config.input.width || config.output.height != config.input.height)
        throw std::runtime_error("libwebp decodes " + std::to_string(config.output.width) + "x" +
                                 std::to_string(config.output.height) + " pixels, not the header's " +
                                 std::to_string(layout.width) + "x" + std::to_string(layout.height));
}

} // namespace inkgraph
