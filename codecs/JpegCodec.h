#pragma once
/** @file JPEG through libjpeg-turbo (Debian's libjpeg62-turbo), on plain buffers: a texture is decoded row by row
 *  straight into 8-bit RGBA, so the only buffer of the image's size is the caller's. A progressive (or otherwise
 *  multi-scan) file also needs libjpeg's whole-image coefficient buffers: the header says how large they are
 *  (JpegLayout::decoderBytes), so the caller can judge them with the pixels before anything is allocated, and the
 *  decoder is held to that figure. */

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace inkgraph {

struct JpegLayout {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    int components = 0;         ///< in the file: 1 grey, 3 YCbCr, 4 CMYK or YCCK
    bool multipleScans = false; ///< progressive or non-interleaved: decoded through whole-image buffers
    /** What libjpeg allocates of its own while decoding: the coefficient buffers of a multi-scan file (2 bytes per
     *  coefficient, 64 per block of each component), plus the row buffers and tables of any file. */
    std::size_t decoderBytes = 0;
};

/** Called once the header is read: returns one pointer per row, each to width x 4 writable bytes (RGBA). It may throw
 *  (a limit's refusal), which propagates before libjpeg allocates anything of the image's size. */
using JpegRowProvider = std::function<std::vector<unsigned char*>(const JpegLayout&)>;

/** Decodes a JPEG held in memory to 8-bit RGBA (alpha 255; grey and CMYK files converted as libjpeg-turbo does).
 *  Throws std::runtime_error with libjpeg's reason for a corrupt, truncated or unsupported file. */
void decodeJpegRgba8(const unsigned char* bytes, std::size_t byteCount, const JpegRowProvider& rowsFor);

} // namespace inkgraph
