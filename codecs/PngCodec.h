#pragma once
/** @file PNG through libpng, on plain buffers (no OpenCV, no GL): the one place that drives libpng. render/PngFiles
 *  adapts it to cv::Mat for the pictures inkgraph writes and reads back, scene/TextureImage to the RGBA8 a texture
 *  upload takes. Decoding is bounded by the header alone: libpng inflates the image data row by row into the rows
 *  the caller provides and stops at the bytes the declared image holds, so a small file whose data would inflate to
 *  gigabytes costs no more memory than its header's pixels (and, for textures, no more time) (text and colour-profile
 * chunks are the caller's to drop: codecs/PngChunks.h). */

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <vector>

namespace inkgraph {

/** The pixels a decode delivers, after its expansion. */
struct PngLayout {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    int bitDepth = 0; ///< 8 or 16
    int channels = 0; ///< 1 to 4
    std::size_t rowBytes() const { return std::size_t(width) * std::size_t(channels) * std::size_t(bitDepth / 8); }
};

enum class PngExpansion {
    /** OpenImageIO's rules, so either reader gives the same pixels: palettes to RGB (RGBA with tRNS), grey below 8
     *  bits to 8, tRNS to alpha; 16-bit samples stay 16-bit (native byte order). */
    AsStored,
    /** What a texture upload takes: every file as 8-bit RGBA (16-bit samples rounded to 8, grey to RGB, an opaque
     *  alpha where the file has none), so no wider buffer than width x height x 4 bytes is ever allocated; and the
     *  decode stops at the last row, so its time too is bounded by the header's pixels, not by the data. */
    Rgba8,
};

/** Called once the header is read, with the layout the decode will deliver: returns one pointer per row, each to
 *  layout.rowBytes() writable bytes. It may throw (a limit's refusal), which propagates before any pixel is read. */
using PngRowProvider = std::function<std::vector<unsigned char*>(const PngLayout&)>;

/** Decodes a PNG held in memory. Throws std::runtime_error with libpng's reason (or ours) for a corrupt, truncated
 *  or unsupported file; the caller names the file. */
void decodePngBytes(const unsigned char* bytes, std::size_t byteCount, PngExpansion expansion,
                    const PngRowProvider& rowsFor);

/** The same, reading `file` as libpng asks (our own outputs, read back by tests and tools). */
void decodePngStream(std::FILE* file, PngExpansion expansion, const PngRowProvider& rowsFor);

/** Encodes 8-bit rows (1 to 4 channels: grey, grey and alpha, RGB, RGBA; alpha straight) as a PNG marked sRGB.
 *  Throws std::runtime_error when libpng fails. */
std::vector<unsigned char> encodePngRows(std::uint32_t width, std::uint32_t height, int channels,
                                         const unsigned char* const* rows);

} // namespace inkgraph
