// Materials in the passes that draw the surface, against known answers: a texture atlas seen as its exact texel
// colours, KHR_texture_transform picking one texel, vertex colours interpolated in linear light, emissive and unlit,
// an alpha-masked disc whose G-buffer coverage follows the mask to within a pixel (and whose mesh edges are cut
// with it), a blended quad over an opaque one (the blend in the shading, the G-buffer seeing through), single- and
// double-sided faces seen from behind, sheets back to back each seen from its own side, MToon's band (linearstep of
// n.l + shift) on a sphere against ray casting, MToon's shading shift texture, matcap, rim multiply texture, normal
// map, UV animation and outline width texture against their closed forms, and textures decoded only when a pass
// samples them. Needs a GL context (llvmpipe in CI).
#include "graph/GraphCompiler.h"
#include "passes/StillGraph.h"
#include "passes/lines/LineLayerPass.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/outline/OutlinePass.h"
#include "passes/material/SceneMaterials.h"
#include "passes/mtoon/MToonOutlinePass.h"
#include "passes/shade/ShadeMap.h"
#include "passes/shade/ShadePass.h"
#include "passes/edges/MeshEdgesPass.h"
#include "scene/mesh/BackToBackSheets.h"
#include "scene/mesh/Procedural.h"
#include "scene/TextureImage.h"
#include "tests/support/AnalyticSphere.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/PassHarness.h"
#include "tests/support/Srgb.h"
#include "tests/support/TestCamera.h"

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

constexpr int kSize = 128;
constexpr double kDistance = 4.0;
constexpr double kFovDegrees = 35.0;

using test::linearOf;
using test::srgbCode;

/** A PNG of `image` (CV_8UC4 in RGBA order, row 0 at the top) as a scene image, written by stb_image_write (the
 *  library that decodes it is stb_image). */
SceneImage pngImage(const cv::Mat& rgba, const std::string& name) {
    std::vector<unsigned char> bytes;
    const int written = stbi_write_png_to_func(
        [](void* context, void* data, int size) {
            auto* out = static_cast<std::vector<unsigned char>*>(context);
            out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
        },
        &bytes, rgba.cols, rgba.rows, 4, rgba.data, int(rgba.step));
    EXPECT_NE(written, 0);
    SceneImage image;
    image.name = name;
    image.mimeType = "image/png";
    image.encoded = std::make_shared<const std::vector<unsigned char>>(std::move(bytes));
    return image;
}

TextureRef nearestTexture(int image) {
    TextureRef reference;
    reference.image = image;
    reference.sampler.magFilter = TextureFilter::Nearest;
    reference.sampler.minFilter = TextureFilter::Nearest;
    reference.sampler.wrapS = TextureWrap::ClampToEdge;
    reference.sampler.wrapT = TextureWrap::ClampToEdge;
    return reference;
}

/** The square [-half, half]^2 in the plane z = `z`, facing +Z (or -Z when `backward`), glTF texture coordinates:
 *  (0, 0) at its top-left corner (-half, +half). */
Mesh square(float half, float z, bool backward = false) {
    Mesh mesh;
    mesh.name = "square";
    mesh.positions = {{-half, -half, z}, {half, -half, z}, {half, half, z}, {-half, half, z}};
    const glm::vec3 normal(0.0f, 0.0f, backward ? -1.0f : 1.0f);
    mesh.normals.assign(4, normal);
    mesh.texcoords[0] = {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}, {0.0f, 0.0f}};
    mesh.triangles =
        backward ? std::vector<glm::uvec3>{{0, 2, 1}, {0, 3, 2}} : std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}};
    return mesh;
}

class MaterialPasses : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override { test::sharedGlContext(); }

    void useScene(Scene built) {
        scene = std::move(built);
        frame.camera =
            test::lookingAt(scene, glm::dvec3(0.0, 0.0, kDistance), glm::dvec3(0.0), kFovDegrees, kSize, kSize);
        frame.worldOrigin = glm::dvec3(0.0);
        frame.towardLightWorld = glm::dvec3(0.0, 0.0, 1.0);
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    }

    cv::Mat shade(ShadingModel model = ShadingModel::Lambert) {
        ShadeSettings settings;
        settings.model = model;
        std::optional<ShadeMap> map;
        if (model == ShadingModel::Cel) map = makeBandShadeMap(5);
        // MToon's outlines are a layer of their own, which the shade pass lays in, wired as the still graph does.
        MToonOutlinePass outlines(kMToonOutlinePass, shaders, *gpuScene, frame);
        if (traitsOf(model).materialOutlines && MToonOutlinePass::drawsAnyOutline(scene))
            settings.materialOutlines = kMToonOutlinePass;
        ShadePass pass("shade", shaders, *gpuScene, frame, settings, std::move(map));
        const Plan plan = compile({&outlines, &pass}, {"shade.color"});
        executor.run(plan, {&outlines, &pass}, {kSize, kSize, false});
        cv::Mat image = executor.store().image("shade.color").clone();
        executor.store().clear();
        return image;
    }

    cv::Mat gbuffer(const std::string& field) {
        GBufferPass pass("gbuffer", shaders, *gpuScene, frame, 1, GBufferPrecision::Float32);
        const Plan plan = compile({&pass}, {"gbuffer." + field});
        executor.run(plan, {&pass}, {kSize, kSize, false});
        cv::Mat image = executor.store().image("gbuffer." + field).clone();
        executor.store().clear();
        return image;
    }

    /** The point of the plane z = `planeZ` (world) that pixel (col, row)'s centre sees. */
    static glm::dvec2 planePoint(int col, int row, double planeZ) {
        const double focal = (kSize / 2.0) / std::tan(glm::radians(kFovDegrees) / 2.0);
        const double x = (col + 0.5 - kSize / 2.0) / focal;
        const double y = -(row + 0.5 - kSize / 2.0) / focal;
        return glm::dvec2(x, y) * (kDistance - planeZ);
    }
    /** The pixel that sees world point (x, y, planeZ). */
    static cv::Point pixelOf(double x, double y, double planeZ) {
        const double focal = (kSize / 2.0) / std::tan(glm::radians(kFovDegrees) / 2.0);
        const double scale = focal / (kDistance - planeZ);
        return {int(std::floor(kSize / 2.0 + x * scale)), int(std::floor(kSize / 2.0 - y * scale))};
    }
};

cv::Vec4b at(const cv::Mat& image, cv::Point pixel) { return image.at<cv::Vec4b>(pixel.y, pixel.x); }

void expectColor(const cv::Vec4b& actual, cv::Vec3i rgb, int alpha, int tolerance, const std::string& where) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(int(actual[c]), rgb[c], tolerance) << where << " channel " << c;
    EXPECT_NEAR(int(actual[3]), alpha, tolerance) << where << " alpha";
}

