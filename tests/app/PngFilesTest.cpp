// PNG through libpng (render/PngFiles.h) behind writeImage/readImage/readPngImage (render/ImageFiles.h): round trips
// with analytic pixels, the expansions OpenImageIO made (16-bit, palette, low bit depths, tRNS, grey and alpha, Adam7),
// checked against the OpenImageIO module itself, and broken files refused with the file named, never a crash.
// The fixtures are built byte by byte here (zlib for the deflate stream and the CRCs), not by libpng, so the reader
// is not only checked against its own writer.
#include "render/ImageFiles.h"
#include "render/ImageIoModule.h"
#include "tests/support/PngFixtures.h"
#include "tests/support/TestFolder.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <dlfcn.h>

#include <cstdint>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

namespace fs = std::filesystem;

std::string deflated(const std::string& raw) {
    uLongf size = compressBound(uLong(raw.size()));
    std::string out(size, '\0');
    EXPECT_EQ(compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                        uLong(raw.size()), 9),
              Z_OK);
    out.resize(size);
    return out;
}

/** A PNG of `scanlines` (each row already packed and prefixed with its filter byte), with `extra` chunks (PLTE,
 *  tRNS) between IHDR and IDAT. */
std::string pngFile(std::uint32_t width, std::uint32_t height, int bitDepth, int colorType,
                    const std::string& scanlines, const std::string& extra = "", int interlace = 0) {
    return test::pngWithImageData(width, height, bitDepth, colorType, deflated(scanlines), extra, interlace);
}

/** Rows of samples packed at `bitDepth` (1, 2, 4, 8 or 16 bits, big-endian, first sample in the high bits), each
 *  prefixed with filter 0 (none). */
std::string scanlinesOf(const std::vector<std::vector<int>>& rows, int bitDepth) {
    std::string out;
    for (const std::vector<int>& samples : rows) {
        out.push_back('\0');
        if (bitDepth >= 8) {
            for (const int sample : samples) {
                if (bitDepth == 16) out.push_back(char(sample >> 8));
                out.push_back(char(sample & 0xFF));
            }
            continue;
        }
        int bits = 0;
        unsigned accumulated = 0;
        for (const int sample : samples) {
            accumulated = accumulated << bitDepth | unsigned(sample);
            bits += bitDepth;
            if (bits == 8) {
                out.push_back(char(accumulated));
                bits = 0;
                accumulated = 0;
            }
        }
        if (bits > 0) out.push_back(char(accumulated << (8 - bits)));
    }
    return out;
}

