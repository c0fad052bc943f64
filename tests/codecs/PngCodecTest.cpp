// encodePngRows(): the pixels come back exactly, and the row filter follows the picture (none for flat cel shading,
// Up for gradients), read from the file's own inflated scanlines rather than from libpng's state.
#include "codecs/PngCodec.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

constexpr std::uint32_t kSide = 96;

/** RGBA rows of kSide x kSide pixels, each given by `pixel(col, row, channel)`. */
template <typename Pixel>
std::vector<unsigned char> picture(Pixel pixel) {
    std::vector<unsigned char> rgba(std::size_t(kSide) * kSide * 4);
    for (std::uint32_t row = 0; row < kSide; ++row)
        for (std::uint32_t col = 0; col < kSide; ++col)
            for (std::uint32_t channel = 0; channel < 4; ++channel)
                rgba[(std::size_t(row) * kSide + col) * 4 + channel] = pixel(col, row, channel);
    return rgba;
}

/** Flat areas with sharp edges, as cel shading draws them: a disc of one colour on paper, and a dark line. */
std::vector<unsigned char> celPicture() {
    return picture([](std::uint32_t col, std::uint32_t row, std::uint32_t channel) -> unsigned char {
        if (channel == 3) return 255;
        if (col == 70) return 20;
        const int dx = int(col) - 40;
        const int dy = int(row) - 48;
        return dx * dx + dy * dy < 900 ? (unsigned char)(100 + 40 * channel) : 250;
    });
}

/** Smooth shading: every pixel differs from its neighbours. */
std::vector<unsigned char> gradientPicture() {
    return picture([](std::uint32_t col, std::uint32_t row, std::uint32_t channel) -> unsigned char {
        return channel == 3 ? 255 : (unsigned char)((col * 2 + row * 3 + channel * 7) & 0xFF);
    });
}

std::vector<unsigned char> encode(const std::vector<unsigned char>& rgba) {
    std::vector<const unsigned char*> rows;
    for (std::uint32_t row = 0; row < kSide; ++row) rows.push_back(&rgba[std::size_t(row) * kSide * 4]);
    return encodePngRows(kSide, kSide, 4, rows.data());
}

std::vector<unsigned char> decode(const std::vector<unsigned char>& file) {
    std::vector<unsigned char> rgba(std::size_t(kSide) * kSide * 4);
    decodePngBytes(file.data(), file.size(), PngExpansion::AsStored, [&](const PngLayout& layout) {
        EXPECT_EQ(layout.width, kSide);
        EXPECT_EQ(layout.height, kSide);
        EXPECT_EQ(layout.channels, 4);
        EXPECT_EQ(layout.bitDepth, 8);
        std::vector<unsigned char*> rows;
        for (std::uint32_t row = 0; row < kSide; ++row) rows.push_back(&rgba[std::size_t(row) * kSide * 4]);
        return rows;
    });
    return rgba;
}

/** The filter type byte of every scanline: the IDAT chunks joined and inflated. */
std::set<int> rowFiltersOf(const std::vector<unsigned char>& file, std::uint32_t height = kSide) {
    std::string deflated;
    for (std::size_t at = 8; at + 12 <= file.size();) {
        const std::uint32_t length = std::uint32_t(file[at]) << 24 | std::uint32_t(file[at + 1]) << 16 |
                                     std::uint32_t(file[at + 2]) << 8 | std::uint32_t(file[at + 3]);
        const std::string type(reinterpret_cast<const char*>(&file[at + 4]), 4);
        if (type == "IDAT") deflated.append(reinterpret_cast<const char*>(&file[at + 8]), length);
        at += 12 + std::size_t(length);
    }
    const std::size_t scanlineBytes = 1 + std::size_t(kSide) * 4;
    std::vector<unsigned char> scanlines(scanlineBytes * height);
    uLongf inflatedSize = uLongf(scanlines.size());
    EXPECT_EQ(uncompress(scanlines.data(), &inflatedSize, reinterpret_cast<const Bytef*>(deflated.data()),
                         uLong(deflated.size())),
              Z_OK);
    EXPECT_EQ(inflatedSize, scanlines.size());
    std::set<int> filters;
    for (std::uint32_t row = 0; row < height; ++row) filters.insert(scanlines[row * scanlineBytes]);
    return filters;
}

TEST(PngCodec, FlatCelShadingIsWrittenUnfilteredAndComesBackExactly) {
    const std::vector<unsigned char> rgba = celPicture();
    const std::vector<unsigned char> file = encode(rgba);
    EXPECT_EQ(decode(file), rgba);
    EXPECT_EQ(rowFiltersOf(file), std::set<int>{0}); // PNG filter type 0: none
}

TEST(PngCodec, GradientsAreWrittenWithTheUpFilterAndComeBackExactly) {
    const std::vector<unsigned char> rgba = gradientPicture();
    const std::vector<unsigned char> file = encode(rgba);
    EXPECT_EQ(decode(file), rgba);
    EXPECT_EQ(rowFiltersOf(file), std::set<int>{2}); // PNG filter type 2: Up
}

TEST(PngCodec, PicturesTooShortToSampleAreWrittenUnfiltered) {
    const std::vector<unsigned char> rgba = gradientPicture();
    const std::vector<const unsigned char*> rows{rgba.data(), rgba.data() + kSide * 4};
    const std::vector<unsigned char> file = encodePngRows(kSide, 2, 4, rows.data());
    std::vector<unsigned char> decoded(std::size_t(kSide) * 2 * 4);
    decodePngBytes(file.data(), file.size(), PngExpansion::AsStored, [&](const PngLayout&) {
        return std::vector<unsigned char*>{decoded.data(), decoded.data() + kSide * 4};
    });
    EXPECT_EQ(decoded, std::vector<unsigned char>(rgba.begin(), rgba.begin() + kSide * 2 * 4));
    EXPECT_EQ(rowFiltersOf(file, 2), std::set<int>{0});
}

} // namespace
} // namespace inkgraph
