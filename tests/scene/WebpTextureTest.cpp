// EXT_texture_webp (issue 35): WebP images made here by libwebp's encoder with known pixels decode to exactly those
// pixels, alone (scene/TextureImage.h) and as the image a glTF texture names through the extension, preferred over the
// texture's PNG fallback; a corrupt, truncated or animated WebP and one above the memory limit are refused naming
// the model and the image; an image index out of range is refused naming the material and the texture.
#include "scene/Scene.h"
#include "scene/TextureImage.h"
#include "tests/scene/SceneTestSupport.h"

#include <gtest/gtest.h>

#include <webp/encode.h>
#include <webp/types.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace inkgraph::webp_texture_test {
namespace {

constexpr std::size_t kPlenty = std::size_t(1) << 30;

/** 3 x 2 RGBA pixels, rows top to bottom, with every alpha from opaque to clear; lossless WebP keeps each exactly
 *  (the encoder is told to keep the colour under alpha 0). */
const std::vector<unsigned char> kPixels = {255, 0,  0,  255, 0,  255, 0,  128, 0,  0,   255, 0,
                                            10,  20, 30, 40,  50, 60,  70, 80,  90, 100, 110, 120};

/** kPixels as a lossless WebP, through libwebp's encoder. */
std::string losslessWebp() {
    WebPConfig config;
    WebPConfigInit(&config);
    config.lossless = 1;
    config.exact = 1; // keep the RGB of transparent pixels
    WebPPicture picture;
    WebPPictureInit(&picture);
    picture.use_argb = 1;
    picture.width = 3;
    picture.height = 2;
    WebPMemoryWriter writer;
    WebPMemoryWriterInit(&writer);
    picture.writer = WebPMemoryWrite;
    picture.custom_ptr = &writer;
    std::string bytes;
    if (WebPPictureImportRGBA(&picture, kPixels.data(), 3 * 4) && WebPEncode(&config, &picture))
        bytes.assign(reinterpret_cast<const char*>(writer.mem), writer.size);
    WebPPictureFree(&picture);
    WebPMemoryWriterClear(&writer);
    return bytes;
}

SceneImage embedded(const std::string& bytes, const std::string& name = "skin") {
    SceneImage image;
    image.name = name;
    image.mimeType = "image/webp";
    image.encoded = std::make_shared<const std::vector<unsigned char>>(bytes.begin(), bytes.end());
    return image;
}

std::vector<unsigned char> pixelsOf(const DecodedImage& decoded) {
    return std::vector<unsigned char>(decoded.rgba.get(),
                                      decoded.rgba.get() + std::size_t(decoded.width) * decoded.height * 4);
}

std::string refusal(const SceneImage& image, std::size_t limit = kPlenty) {
    return test::sceneErrorMessage([&] { decodeSceneImage(image, 3, "model.glb", limit); });
}

TEST(WebpTexture, LosslessPixelsRoundTripExactly) {
    const std::string webp = losslessWebp();
    ASSERT_FALSE(webp.empty()) << "libwebp's encoder failed";
    const DecodedImage decoded = decodeSceneImage(embedded(webp), 0, "model.glb", kPlenty);
    ASSERT_EQ(decoded.width, 3);
    ASSERT_EQ(decoded.height, 2);
    EXPECT_EQ(pixelsOf(decoded), kPixels);
}

TEST(WebpTexture, CorruptTruncatedAndAnimatedWebpAreRefusedNamingTheModelAndTheImage) {
    const std::string webp = losslessWebp();
    const std::string prefix =
        "decodeSceneImage(): 'model.glb' image 3 'skin': cannot be decoded: a corrupt, truncated "
        "or unsupported WebP (declared image/webp) (";
    // The bitstream cut off after its header: libwebp reads the size, then runs out of data.
    const std::string truncated = refusal(embedded(webp.substr(0, webp.size() - 4)));
    EXPECT_EQ(truncated.rfind(prefix, 0), 0u) << truncated;
    EXPECT_NE(truncated.find("libwebp "), std::string::npos) << truncated;
    // A RIFF WEBP container with no image chunk in it.
    const std::string bogus = refusal(embedded(std::string("RIFF\x0c\0\0\0WEBPJUNKJUNK", 20)));
    EXPECT_EQ(bogus.rfind(prefix, 0), 0u) << bogus;
    EXPECT_NE(bogus.find("(libwebp header: "), std::string::npos) << bogus;
    // Its image data overwritten with noise after the header.
    std::string noisy = webp;
    for (std::size_t i = 25; i < noisy.size(); ++i) noisy[i] = char(0xA5 ^ i);
    const std::string corrupt = refusal(embedded(noisy));
    EXPECT_EQ(corrupt.rfind(prefix, 0), 0u) << corrupt;
    // An extended (VP8X) header whose flags say animation (0x02), 16 x 16: the still decoder does not read it.
    const std::string animated =
        refusal(embedded(std::string("RIFF\x16\0\0\0WEBPVP8X\x0a\0\0\0\x02\0\0\0\x0f\0\0\x0f\0\0"
                                     "ANIM\x06\0\0\0\0\0\0\0\0\0",
                                     44)));
    EXPECT_EQ(animated.rfind(prefix, 0), 0u) << animated;
    EXPECT_NE(animated.find("an animated WebP"), std::string::npos) << animated;
}

TEST(WebpTexture, AboveTheLimitIsRefusedBeforeDecoding) {
    // The pixels and their GL copy (decodedImageBytes) and libwebp's own whole ARGB image of a lossless file, its row
    // caches and 1 MiB for its tables: a limit just below that sum refuses the image, one at it decodes it.
    const std::size_t needed = decodedImageBytes(3, 2) + (3 * 2 * 4 + 3 * 17 * 4) + 3 * 256 + (std::size_t(1) << 20);
    const std::string refused = refusal(embedded(losslessWebp()), needed - 1);
    EXPECT_NE(refused.find("3x2 needs " + std::to_string(needed) + " bytes"), std::string::npos) << refused;
    EXPECT_NO_THROW(decodeSceneImage(embedded(losslessWebp()), 0, "model.glb", needed));
}

/** A glTF triangle whose material's base colour texture 0 is `texture` (JSON), with images 0 (a PNG signature as a
 *  data: URI, never decoded here) and 1 (the lossless WebP in a buffer view, as a GLB or an exporter's .gltf keeps
 *  it, or with `webpDataUri` as a data:image/webp URI, a media type tinygltf does not decode). */
std::string triangleWithTexture(const std::string& texture, const std::string& required, bool webpDataUri = false) {
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const float uvs[6] = {0, 0, 1, 0, 0, 1};
    std::string buffer(reinterpret_cast<const char*>(positions), sizeof positions);
    buffer.append(reinterpret_cast<const char*>(uvs), sizeof uvs);
    const std::string webp = losslessWebp();
    buffer += webp;
    return "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"uri\": \"data:application/octet-stream;base64," +
           test::base64(buffer) + "\", \"byteLength\": " + std::to_string(buffer.size()) +
           "}], \"bufferViews\": [{\"buffer\": 0, \"byteLength\": 36}, {\"buffer\": 0, \"byteOffset\": 36, "
           "\"byteLength\": 24}, {\"buffer\": 0, \"byteOffset\": 60, \"byteLength\": " +
           std::to_string(webp.size()) +
           "}], \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\"}, "
           "{\"bufferView\": 1, \"componentType\": 5126, \"count\": 3, \"type\": \"VEC2\"}], \"meshes\": "
           "[{\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"TEXCOORD_0\": 1}, \"material\": 0}]}], \"nodes\": "
           "[{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}], \"scene\": 0, \"materials\": [{\"name\": \"coat\", "
           "\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0}}}], \"textures\": [" +
           texture + "], \"images\": [{\"uri\": \"data:image/png;base64," +
           test::base64(std::string("\x89PNG\r\n\x1a\n", 8)) + "\"}, {\"name\": \"fur\", " +
           (webpDataUri ? "\"uri\": \"data:image/webp;base64," + test::base64(webp) + "\""
                        : std::string("\"bufferView\": 2, \"mimeType\": \"image/webp\"")) +
           "}], \"extensionsUsed\": [\"EXT_texture_webp\"]" +
           (required.empty() ? "" : ", \"extensionsRequired\": [" + required + "]") + "}";
}

TEST(WebpTexture, AGltfTexturesWebpSourceIsPreferredAndDecodesToItsPixels) {
    // The extension required, the PNG the fallback of viewers without WebP: the material shows the WebP.
    const test::TempFile file("webp.gltf", triangleWithTexture("{\"source\": 0, \"extensions\": "
                                                               "{\"EXT_texture_webp\": {\"source\": 1}}}",
                                                               "\"EXT_texture_webp\""));
    const Scene scene = loadScene(file.path());
    const Material& material = scene.meshes.at(0).material;
    ASSERT_EQ(material.baseColorTexture.image, 1);
    EXPECT_TRUE(scene.report.warnings.empty()) << ::testing::PrintToString(scene.report.warnings);
    const DecodedImage decoded = decodeSceneImage(scene.images.at(1), 1, file.path(), kPlenty);
    ASSERT_EQ(decoded.width, 3);
    ASSERT_EQ(decoded.height, 2);
    EXPECT_EQ(pixelsOf(decoded), kPixels);

    // With no fallback at all, and not required.
    const test::TempFile alone("webp-alone.gltf",
                               triangleWithTexture("{\"extensions\": {\"EXT_texture_webp\": {\"source\": 1}}}", ""));
    EXPECT_EQ(loadScene(alone.path()).meshes.at(0).material.baseColorTexture.image, 1);

    // As a data:image/webp URI, which tinygltf takes for a file name: the same pixels, and no file looked for.
    const test::TempFile dataUri(
        "webp-data-uri.gltf",
        triangleWithTexture("{\"extensions\": {\"EXT_texture_webp\": {\"source\": 1}}}", "\"EXT_texture_webp\"", true));
    const Scene fromUri = loadScene(dataUri.path());
    ASSERT_EQ(fromUri.meshes.at(0).material.baseColorTexture.image, 1);
    EXPECT_TRUE(fromUri.images.at(1).path.empty());
    EXPECT_EQ(fromUri.images.at(1).name, "fur");
    EXPECT_EQ(pixelsOf(decodeSceneImage(fromUri.images.at(1), 1, dataUri.path(), kPlenty)), kPixels);
    EXPECT_TRUE(std::ranges::none_of(fromUri.report.inputFiles, [](const std::string& read) {
        return read.find("data:") != std::string::npos;
    })) << ::testing::PrintToString(fromUri.report.inputFiles);
}

TEST(WebpTexture, AnImageDataUriThatIsNotBase64IsRefused) {
    std::string gltf = triangleWithTexture("{\"extensions\": {\"EXT_texture_webp\": {\"source\": 1}}}", "", true);
    const std::size_t at = gltf.find("data:image/webp;base64,");
    ASSERT_NE(at, std::string::npos);
    const test::TempFile notBase64("webp-percent.gltf", std::string(gltf).replace(at, 23, "data:image/webp,"));
    std::string message = test::sceneErrorMessage([&] { loadScene(notBase64.path()); });
    EXPECT_NE(message.find("image 1: its data: URI 'data:image/webp' is not base64"), std::string::npos) << message;
    const test::TempFile badCharacters("webp-bad.gltf", std::string(gltf).insert(at + 23, "!!"));
    message = test::sceneErrorMessage([&] { loadScene(badCharacters.path()); });
    EXPECT_NE(message.find("image 1: its data: URI 'data:image/webp;base64' holds characters that are not base64"),
              std::string::npos)
        << message;
}

TEST(WebpTexture, AWebpSourceOutOfRangeIsRefusedNamingTheMaterialAndTheTexture) {
    const test::TempFile file(
        "webp-range.gltf",
        triangleWithTexture("{\"name\": \"pelt\", \"source\": 0, \"extensions\": {\"EXT_texture_webp\": {\"source\": "
                            "2}}}",
                            "\"EXT_texture_webp\""));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find(file.path()), std::string::npos) << message;
    EXPECT_NE(message.find("material 0 'coat' baseColorTexture: texture 0 'pelt' EXT_texture_webp: image index 2 out "
                           "of range (file has 2 images)"),
              std::string::npos)
        << message;
}

} // namespace
} // namespace inkgraph::webp_texture_test