void writeFile(const fs::path& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

std::string readFile(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

std::string failureOf(const std::function<void()>& action) {
    try {
        action();
    } catch (const FileError& error) {
        return error.what();
    }
    ADD_FAILURE() << "expected FileError";
    return {};
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class PngFiles : public test::TestFolder {};

TEST_F(PngFiles, GreyAndRgbaRoundTripExactly) {
    cv::Mat grey(37, 53, CV_8UC1);
    cv::Mat rgba(37, 53, CV_8UC4);
    for (int row = 0; row < grey.rows; ++row)
        for (int col = 0; col < grey.cols; ++col) {
            grey.at<uchar>(row, col) = uchar((7 * row + 3 * col) % 256);
            // Every channel its own function, and alpha 0 under colour: straight alpha, never premultiplied.
            rgba.at<cv::Vec4b>(row, col) = cv::Vec4b(uchar(row * 5), uchar(col * 4), uchar((row * col) % 256),
                                                     uchar((row + col) % 3 == 0 ? 0 : 200));
        }
    writeImage(directory / "grey.png", grey);
    writeImage(directory / "rgba.png", rgba);
    const cv::Mat greyBack = readImage(directory / "grey.png");
    const cv::Mat rgbaBack = readImage(directory / "rgba.png");
    ASSERT_EQ(greyBack.type(), CV_8UC1);
    ASSERT_EQ(rgbaBack.type(), CV_8UC4);
    EXPECT_EQ(cv::norm(greyBack, grey, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(rgbaBack, rgba, cv::NORM_INF), 0.0);
    // Row 0 at the top, RGBA order: the first pixel's bytes in the file's own order.
    EXPECT_EQ(rgbaBack.at<cv::Vec4b>(0, 1), cv::Vec4b(0, 4, 0, 200));
    EXPECT_EQ(imageFilePixelType(directory / "rgba.png"), "uint8") << "OpenImageIO reads what libpng wrote";
    // An upper-case extension is PNG too, and a sub-matrix (rows not contiguous) is written as it looks.
    const cv::Mat part = rgba(cv::Rect(5, 3, 17, 11));
    writeImage(directory / "part.PNG", part);
    EXPECT_EQ(cv::norm(readImage(directory / "part.PNG"), part, cv::NORM_INF), 0.0);
}

TEST_F(PngFiles, FloatImagesAreRefusedNamingTheFile) {
    const std::string message =
        failureOf([&] { writeImage(directory / "depth.png", cv::Mat(4, 4, CV_32FC1, cv::Scalar(0.5))); });
    EXPECT_TRUE(contains(message, "writeImage(): cannot write '" + (directory / "depth.png").string() + "'"))
        << message;
    EXPECT_TRUE(contains(message, "float images go to .exr")) << message;
    EXPECT_FALSE(fs::exists(directory / "depth.png"));
}

/** The fixtures below, each with the image OpenImageIO gave for it (and so must we). */
struct Fixture {
    std::string name;
    std::string bytes;
    cv::Mat expected;
};

std::vector<Fixture> expansionFixtures() {
    std::vector<Fixture> fixtures;
    // 16-bit grey: float, 65535 as 1.
    {
        std::vector<std::vector<int>> rows(3, std::vector<int>(5));
        cv::Mat expected(3, 5, CV_32FC1);
        for (int row = 0; row < 3; ++row)
            for (int col = 0; col < 5; ++col) {
                rows[row][col] = row == 2 && col == 4 ? 65535 : 1000 * row + 257 * col + 1;
                expected.at<float>(row, col) = float(rows[row][col]) / 65535.0f;
            }
        fixtures.push_back({"grey16.png", pngFile(5, 3, 16, 0, scanlinesOf(rows, 16)), expected});
    }
    // 16-bit RGBA: four float channels.
    {
        std::vector<std::vector<int>> rows(2, std::vector<int>(2 * 4));
        cv::Mat expected(2, 2, CV_32FC4);
        for (int row = 0; row < 2; ++row)
            for (int i = 0; i < 8; ++i) {
                rows[row][i] = 4099 * (i + 1) + 31 * row;
                expected.ptr<float>(row)[i] = float(rows[row][i]) / 65535.0f;
            }
        fixtures.push_back({"rgba16.png", pngFile(2, 2, 16, 6, scanlinesOf(rows, 16)), expected});
    }
    // A 2-bit palette of four colours, two made translucent by tRNS (the others opaque): RGBA.
    const std::string palette = std::string("\x10\x20\x30", 3) + "\x40\x50\x60" + "\x70\x80\x90" + "\xa0\xb0\xc0";
    const std::vector<std::vector<int>> indices = {{0, 1, 2, 3, 0}, {3, 2, 1, 0, 1}};
    {
        cv::Mat expected(2, 5, CV_8UC4);
        const std::uint8_t alpha[] = {0, 128, 255, 255};
        for (int row = 0; row < 2; ++row)
            for (int col = 0; col < 5; ++col) {
                const int index = indices[row][col];
                expected.at<cv::Vec4b>(row, col) = cv::Vec4b(uchar(palette[3 * index]), uchar(palette[3 * index + 1]),
                                                             uchar(palette[3 * index + 2]), alpha[index]);
            }
        fixtures.push_back(
            {"palette-trns.png",
             pngFile(5, 2, 2, 3, scanlinesOf(indices, 2),
                     test::pngChunk("PLTE", palette) + test::pngChunk("tRNS", std::string("\x00\x80", 2))),
             expected});
    }
    // The same palette without tRNS: RGB.
    {
        cv::Mat expected(2, 5, CV_8UC3);
        for (int row = 0; row < 2; ++row)
            for (int col = 0; col < 5; ++col) {
                const int index = indices[row][col];
                expected.at<cv::Vec3b>(row, col) =
                    cv::Vec3b(uchar(palette[3 * index]), uchar(palette[3 * index + 1]), uchar(palette[3 * index + 2]));
            }
        fixtures.push_back(
            {"palette.png", pngFile(5, 2, 2, 3, scanlinesOf(indices, 2), test::pngChunk("PLTE", palette)), expected});
    }
    // 2-bit and 1-bit grey, scaled up to 8 bits (0, 85, 170, 255; 0, 255), rows not ending on a byte.
    {
        const std::vector<std::vector<int>> samples = {{0, 1, 2}, {3, 2, 1}};
        cv::Mat expected(2, 3, CV_8UC1);
        for (int row = 0; row < 2; ++row)
            for (int col = 0; col < 3; ++col) expected.at<uchar>(row, col) = uchar(85 * samples[row][col]);
        fixtures.push_back({"grey2.png", pngFile(3, 2, 2, 0, scanlinesOf(samples, 2)), expected});
        const std::vector<std::vector<int>> bits = {{1, 0, 1, 1, 0, 0, 1, 0, 1}};
        cv::Mat expectedBits(1, 9, CV_8UC1);
        for (int col = 0; col < 9; ++col) expectedBits.at<uchar>(0, col) = uchar(255 * bits[0][col]);
        fixtures.push_back({"grey1.png", pngFile(9, 1, 1, 0, scanlinesOf(bits, 1)), expectedBits});
    }
    // 8-bit grey and alpha: two channels.
    {
        const std::vector<std::vector<int>> samples = {{10, 255, 20, 0}, {30, 128, 40, 7}};
        cv::Mat expected(2, 2, CV_8UC2);
        for (int row = 0; row < 2; ++row)
            for (int i = 0; i < 4; ++i) expected.ptr<uchar>(row)[i] = uchar(samples[row][i]);
        fixtures.push_back({"grey-alpha.png", pngFile(2, 2, 8, 4, scanlinesOf(samples, 8)), expected});
    }
    // 8-bit grey whose tRNS names grey 17 transparent: grey and alpha.
    {
        const std::vector<std::vector<int>> samples = {{17, 18, 17}};
        cv::Mat expected(1, 3, CV_8UC2);
        expected.at<cv::Vec2b>(0, 0) = cv::Vec2b(17, 0);
        expected.at<cv::Vec2b>(0, 1) = cv::Vec2b(18, 255);
        expected.at<cv::Vec2b>(0, 2) = cv::Vec2b(17, 0);
        fixtures.push_back(
            {"grey-trns.png",
             pngFile(3, 1, 8, 0, scanlinesOf(samples, 8), test::pngChunk("tRNS", std::string("\x00\x11", 2))),
             expected});
    }
    // Adam7-interlaced 8-bit grey, 10x9: the seven passes' sub-images, each row with its filter byte.
    {
        cv::Mat expected(9, 10, CV_8UC1);
        for (int row = 0; row < 9; ++row)
            for (int col = 0; col < 10; ++col) expected.at<uchar>(row, col) = uchar(row * 10 + col);
        const int passes[7][4] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
                                  {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}}; // x start, y start, x step, y step
        std::string scanlines;
        for (const auto& pass : passes) {
            std::vector<std::vector<int>> rows;
            for (int row = pass[1]; row < 9; row += pass[3]) {
                std::vector<int> samples;
                for (int col = pass[0]; col < 10; col += pass[2]) samples.push_back(expected.at<uchar>(row, col));
                if (!samples.empty()) rows.push_back(samples);
            }
            scanlines += scanlinesOf(rows, 8);
        }
        fixtures.push_back({"adam7.png", pngFile(10, 9, 8, 0, scanlines, "", 1), expected});
    }
    return fixtures;
}

TEST_F(PngFiles, ExpandsPalettesLowDepthsTransparencyAnd16BitAsOpenImageIoDid) {
    for (const Fixture& fixture : expansionFixtures()) {
        SCOPED_TRACE(fixture.name);
        writeFile(directory / fixture.name, fixture.bytes);
        const cv::Mat image = readImage(directory / fixture.name);
        ASSERT_EQ(image.type(), fixture.expected.type());
        ASSERT_EQ(image.size(), fixture.expected.size());
        EXPECT_EQ(cv::norm(image, fixture.expected, cv::NORM_INF), 0.0);
        // A shade map's reader (critical chunks only, from memory) gives the same.
        const cv::Mat fromMemory = readPngImage(directory / fixture.name, kDefaultMaxReadPixels, 1 << 20);
        EXPECT_EQ(cv::norm(fromMemory, fixture.expected, cv::NORM_INF), 0.0);
    }
}

TEST_F(PngFiles, ReadsEveryFixtureAsTheOpenImageIoModuleDoes) {
    // The module's own reader, which served PNG before (readImage no longer sends .png to it).
    const fs::path modulePath = fs::path(INKGRAPH_BINARY_ROOT) / "libinkgraph_imageio.so";
    void* module = dlopen(modulePath.c_str(), RTLD_NOW | RTLD_LOCAL);
    ASSERT_NE(module, nullptr) << dlerror();
    using Entry = const ImageIoFunctions* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(module, "inkgraph_image_io_functions"));
    ASSERT_NE(entry, nullptr);
    const ImageIoFunctions& oiio = *entry();
    ASSERT_EQ(oiio.version, kImageIoVersion);
    std::vector<Fixture> fixtures = expansionFixtures();
    cv::Mat rgba(3, 4, CV_8UC4);
    cv::randu(rgba, 0, 256);
    writeImage(directory / "ours.png", rgba);
    fixtures.push_back({"ours.png", readFile(directory / "ours.png"), rgba});
    for (const Fixture& fixture : fixtures) {
        SCOPED_TRACE(fixture.name);
        writeFile(directory / fixture.name, fixture.bytes);
        cv::Mat theirs;
        std::string error;
        ASSERT_TRUE(oiio.readImage((directory / fixture.name).string(), kDefaultMaxReadPixels, theirs, error)) << error;
        const cv::Mat ours = readImage(directory / fixture.name);
        ASSERT_EQ(ours.type(), theirs.type());
        ASSERT_EQ(ours.size(), theirs.size());
        // 16-bit samples: OpenImageIO multiplies by 1/65535 where we divide, an ulp apart at most.
        EXPECT_LE(cv::norm(ours, theirs, cv::NORM_INF), ours.depth() == CV_8U ? 0.0 : 2e-7);
    }
    // The module stays loaded: OpenImageIO keeps global state until exit.
}

TEST_F(PngFiles, BrokenFilesAreRefusedNamingTheFile) {
    cv::Mat rgba(8, 8, CV_8UC4);
    cv::randu(rgba, 0, 256);
    writeImage(directory / "good.png", rgba);
    const std::string good = readFile(directory / "good.png");
    const fs::path bad = directory / "bad.png";
    // Appended, not "'" + name + "'": GCC 12 warns falsely (-Wrestrict, bug 105329) on that inlined.
    std::string named = "'";
    named.append(bad.string()).append("'");

    writeFile(bad, "GIF89a, not a PNG at all");
    std::string message = failureOf([&] { readImage(bad); });
    EXPECT_TRUE(contains(message, "readImage(): cannot read " + named + ": libpng: ")) << message;

    // A flipped bit in the pixel data's CRC: libpng checks it.
    std::string flipped = good;
    const std::size_t idat = good.find("IDAT");
    ASSERT_NE(idat, std::string::npos);
    const std::size_t idatLength = (std::size_t(std::uint8_t(good[idat - 2])) << 8) | std::uint8_t(good[idat - 1]);
    ASSERT_LT(idatLength, 65536u) << "an 8x8 picture's one IDAT chunk";
    const std::size_t crc = idat + 4 + idatLength;
    flipped[crc] = char(flipped[crc] ^ 1);
    writeFile(bad, flipped);
    message = failureOf([&] { readImage(bad); });
    EXPECT_TRUE(contains(message, "readImage(): cannot read " + named + ": libpng: IDAT: CRC error")) << message;
    message = failureOf([&] { readPngImage(bad, kDefaultMaxReadPixels, 1 << 20); });
    EXPECT_TRUE(contains(message, "readPngImage(): " + named + ": libpng: IDAT: CRC error")) << message;

    // Cut anywhere, up to IEND's CRC, the file is refused, and nothing crashes.
    for (std::size_t length = 0; length < good.size(); ++length) {
        writeFile(bad, good.substr(0, length));
        try {
            readImage(bad);
            ADD_FAILURE() << "a PNG cut to " << length << " of " << good.size() << " bytes was read";
        } catch (const FileError& error) {
            EXPECT_TRUE(contains(error.what(), "readImage(): cannot read " + named)) << error.what();
        }
        try {
            readPngImage(bad, kDefaultMaxReadPixels, 1 << 20);
            ADD_FAILURE() << "a PNG cut to " << length << " bytes passed readPngImage";
        } catch (const FileError& error) {
            EXPECT_TRUE(contains(error.what(), "readPngImage(): " + named)) << error.what();
        }
    }
    writeFile(bad, good.substr(0, idat + 20));
    message = failureOf([&] { readImage(bad); });
    EXPECT_TRUE(contains(message, "truncated PNG")) << message;

    // Every byte of the file changed in turn: an image (a change libpng cannot see, as in an ancillary chunk) or
    // FileError, never a crash.
    for (std::size_t at = 8; at < good.size(); ++at) {
        std::string changed = good;
        changed[at] = char(changed[at] ^ 0x5a);
        writeFile(bad, changed);
        try {
            readImage(bad);
        } catch (const FileError&) {
        }
    }
}

TEST_F(PngFiles, APixelCountAboveTheLimitIsRefusedBeforeAllocating) {
    // 50000 x 50000 16-bit RGBA would be 20 GB: the header alone is judged, with a tiny IDAT behind it.
    const std::string header = test::bigEndian32(50000) + test::bigEndian32(50000) + "\x10\x06" + std::string(3, '\0');
    const std::string huge = std::string("\x89PNG\r\n\x1a\n", 8) + test::pngChunk("IHDR", header) +
                             test::pngChunk("IDAT", deflated(std::string(64, '\0'))) + test::pngChunk("IEND", "");
    writeFile(directory / "huge.png", huge);
    std::string message = failureOf([&] { readImage(directory / "huge.png"); });
    EXPECT_TRUE(contains(message, "it declares 50000x50000 pixels, more than the 268435456 allowed here")) << message;
    message = failureOf([&] { readPngImage(directory / "huge.png", 4096 * 4096, 1 << 20); });
    EXPECT_TRUE(contains(message, "readPngImage(): '" + (directory / "huge.png").string() +
                                      "': it declares 50000x50000 pixels, more than the 16777216 allowed here"))
        << message;
    // And an ordinary file against a small limit.
    writeImage(directory / "small.png", cv::Mat(64, 64, CV_8UC1, cv::Scalar(9)));
    message = failureOf([&] { readImage(directory / "small.png", 1000); });
    EXPECT_TRUE(contains(message, "it declares 64x64 pixels, more than the 1000 allowed here")) << message;
}

TEST_F(PngFiles, PngAloneNeverLoadsTheImageModule) {
    if (imageIoModuleState() != "not loaded") GTEST_SKIP() << "an earlier test of this process loaded the module";
    writeImage(directory / "a.png", cv::Mat(8, 8, CV_8UC4, cv::Scalar(1, 2, 3, 4)));
    readImage(directory / "a.png");
    readPngImage(directory / "a.png", 64, 1 << 20);
    EXPECT_EQ(imageIoModuleState(), "not loaded");
}

} // namespace
} // namespace inkgraph