TEST_F(MaterialPasses, TextureAtlasShowsItsExactTexelColours) {
    // A 2 x 2 atlas, nearest: each quarter of the square shows one texel, unlit, so the picture holds the file's
    // codes (sRGB decoded by the sampler, encoded again by the shader: a round trip exact to the code).
    const cv::Vec3i texels[2][2] = {{{200, 30, 40}, {20, 180, 60}}, {{40, 60, 220}, {230, 210, 20}}};
    cv::Mat atlas(2, 2, CV_8UC4);
    for (int row = 0; row < 2; ++row)
        for (int col = 0; col < 2; ++col)
            atlas.at<cv::Vec4b>(row, col) =
                cv::Vec4b(uchar(texels[row][col][0]), uchar(texels[row][col][1]), uchar(texels[row][col][2]), 255);
    Mesh mesh = square(1.0f, 0.0f);
    mesh.material.baseColorFactor = glm::vec4(1.0f);
    mesh.material.baseColorTexture = nearestTexture(0);
    mesh.material.unlit = true;
    Scene built = makeScene(std::move(mesh));
    built.images.push_back(pngImage(atlas, "atlas"));
    useScene(std::move(built));
    const cv::Mat color = shade();
    for (int row = 0; row < 2; ++row) {
        for (int col = 0; col < 2; ++col) {
            // Quarter centres: x = -0.5 (left) or 0.5, y = 0.5 (top, texel row 0) or -0.5.
            const cv::Point pixel = pixelOf(col == 0 ? -0.5 : 0.5, row == 0 ? 0.5 : -0.5, 0.0);
            expectColor(at(color, pixel), texels[row][col], 255, 1,
                        "texel (" + std::to_string(col) + ", " + std::to_string(row) + ")");
        }
    }
    EXPECT_EQ(gpuScene->materials().texturesDecoded(), 1u);
    EXPECT_EQ(gpuScene->materials().textureBytes(), decodedImageBytes(2, 2));
}

TEST_F(MaterialPasses, TextureAtlasOnACubeShowsEachFacesTexel) {
    // A 3 x 2 atlas, one texel per face of a cube (face f takes texel (f mod 3, f div 3)), nearest, unlit: seen from
    // a corner, each of the three visible faces is exactly its texel's colour.
    const cv::Vec3i texels[6] = {{200, 30, 40},  {20, 180, 60},  {40, 60, 220},
                                 {230, 210, 20}, {120, 20, 160}, {10, 200, 200}};
    cv::Mat atlas(2, 3, CV_8UC4);
    for (int face = 0; face < 6; ++face)
        atlas.at<cv::Vec4b>(face / 3, face % 3) =
            cv::Vec4b(uchar(texels[face][0]), uchar(texels[face][1]), uchar(texels[face][2]), 255);
    Mesh cube = makeCube(glm::vec3(0.0f), 0.5f); // faces +X, -X, +Y, -Y, +Z, -Z, four corners each
    for (int face = 0; face < 6; ++face) {
        const glm::vec2 low((face % 3) / 3.0f, (face / 3) / 2.0f);
        const glm::vec2 high(low.x + 1.0f / 3.0f, low.y + 0.5f);
        const glm::vec2 inset(0.01f);
        for (const glm::vec2 corner : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)})
            cube.texcoords[0].push_back(glm::mix(low + inset, high - inset, corner));
    }
    cube.material.baseColorFactor = glm::vec4(1.0f);
    cube.material.baseColorTexture = nearestTexture(0);
    cube.material.unlit = true;
    Scene built = makeScene(std::move(cube));
    built.images.push_back(pngImage(atlas, "atlas"));
    scene = std::move(built);
    frame.camera = test::lookingAt(scene, glm::dvec3(2.0, 1.6, 2.4), glm::dvec3(0.0), kFovDegrees, kSize, kSize);
    frame.worldOrigin = glm::dvec3(0.0);
    gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    const cv::Mat color = shade();
    const glm::dmat4 clipFromWorld = frame.camera.projectionMatrix() * frame.camera.viewMatrix();
    for (const int face : {0, 2, 4}) { // +X, +Y, +Z face the eye
        const glm::dvec3 centre = 0.5 * glm::dvec3(face == 0, face == 2, face == 4);
        const glm::dvec4 clip = clipFromWorld * glm::dvec4(centre, 1.0);
        const cv::Point pixel(int(std::floor((clip.x / clip.w + 1.0) * 0.5 * kSize)),
                              int(std::floor((1.0 - clip.y / clip.w) * 0.5 * kSize)));
        expectColor(at(color, pixel), texels[face], 255, 1, "face " + std::to_string(face));
    }
}

TEST_F(MaterialPasses, TextureTransformPicksTheTexelItMapsTo) {
    // uv' = translate(0.5, 0.5) x scale(0.5, 0.5) x uv maps the whole square into the bottom-right texel.
    cv::Mat atlas(2, 2, CV_8UC4, cv::Scalar(0, 0, 0, 255));
    atlas.at<cv::Vec4b>(1, 1) = cv::Vec4b(230, 210, 20, 255);
    Mesh mesh = square(1.0f, 0.0f);
    mesh.material.baseColorFactor = glm::vec4(1.0f);
    mesh.material.baseColorTexture = nearestTexture(0);
    mesh.material.baseColorTexture.transform =
        glm::mat3(1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.5f, 0.5f, 1.0f) * glm::mat3(0.5f, 0, 0, 0, 0.5f, 0, 0, 0, 1);
    mesh.material.unlit = true;
    Scene built = makeScene(std::move(mesh));
    built.images.push_back(pngImage(atlas, "atlas"));
    useScene(std::move(built));
    const cv::Mat color = shade();
    for (const auto& [x, y] : std::vector<std::pair<double, double>>{{-0.9, 0.9}, {0.9, -0.9}, {0.0, 0.0}})
        expectColor(at(color, pixelOf(x, y, 0.0)), {230, 210, 20}, 255, 1, "point " + std::to_string(x));
}

