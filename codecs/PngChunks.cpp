#include "codecs/PngChunks.h"

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

constexpr std::string_view kSignature("\x89PNG\r\n\x1a\n", 8);
constexpr std::size_t kChunkOverhead = 12; // length, type, CRC

std::uint32_t bigEndian32(std::string_view bytes) {
    return std::uint32_t(std::uint8_t(bytes[0])) << 24 | std::uint32_t(std::uint8_t(bytes[1])) << 16 |
           std::uint32_t(std::uint8_t(bytes[2])) << 8 | std::uint32_t(std::uint8_t(bytes[3]));
}

/** A chunk type as text for messages: letters as they are, anything else as \xNN. */
std::string shownType(std::string_view type) {
    std::string shown;
    for (const char c : type) {
        const auto code = std::uint8_t(c);
        if ((code >= 'A' && code <= 'Z') || (code >= 'a' && code <= 'z')) {
            shown += c;
        } else {
            constexpr char kHex[] = "0123456789abcdef";
            shown += std::string("\\x") + kHex[code >> 4] + kHex[code & 15];
        }
    }
    return shown;
}

bool isKept(std::string_view type) {
    return type == "IHDR" || type == "PLTE" || type == "tRNS" || type == "IDAT" || type == "IEND";
}

} // namespace

std::vector<unsigned char> criticalPngChunks(std::string_view bytes) {
    if (bytes.substr(0, kSignature.size()) != kSignature) throw std::invalid_argument("it is not a PNG file");
    std::vector<unsigned char> kept(kSignature.begin(), kSignature.end());
    std::size_t offset = kSignature.size();
    bool sawData = false;
    for (std::size_t index = 0;; ++index) {
        if (bytes.size() - offset < kChunkOverhead)
            throw std::invalid_argument("truncated PNG: the chunk list ends at byte " + std::to_string(offset) +
                                        " without an IEND chunk");
        const std::uint32_t length = bigEndian32(bytes.substr(offset, 4));
        const std::string_view type = bytes.substr(offset + 4, 4);
        if (length > bytes.size() - offset - kChunkOverhead)
            throw std::invalid_argument("PNG chunk '" + shownType(type) + "' at byte " + std::to_string(offset) +
                                        " declares " + std::to_string(length) + " bytes but only " +
                                        std::to_string(bytes.size() - offset - kChunkOverhead) + " follow");
        if (index == 0 && (type != "IHDR" || length != 13))
            throw std::invalid_argument("PNG does not start with a 13-byte IHDR chunk");
        if (type == "IDAT") sawData = true;
        const std::size_t chunkBytes = kChunkOverhead + length;
        if (isKept(type)) kept.insert(kept.end(), bytes.begin() + offset, bytes.begin() + offset + chunkBytes);
        offset += chunkBytes;
        if (type == "IEND") break;
    }
    if (!sawData) throw std::invalid_argument("PNG has no image data (IDAT chunk)");
    return kept;
}

} // namespace inkgraph
