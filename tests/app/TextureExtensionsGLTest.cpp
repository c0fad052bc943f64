// glTF's texture and material extensions as a user meets them, through the real executable (issue 35):
// KHR_texture_transform's rotation on Khronos's TextureTransformTest sample (tests/scene/data/TextureTransformTest),
// KHR_materials_pbrSpecularGlossiness's diffuse colour, EXT_texture_webp's images (made here by libwebp's encoder).
#include "CliTestSupport.h"
#include "GltfTestFiles.h"
#include "tests/support/Srgb.h"

#include "render/ImageFiles.h"

#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <webp/encode.h>
#include <webp/types.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::Cli;
using test::CliRun;
namespace fs = std::filesystem;

fs::path sampleFolder() { return fs::path(INKGRAPH_SOURCE_ROOT) / "tests" / "scene" / "data" / "TextureTransformTest"; }

class TextureExtensions : public Cli {
protected:
    /** The centre pixel (R, G, B, A: readImage()'s order for PNG) of `arguments` rendered with kQuadView. */
    cv::Vec4b centrePixel(const std::string& arguments) {
        const CliRun result = run("render " + arguments + " -o centre.png" + kQuadView);
        EXPECT_EQ(result.exitCode, 0) << result.err;
        const cv::Mat picture = readImage(directory / "centre.png");
        return picture.at<cv::Vec4b>(picture.rows / 2, picture.cols / 2);
    }

    /** Lit by ambient light 1 alone, so a pixel is its base colour: the quad fills the middle of the picture. */
    static inline const std::string kQuadView =
        " --size 32x32 --eye 0,0,3 --target 0,0,0 --fov 45 --shading flat --ambient 1 --lines none -q";
};

/** A glTF of a square (-1..1 in x and y, facing +Z) with TEXCOORD_0 (0, 0) at its upper left corner, whose material
 *  is `material`, beside `members` (textures, images, extensionsUsed, ...). */