TEST_F(MaterialPasses, VertexColoursInterpolateInLinearLight) {
    Mesh mesh;
    mesh.name = "triangle";
    mesh.positions = {{-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    mesh.normals.assign(3, glm::vec3(0.0f, 0.0f, 1.0f));
    mesh.triangles = {{0, 1, 2}};
    mesh.colors = {{1.0f, 0.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f, 1.0f}};
    mesh.material.baseColorFactor = glm::vec4(1.0f);
    mesh.material.unlit = true;
    useScene(makeScene(std::move(mesh)));
    const cv::Mat color = shade();
    // Near each corner its own colour dominates; at the centroid each channel is 1/3 in linear light.
    const int third = srgbCode(1.0 / 3.0);
    expectColor(at(color, pixelOf(0.0, -1.0 / 3.0, 0.0)), {third, third, third}, 255, 3, "centroid");
    const cv::Vec4b nearRed = at(color, pixelOf(-0.85, -0.9, 0.0));
    EXPECT_GT(nearRed[0], 200);
    EXPECT_LT(nearRed[1], 120);
    EXPECT_LT(nearRed[2], 120);
}

TEST_F(MaterialPasses, EmissiveAddsToTheLitColourAndUnlitIgnoresTheLight) {
    Mesh mesh = square(1.0f, 0.0f);
    mesh.material.baseColorFactor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    mesh.material.emissiveFactor = glm::vec3(0.5f, 0.25f, 0.0f);
    useScene(makeScene(std::move(mesh)));
    const cv::Mat color = shade(ShadingModel::Lambert);
    expectColor(at(color, pixelOf(0.0, 0.0, 0.0)), {srgbCode(0.5), srgbCode(0.25), 0}, 255, 1, "emissive");

    Mesh lit = square(1.0f, 0.0f);
    lit.material.baseColorFactor = glm::vec4(0.2f, 0.4f, 0.6f, 1.0f);
    lit.material.unlit = true;
    useScene(makeScene(std::move(lit)));
    frame.towardLightWorld = glm::normalize(glm::dvec3(1.0, 0.0, 0.2)); // grazing: lit, it would be dark
    const cv::Mat unlit = shade(ShadingModel::Cel);
    expectColor(at(unlit, pixelOf(0.0, 0.0, 0.0)), {srgbCode(0.2), srgbCode(0.4), srgbCode(0.6)}, 255, 1, "unlit");
}

TEST_F(MaterialPasses, MaskedDiscCoverageFollowsTheMaskWithinOnePixel) {
    // A 64 x 64 mask: texels whose centre lies within 0.35 of the texture's centre are opaque, the rest clear.
    constexpr int kTexels = 64;
    constexpr double kDiscRadius = 0.35;
    cv::Mat mask(kTexels, kTexels, CV_8UC4);
    auto inside = [&](double u, double v) { return std::hypot(u - 0.5, v - 0.5) <= kDiscRadius; };
    for (int row = 0; row < kTexels; ++row)
        for (int col = 0; col < kTexels; ++col)
            mask.at<cv::Vec4b>(row, col) =
                cv::Vec4b(255, 255, 255, inside((col + 0.5) / kTexels, (row + 0.5) / kTexels) ? 255 : 0);
    Mesh mesh = square(1.0f, 0.0f);
    mesh.material.baseColorTexture = nearestTexture(0);
    mesh.material.alphaMode = AlphaMode::Mask;
    mesh.material.alphaCutoff = 0.5f;
    Scene built = makeScene(std::move(mesh));
    built.images.push_back(pngImage(mask, "disc"));
    useScene(std::move(built));
    const cv::Mat coverage = gbuffer("coverage");
    ASSERT_EQ(coverage.type(), CV_8UC1);
    // The mask's edge is a staircase of texels, 1/32 of the square (about 1 px here): pixels whose centre's texel is
    // opaque must be covered and those whose texel is clear must not, except within a pixel of the disc's edge.
    const double pixelInUv = (planePoint(1, 0, 0.0).x - planePoint(0, 0, 0.0).x) / 2.0;
    int checked = 0, wrong = 0;
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            const glm::dvec2 point = planePoint(col, row, 0.0);
            if (std::abs(point.x) >= 1.0 || std::abs(point.y) >= 1.0) continue;
            const double u = (point.x + 1.0) / 2.0, v = (1.0 - point.y) / 2.0;
            const double distance = std::hypot(u - 0.5, v - 0.5);
            if (std::abs(distance - kDiscRadius) <= pixelInUv + 1.0 / kTexels) continue;
            ++checked;
            const bool expected = distance < kDiscRadius;
            if ((coverage.at<uchar>(row, col) == 255) != expected) ++wrong;
        }
    }
    EXPECT_GT(checked, 1000);
    EXPECT_EQ(wrong, 0) << "pixels whose coverage disagrees with the mask away from its edge";

    // The square's border edges run through the cut-out part only: the mesh-edge pass draws none of them, while
    // an opaque square's border is drawn.
    auto borderPixels = [&] {
        MeshEdgesPass pass("mesh-edges", shaders, *gpuScene, frame);
        const Plan plan = compile({&pass}, {"mesh-edges.border"});
        executor.run(plan, {&pass}, {kSize, kSize, false});
        const int drawn = cv::countNonZero(executor.store().image("mesh-edges.border"));
        executor.store().clear();
        return drawn;
    };
    EXPECT_EQ(borderPixels(), 0) << "border edges through the cut-out";
    scene.meshes[0].material.alphaMode = AlphaMode::Opaque;
    gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    EXPECT_GT(borderPixels(), 400) << "the opaque square's border";
}

/** A square of half-width 1 at z = 0 whose texture is a disc of radius `radius` (in texture units) on `texels`^2
 *  texels, alpha-masked at 0.5, nearest. */
Scene maskedDiscScene(int texels, double radius, bool backward = false) {
    cv::Mat mask(texels, texels, CV_8UC4);
    for (int row = 0; row < texels; ++row)
        for (int col = 0; col < texels; ++col) {
            const bool inside = std::hypot((col + 0.5) / texels - 0.5, (row + 0.5) / texels - 0.5) <= radius;
            mask.at<cv::Vec4b>(row, col) = cv::Vec4b(255, 255, 255, inside ? 255 : 0);
        }
    Mesh mesh = square(1.0f, 0.0f, backward);
    mesh.material.baseColorTexture = nearestTexture(0);
    mesh.material.alphaMode = AlphaMode::Mask;
    mesh.material.doubleSided = true;
    Scene built = makeScene(std::move(mesh));
    built.images.push_back(pngImage(mask, "disc"));
    return built;
}

