// glTF's metallic-roughness under --shading mtoon (shaders/common/pbr.glsl, docs/mtoon.md), for materials without
// MToon, against closed forms per pixel: a rough dielectric facing the light shows its base colour (plus its 4%
// specular), a metal has no diffuse (dark away from its highlight), the GGX highlight peaks where the normal bisects
// the light and the eye with the value of D V F worked out by hand, roughness 0 takes three.js' floor, the
// metallic-roughness texture's blue channel is the metalness and its green the roughness, as linear data, decoded only
// for a material that reads it, and an unlit material stays unlit. Needs a GL context (llvmpipe in CI).
#include "codecs/PngCodec.h"
#include "graph/GraphCompiler.h"
#include "passes/shade/ShadePass.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/AnalyticSphere.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/PassHarness.h"
#include "tests/support/Srgb.h"
#include "tests/support/TestCamera.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph::pbr_gl_test {
namespace {

constexpr int kSize = 128;
constexpr double kDistance = 4.0;
constexpr double kFovDegrees = 35.0;
constexpr double kPi = 3.14159265358979323846;

using test::linearOf;
using test::srgbCode;

/** What pbr.glsl computes, in double: three.js' direct lighting of glTF's metallic-roughness under a white light of
 *  irradiance pi (so that Lambert's base / pi gives the lit side its base colour), plus `ambient` on the diffuse
 *  colour. */
glm::dvec3 metallicRoughness(glm::dvec3 base, double metallic, double roughness, glm::dvec3 n, glm::dvec3 l,
                             glm::dvec3 v, glm::dvec3 ambient = glm::dvec3(0.0)) {
    const glm::dvec3 ambientTerm = ambient * base * (1.0 - metallic);
    const double nDotL = glm::dot(n, l);
    if (nDotL <= 0.0) return ambientTerm;
    const double alpha = std::pow(std::clamp(roughness, 0.0525, 1.0), 2.0);
    const double a2 = alpha * alpha;
    const double nDotV = std::clamp(glm::dot(n, v), 0.0, 1.0);
    const glm::dvec3 h = glm::normalize(l + v);
    const double nDotH = glm::dot(n, h);
    const double distribution = a2 / (kPi * std::pow(nDotH * nDotH * (a2 - 1.0) + 1.0, 2.0));
    const double visibility =
        0.5 / (nDotL * std::sqrt(nDotV * nDotV * (1.0 - a2) + a2) + nDotV * std::sqrt(nDotL * nDotL * (1.0 - a2) + a2));
    const glm::dvec3 f0 = glm::mix(glm::dvec3(0.04), base, metallic);
    const glm::dvec3 fresnel = f0 + (1.0 - f0) * std::pow(1.0 - glm::dot(v, h), 5.0);
    return ambientTerm + (base * (1.0 - metallic) / kPi + fresnel * distribution * visibility) * nDotL * kPi;
}

/** The square [-1, 1]^2 in the plane z = 0 facing +Z, glTF texture coordinates: u from left to right. */
Mesh unitSquare() {
    Mesh mesh;
    mesh.name = "square";
    mesh.positions = {{-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 0.0f}, {-1.0f, 1.0f, 0.0f}};
    mesh.normals.assign(4, glm::vec3(0.0f, 0.0f, 1.0f));
    mesh.texcoords[0] = {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}, {0.0f, 0.0f}};
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    return mesh;
}

/** One row of RGBA texels as an embedded PNG: texture data is stored as bytes, whatever the file says about sRGB. */
SceneImage pngRow(const std::vector<std::array<unsigned char, 4>>& texels) {
    std::vector<unsigned char> row;
    for (const auto& texel : texels) row.insert(row.end(), texel.begin(), texel.end());
    const unsigned char* rows[] = {row.data()};
    SceneImage image;
    image.name = "metallic-roughness";
    image.mimeType = "image/png";
    image.encoded =
        std::make_shared<const std::vector<unsigned char>>(encodePngRows(std::uint32_t(texels.size()), 1, 4, rows));
    return image;
}