std::string quadGltf(const nlohmann::json& material, const nlohmann::json& members) {
    std::string buffer;
    const float positions[12] = {-1, 1, 0, 1, 1, 0, 1, -1, 0, -1, -1, 0};
    const float uvs[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    const std::uint16_t indices[6] = {0, 3, 2, 0, 2, 1}; // counter-clockwise seen from +Z
    buffer.append(reinterpret_cast<const char*>(positions), sizeof positions);
    buffer.append(reinterpret_cast<const char*>(uvs), sizeof uvs);
    buffer.append(reinterpret_cast<const char*>(indices), sizeof indices);
    nlohmann::json gltf = {
        {"asset", {{"version", "2.0"}}},
        {"buffers",
         {{{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + test::base64(buffer)}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
          {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}},
          {{"buffer", 0}, {"byteOffset", 80}, {"byteLength", 12}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", 4},
           {"type", "VEC3"},
           {"min", {-1, -1, 0}},
           {"max", {1, 1, 0}}},
          {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
          {{"bufferView", 2}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
        {"materials", {material}},
        {"meshes",
         {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"indices", 2}, {"material", 0}}}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"scenes", {{{"nodes", {0}}}}},
        {"scene", 0}};
    gltf.update(members);
    return gltf.dump();
}

/** The sample's camera for these tests: looking down -Z at the origin from 4 units, 45 degrees high, on a square
 *  picture, so a world point (x, y, 0) lies at pixel ((1 + x / h) W / 2, (1 - y / h) W / 2) with h = 4 tan(22.5°). */
constexpr int kSamplePixels = 400;
const std::string kSampleView = " --size 400x400 --eye 0,0,4 --target 0,0,0 --fov 45 --shading flat --ambient 1"
                                " --lines none";

/** KHR_texture_transform's uv' = T R S (u, v, 1) with R counter-clockwise in glTF's UV space (v down). */
glm::dmat3 textureTransform(glm::dvec2 offset, double rotation, glm::dvec2 scale) {
    const double c = std::cos(rotation);
    const double s = std::sin(rotation);
    return glm::dmat3(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1) * glm::dmat3(c, -s, 0, s, c, 0, 0, 0, 1) *
           glm::dmat3(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
}

/** One of the sample's arrow tiles: its centre in the world and its transform; the markers on it (quads of half size
 *  `markerHalf` at their centres, tile-relative), which the arrow test leaves out. */
struct ArrowTile {
    const char* name;
    glm::dvec2 centre;
    glm::dmat3 transform;
    std::vector<glm::dvec2> markers;
    double markerHalf;
};

enum class Ink { Dark, Light, Unsure };

/** The arrow texture's ink at texture coordinates `st` (clamped to the edge, as the sample's sampler is): dark or light
 *  only where the texels a texel and a half around agree, so bilinear filtering at the arrow's edge does not count. */
Ink arrowInk(const cv::Mat& arrow, glm::dvec2 st) {
    int dark = 0;
    int light = 0;
    for (double du : {-1.5, 0.0, 1.5}) {
        for (double dv : {-1.5, 0.0, 1.5}) {
            const int x = std::clamp(int(std::floor(st.x * arrow.cols + du)), 0, arrow.cols - 1);
            const int y = std::clamp(int(std::floor(st.y * arrow.rows + dv)), 0, arrow.rows - 1);
            const cv::Vec4b texel = arrow.at<cv::Vec4b>(y, x);
            const int luma = (texel[0] + texel[1] + texel[2]) / 3;
            if (luma < 64) ++dark;
            if (luma > 160) ++light;
        }
    }
    return dark == 9 ? Ink::Dark : light == 9 ? Ink::Light : Ink::Unsure;
}

/** How well the dark pixels of `tile` in `picture` match the arrow drawn with `transform`: the shared dark pixels over
 *  the pixels dark in either (1: the same arrow), over the tile's pixels off its markers and edges whose ink is sure.
 */
double arrowOverlap(const cv::Mat& picture, const cv::Mat& arrow, const ArrowTile& tile, const glm::dmat3& transform) {
    const double halfHeight = 4.0 * std::tan(glm::radians(22.5));
    int both = 0;
    int either = 0;
    for (int row = 0; row < picture.rows; ++row) {
        for (int column = 0; column < picture.cols; ++column) {
            const glm::dvec2 world((2.0 * (column + 0.5) / kSamplePixels - 1.0) * halfHeight,
                                   (1.0 - 2.0 * (row + 0.5) / kSamplePixels) * halfHeight);
            const glm::dvec2 local = world - tile.centre;
            if (std::abs(local.x) > 0.48 || std::abs(local.y) > 0.48) continue;
            const bool onMarker = std::ranges::any_of(tile.markers, [&](glm::dvec2 marker) {
                return std::abs(local.x - marker.x) < tile.markerHalf + 0.02 &&
                       std::abs(local.y - marker.y) < tile.markerHalf + 0.02;
            });
            if (onMarker) continue;
            // The quad's TEXCOORD_0: (0, 0) at its upper left corner, v down.
            const glm::dvec3 st = transform * glm::dvec3(local.x + 0.5, 0.5 - local.y, 1.0);
            const Ink expected = arrowInk(arrow, glm::dvec2(st));
            if (expected == Ink::Unsure) continue;
            const cv::Vec4b pixel = picture.at<cv::Vec4b>(row, column);
            const bool drawnDark = (pixel[0] + pixel[1] + pixel[2]) / 3 < 96;
            both += drawnDark && expected == Ink::Dark;
            either += drawnDark || expected == Ink::Dark;
        }
    }
    return either == 0 ? 0.0 : double(both) / double(either);
}

TEST_F(TextureExtensions, TheTextureTransformSamplesArrowsPointAtTheirCorrectMarks) {
    // Khronos's TextureTransformTest: an arrow turned by KHR_texture_transform points at a green mark when the turn is
    // read as the extension means it, at a red one when it is turned the other way (the GLSL listing's matrix, which
    // inkgraph used before issue 35). The arrow drawn is compared with the texture through the extension's transform,
    // and through the opposite turn, which must not match.
    const CliRun result =
        run("render " + test::shellQuoted(sampleFolder() / "TextureTransformTest.gltf") + " -o out.png" + kSampleView);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const cv::Mat picture = readImage(directory / "out.png");
    const cv::Mat arrow = readImage(sampleFolder() / "Arrow.png");
    ASSERT_EQ(picture.type(), CV_8UC4);
    ASSERT_EQ(arrow.type(), CV_8UC4);
    // From the sample's nodes: the Rotation tile (22.5 degrees) with its three marks, the All tile (offset, rotation
    // and scale) with its one.
    const double rotationAngle = 0.39269908169872414;
    const std::vector<ArrowTile> tiles = {
        {"Rotation",
         {-1.1, -0.55},
         textureTransform({0, 0}, rotationAngle, {1, 1}),
         {{-0.0790, -0.5163}, {0.2778, -0.2778}, {0.5163, 0.0790}},
         0.075},
        {"All", {1.1, -0.55}, textureTransform({-0.2, -0.1}, 0.3, {1.5, 1.5}), {{-0.07, -0.25}}, 0.05},
    };
    const std::vector<glm::dmat3> opposite = {textureTransform({0, 0}, -rotationAngle, {1, 1}),
                                              textureTransform({-0.2, -0.1}, -0.3, {1.5, 1.5})};
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        SCOPED_TRACE(tiles[i].name);
        const double overlap = arrowOverlap(picture, arrow, tiles[i], tiles[i].transform);
        const double overlapTurnedBack = arrowOverlap(picture, arrow, tiles[i], opposite[i]);
        // Measured: 1.000 and 0.000 on both tiles; the opposite turn (before issue 35) gave 0.000 and 1.000.
        EXPECT_GT(overlap, 0.9);
        EXPECT_LT(overlapTurnedBack, 0.5);
    }
}

TEST_F(TextureExtensions, ASpecularGlossinessMaterialIsDrawnInItsDiffuseColour) {
    // Required, so refused before issue 35. Its metallic-roughness fallback (red) is what a viewer without the
    // extension draws; the diffuse factor is what this one must.
    const nlohmann::json material = {
        {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}},
        {"extensions",
         {{"KHR_materials_pbrSpecularGlossiness",
           {{"diffuseFactor", {0.2, 0.5, 0.8, 1}}, {"specularFactor", {1, 1, 1}}, {"glossinessFactor", 0.5}}}}}};
    const nlohmann::json required = {"KHR_materials_pbrSpecularGlossiness"};
    std::ofstream(directory / "gloss.gltf")
        << quadGltf(material, {{"extensionsUsed", required}, {"extensionsRequired", required}});
    const cv::Vec4b pixel = centrePixel("gloss.gltf");
    EXPECT_NEAR(pixel[0], test::srgbCode(0.2), 1);
    EXPECT_NEAR(pixel[1], test::srgbCode(0.5), 1);
    EXPECT_NEAR(pixel[2], test::srgbCode(0.8), 1);
}

/** A `side` x `side` WebP of one colour (RGBA), lossless, through libwebp's encoder. */
std::string uniformWebp(int side, const std::vector<unsigned char>& rgba) {
    std::vector<unsigned char> pixels;
    for (int i = 0; i < side * side; ++i) pixels.insert(pixels.end(), rgba.begin(), rgba.end());
    unsigned char* encoded = nullptr;
    const std::size_t size = WebPEncodeLosslessRGBA(pixels.data(), side, side, side * 4, &encoded);
    std::string bytes(reinterpret_cast<const char*>(encoded), size);
    WebPFree(encoded);
    return bytes;
}

TEST_F(TextureExtensions, AWebpTextureIsDrawnAndABrokenOneIsAWarningNamingIt) {
    // EXT_texture_webp required, its image an external .webp beside the model; the texture's PNG fallback names a file
    // that is not there, which a render that used it would refuse.
    const nlohmann::json material = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}};
    const nlohmann::json required = {"EXT_texture_webp"};
    const nlohmann::json members = {
        {"textures", {{{"source", 0}, {"extensions", {{"EXT_texture_webp", {{"source", 1}}}}}}}},
        {"images", {{{"uri", "missing.png"}}, {{"uri", "fur.webp"}, {"name", "fur"}}}},
        {"extensionsUsed", required},
        {"extensionsRequired", required}};
    std::ofstream(directory / "webp.gltf") << quadGltf(material, members);
    const std::string webp = uniformWebp(4, {200, 100, 50, 255});
    ASSERT_FALSE(webp.empty());
    std::ofstream(directory / "fur.webp", std::ios::binary) << webp;
    const cv::Vec4b pixel = centrePixel("webp.gltf");
    EXPECT_NEAR(pixel[0], 200, 1);
    EXPECT_NEAR(pixel[1], 100, 1);
    EXPECT_NEAR(pixel[2], 50, 1);

    // The same file cut short: a texture-undecodable warning naming the model and the image, and the quad drawn in its
    // factor alone (white); with --strict, exit 3 and nothing written.
    std::ofstream(directory / "fur.webp", std::ios::binary | std::ios::trunc) << webp.substr(0, webp.size() / 2);
    const std::string expected =
        "'webp.gltf': image 1 'fur': cannot be decoded: a corrupt, truncated or unsupported WebP (libwebp header: not "
        "enough data (truncated))";
    const CliRun broken = run("render webp.gltf -o centre.png" + kQuadView);
    EXPECT_EQ(broken.exitCode, 0) << broken.err;
    EXPECT_NE(broken.err.find("warning: "), std::string::npos) << broken.err;
    EXPECT_NE(broken.err.find(expected), std::string::npos) << broken.err;
    const cv::Mat untextured = readImage(directory / "centre.png");
    EXPECT_EQ(untextured.at<cv::Vec4b>(untextured.rows / 2, untextured.cols / 2), cv::Vec4b(255, 255, 255, 255));
    const CliRun strict = run("render webp.gltf -o strict.png --strict" + kQuadView);
    EXPECT_EQ(strict.exitCode, 3) << strict.err;
    EXPECT_NE(strict.err.find(expected), std::string::npos) << strict.err;
    EXPECT_FALSE(fs::exists(directory / "strict.png"));
}

} // namespace
} // namespace inkgraph