TEST_F(MaterialPasses, MaskedDiscContourFollowsTheMaskWithinOnePixel) {
    // The contour line type through the still graph: its skeleton lies on the cut-out's edge, a circle of radius
    // 0.35 x 2 world units, not on the square's border. 256 texels put the mask's staircase within 0.2 px of it.
    useScene(maskedDiscScene(256, 0.35));
    Look look;
    look.shading = ShadingModel::None;
    look.lines = {"contour"};
    StillGraphSetup setup{look, shaders, scene, computeBoundingSphere(scene), *gpuScene, frame, std::nullopt};
    const StillGraph graph = buildStillGraph(setup);
    const Plan plan = compile(graph.view(), {graph.finalResource, "contour.skeleton"});
    executor.run(plan, graph.mutableView(), {kSize, kSize, false});
    const std::vector<LinePoint> points = executor.store().object<LineSkeleton>("contour.skeleton").points;
    executor.store().clear();
    ASSERT_GT(points.size(), 100u);
    const double focal = (kSize / 2.0) / std::tan(glm::radians(kFovDegrees) / 2.0);
    const double radius = 0.7 * focal / kDistance; // pixels
    double worst = 0.0;
    for (const LinePoint& point : points) {
        // Pixel centres at integers: the disc's centre, on the axis, is at (kSize - 1) / 2.
        const double distance = std::hypot(point.position.x - (kSize - 1) / 2.0, point.position.y - (kSize - 1) / 2.0);
        worst = std::max(worst, std::abs(distance - radius));
    }
    EXPECT_LE(worst, 1.0) << "farthest contour point from the mask's circle, in pixels";
}

TEST_F(MaterialPasses, BackFaceOutlineIsCutWithTheMask) {
    // Seen from behind, the square is an open sheet, so the outline draws its border (and, since issue 19, not its
    // diagonal: only contour and border edges). With the disc mask the border lies in the cut-out part and is not
    // drawn. Counted: line pixels farther out than the disc.
    const double focal = (kSize / 2.0) / std::tan(glm::radians(kFovDegrees) / 2.0);
    const double discRadius = 0.7 * focal / kDistance; // pixels
    auto outlinePixelsOutsideTheDisc = [&] {
        OutlinePass pass("outline", shaders, *gpuScene, frame, 2.0f);
        const Plan plan = compile({&pass}, {"outline.lines"});
        executor.run(plan, {&pass}, {kSize, kSize, false});
        const cv::Mat lines = executor.store().image("outline.lines").clone();
        executor.store().clear();
        int outside = 0;
        for (int row = 0; row < kSize; ++row)
            for (int col = 0; col < kSize; ++col)
                if (lines.at<uchar>(row, col) != 0 &&
                    std::hypot(col - (kSize - 1) / 2.0, row - (kSize - 1) / 2.0) > discRadius + 3.0)
                    ++outside;
        return outside;
    };
    useScene(maskedDiscScene(64, 0.35, /*backward=*/true));
    EXPECT_EQ(outlinePixelsOutsideTheDisc(), 0) << "the square's border runs through the cut-out";
    scene.meshes[0].material.alphaMode = AlphaMode::Opaque;
    gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    EXPECT_GT(outlinePixelsOutsideTheDisc(), 400) << "the opaque square's border";
}

TEST_F(MaterialPasses, BlendedQuadOverOpaqueOneMixesAndTheGBufferSeesThrough) {
    Mesh back = makeCube(glm::vec3(0.0f, 0.0f, -1.0f), 0.5f); // an opaque box, its front face at z = -0.5
    back.name = "back";
    back.material.baseColorFactor = glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
    back.material.unlit = true;
    Mesh front = square(0.2f, 0.0f);
    front.name = "front";
    front.material.baseColorFactor = glm::vec4(1.0f, 0.0f, 0.0f, 0.5f);
    front.material.alphaMode = AlphaMode::Blend;
    front.material.unlit = true;
    // A blended square over nothing, off to the side, clear of the box.
    Mesh beside = square(0.1f, 0.0f);
    for (glm::vec3& position : beside.positions) position.x += 1.1f;
    beside.name = "beside";
    beside.material = front.material;
    Scene built = makeScene(std::move(back));
    built.meshes.push_back(std::move(front));
    built.meshes.push_back(std::move(beside));
    useScene(std::move(built));
    const cv::Mat color = shade();
    // Blended in the stored (sRGB-encoded) values: red 255 x 0.5 over blue 255 x 0.5.
    expectColor(at(color, pixelOf(0.0, 0.0, 0.0)), {128, 0, 128}, 255, 1, "blend over the opaque box");
    expectColor(at(color, pixelOf(0.45, 0.45, -0.5)), {0, 0, 255}, 255, 0, "the opaque box alone");
    // Over nothing: premultiplied (postfx/Composite.h), colour x alpha and the alpha.
    expectColor(at(color, pixelOf(1.1, 0.0, 0.0)), {128, 0, 0}, 128, 1, "blend over nothing");
    // The G-buffer sees the opaque box through the glass, so its lines stay visible.
    const cv::Mat depth = gbuffer("depth");
    const cv::Point middle = pixelOf(0.0, 0.0, 0.0);
    EXPECT_NEAR(depth.at<float>(middle.y, middle.x), kDistance + 0.5, 1e-4);
}

TEST_F(MaterialPasses, SingleSidedBackFacesAreCulledDoubleSidedOnesLit) {
    Mesh away = square(1.0f, 0.0f, /*backward=*/true);
    away.material.baseColorFactor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
    away.material.doubleSided = false;
    useScene(makeScene(away));
    EXPECT_EQ(at(shade(), pixelOf(0.0, 0.0, 0.0))[3], 0) << "a single-sided face seen from behind is culled";
    EXPECT_EQ(gbuffer("coverage").at<uchar>(kSize / 2, kSize / 2), 0);

    away.material.doubleSided = true;
    useScene(makeScene(away));
    // Seen from behind, lit with the flipped normal: the light at the eye gives full diffuse.
    const cv::Vec4b lit = at(shade(ShadingModel::Lambert), pixelOf(0.0, 0.0, 0.0));
    EXPECT_EQ(lit[3], 255);
    EXPECT_GT(lit[0], srgbCode(0.4));
}

TEST_F(MaterialPasses, SheetsBackToBackOfTwoMaterialsShowEachFromItsOwnSide) {
    // A card printed red on its front and blue on its back, as two sheets on the same corners of two-sided materials:
    // both drew at one depth, stripes of each from either side. The load marks each sheet's back covered
    // (cullBackToBackSheets(), Mesh::backCulled), so each side shows its own colour alone.
    Mesh front = square(1.0f, 0.0f);
    front.name = "front";
    front.material.baseColorFactor = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
    front.material.unlit = true;
    Mesh back = square(1.0f, 0.0f, /*backward=*/true);
    back.name = "back";
    back.material.baseColorFactor = glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
    back.material.unlit = true;
    std::vector<Mesh> sheets{front, back};
    ASSERT_EQ(cullBackToBackSheets(sheets, 1e-6), 4u);
    Scene card = makeScene(std::move(sheets[0]));
    card.meshes.push_back(std::move(sheets[1]));
    for (const bool behind : {false, true}) {
        useScene(card);
        if (behind)
            frame.camera =
                test::lookingAt(scene, glm::dvec3(0.0, 0.0, -kDistance), glm::dvec3(0.0), kFovDegrees, kSize, kSize);
        const cv::Mat color = shade();
        const cv::Vec4b expected = behind ? cv::Vec4b(0, 0, 255, 255) : cv::Vec4b(255, 0, 0, 255);
        int covered = 0;
        int otherColour = 0;
        for (int row = 0; row < color.rows; ++row)
            for (int col = 0; col < color.cols; ++col) {
                const cv::Vec4b pixel = color.at<cv::Vec4b>(row, col);
                if (pixel[3] != 255) continue;
                ++covered;
                otherColour += pixel != expected;
            }
        EXPECT_GT(covered, 1000) << (behind ? "from behind" : "from the front");
        EXPECT_EQ(otherColour, 0) << (behind ? "from behind" : "from the front");
    }
}