class MetallicRoughness : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override { test::sharedGlContext(); }

    /** The camera at (0, 0, kDistance) looks at the origin: view directions are world directions. No ambient light
     *  unless `ambient` says. */
    void useScene(Scene built, glm::dvec3 towardLight, glm::vec3 ambient = glm::vec3(0.0f)) {
        scene = std::move(built);
        frame.camera =
            test::lookingAt(scene, glm::dvec3(0.0, 0.0, kDistance), glm::dvec3(0.0), kFovDegrees, kSize, kSize);
        frame.worldOrigin = glm::dvec3(0.0);
        frame.towardLightWorld = glm::normalize(towardLight);
        frame.ambientLight = ambient;
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    }

    cv::Mat shadeMToon() {
        ShadeSettings settings;
        settings.model = ShadingModel::MToon;
        ShadePass pass("shade", shaders, *gpuScene, frame, settings, std::nullopt);
        const Plan plan = compile({&pass}, {"shade.color"});
        executor.run(plan, {&pass}, {kSize, kSize, false});
        cv::Mat image = executor.store().image("shade.color").clone();
        executor.store().clear();
        return image;
    }

    /** The point of the plane z = 0 that pixel (col, row)'s centre sees. */
    static glm::dvec3 planePoint(int col, int row) {
        const double focal = (kSize / 2.0) / std::tan(glm::radians(kFovDegrees) / 2.0);
        return glm::dvec3((col + 0.5 - kSize / 2.0) / focal, -(row + 0.5 - kSize / 2.0) / focal, 0.0) * kDistance;
    }
    static glm::dvec3 towardEyeFrom(glm::dvec3 point) {
        return glm::normalize(glm::dvec3(0.0, 0.0, kDistance) - point);
    }
};

/** The largest difference in 8-bit codes between the pixel and the linear colour `expected`, over RGB. */
int codeError(const cv::Vec4b& actual, glm::dvec3 expected) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(actual[c]) - srgbCode(expected[c])));
    return worst;
}

TEST_F(MetallicRoughness, RoughDielectricFacingTheLightShowsItsBaseColour) {
    // A material that does not come from glTF keeps metallic 0, roughness 1.
    Mesh square = unitSquare();
    const glm::dvec3 base(0.6, 0.4, 0.2);
    square.material.baseColorFactor = glm::vec4(glm::vec3(base), 1.0f);
    ASSERT_EQ(square.material.metallicFactor, 0.0f);
    ASSERT_EQ(square.material.roughnessFactor, 1.0f);
    useScene(makeScene(std::move(square)), {0.0, 0.0, 1.0});
    const cv::Mat color = shadeMToon();

    // At the centre n = l = v: Lambert gives the base colour (as MToon's lit side), and GGX with alpha 1 adds
    // D V F pi = (1 / pi) (1 / 4) 0.04 pi = 0.01.
    const glm::dvec3 centre = base + 0.01;
    const glm::dvec3 n(0.0, 0.0, 1.0);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(metallicRoughness(base, 0.0, 1.0, n, n, n)[c], centre[c], 1e-12);
    const cv::Vec4b middle = color.at<cv::Vec4b>(kSize / 2, kSize / 2);
    EXPECT_LE(codeError(middle, centre), 1) << middle;
    EXPECT_EQ(middle[3], 255);
    // Everywhere on the square (the eye off the normal by up to 14 degrees): the closed form per pixel, within a code
    // (float against double, rounded to 8 bits).
    int compared = 0, worst = 0;
    for (int row = 0; row < kSize; row += 2) {
        for (int col = 0; col < kSize; col += 2) {
            const glm::dvec3 point = planePoint(col, row);
            if (std::max(std::abs(point.x), std::abs(point.y)) > 0.95) continue; // off or at the square's border
            const glm::dvec3 expected = metallicRoughness(base, 0.0, 1.0, n, n, towardEyeFrom(point));
            worst = std::max(worst, codeError(color.at<cv::Vec4b>(row, col), expected));
            ++compared;
        }
    }
    EXPECT_GT(compared, 1000);
    EXPECT_LE(worst, 1);

    // Lit from behind, only the ambient light (--ambient, per channel) reaches it: ambient x base x (1 - metallic).
    useScene(scene, {0.0, 0.0, -1.0}, glm::vec3(0.1f, 0.2f, 0.3f));
    const cv::Vec4b ambientOnly = shadeMToon().at<cv::Vec4b>(kSize / 2, kSize / 2);
    EXPECT_LE(codeError(ambientOnly, base * glm::dvec3(0.1, 0.2, 0.3)), 1) << ambientOnly;
}

