#pragma once
/** @file PNG through libpng (codecs/PngCodec.h), in the process. Every still writes a PNG, and OpenImageIO's ~0.2 s of
 * dynamic linking (render/ImageIoModule.h) was most of a small still's run; libpng is one small library beside zlib,
 * which the process links anyway. render/ImageFiles sends every .png here and every other format to OpenImageIO. Images
 * are cv::Mat with row 0 at the top and channels in RGBA order, as everywhere in inkgraph. Encoding stays in memory:
 * the caller writes the bytes (render/ImageFiles' writeBytes), so the output transaction is the same for every format.
 */

#include <opencv2/core.hpp>

#include <cstddef>
#include <filesystem>
#include <vector>

namespace inkgraph {

/** Encodes CV_8UC1..CV_8UC4 (grey, grey and alpha, RGB, RGBA; alpha straight) as an 8-bit PNG marked sRGB. Throws
 *  std::runtime_error saying why for any other type (float images belong in EXR: PNG would quantise them) or when
 *  libpng fails; the caller names the file. */
std::vector<unsigned char> encodePng(const cv::Mat& image);

/** Decodes a PNG as OpenImageIO did, so either reader gives the same pixels: palettes become RGB (RGBA with a tRNS
 *  chunk), grey below 8 bits becomes 8-bit grey, tRNS becomes an alpha channel; 8-bit files come back as CV_8UCn,
 *  16-bit ones as CV_32FCn scaled to [0, 1]. A header declaring more than `maxPixels` pixels is refused before the
 *  pixels are allocated. Throws std::runtime_error with libpng's reason (or ours); the caller names the file. */
cv::Mat decodePng(const unsigned char* bytes, std::size_t byteCount, std::size_t maxPixels);

/** decodePng() reading from a file as it goes (our own outputs, read back by tests and tools), so the file's size
 *  needs no limit of its own: only the declared pixels are judged. */
cv::Mat readPngFile(const std::filesystem::path& path, std::size_t maxPixels);

} // namespace inkgraph