TEST_F(MaterialPasses, MToonBandIsLinearstepOfNDotLPlusShift) {
    Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 256, 128);
    sphere.material.baseColorFactor = glm::vec4(0.9f, 0.8f, 0.7f, 1.0f);
    MToonMaterial mtoon;
    mtoon.shadeColorFactor = glm::vec3(0.2f, 0.1f, 0.3f);
    mtoon.shadingToonyFactor = 0.5f;
    mtoon.shadingShiftFactor = -0.2f;
    sphere.material.mtoon = mtoon;
    useScene(makeScene(std::move(sphere)));
    frame.towardLightWorld = glm::normalize(glm::dvec3(1.0, 0.0, 0.3));
    // MToon's global illumination adds ambient x lit colour (the ambient light is uniform: no equalization).
    const glm::dvec3 ambient(0.1, 0.05, 0.02);
    frame.ambientLight = glm::vec3(ambient);
    const cv::Mat color = shade(ShadingModel::MToon);
    const test::AnalyticSphereView view{kSize, 1.0, kDistance, kFovDegrees};
    const glm::dvec3 light = frame.towardLightWorld; // the camera only translates: view = world directions
    int compared = 0;
    double worst = 0.0;
    for (int row = 0; row < kSize; row += 3) {
        for (int col = 0; col < kSize; col += 3) {
            const std::optional<test::SphereHit> hit = view.castPixel(col, row);
            if (!hit || glm::dot(hit->normal, hit->towardEye) < 0.3) continue; // away from the polygonal rim
            const double t = std::clamp((glm::dot(hit->normal, light) - 0.2 - (-0.5)) / (0.5 - (-0.5)), 0.0, 1.0);
            const glm::dvec3 lit(0.9, 0.8, 0.7);
            const glm::dvec3 expected = glm::mix(glm::dvec3(0.2, 0.1, 0.3), lit, t) + ambient * lit;
            const cv::Vec4b actual = color.at<cv::Vec4b>(row, col);
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(linearOf(actual[c]) - expected[c]));
            ++compared;
        }
    }
    EXPECT_GT(compared, 300);
    // The mesh's interpolated normals differ from the sphere's by well under a degree at this tessellation; 8-bit
    // codes add half a step.
    EXPECT_LT(worst, 0.02);
}

TEST_F(MaterialPasses, MToonRimTakesTheLightingAndGiAsFarAsItsMixFactorSays) {
    // Black lit and shade colours leave the rim alone; a lift of 1 makes the rim's shape 1 at every pixel, so the
    // colour is rimColor x mix(1, 1 + gi, rimLightingMixFactor) (VRMC_materials_mtoon-1.0, Rim Lighting).
    const glm::dvec3 rimColor(0.2, 0.3, 0.1);
    const glm::dvec3 gi(0.5, 0.25, 1.0);
    for (const float mixFactor : {0.0f, 0.5f, 1.0f}) {
        Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 64, 32);
        sphere.material.baseColorFactor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
        MToonMaterial mtoon;
        mtoon.parametricRimColorFactor = glm::vec3(rimColor);
        mtoon.parametricRimLiftFactor = 1.0f;
        mtoon.parametricRimFresnelPowerFactor = 3.0f;
        mtoon.rimLightingMixFactor = mixFactor;
        sphere.material.mtoon = mtoon;
        useScene(makeScene(std::move(sphere)));
        frame.ambientLight = glm::vec3(gi);
        const cv::Mat color = shade(ShadingModel::MToon);
        const glm::dvec3 expected = rimColor * glm::mix(glm::dvec3(1.0), glm::dvec3(1.0) + gi, double(mixFactor));
        const cv::Vec4b centre = at(color, cv::Point(kSize / 2, kSize / 2));
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(linearOf(centre[c]), expected[c], 0.01) << "channel " << c << ", mix " << mixFactor;
    }
}

TEST_F(MaterialPasses, MToonScreenOutlineIsItsShareOfTheScreenHeight) {
    // A sphere of radius 1 at distance 4: its outline is a ring from the silhouette (focal x tan(asin(1/4)) pixels
    // from the centre) out to outlineWidthFactor x the image height, in the outline colour (lighting mix 0).
    Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 256, 128);
    sphere.material.baseColorFactor = glm::vec4(1.0f);
    MToonMaterial mtoon;
    mtoon.shadeColorFactor = glm::vec3(1.0f);
    mtoon.outlineWidthMode = MToonMaterial::OutlineWidthMode::ScreenCoordinates;
    mtoon.outlineWidthFactor = 0.04f; // 5.12 pixels of 128
    mtoon.outlineColorFactor = glm::vec3(0.0f, 0.0f, 1.0f);
    mtoon.outlineLightingMixFactor = 0.0f;
    sphere.material.mtoon = mtoon;
    useScene(makeScene(std::move(sphere)));
    const cv::Mat color = shade(ShadingModel::MToon);
    const double focal = (kSize / 2.0) / std::tan(glm::radians(kFovDegrees) / 2.0);
    const double silhouette = focal * std::tan(std::asin(1.0 / kDistance));
    const double width = 0.04 * kSize;
    int inRing = 0, outside = 0, samples = 0;
    for (int step = 0; step < 64; ++step) {
        const double angle = step * 2.0 * 3.14159265358979 / 64.0;
        auto pixelAtRadius = [&](double radius) {
            return cv::Point(int(std::floor(kSize / 2.0 + radius * std::cos(angle))),
                             int(std::floor(kSize / 2.0 - radius * std::sin(angle))));
        };
        ++samples;
        const cv::Vec4b ring = at(color, pixelAtRadius(silhouette + width / 2.0));
        if (ring == cv::Vec4b(0, 0, 255, 255)) ++inRing;
        if (at(color, pixelAtRadius(silhouette + width + 1.5))[3] == 0) ++outside;
    }
    EXPECT_EQ(inRing, samples) << "the outline colour halfway across the ring";
    EXPECT_EQ(outside, samples) << "nothing beyond the ring's width";
    // The surface itself is not covered by its outline: the centre is the lit white.
    expectColor(at(color, cv::Point(kSize / 2, kSize / 2)), {255, 255, 255}, 255, 1, "centre");
}

