#pragma once
/** @file WebP through libwebp (Debian's libwebp7), on plain buffers: a texture (EXT_texture_webp) is decoded straight
 *  into the caller's 8-bit RGBA buffer. The header (the RIFF container's VP8, VP8L or VP8X chunk) gives the size and
 *  the kind of bitstream before anything of the image's size is allocated, so the caller can judge the pixels and what
 *  libwebp allocates of its own. */

#include <cstddef>
#include <cstdint>
#include <functional>

namespace inkgraph {

struct WebpLayout {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    bool hasAlpha = false;
    bool lossless = false; ///< VP8L; false: VP8 (lossy), whose alpha, when it has one, is a lossless plane of its own
    /** What libwebp allocates of its own while decoding, as its decoders size their buffers: a lossless image is
     *  decoded whole into 32-bit ARGB first (4 bytes a pixel, plus a cache of 17 rows); a lossy one keeps a few rows of
     *  its planes, and its alpha plane whole (a byte a pixel, and as much again for the lossless decode of it); plus
     *  1 MiB for the Huffman tables, the transforms' data and the rest. */
    std::size_t decoderBytes = 0;
};

/** Called once the header is read: returns the start of width x height x 4 writable bytes (RGBA, rows top to bottom,
 *  no padding). It may throw (a limit's refusal), which propagates before libwebp allocates anything. */
using WebpPixelProvider = std::function<unsigned char*(const WebpLayout&)>;

/** True when `bytes` begin as a WebP file does: "RIFF", the size, "WEBP". */
bool looksLikeWebp(const unsigned char* bytes, std::size_t byteCount);

/** Decodes a still WebP held in memory to 8-bit RGBA, alpha straight (255 where the file has none). Throws
 *  std::runtime_error with libwebp's status for a corrupt, truncated or unsupported file, and for an animated one
 *  (libwebp's still decoder does not read animations). */
void decodeWebpRgba8(const unsigned char* bytes, std::size_t byteCount, const WebpPixelProvider& pixelsFor);

} // namespace inkgraph