TEST_F(MetallicRoughness, MetalHasNoDiffuseOnlyItsSpecularLobe) {
    Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 256, 128);
    const glm::dvec3 base(0.9, 0.8, 0.7);
    sphere.material.baseColorFactor = glm::vec4(glm::vec3(base), 1.0f);
    sphere.material.metallicFactor = 1.0f;
    sphere.material.roughnessFactor = 0.3f;
    // An ambient light, which lights only the diffuse colour: a metal has none.
    useScene(makeScene(std::move(sphere)), {1.0, 0.5, 1.0}, glm::vec3(0.2f));
    const glm::dvec3 light = frame.towardLightWorld;
    const cv::Mat color = shadeMToon();
    const test::AnalyticSphereView view{kSize, 1.0, kDistance, kFovDegrees};
    int compared = 0, worst = 0, darkLit = 0, unlitSide = 0, unlitBlack = 0;
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            const std::optional<test::SphereHit> hit = view.castPixel(col, row);
            if (!hit || glm::dot(hit->normal, hit->towardEye) < 0.3) continue; // away from the polygonal rim
            const cv::Vec4b actual = color.at<cv::Vec4b>(row, col);
            const glm::dvec3 expected = metallicRoughness(base, 1.0, 0.3, hit->normal, light, hit->towardEye);
            worst = std::max(worst, codeError(actual, expected));
            ++compared;
            const double nDotL = glm::dot(hit->normal, light);
            if (nDotL < -0.05) {
                ++unlitSide;
                if (actual[0] == 0 && actual[1] == 0 && actual[2] == 0) ++unlitBlack;
            } else if (nDotL > 0.3 && expected.r < 0.01) {
                // Lit, where Lambert alone would give 0.9 x 0.3 or more, yet outside the highlight: dark.
                ++darkLit;
                EXPECT_LT(linearOf(actual[0]), 0.015) << "(" << col << ", " << row << ")";
            }
        }
    }
    EXPECT_GT(compared, 3000);
    EXPECT_LE(worst, 1);
    EXPECT_GT(darkLit, 100);
    EXPECT_GT(unlitSide, 100);
    EXPECT_EQ(unlitBlack, unlitSide)
        << "the ambient light does not reach a metal: the side away from the light is black";
}

TEST_F(MetallicRoughness, HighlightPeaksWhereTheNormalBisectsLightAndEyeWithTheClosedFormValue) {
    // A black dielectric: no diffuse, and the specular's F0 is 0.04, which keeps the peak below white.
    Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 256, 128);
    sphere.material.baseColorFactor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    sphere.material.metallicFactor = 0.0f;
    sphere.material.roughnessFactor = 0.4f;
    const glm::dvec3 light(std::sin(glm::radians(60.0)), 0.0, std::cos(glm::radians(60.0)));
    useScene(makeScene(std::move(sphere)), light);
    const cv::Mat color = shadeMToon();
    const test::AnalyticSphereView view{kSize, 1.0, kDistance, kFovDegrees};

    // The mirror point: its normal is the half vector of the light and its own direction to the eye (view space:
    // the sphere's centre at (0, 0, -4), the eye at the origin), found by iterating to the fixed point.
    glm::dvec3 normal = glm::normalize(light + glm::dvec3(0.0, 0.0, 1.0));
    for (int step = 0; step < 100; ++step) normal = glm::normalize(light + glm::normalize(-(view.center() + normal)));
    const glm::dvec2 mirror = view.project(view.center() + normal);
    const int mirrorCol = int(std::floor(mirror.x));
    const int mirrorRow = int(std::floor(mirror.y));

    // D V F pi n.l by hand at that pixel's centre, with alpha = 0.4^2 = 0.16.
    const test::SphereHit hit = *view.castPixel(mirrorCol, mirrorRow);
    const glm::dvec3 n = hit.normal;
    const glm::dvec3 v = hit.towardEye;
    const glm::dvec3 h = glm::normalize(light + v);
    const double alpha = 0.16;
    const double a2 = alpha * alpha;
    const double nl = glm::dot(n, light);
    const double nv = glm::dot(n, v);
    const double nh = glm::dot(n, h);
    const double d = a2 / (kPi * (nh * nh * (a2 - 1.0) + 1.0) * (nh * nh * (a2 - 1.0) + 1.0));
    const double visibility =
        0.5 / (nl * std::sqrt(nv * nv * (1.0 - a2) + a2) + nv * std::sqrt(nl * nl * (1.0 - a2) + a2));
    const double f = 0.04 + 0.96 * std::pow(1.0 - glm::dot(v, h), 5.0);
    const double peak = d * visibility * f * kPi * nl;
    EXPECT_NEAR(nh, 1.0, 1e-4) << "the pixel's centre is within a pixel of the mirror point";
    EXPECT_NEAR(peak, metallicRoughness(glm::dvec3(0.0), 0.0, 0.4, n, light, v).r, 1e-12);
    EXPECT_GT(peak, 0.3); // a highlight well above black and below white: 8-bit codes resolve it
    EXPECT_LT(peak, 0.7);
    const cv::Vec4b atMirror = color.at<cv::Vec4b>(mirrorRow, mirrorCol);
    EXPECT_LE(codeError(atMirror, glm::dvec3(peak)), 1) << atMirror << " against " << peak;
    EXPECT_EQ(atMirror[0], atMirror[1]) << "a dielectric's highlight is white";

    // The brightest pixel is the mirror pixel or a neighbour: n.l and V lean the product's maximum a little toward
    // the light, within a pixel here (the lobe is about 10 pixels wide).
    cv::Point brightest(-1, -1);
    int brightestCode = -1;
    for (int row = 0; row < kSize; ++row)
        for (int col = 0; col < kSize; ++col)
            if (color.at<cv::Vec4b>(row, col)[3] == 255 && color.at<cv::Vec4b>(row, col)[0] > brightestCode) {
                brightestCode = color.at<cv::Vec4b>(row, col)[0];
                brightest = cv::Point(col, row);
            }
    EXPECT_LE(std::abs(brightest.x - mirrorCol), 1) << brightest << " against " << cv::Point(mirrorCol, mirrorRow);
    EXPECT_LE(std::abs(brightest.y - mirrorRow), 1) << brightest << " against " << cv::Point(mirrorCol, mirrorRow);
}