/** A row of `texels` (RGBA) as an image one texel high. */
cv::Mat texelRow(const std::vector<cv::Vec4b>& texels) {
    cv::Mat row(1, int(texels.size()), CV_8UC4);
    for (std::size_t i = 0; i < texels.size(); ++i) row.at<cv::Vec4b>(0, int(i)) = texels[i];
    return row;
}

/** The pixel that sees the point of square(1, 0) at texture coordinates (u, v). */
cv::Point pixelOfUv(double u, double v) {
    const double focal = (kSize / 2.0) / std::tan(glm::radians(kFovDegrees) / 2.0);
    const double scale = focal / kDistance;
    return {int(std::floor(kSize / 2.0 + (2.0 * u - 1.0) * scale)),
            int(std::floor(kSize / 2.0 - (1.0 - 2.0 * v) * scale))};
}

void expectLinear(const cv::Vec4b& actual, glm::dvec3 expected, double tolerance, const std::string& where) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(linearOf(actual[c]), expected[c], tolerance)
            << where << " channel " << c << " code " << int(actual[c]);
}

TEST_F(MaterialPasses, MToonShadingShiftTextureAddsItsRedChannelTimesTheScale) {
    // n.l = 0 (light along the square), toony 0.5: the band is linearstep(-0.5, 0.5, shift + R x scale) with R read as
    // linear data (code 128 is 0.502, not sRGB's 0.216); the green and blue channels are not read.
    Mesh mesh = square(1.0f, 0.0f);
    mesh.material.baseColorFactor = glm::vec4(0.9f, 0.8f, 0.7f, 1.0f);
    MToonMaterial mtoon;
    mtoon.shadeColorFactor = glm::vec3(0.1f, 0.2f, 0.3f);
    mtoon.shadingToonyFactor = 0.5f;
    mtoon.shadingShiftFactor = -0.1f;
    mtoon.shadingShiftTexture = nearestTexture(0);
    mtoon.shadingShiftTextureScale = 0.5f;
    mesh.material.mtoon = mtoon;
    Scene built = makeScene(std::move(mesh));
    built.images.push_back(pngImage(texelRow({{128, 255, 255, 255}, {0, 255, 255, 255}}), "shift"));
    useScene(std::move(built));
    frame.ambientLight = glm::vec3(0.0f); // the feature alone, without the global illumination term
    frame.towardLightWorld = glm::dvec3(1.0, 0.0, 0.0);
    const cv::Mat color = shade(ShadingModel::MToon);
    const glm::dvec3 shadeColor(0.1, 0.2, 0.3), lit(0.9, 0.8, 0.7);
    for (const auto& [u, red] : std::vector<std::pair<double, double>>{{0.25, 128.0 / 255.0}, {0.75, 0.0}}) {
        const double shading = std::clamp(-0.1 + red * 0.5 + 0.5, 0.0, 1.0);
        expectLinear(at(color, pixelOfUv(u, 0.5)), glm::mix(shadeColor, lit, shading), 0.006, "u " + std::to_string(u));
    }
}

TEST_F(MaterialPasses, MToonRimMultiplyTextureMultipliesTheMatcapAndTheParametricRim) {
    // Lift 1 makes the parametric rim its colour everywhere (saturate(1 - n.v + 1) = 1); a one-texel matcap adds its
    // sRGB-decoded colour times the factor; the rim multiply texture (sRGB) scales the sum; all on the lit colour.
    Mesh mesh = square(1.0f, 0.0f);
    mesh.material.baseColorFactor = glm::vec4(0.1f, 0.1f, 0.1f, 1.0f);
    MToonMaterial mtoon;
    mtoon.parametricRimColorFactor = glm::vec3(0.25f, 0.0f, 0.0f);
    mtoon.parametricRimLiftFactor = 1.0f;
    mtoon.matcapTexture = nearestTexture(0);
    mtoon.matcapFactor = glm::vec3(1.0f, 0.5f, 1.0f);
    mtoon.rimMultiplyTexture = nearestTexture(1);
    mesh.material.mtoon = mtoon;
    Scene built = makeScene(std::move(mesh));
    built.images.push_back(pngImage(texelRow({{0, 188, 128, 255}}), "matcap"));
    built.images.push_back(pngImage(texelRow({{255, 255, 0, 255}, {128, 0, 255, 255}}), "rim multiply"));
    useScene(std::move(built));
    frame.ambientLight = glm::vec3(0.0f); // the feature alone, without the global illumination term
    const cv::Mat color = shade(ShadingModel::MToon);
    const glm::dvec3 rim =
        glm::dvec3(0.25, 0.0, 0.0) + glm::dvec3(1.0, 0.5, 1.0) * glm::dvec3(0.0, linearOf(188), linearOf(128));
    expectLinear(at(color, pixelOfUv(0.25, 0.5)), glm::dvec3(0.1) + rim * glm::dvec3(1.0, 1.0, 0.0), 0.006, "left");
    expectLinear(at(color, pixelOfUv(0.75, 0.5)), glm::dvec3(0.1) + rim * glm::dvec3(linearOf(128), 0.0, 1.0), 0.006,
                 "right");
}

