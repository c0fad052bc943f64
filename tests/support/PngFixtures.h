#pragma once
/** @file PNG files built byte by byte for tests (zlib for the CRCs), not by libpng, so the readers are not only
 *  checked against their own writer. Link ZLIB::ZLIB. */

#include <zlib.h>

#include <cstdint>
#include <string>

namespace inkgraph::test {

inline std::string bigEndian32(std::uint32_t value) {
    std::string bytes;
    for (int shift = 24; shift >= 0; shift -= 8) bytes.push_back(char((value >> shift) & 0xFF));
    return bytes;
}

/** One chunk: length, type, data and the CRC of type and data. */
inline std::string pngChunk(const std::string& type, const std::string& data) {
    const std::string body = type + data;
    const auto crc = std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size())));
    return bigEndian32(std::uint32_t(data.size())) + body + bigEndian32(crc);
}

/** A PNG whose one IDAT chunk holds `idat` (a zlib stream), with `extra` chunks (PLTE, tRNS) between IHDR and IDAT. */
inline std::string pngWithImageData(std::uint32_t width, std::uint32_t height, int bitDepth, int colorType,
                                    const std::string& idat, const std::string& extra = "", int interlace = 0) {
    std::string header = bigEndian32(width) + bigEndian32(height);
    for (const int field : {bitDepth, colorType, 0, 0, interlace}) header.push_back(char(field));
    return std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", header) + extra + pngChunk("IDAT", idat) +
           pngChunk("IEND", "");
}

} // namespace inkgraph::test
