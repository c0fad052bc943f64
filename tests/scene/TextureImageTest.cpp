// Decoding a material's image (scene/TextureImage.h) without GL: the pixels of a PNG round trip exactly, and every
// kind of bad image is refused with a message that names the model and the image, before it can block, read without
// end or allocate beyond the limit: garbage, an empty file, a header claiming 60000 x 60000 pixels, a FIFO, a folder,
// a missing file, a file larger than the limit, and a texture above the limit.
#include "scene/TextureImage.h"
#include "tests/scene/SceneTestSupport.h"

#include <gtest/gtest.h>

#include <stb/stb_image_write.h>
#include <sys/stat.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

constexpr std::size_t kPlenty = std::size_t(1) << 30;

/** A 3 x 2 RGBA PNG with known pixels, written by stb_image_write. */
std::vector<unsigned char> smallPng() {
    const unsigned char pixels[2][3][4] = {{{255, 0, 0, 255}, {0, 255, 0, 128}, {0, 0, 255, 0}},
                                           {{10, 20, 30, 40}, {50, 60, 70, 80}, {90, 100, 110, 120}}};
    std::vector<unsigned char> png;
    stbi_write_png_to_func(
        [](void* context, void* data, int size) {
            auto* out = static_cast<std::vector<unsigned char>*>(context);
            out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
        },
        &png, 3, 2, 4, pixels, 3 * 4);
    return png;
}

SceneImage embedded(std::vector<unsigned char> bytes, const std::string& name = "skin") {
    SceneImage image;
    image.name = name;
    image.mimeType = "image/png";
    image.encoded = std::make_shared<const std::vector<unsigned char>>(std::move(bytes));
    return image;
}

SceneImage external(const std::string& path) {
    SceneImage image;
    image.name = std::filesystem::path(path).filename().string();
    image.path = path;
    return image;
}

std::string refusal(const SceneImage& image, std::size_t limit = kPlenty) {
    return test::sceneErrorMessage([&] { decodeSceneImage(image, 3, "model.glb", limit); });
}

TEST(TextureImage, PngPixelsRoundTripExactly) {
    const DecodedImage decoded = decodeSceneImage(embedded(smallPng()), 0, "model.glb", kPlenty);
    ASSERT_EQ(decoded.width, 3);
    ASSERT_EQ(decoded.height, 2);
    const unsigned char* pixel = decoded.rgba.get();
    EXPECT_EQ(std::vector<int>(pixel, pixel + 4), (std::vector<int>{255, 0, 0, 255})) << "top-left first";
    EXPECT_EQ(std::vector<int>(pixel + 20, pixel + 24), (std::vector<int>{90, 100, 110, 120})) << "bottom-right last";
    EXPECT_EQ(decodedImageBytes(3, 2), 3u * 2u * 4u * 7u / 3u);
}

TEST(TextureImage, BadBytesAreRefusedNamingTheModelAndTheImage) {
    const std::string garbage = refusal(embedded({'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'}));
    EXPECT_EQ(garbage.rfind("decodeSceneImage(): 'model.glb' image 3 'skin': cannot be decoded", 0), 0u) << garbage;
    EXPECT_NE(garbage.find("declared image/png"), std::string::npos) << garbage;
    EXPECT_NE(refusal(embedded({})).find("is empty"), std::string::npos);

    // A PNG whose header claims 60000 x 60000 pixels (the width and height of its IHDR chunk patched; stb_image does
    // not check the chunk's CRC): refused from the header, nothing allocated.
    std::vector<unsigned char> huge = smallPng();
    const unsigned char side[4] = {0x00, 0x00, 0xEA, 0x60}; // 60000, big-endian
    std::memcpy(huge.data() + 16, side, 4);
    std::memcpy(huge.data() + 20, side, 4);
    const std::string tooLarge = refusal(embedded(huge));
    EXPECT_EQ(tooLarge.rfind("decodeSceneImage(): 'model.glb' image 3 'skin': ", 0), 0u) << tooLarge;

    // Truncated after its header: refused when decoded.
    std::vector<unsigned char> truncated = smallPng();
    truncated.resize(40);
    EXPECT_NE(refusal(embedded(truncated)).find("image 3 'skin'"), std::string::npos);
}