TEST_F(MaterialPasses, MToonMatcapIsReadAtTheSpecificationsUvWithTheImageTopUp) {
    // A sphere, black but for its matcap: each pixel shows the quadrant of a 2x2 matcap that the specification's uv
    // (x = dot(normalize(v.z, 0, -v.x), n), y = dot(v x that, n), times 0.495, plus 0.5) falls in, with a normal
    // facing up reading the image's top row.
    Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 256, 128);
    sphere.material.baseColorFactor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    MToonMaterial mtoon;
    mtoon.matcapTexture = nearestTexture(0);
    mtoon.matcapFactor = glm::vec3(1.0f, 0.5f, 1.0f);
    sphere.material.mtoon = mtoon;
    cv::Mat matcap(2, 2, CV_8UC4);
    matcap.at<cv::Vec4b>(0, 0) = {255, 0, 0, 255};     // top left: red
    matcap.at<cv::Vec4b>(0, 1) = {0, 255, 0, 255};     // top right: green
    matcap.at<cv::Vec4b>(1, 0) = {0, 0, 255, 255};     // bottom left: blue
    matcap.at<cv::Vec4b>(1, 1) = {255, 255, 255, 255}; // bottom right: white
    Scene built = makeScene(std::move(sphere));
    built.images.push_back(pngImage(matcap, "matcap"));
    useScene(std::move(built));
    frame.ambientLight = glm::vec3(0.0f); // the feature alone, without the global illumination term
    const cv::Mat color = shade(ShadingModel::MToon);
    const test::AnalyticSphereView view{kSize, 1.0, kDistance, kFovDegrees};
    const glm::dvec3 quadrants[2][2] = {{{1, 0, 0}, {0, 1, 0}}, {{0, 0, 1}, {1, 1, 1}}}; // [row from top][column]
    int compared = 0;
    for (int row = 0; row < kSize; row += 2) {
        for (int col = 0; col < kSize; col += 2) {
            const std::optional<test::SphereHit> hit = view.castPixel(col, row);
            if (!hit || glm::dot(hit->normal, hit->towardEye) < 0.2) continue;
            const glm::dvec3 v = hit->towardEye; // the camera only translates: view = world directions
            const glm::dvec3 across = glm::normalize(glm::dvec3(v.z, 0.0, -v.x));
            const glm::dvec3 up = glm::cross(v, across);
            const double x = glm::dot(across, hit->normal), y = glm::dot(up, hit->normal);
            if (std::abs(x) < 0.05 || std::abs(y) < 0.05) continue; // a quadrant's border: the mesh's normal decides
            const glm::dvec3 expected = quadrants[y > 0.0 ? 0 : 1][x > 0.0 ? 1 : 0] * glm::dvec3(1.0, 0.5, 1.0);
            expectLinear(color.at<cv::Vec4b>(row, col), expected, 0.006,
                         "pixel " + std::to_string(col) + ", " + std::to_string(row));
            ++compared;
        }
    }
    EXPECT_GT(compared, 500);
}

TEST_F(MaterialPasses, MToonNormalMapBendsTheNormalInTheSurfacesUvFrame) {
    // A square (u along +x, v down the picture) whose normal map holds a texel bent toward +u on the left and one bent
    // up the image (glTF's +y, against v) on the right; toony 0 makes the band linear, (n.l + 1) / 2 from shade black
    // to lit white, so each half shows the bent normal's n.l for the light (0.6, 0.8, 0). The scale halves x and y.
    for (const float scale : {1.0f, 0.5f}) {
        Mesh mesh = square(1.0f, 0.0f);
        mesh.material.baseColorFactor = glm::vec4(1.0f);
        mesh.material.normalTexture = nearestTexture(0);
        mesh.material.normalScale = scale;
        MToonMaterial mtoon;
        mtoon.shadingToonyFactor = 0.0f;
        mesh.material.mtoon = mtoon;
        Scene built = makeScene(std::move(mesh));
        const cv::Vec4b towardU(204, 128, 230, 255), upTheImage(128, 230, 204, 255);
        built.images.push_back(pngImage(texelRow({towardU, upTheImage}), "normals"));
        useScene(std::move(built));
        frame.ambientLight = glm::vec3(0.0f); // the feature alone, without the global illumination term
        const glm::dvec3 light(0.6, 0.8, 0.0);
        frame.towardLightWorld = light;
        const cv::Mat color = shade(ShadingModel::MToon);
        for (const auto& [u, texel] : std::vector<std::pair<double, cv::Vec4b>>{{0.25, towardU}, {0.75, upTheImage}}) {
            const glm::dvec3 tangentSpace = glm::dvec3(texel[0], texel[1], texel[2]) * (2.0 / 255.0) - 1.0;
            const glm::dvec3 bent =
                glm::normalize(glm::dvec3(tangentSpace.x * scale, tangentSpace.y * scale, tangentSpace.z));
            const double shading = (glm::dot(bent, light) + 1.0) / 2.0;
            expectLinear(at(color, pixelOfUv(u, 0.5)), glm::dvec3(shading), 0.006,
                         "scale " + std::to_string(scale) + " u " + std::to_string(u));
        }
    }
}

TEST_F(MaterialPasses, MToonUvAnimationScrollsAndTurnsTheTexturesAtTheRendersTime) {
    // Lit MToon (n.l = 1): each pixel shows its base colour texel. A 4-texel row scrolled 0.25 in u per second shows,
    // at time 1, the next texel (wrapping); a mask whose blue is 0 on the right half keeps that half still. A 2x2
    // texture turned pi/2 per second is, at time 1, the specification's (u, v) -> (v, 1 - u).
    const std::vector<cv::Vec4b> row = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}, {255, 255, 0, 255}};
    Mesh scrolled = square(1.0f, 0.0f);
    scrolled.material.baseColorFactor = glm::vec4(1.0f);
    scrolled.material.baseColorTexture = nearestTexture(0);
    scrolled.material.baseColorTexture.sampler.wrapS = TextureWrap::Repeat;
    MToonMaterial mtoon;
    mtoon.uvAnimationScrollXSpeedFactor = 0.25f;
    mtoon.uvAnimationMaskTexture = nearestTexture(1);
    scrolled.material.mtoon = mtoon;
    Scene built = makeScene(std::move(scrolled));
    built.images.push_back(pngImage(texelRow(row), "row"));
    built.images.push_back(pngImage(texelRow({{0, 0, 255, 255}, {255, 255, 0, 255}}), "mask"));
    useScene(std::move(built));
    frame.ambientLight = glm::vec3(0.0f); // the feature alone, without the global illumination term
    const auto texelColour = [](const cv::Vec4b& texel) { return cv::Vec3i(texel[0], texel[1], texel[2]); };
    gpuScene->materials().setTime(1.0);
    const cv::Mat moved = shade(ShadingModel::MToon);
    for (int texel = 0; texel < 4; ++texel) {
        const int shown = texel < 2 ? (texel + 1) % 4 : texel; // the left half moves, the masked right half not
        expectColor(at(moved, pixelOfUv((texel + 0.5) / 4.0, 0.5)), texelColour(row[std::size_t(shown)]), 255, 1,
                    "texel " + std::to_string(texel));
    }
    gpuScene->materials().setTime(0.0);
    const cv::Mat still = shade(ShadingModel::MToon);
    for (int texel = 0; texel < 4; ++texel)
        expectColor(at(still, pixelOfUv((texel + 0.5) / 4.0, 0.5)), texelColour(row[std::size_t(texel)]), 255, 1,
                    "time 0, texel " + std::to_string(texel));

    Mesh turned = square(1.0f, 0.0f);
    turned.material.baseColorFactor = glm::vec4(1.0f);
    turned.material.baseColorTexture = nearestTexture(0);
    MToonMaterial turning;
    turning.uvAnimationRotationSpeedFactor = float(glm::half_pi<double>());
    turned.material.mtoon = turning;
    cv::Mat quadrants(2, 2, CV_8UC4);
    quadrants.at<cv::Vec4b>(0, 0) = {255, 0, 0, 255};     // uv (0.25, 0.25)
    quadrants.at<cv::Vec4b>(0, 1) = {0, 255, 0, 255};     // uv (0.75, 0.25)
    quadrants.at<cv::Vec4b>(1, 0) = {0, 0, 255, 255};     // uv (0.25, 0.75)
    quadrants.at<cv::Vec4b>(1, 1) = {255, 255, 255, 255}; // uv (0.75, 0.75)
    Scene turnedScene = makeScene(std::move(turned));
    turnedScene.images.push_back(pngImage(quadrants, "quadrants"));
    useScene(std::move(turnedScene));
    frame.ambientLight = glm::vec3(0.0f);
    gpuScene->materials().setTime(1.0);
    const cv::Mat quarter = shade(ShadingModel::MToon);
    for (const double u : {0.25, 0.75}) {
        for (const double v : {0.25, 0.75}) {
            // (u, v) shows the texel at (v, 1 - u).
            const cv::Vec4b texel = quadrants.at<cv::Vec4b>(1 - int(u * 2.0), int(v * 2.0));
            expectColor(at(quarter, pixelOfUv(u, v)), texelColour(texel), 255, 1,
                        "turned, uv " + std::to_string(u) + ", " + std::to_string(v));
        }
    }
}

