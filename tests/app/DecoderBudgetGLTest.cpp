// Every decoder is bounded by the header and --memory-limit (issue 31), through the real executable: a PNG whose
// data inflates far beyond its header, a 16-bit PNG, a baseline and a progressive JPEG, a Draco buffer that decodes
// to millions of triangles, a header declaring 60000 x 60000 pixels, a lossless WebP whose decoder holds the whole
// image. Each run's peak resident set (CliRun::peakMib, wait4's figure for that run) is compared with the limit in the
// Release suite only (AddressSanitizer's shadow memory is not the program's; MemoryBudgetGLTest says the same). Also
// here: a texture wider than the driver's largest is downscaled with a warning (PreparedStill::warnings holds it too),
// and a 5000-byte image path gives a message under 2000 bytes.
#include "CliTestSupport.h"
#include "render/StillRenderer.h"
#include "tests/support/PngFixtures.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <zlib.h>

#include <cstdio>
// jpeglib.h needs FILE and size_t declared first.
#include <jpeglib.h>
#include <webp/encode.h>
#include <webp/types.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <regex>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::Cli;
using test::CliRun;
using test::readText;
namespace fs = std::filesystem;

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kPeakIsComparable = false;
#else
constexpr bool kPeakIsComparable = true;
#endif

void writeBytes(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

/** A zlib stream of `rawBytes` bytes whose first `head` bytes are given and the rest zeros, deflated in pieces so the
 *  test never holds the inflated data. */
std::string deflatedZeros(const std::string& head, std::size_t rawBytes) {
    z_stream stream{};
    deflateInit(&stream, Z_BEST_COMPRESSION);
    std::string out;
    std::vector<unsigned char> zeros(1 << 20, 0);
    std::vector<unsigned char> buffer(1 << 16);
    std::size_t fed = 0;
    auto feed = [&](const unsigned char* data, std::size_t size, int flush) {
        stream.next_in = const_cast<unsigned char*>(data);
        stream.avail_in = uInt(size);
        do {
            stream.next_out = buffer.data();
            stream.avail_out = uInt(buffer.size());
            deflate(&stream, flush);
            out.append(reinterpret_cast<const char*>(buffer.data()), buffer.size() - stream.avail_out);
        } while (stream.avail_out == 0);
    };
    feed(reinterpret_cast<const unsigned char*>(head.data()), head.size(), Z_NO_FLUSH);
    fed = head.size();
    while (fed < rawBytes) {
        const std::size_t piece = std::min(zeros.size(), rawBytes - fed);
        fed += piece;
        feed(zeros.data(), piece, Z_NO_FLUSH);
    }
    feed(nullptr, 0, Z_FINISH);
    deflateEnd(&stream);
    return out;
}

/** A PNG of `width` x `height` (colour type 6, RGBA, `bitDepth` 8 or 16) whose image data is `idat`. */
std::string pngFile(std::uint32_t width, std::uint32_t height, int bitDepth, const std::string& idat) {
    return test::pngWithImageData(width, height, bitDepth, 6, idat);
}

/** A JPEG of `width` x `height` mid-grey RGB pixels (quality 90), progressive or baseline, through libjpeg. */
std::string jpegFile(int width, int height, bool progressive) {
    jpeg_compress_struct info{};
    jpeg_error_mgr errors{};
    info.err = jpeg_std_error(&errors);
    jpeg_create_compress(&info);
    unsigned char* bytes = nullptr;
    unsigned long size = 0;
    jpeg_mem_dest(&info, &bytes, &size);
    info.image_width = JDIMENSION(width);
    info.image_height = JDIMENSION(height);
    info.input_components = 3;
    info.in_color_space = JCS_RGB;
    jpeg_set_defaults(&info);
    jpeg_set_quality(&info, 90, TRUE);
    if (progressive) jpeg_simple_progression(&info);
    jpeg_start_compress(&info, TRUE);
    std::vector<unsigned char> row(std::size_t(width) * 3, 128);
    while (info.next_scanline < info.image_height) {
        JSAMPROW pointer = row.data();
        jpeg_write_scanlines(&info, &pointer, 1);
    }
    jpeg_finish_compress(&info);
    jpeg_destroy_compress(&info);
    std::string file(reinterpret_cast<const char*>(bytes), size);
    std::free(bytes);
    return file;
}

/** A lossless WebP of `side` x `side` opaque pixels of one colour (quick to encode, a few hundred bytes), through
 *  libwebp. */
std::string losslessWebpFile(int side) {
    std::vector<unsigned char> rgba(std::size_t(side) * std::size_t(side) * 4);
    for (std::size_t i = 0; i < rgba.size(); i += 4) {
        rgba[i] = 90;
        rgba[i + 1] = 120;
        rgba[i + 2] = 150;
        rgba[i + 3] = 255;
    }
    unsigned char* bytes = nullptr;
    const std::size_t size = WebPEncodeLosslessRGBA(rgba.data(), side, side, side * 4, &bytes);
    std::string file(reinterpret_cast<const char*>(bytes), size);
    WebPFree(bytes);
    return file;
}

class DecoderBudget : public Cli {
protected:
    /** A textured triangle: tri.obj with tri.mtl naming `texture` as its base colour map. */
    void writeTexturedTriangle(const std::string& texture) {
        std::ofstream(directory / "tri.mtl") << "newmtl skin\nmap_Kd " << texture << "\n";
        std::ofstream(directory / "tri.obj")
            << "mtllib tri.mtl\nusemtl skin\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
    }
};

TEST_F(DecoderBudget, APngWhoseDataInflatesFarBeyondItsHeaderCostsOnlyItsPixels) {
    // 8 x 8 RGBA: 8 rows of a filter byte and 32 bytes, then 512 MiB more zeros in the same stream (about 500 KB of
    // file). stb_image inflated all of it (1125 MiB resident under --memory-limit 256); libpng stops at the image.
    std::string rows;
    for (int row = 0; row < 8; ++row) {
        rows.push_back('\0'); // no filter
        rows.append(32, char(200));
    }
    writeBytes(directory / "bomb.png", pngFile(8, 8, 8, deflatedZeros(rows, std::size_t(512) << 20)));
    ASSERT_LT(fs::file_size(directory / "bomb.png"), std::uintmax_t(1) << 20);
    writeTexturedTriangle("bomb.png");
    const CliRun result = run("render tri.obj -o out.png --size 64x64 --memory-limit 256 --stats s.json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const auto stats = nlohmann::json::parse(readText(directory / "s.json"));
    EXPECT_EQ(stats["scene"]["images"]["decoded"], 1);
    if (kPeakIsComparable) {
        EXPECT_LT(result.peakMib, 256.0);
    }
}

TEST_F(DecoderBudget, APngWhoseImageDataEndsBeforeItsLastRowIsRefused) {
    // A complete zlib stream of 4 of the 8 rows: libpng goes on to IEND without a word, and the other rows would be
    // whatever the buffer held. The decode counts the rows delivered.
    std::string rows;
    for (int row = 0; row < 4; ++row) {
        rows.push_back('\0'); // no filter
        rows.append(32, char(200));
    }
    writeBytes(directory / "short.png", pngFile(8, 8, 8, deflatedZeros(rows, rows.size())));
    writeTexturedTriangle("short.png");
    // A warning (the material is drawn without it); --strict makes it the still's failure.
    const CliRun result = run("render tri.obj -o out.png --size 32x32 --strict");
    EXPECT_EQ(result.exitCode, 3) << result.err;
    EXPECT_NE(result.err.find("'short.png': cannot be decoded: a corrupt or truncated PNG (libpng: truncated PNG: "
                              "the image data ends before the last row)"),
              std::string::npos)
        << result.err;
}

TEST_F(DecoderBudget, ASixteenBitPngIsDecodedAtEightBitsWithinTheLimit) {
    // 8192 x 4096 RGBA at 16 bits: stb_image held the 256 MiB of 16-bit samples beside the 8-bit copy, uncharged
    // (595 MiB resident under --memory-limit 410). Now each row is reduced to 8 bits as libpng inflates it.
    constexpr std::uint32_t kWidth = 8192, kHeight = 4096;
    const std::size_t rowBytes = 1 + std::size_t(kWidth) * 8;
    writeBytes(directory / "deep.png", pngFile(kWidth, kHeight, 16, deflatedZeros("", rowBytes * kHeight)));
    writeTexturedTriangle("deep.png");
    const CliRun result = run("render tri.obj -o out.png --size 64x64 --memory-limit 410");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    if (kPeakIsComparable) {
        EXPECT_LT(result.peakMib, 410.0);
    }
}

TEST_F(DecoderBudget, TheRunsEstimateCountsTheTexturesTheModelWillDecode) {
    // Issue 35: a textured model's estimate left its images out (131 MiB reported for a 16384^2 texture whose run
    // peaked at 2.5 GiB), so a batch could not be sized from --stats. Now each image the materials name is counted
    // from its header, at what decoding charges it: 7/3 x 4096^2 x 4 bytes = 149.33 MiB for one 4096^2 PNG.
    constexpr std::uint32_t kSide = 4096;
    const std::size_t rowBytes = 1 + std::size_t(kSide) * 4;
    writeBytes(directory / "big.png", pngFile(kSide, kSide, 8, deflatedZeros("", rowBytes * kSide)));
    writeTexturedTriangle("big.png");
    const CliRun textured = run("render tri.obj -o out.png --size 64x64 --stats textured.json");
    ASSERT_EQ(textured.exitCode, 0) << textured.err;
    writeTexturedTriangle("absent.png"); // the same triangle, its image missing: nothing to decode, nothing counted
    const CliRun untextured = run("render tri.obj -o out.png --size 64x64 --stats untextured.json");
    ASSERT_EQ(untextured.exitCode, 0) << untextured.err;
    const auto withTexture = nlohmann::json::parse(readText(directory / "textured.json"));
    const auto without = nlohmann::json::parse(readText(directory / "untextured.json"));
    const double difference =
        withTexture["estimated_peak_mib"].get<double>() - without["estimated_peak_mib"].get<double>();
    EXPECT_NEAR(difference, 7.0 / 3.0 * 4096.0 * 4096.0 * 4.0 / 1048576.0, 0.1) << withTexture.dump();
    EXPECT_NEAR(withTexture["estimated_textures_mib"].get<double>(), 7.0 / 3.0 * 4096.0 * 4096.0 * 4.0 / 1048576.0,
                0.001);
    EXPECT_NEAR(withTexture["scene"]["images"]["decoded_bytes"].get<double>(), 7.0 / 3.0 * 4096 * 4096 * 4, 1.0);
    if (kPeakIsComparable) {
        EXPECT_LE(withTexture["peak_rss_mib"].get<double>(), withTexture["estimated_peak_mib"].get<double>());
    }
}

TEST_F(DecoderBudget, ABaselineJpegIsDecodedRowByRowWithinTheLimit) {
    // 8192 x 8192: stb_image's component planes came on top of the charged pixels (726 MiB under a limit of 709).
    writeBytes(directory / "photo.jpg", jpegFile(8192, 8192, false));
    writeTexturedTriangle("photo.jpg");
    const CliRun result = run("render tri.obj -o out.png --size 64x64 --memory-limit 709");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    if (kPeakIsComparable) {
        EXPECT_LT(result.peakMib, 709.0);
    }
}

TEST_F(DecoderBudget, AProgressiveJpegsCoefficientsAreChargedBeforeTheyAreAllocated) {
    // A progressive file is decoded through whole-image coefficient buffers (2 bytes per coefficient): 4096 x 4096
    // RGB at 4:2:0 needs 48 MiB of them beside the pixels. Charged from the header, so a limit that holds the pixels
    // but not them is refused before libjpeg allocates anything, naming the image, the model and --memory-limit.
    writeBytes(directory / "photo.jpg", jpegFile(4096, 4096, true));
    writeTexturedTriangle("photo.jpg");
    const CliRun refused = run("render tri.obj -o out.png --size 64x64 --memory-limit 300");
    EXPECT_EQ(refused.exitCode, 3) << refused.err;
    EXPECT_NE(refused.err.find("'tri.obj' image 0 'photo.jpg': 4096x4096 needs"), std::string::npos) << refused.err;
    // The pixels with their GL copy (7/3 x 4096^2 x 4 = 156,587,349 bytes) and the coefficients of the default 4:2:0
    // sampling (512^2 luma blocks and 2 x 256^2 chroma blocks of 128 bytes: 50,331,648 bytes).
    std::smatch needs;
    ASSERT_TRUE(std::regex_search(refused.err, needs, std::regex("needs ([0-9]+) bytes"))) << refused.err;
    EXPECT_GE(std::stoull(needs[1]), 156587349ull + 50331648ull) << refused.err;
    EXPECT_NE(refused.err.find("--memory-limit"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(directory / "out.png"));
    const CliRun accepted = run("render tri.obj -o out.png --size 64x64 --memory-limit 480");
    ASSERT_EQ(accepted.exitCode, 0) << accepted.err;
    if (kPeakIsComparable) {
        EXPECT_LT(accepted.peakMib, 480.0);
    }
}

TEST_F(DecoderBudget, ALosslessWebpsWholeImageIsChargedBeforeItIsAllocated) {
    // libwebp decodes a lossless file whole into 32-bit ARGB before converting it into the texture's RGBA: 4096^2 x 4
    // bytes beside the pixels and their GL copy (156,587,349 bytes), so a limit that holds those but not it refuses the
    // image before libwebp allocates anything (issue 35). Measured: 226,071,893 bytes needed besides the file's own;
    // at --memory-limit 340 it renders with a peak of about 243 MiB (measured on a patterned 4096^2 file).
    writeBytes(directory / "fur.webp", losslessWebpFile(4096));
    writeTexturedTriangle("fur.webp");
    const CliRun refused = run("render tri.obj -o out.png --size 64x64 --memory-limit 300");
    EXPECT_EQ(refused.exitCode, 3) << refused.err;
    std::smatch needs;
    ASSERT_TRUE(std::regex_search(refused.err, needs, std::regex("'fur.webp': 4096x4096 needs ([0-9]+) bytes")))
        << refused.err;
    EXPECT_GE(std::stoull(needs[1]), 156587349ull + 67108864ull) << refused.err;
    EXPECT_FALSE(fs::exists(directory / "out.png"));
    const CliRun result = run("render tri.obj -o out.png --size 64x64 --memory-limit 340 --stats s.json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_EQ(nlohmann::json::parse(readText(directory / "s.json"))["scene"]["images"]["decoded"], 1);
    if (kPeakIsComparable) {
        EXPECT_LT(result.peakMib, 340.0);
    }
}

TEST_F(DecoderBudget, StbImagesOwnBufferIsChargedBeforeItIsAllocated) {
    // The formats stb_image decodes besides PNG and JPEG hold the whole image in their own samples before the 8-bit
    // conversion, uncharged before: for Radiance HDR, 4 floats a pixel. A 1024 x 1024 file (flat RGBE pixels) given
    // 20 MiB of texture budget, which holds its 8-bit pixels and GL copy (7/3 x 1024^2 x 4 = 9,786,709 bytes) but not
    // the floats beside them (16 x 1024^2 = 16,777,216 bytes), is refused before stb decodes it.
    std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1024 +X 1024\n";
    for (int i = 0; i < 1024 * 1024; ++i) hdr += "\x80\x80\x80\x80";
    writeBytes(directory / "sky.hdr", hdr);
    writeTexturedTriangle("sky.hdr");
    const CliRun measured = run("render tri.obj -o out.png --size 64x64 --stats s.json");
    ASSERT_EQ(measured.exitCode, 0) << measured.err;
    // The estimate counts the image (issue 35); the limit leaves 20 MiB for it beside the rest of the run.
    const auto stats = nlohmann::json::parse(readText(directory / "s.json"));
    const double textureMib = stats["estimated_textures_mib"].get<double>();
    EXPECT_NEAR(textureMib, (9786709.0 + 16777216.0) / 1048576.0, 0.01);
    const int limitMib = int(std::ceil(stats["estimated_peak_mib"].get<double>() - textureMib)) + 20;
    const CliRun refused = run("render tri.obj -o out.png --size 64x64 --memory-limit " + std::to_string(limitMib));
    EXPECT_EQ(refused.exitCode, 3) << refused.err;
    std::smatch needs;
    ASSERT_TRUE(std::regex_search(refused.err, needs, std::regex("'sky.hdr': 1024x1024 needs ([0-9]+) bytes")))
        << refused.err;
    EXPECT_GE(std::stoull(needs[1]), 9786709ull + 16777216ull) << refused.err;
}

TEST_F(DecoderBudget, APnmTextureIsRefusedRatherThanReadPastItsBuffer) {
    // fuzz_texture's finding: a 16-bit binary PNM (maxval above 255) made stb_image read twice the bytes of its
    // buffer (a heap over-read; a crash for some sizes), and a truncated one decoded to uninitialised pixels.
    writeBytes(directory / "deep.ppm", "P6\n3 2\n65535\n" + std::string(36, 'x'));
    writeTexturedTriangle("deep.ppm");
    const CliRun result = run("render tri.obj -o out.png --size 32x32 --strict");
    EXPECT_EQ(result.exitCode, 3) << result.err;
    EXPECT_NE(result.err.find("'tri.obj': image 0 'deep.ppm': is a PNM image, which is not read as a texture"),
              std::string::npos)
        << result.err;
    EXPECT_FALSE(fs::exists(directory / "out.png"));
}

TEST_F(DecoderBudget, AHeaderOfSixtyThousandPixelsASideIsRefusedNamingItsSizeAndTheLimit) {
    // Reported as "not a PNG" before: stb_image refuses such a header without saying why.
    writeBytes(directory / "huge.png", pngFile(60000, 60000, 8, deflatedZeros("", 1000)));
    writeTexturedTriangle("huge.png");
    const CliRun result = run("render tri.obj -o out.png --size 64x64 --memory-limit 512");
    EXPECT_EQ(result.exitCode, 3) << result.err;
    EXPECT_NE(result.err.find("image 0 'huge.png': 60000x60000 needs 33600000"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("raise --memory-limit"), std::string::npos) << result.err;
    EXPECT_EQ(result.err.find("not a PNG"), std::string::npos) << result.err;
}

TEST_F(DecoderBudget, ADracoBufferIsChargedFromItsHeaderBeforeItIsDecoded) {
    // 1000 x 1000 vertices, 1,996,002 triangles in a few hundred kilobytes. Charged only once decoded before (188 MiB
    // resident under --memory-limit 150); now the counts are read from the Draco header and refused first.
    const std::string command =
        test::shellQuoted(INKGRAPH_MAKE_DRACO_GRID) + " 1000 " + test::shellQuoted(directory / "grid.drc");
    ASSERT_EQ(std::system(command.c_str()), 0);
    const auto drcBytes = fs::file_size(directory / "grid.drc");
    const nlohmann::json gltf = {
        {"asset", {{"version", "2.0"}}},
        {"extensionsUsed", {"KHR_draco_mesh_compression"}},
        {"extensionsRequired", {"KHR_draco_mesh_compression"}},
        {"buffers", {{{"uri", "grid.drc"}, {"byteLength", drcBytes}}}},
        {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", drcBytes}}}},
        {"accessors",
         {{{"componentType", 5126}, {"count", 1000000}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
          {{"componentType", 5125}, {"count", 1996002 * 3}, {"type", "SCALAR"}}}},
        {"meshes",
         {{{"primitives",
            {{{"attributes", {{"POSITION", 0}}},
              {"indices", 1},
              {"extensions",
               {{"KHR_draco_mesh_compression", {{"bufferView", 0}, {"attributes", {{"POSITION", 0}}}}}}}}}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"scenes", {{{"nodes", {0}}}}},
        {"scene", 0}};
    std::ofstream(directory / "grid.gltf") << gltf.dump();
    const CliRun result = run("render grid.gltf -o out.png --size 64x64 --memory-limit 150");
    EXPECT_EQ(result.exitCode, 3) << result.err;
    EXPECT_NE(result.err.find("--memory-limit"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("1996002 triangles"), std::string::npos) << result.err;
    if (kPeakIsComparable) {
        EXPECT_LT(result.peakMib, 150.0);
    }
}

TEST_F(DecoderBudget, ATextureWiderThanTheDriverTakesIsDownscaledWithAWarningAndABatchGoesOn) {
    // 17000 x 1 is more than llvmpipe's GL_MAX_TEXTURE_SIZE (16384): "internal error", exit 1 before, which also
    // stopped a batch.
    std::string row(1, '\0');
    for (int x = 0; x < 17000; ++x) row += std::string("\xff\x80\x00\xff", 4);
    writeBytes(directory / "strip.png", pngFile(17000, 1, 8, deflatedZeros(row, row.size())));
    writeTexturedTriangle("strip.png");
    const CliRun single = run("render tri.obj -o out.png --size 64x64 --stats s.json");
    ASSERT_EQ(single.exitCode, 0) << single.err;
    EXPECT_NE(single.err.find("inkgraph: warning: image 0 'strip.png' is 17000x1 pixels, more than the driver's "
                              "largest texture (16384 a side): downscaled to 16384x1"),
              std::string::npos)
        << single.err;
    const auto stats = nlohmann::json::parse(readText(directory / "s.json"));
    const auto& downscaled = stats["scene"]["images"]["downscaled"];
    ASSERT_EQ(downscaled.size(), 1u) << stats["scene"]["images"].dump();
    EXPECT_EQ(downscaled[0]["decoded"], nlohmann::json::array({17000, 1}));
    EXPECT_EQ(downscaled[0]["uploaded"], nlohmann::json::array({16384, 1}));

    std::ofstream(directory / "plain.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    fs::create_directories(directory / "out");
    const CliRun batch = run("render tri.obj plain.obj -o 'out/{name}.png' --size 32x32");
    EXPECT_EQ(batch.exitCode, 0) << batch.err;
    EXPECT_TRUE(fs::exists(directory / "out" / "tri.png"));
    EXPECT_TRUE(fs::exists(directory / "out" / "plain.png"));
}

TEST_F(DecoderBudget, ADownscaledTextureIsAWarningOfTheStill) {
    // In process: the record a library returns (PreparedStill::warnings), filled when execute() decodes the texture.
    std::string row(1, '\0');
    for (int x = 0; x < 17000; ++x) row += std::string("\xff\x80\x00\xff", 4);
    writeBytes(directory / "strip.png", pngFile(17000, 1, 8, deflatedZeros(row, row.size())));
    writeTexturedTriangle("strip.png");
    StillRequest request;
    request.modelPath = (directory / "tri.obj").string();
    request.camera.width = 32;
    request.camera.height = 32;
    std::ostringstream log;
    StillRenderer renderer;
    const std::unique_ptr<PreparedStill> still = renderer.prepare(request, StillLog{log});
    EXPECT_TRUE(still->warnings.empty()) << ::testing::PrintToString(still->warnings);
    renderer.execute(*still, StillLog{log});
    ASSERT_EQ(still->scene().images.size(), 1u);
    const Warning expected{"texture-downscaled",
                           "image 0 'strip.png' is 17000x1 pixels, more than the driver's largest texture (16384 a "
                           "side): downscaled to 16384x1",
                           still->scene().images[0].path, "image 0 'strip.png'"};
    EXPECT_EQ(still->warnings, std::vector<Warning>{expected});
    EXPECT_NE(log.str().find("inkgraph: warning: " + expected.message + "\n"), std::string::npos) << log.str();
}

TEST_F(DecoderBudget, AFiveThousandByteImagePathGivesAMessageUnderTwoThousandBytes) {
    // Every message stays under 2000 bytes (render/Messages.h): a glTF image's file that is missing is named by its
    // path, which keeps its two ends and says its length (5 KB of stderr before).
    const std::string name = std::string(4990, 'p') + "x.png";
    std::string buffer;
    for (float value : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f})
        buffer.append(reinterpret_cast<const char*>(&value), sizeof value);
    writeBytes(directory / "tri.bin", buffer);
    const nlohmann::json gltf = {
        {"asset", {{"version", "2.0"}}},
        {"buffers", {{{"uri", "tri.bin"}, {"byteLength", 60}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
          {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", 3},
           {"type", "VEC3"},
           {"min", {0, 0, 0}},
           {"max", {1, 1, 0}}},
          {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}}}},
        {"images", {{{"uri", name}}}},
        {"textures", {{{"source", 0}}}},
        {"materials", {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"material", 0}}}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"scenes", {{{"nodes", {0}}}}},
        {"scene", 0}};
    std::ofstream(directory / "tri.gltf") << gltf.dump();
    const CliRun result = run("render tri.gltf -o out.png --size 32x32 --strict");
    EXPECT_EQ(result.exitCode, 3) << result.err.substr(0, 300);
    EXPECT_LT(result.err.size(), 2000u);
    EXPECT_NE(result.err.find("cannot be found"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("pppx.png"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(" bytes)"), std::string::npos) << result.err;
}

} // namespace
} // namespace inkgraph