TEST(TextureImage, AboveTheLimitIsRefusedBeforeDecoding) {
    const std::string message = refusal(embedded(smallPng()), decodedImageBytes(3, 2) - 1);
    EXPECT_NE(message.find("3x2 needs 56 bytes"), std::string::npos) << message;
    EXPECT_NE(message.find("--memory-limit"), std::string::npos) << message;
}

/** The kind of error decodeSceneImage() throws for `image`: "missing" or "undecodable" (ImageUnusableError: the
 *  renderer warns and draws without it), "limit" (a plain SceneError: the run's size, not the model), or "none". */
std::string refusalKind(const SceneImage& image, std::size_t limit = kPlenty) {
    try {
        decodeSceneImage(image, 0, "model.glb", limit);
    } catch (const ImageUnusableError& error) {
        return error.reason() == ImageUnusableError::Reason::Missing ? "missing" : "undecodable";
    } catch (const SceneError&) {
        return "limit";
    }
    return "none";
}

TEST(TextureImage, MissingAndUndecodableImagesAreUnusableWhileTheLimitIsAnError) {
    EXPECT_EQ(refusalKind(external("/nonexistent/inkgraph/skin.png")), "missing");
    EXPECT_EQ(refusalKind(external("/dev/zero")), "missing") << "not a regular file: nothing to read";
    EXPECT_EQ(refusalKind(embedded({'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'})), "undecodable");
    EXPECT_EQ(refusalKind(embedded({})), "undecodable");
    std::vector<unsigned char> truncated = smallPng();
    truncated.resize(40);
    EXPECT_EQ(refusalKind(embedded(truncated)), "undecodable");
    EXPECT_EQ(refusalKind(embedded(smallPng()), decodedImageBytes(3, 2) - 1), "limit");
    EXPECT_EQ(refusalKind(embedded(smallPng())), "none");
    try {
        decodeSceneImage(embedded({'x'}), 3, "model.glb", kPlenty);
        FAIL() << "one byte decoded";
    } catch (const ImageUnusableError& error) {
        EXPECT_EQ(error.problem().rfind("cannot be decoded", 0), 0u) << "the problem alone: " << error.problem();
    }
}

TEST(TextureImage, ExternalFilesMustBeRegularAndWithinTheLimit) {
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() / ("inkgraph_texture_" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    const std::string fifo = (folder / "pipe.png").string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // A FIFO would block the read forever: refused from its type, never opened.
    EXPECT_NE(refusal(external(fifo)).find("is not a regular file"), std::string::npos);
    EXPECT_NE(refusal(external(folder.string())).find("is not a regular file"), std::string::npos);
    EXPECT_NE(refusal(external("/dev/zero")).find("is not a regular file"), std::string::npos);
    EXPECT_NE(refusal(external((folder / "missing.png").string())).find("cannot be found"), std::string::npos);
    // A glTF's "Skin.png" beside skin.png and SKIN.png: neither is taken, and both are named.
    for (const std::string name : {"skin.png", "SKIN.png"}) std::ofstream(folder / name) << "not decoded here";
    EXPECT_NE(refusal(external((folder / "Skin.png").string()))
                  .find("its file '" + (folder / "Skin.png").string() + "' cannot be found: the folder '" +
                        folder.string() +
                        "' holds 'SKIN.png' and 'skin.png', which differ from its name in case "
                        "alone: rename the one meant to 'Skin.png'"),
              std::string::npos)
        << refusal(external((folder / "Skin.png").string()));
    std::filesystem::remove(folder / "SKIN.png");

    const std::string file = (folder / "skin.png").string();
    const std::vector<unsigned char> png = smallPng();
    {
        std::ofstream out(file, std::ios::binary);
        out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    }
    EXPECT_EQ(decodeSceneImage(external(file), 0, "model.glb", kPlenty).width, 3);
    const std::string large = refusal(external(file), png.size() - 1);
    EXPECT_NE(large.find("is " + std::to_string(png.size()) + " bytes, more than the"), std::string::npos) << large;
    std::filesystem::remove_all(folder);
}

} // namespace
} // namespace inkgraph
