// criticalPngChunks(): what a shade-map PNG is reduced to before libpng sees it.
#include "codecs/PngChunks.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

const std::string kSignature("\x89PNG\r\n\x1a\n", 8);

/** A chunk with a dummy CRC (criticalPngChunks leaves CRCs to libpng). */
std::string chunk(const std::string& type, const std::string& data, std::uint32_t declared = UINT32_MAX) {
    const std::uint32_t length = declared == UINT32_MAX ? std::uint32_t(data.size()) : declared;
    std::string bytes;
    for (int shift = 24; shift >= 0; shift -= 8) bytes.push_back(char((length >> shift) & 0xFF));
    return bytes + type + data + "CRC!";
}

std::string problemOf(const std::string& bytes) {
    try {
        criticalPngChunks(bytes);
    } catch (const std::invalid_argument& error) {
        return error.what();
    }
    ADD_FAILURE() << "expected std::invalid_argument";
    return {};
}

const std::string kHeader = chunk("IHDR", std::string(13, '\1'));

TEST(PngChunks, KeepsCriticalChunksByteForByteAndDropsTheRest) {
    const std::string text = chunk("tEXt", "Comment\0hello");
    const std::string profile = chunk("iCCP", "icc\0\0zlib data");
    const std::string bytes = kSignature + kHeader + text + chunk("PLTE", "abc") + profile + chunk("tRNS", "x") +
                              chunk("IDAT", "pixels") + chunk("IDAT", "more") + chunk("IEND", "") + "trailing junk";
    const std::vector<unsigned char> kept = criticalPngChunks(bytes);
    const std::string expected = kSignature + kHeader + chunk("PLTE", "abc") + chunk("tRNS", "x") +
                                 chunk("IDAT", "pixels") + chunk("IDAT", "more") + chunk("IEND", "");
    EXPECT_EQ(std::string(kept.begin(), kept.end()), expected);
}

TEST(PngChunks, AChunkDeclaringMoreThanTheFileHoldsIsRefused) {
    // The fuzz finding: a 342-byte file with a tEXt chunk declaring 1,979,711,508 bytes.
    const std::string bytes = kSignature + kHeader + chunk("tEXt", "abc", 1979711508u) + chunk("IEND", "");
    EXPECT_EQ(problemOf(bytes), "PNG chunk 'tEXt' at byte 33 declares 1979711508 bytes but only 15 follow");
    EXPECT_EQ(problemOf(kSignature + kHeader + chunk(std::string("\0\1ab", 4), "", 99)),
              "PNG chunk '\\x00\\x01ab' at byte 33 declares 99 bytes but only 0 follow");
}

TEST(PngChunks, StructureProblemsAreNamed) {
    EXPECT_EQ(problemOf("GIF89a"), "it is not a PNG file");
    EXPECT_EQ(problemOf(""), "it is not a PNG file");
    EXPECT_EQ(problemOf(kSignature + chunk("IDAT", "x")), "PNG does not start with a 13-byte IHDR chunk");
    EXPECT_EQ(problemOf(kSignature + chunk("IHDR", "short")), "PNG does not start with a 13-byte IHDR chunk");
    EXPECT_EQ(problemOf(kSignature + kHeader + chunk("IDAT", "x")),
              "truncated PNG: the chunk list ends at byte 46 without an IEND chunk");
    EXPECT_EQ(problemOf(kSignature + kHeader + chunk("IEND", "")), "PNG has no image data (IDAT chunk)");
}

} // namespace
} // namespace inkgraph