TEST_F(MaterialPasses, MToonOutlineWidthTextureScalesTheWidthByItsGreenChannel) {
    // The screen outline of MToonScreenOutlineIsItsShareOfTheScreenHeight with a width texture of green 128 (read as
    // linear data, 0.502) and red 255: the ring is half as wide; red would leave it whole.
    Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 256, 128);
    sphere.material.baseColorFactor = glm::vec4(1.0f);
    MToonMaterial mtoon;
    mtoon.shadeColorFactor = glm::vec3(1.0f);
    mtoon.outlineWidthMode = MToonMaterial::OutlineWidthMode::ScreenCoordinates;
    mtoon.outlineWidthFactor = 0.06f; // 7.68 pixels of 128 at full width
    mtoon.outlineWidthMultiplyTexture = nearestTexture(0);
    mtoon.outlineColorFactor = glm::vec3(0.0f, 0.0f, 1.0f);
    mtoon.outlineLightingMixFactor = 0.0f;
    sphere.material.mtoon = mtoon;
    Scene built = makeScene(std::move(sphere));
    built.images.push_back(pngImage(texelRow({{255, 128, 0, 255}}), "width"));
    useScene(std::move(built));
    const cv::Mat color = shade(ShadingModel::MToon);
    const double focal = (kSize / 2.0) / std::tan(glm::radians(kFovDegrees) / 2.0);
    const double silhouette = focal * std::tan(std::asin(1.0 / kDistance));
    const double width = 0.06 * kSize * 128.0 / 255.0;
    int inRing = 0, outside = 0;
    const int samples = 64;
    for (int step = 0; step < samples; ++step) {
        const double angle = step * 2.0 * 3.14159265358979 / samples;
        auto pixelAtRadius = [&](double radius) {
            return cv::Point(int(std::floor(kSize / 2.0 + radius * std::cos(angle))),
                             int(std::floor(kSize / 2.0 - radius * std::sin(angle))));
        };
        if (at(color, pixelAtRadius(silhouette + width / 2.0)) == cv::Vec4b(0, 0, 255, 255)) ++inRing;
        if (at(color, pixelAtRadius(silhouette + width + 1.5))[3] == 0) ++outside;
    }
    EXPECT_EQ(inRing, samples) << "the outline colour halfway across the narrowed ring";
    EXPECT_EQ(outside, samples) << "nothing beyond the narrowed ring, where the whole width would still draw";
}

TEST_F(MaterialPasses, TexturesAreDecodedOnlyWhenAPassSamplesThem) {
    Mesh mesh = square(1.0f, 0.0f);
    mesh.material.baseColorTexture = nearestTexture(0);
    Scene built = makeScene(std::move(mesh));
    built.images.push_back(pngImage(cv::Mat(4, 4, CV_8UC4, cv::Scalar(10, 20, 30, 255)), "plain"));
    useScene(std::move(built));
    gbuffer("depth"); // opaque: depth needs no colour
    EXPECT_EQ(gpuScene->materials().texturesDecoded(), 0u);
    gbuffer("baseColor");
    EXPECT_EQ(gpuScene->materials().texturesDecoded(), 1u);

    // Beside a cut-out mesh, the depth needs the cut-out's texture and still not the opaque mesh's.
    Mesh opaque = square(1.0f, 0.0f);
    opaque.material.baseColorTexture = nearestTexture(0);
    Mesh cutOut = square(0.5f, 0.5f);
    cutOut.material.baseColorTexture = nearestTexture(1);
    cutOut.material.alphaMode = AlphaMode::Mask;
    Scene mixed = makeScene(std::move(opaque));
    mixed.meshes.push_back(std::move(cutOut));
    mixed.images.push_back(pngImage(cv::Mat(4, 4, CV_8UC4, cv::Scalar(10, 20, 30, 255)), "opaque"));
    mixed.images.push_back(pngImage(cv::Mat(4, 4, CV_8UC4, cv::Scalar(10, 20, 30, 255)), "cut-out"));
    useScene(std::move(mixed));
    gbuffer("depth");
    EXPECT_EQ(gpuScene->materials().texturesDecoded(), 1u) << "only the cut-out's";
}

TEST_F(MaterialPasses, TextureBeyondTheMemoryLimitIsRefusedNamingTheImage) {
    Mesh mesh = square(1.0f, 0.0f);
    mesh.material.baseColorTexture = nearestTexture(0);
    Scene built = makeScene(std::move(mesh));
    built.images.push_back(pngImage(cv::Mat(64, 64, CV_8UC4, cv::Scalar(10, 20, 30, 255)), "big one"));
    useScene(std::move(built));
    gpuScene->materials().setTextureMemoryLimit(decodedImageBytes(64, 64) - 1);
    try {
        shade();
        FAIL() << "no error";
    } catch (const std::exception& error) { // the executor names the pass around the SceneError
        EXPECT_NE(std::string(error.what()).find("image 0 'big one'"), std::string::npos) << error.what();
        EXPECT_NE(std::string(error.what()).find("--memory-limit"), std::string::npos) << error.what();
    }
}

} // namespace
} // namespace inkgraph