TEST_F(MetallicRoughness, TextureBlueIsMetalnessAndGreenRoughnessAsLinearData) {
    // Two texels, nearest: the left half of the square is a rough dielectric (red 255 must not matter), the right a
    // metal of roughness 128/255 = 0.502 (sRGB-decoded it would be 0.216, whose peak is far above white).
    Mesh square = unitSquare();
    const glm::dvec3 base(0.2, 0.15, 0.1);
    square.material.baseColorFactor = glm::vec4(glm::vec3(base), 1.0f);
    square.material.metallicFactor = 1.0f;
    square.material.roughnessFactor = 1.0f;
    square.material.metallicRoughnessTexture.image = 0;
    TextureSampler& sampler = square.material.metallicRoughnessTexture.sampler;
    sampler.magFilter = sampler.minFilter = TextureFilter::Nearest;
    sampler.wrapS = sampler.wrapT = TextureWrap::ClampToEdge;
    Scene built = makeScene(square);
    built.images.push_back(pngRow({{255, 255, 0, 255}, {0, 128, 255, 255}}));
    useScene(built, {0.0, 0.0, 1.0});
    const cv::Mat color = shadeMToon();

    const glm::dvec3 n(0.0, 0.0, 1.0);
    const double roughRight = 128.0 / 255.0;
    // The right half at n = l = v: F = base, D = 1 / (pi alpha^2), V = 1 / 4, so base pi / (4 pi alpha^2).
    const double alphaRight = roughRight * roughRight;
    const glm::dvec3 metalFacing = base / (4.0 * alphaRight * alphaRight);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(metallicRoughness(base, 1.0, roughRight, n, n, n)[c], metalFacing[c], 1e-12);
    int left = 0, right = 0, worstLeft = 0, worstRight = 0;
    for (int row = 0; row < kSize; row += 2) {
        for (int col = 0; col < kSize; col += 2) {
            const glm::dvec3 point = planePoint(col, row);
            if (std::max(std::abs(point.x), std::abs(point.y)) > 0.95 || std::abs(point.x) < 0.1) continue;
            const glm::dvec3 v = towardEyeFrom(point);
            const cv::Vec4b actual = color.at<cv::Vec4b>(row, col);
            if (point.x < 0.0) {
                worstLeft = std::max(worstLeft, codeError(actual, metallicRoughness(base, 0.0, 1.0, n, n, v)));
                ++left;
            } else {
                worstRight = std::max(worstRight, codeError(actual, metallicRoughness(base, 1.0, roughRight, n, n, v)));
                ++right;
            }
        }
    }
    EXPECT_GT(left, 400);
    EXPECT_GT(right, 400);
    EXPECT_LE(worstLeft, 1);
    EXPECT_LE(worstRight, 1);

    // The factors multiply the texels: metallic 0.5 x 1 and roughness 0.5 x 0.502 on the right.
    square.material.metallicFactor = 0.5f;
    square.material.roughnessFactor = 0.5f;
    built.meshes[0].material = square.material;
    useScene(built, {0.0, 0.0, 1.0});
    const cv::Mat scaled = shadeMToon();
    const glm::dvec3 point = planePoint(kSize * 3 / 4, kSize / 2);
    const glm::dvec3 expected = metallicRoughness(base, 0.5, 0.5 * roughRight, n, n, towardEyeFrom(point));
    EXPECT_LE(codeError(scaled.at<cv::Vec4b>(kSize / 2, kSize * 3 / 4), expected), 1);
}

