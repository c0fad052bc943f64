#pragma once
/** @file PNG files from outside (shade maps) reduced to what a picture needs before any decoder sees them. libpng
 *  allocates each chunk's declared length before reading it: fuzz_shademap found a 342-byte file whose tEXt chunk
 *  declares 1.9 GB. Text, colour-profile and other ancillary chunks (some zlib-compressed, so bombs) are dropped; the
 *  critical chunks are kept byte for byte, CRCs included, for libpng to check. No OpenImageIO here. */

#include <string_view>
#include <vector>

namespace inkgraph {

/** The PNG signature followed by the IHDR, PLTE, tRNS, IDAT and IEND chunks of `bytes`, in their order. Throws
 *  std::invalid_argument saying what is wrong (the caller names the file) unless `bytes` starts with the PNG
 *  signature, IHDR comes first with 13 bytes, every chunk lies inside the bytes, there is an IDAT, and IEND ends the
 *  chunk list. */
std::vector<unsigned char> criticalPngChunks(std::string_view bytes);

} // namespace inkgraph