TEST_F(MetallicRoughness, RoughnessZeroTakesThreeJsFloor) {
    // A mirror-smooth metal facing the light: roughness is raised to 0.0525 (alpha 0.00276), so the highlight is
    // finite: white where the normal bisects light and eye, and the floor's own falloff farther out, where the eye is
    // a few degrees off the mirror direction (a floor of 0.04 would give a third of it there).
    Mesh square = unitSquare();
    const glm::dvec3 base(0.5, 0.5, 0.5);
    square.material.baseColorFactor = glm::vec4(glm::vec3(base), 1.0f);
    square.material.metallicFactor = 1.0f;
    square.material.roughnessFactor = 0.0f;
    useScene(makeScene(std::move(square)), {0.0, 0.0, 1.0});
    const cv::Mat color = shadeMToon();
    EXPECT_EQ(color.at<cv::Vec4b>(kSize / 2, kSize / 2), cv::Vec4b(255, 255, 255, 255));
    const glm::dvec3 n(0.0, 0.0, 1.0);
    int compared = 0, worst = 0;
    for (int row = 0; row < kSize; row += 2) {
        for (int col = 0; col < kSize; col += 2) {
            const glm::dvec3 point = planePoint(col, row);
            const double fromCentre = std::hypot(col + 0.5 - kSize / 2.0, row + 0.5 - kSize / 2.0);
            if (std::max(std::abs(point.x), std::abs(point.y)) > 0.95 || fromCentre < 24.0) continue;
            const glm::dvec3 expected = metallicRoughness(base, 1.0, 0.0, n, n, towardEyeFrom(point));
            worst = std::max(worst, codeError(color.at<cv::Vec4b>(row, col), expected));
            ++compared;
        }
    }
    EXPECT_GT(compared, 1000);
    EXPECT_LE(worst, 1);
    // The floor matters at the sampled distances: at 24 pixels from the centre the expected value is well above black.
    const glm::dvec3 near =
        metallicRoughness(base, 1.0, 0.0, n, n, towardEyeFrom(planePoint(kSize / 2 + 24, kSize / 2)));
    EXPECT_GT(near.r, 0.05);
}

TEST_F(MetallicRoughness, TheTextureIsDecodedOnlyForAMaterialThatDrawsIt) {
    // The same texture on an MToon material and an unlit one: neither reads it, so under mtoon neither decodes it.
    Mesh square = unitSquare();
    square.material.metallicRoughnessTexture.image = 0;
    square.material.mtoon = MToonMaterial{};
    Scene built = makeScene(square);
    built.meshes[0].material.mtoon.reset();
    built.meshes[0].material.unlit = true;
    built.meshes.push_back(square);
    built.images.push_back(pngRow({{0, 128, 255, 255}}));
    useScene(built, {0.0, 0.0, 1.0});
    shadeMToon();
    EXPECT_EQ(gpuScene->materials().texturesDecoded(), 0u);

    built.meshes[0].material.unlit = false;
    useScene(built, {0.0, 0.0, 1.0});
    shadeMToon();
    EXPECT_EQ(gpuScene->materials().texturesDecoded(), 1u) << "a lit material without MToon reads it";
}

TEST_F(MetallicRoughness, UnlitMaterialWithoutMToonStaysUnlit) {
    Mesh square = unitSquare();
    square.material.baseColorFactor = glm::vec4(0.3f, 0.5f, 0.7f, 1.0f);
    square.material.metallicFactor = 1.0f; // lit, it would be nearly black
    square.material.unlit = true;
    useScene(makeScene(std::move(square)), {1.0, 0.0, 0.2});
    const cv::Vec4b centre = shadeMToon().at<cv::Vec4b>(kSize / 2, kSize / 2);
    EXPECT_EQ(codeError(centre, glm::dvec3(0.3, 0.5, 0.7)), 0) << centre;
}

} // namespace
} // namespace inkgraph::pbr_gl_test
