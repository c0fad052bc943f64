// MToon's outlines as a layer of their own (passes/mtoon/MToonOutlinePass.h) against closed forms: a sphere of radius
// 1 at distance 4 with a world-width outline w is a shell of radius 1 + w, whose silhouette is a circle of focal x
// tan(asin((1 + w) / 4)) pixels; the layer holds the shell's back faces (its far side at the centre), and the shade
// pass lays in only the ring outside the sphere. Needs a GL context (llvmpipe in CI).
#include "graph/GraphCompiler.h"
#include "passes/mtoon/MToonOutlinePass.h"
#include "passes/shade/ShadePass.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/PassHarness.h"
#include "tests/support/TestCamera.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include <cmath>
#include <string>

namespace inkgraph::mtoon_outline_gl_test {
namespace {

constexpr int kSize = 128;
constexpr double kDistance = 4.0;
constexpr double kFovDegrees = 35.0;
constexpr double kPi = 3.14159265358979323846;

class MToonOutline : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override { test::sharedGlContext(); }

    /** A unit sphere at the origin, white, whose MToon outline is `width` model units, pure red, unlit. */
    void useSphere(float width) {
        Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 256, 128);
        sphere.material.baseColorFactor = glm::vec4(1.0f);
        MToonMaterial mtoon;
        mtoon.shadeColorFactor = glm::vec3(1.0f);
        mtoon.outlineWidthMode = MToonMaterial::OutlineWidthMode::WorldCoordinates;
        mtoon.outlineWidthFactor = width;
        mtoon.outlineColorFactor = glm::vec3(1.0f, 0.0f, 0.0f);
        mtoon.outlineLightingMixFactor = 0.0f;
        sphere.material.mtoon = mtoon;
        scene = makeScene(std::move(sphere));
        frame.camera =
            test::lookingAt(scene, glm::dvec3(0.0, 0.0, kDistance), glm::dvec3(0.0), kFovDegrees, kSize, kSize);
        frame.worldOrigin = glm::dvec3(0.0);
        frame.towardLightWorld = glm::dvec3(0.0, 0.0, 1.0);
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    }

    /** Runs the layer and the mtoon shade pass that lays it in, with `msaa` samples per pixel (the layer's own);
     *  keeps shade.color and the layer (resolved). */
    void run(MToonOutlinePass& outline, int msaa = 1) {
        ShadeSettings settings;
        settings.model = ShadingModel::MToon;
        settings.materialOutlines = std::string(outline.name());
        settings.msaa = msaa;
        ShadePass shade("shade", shaders, *gpuScene, frame, settings, std::nullopt);
        const Plan plan = compile({&outline, &shade}, {"shade.color", "mtoon-outline.color", "mtoon-outline.depth"});
        executor.run(plan, {&outline, &shade}, {kSize, kSize, false});
        color = executor.store().image("shade.color").clone();
        layer = executor.store().image("mtoon-outline.color").clone();
        depth = executor.store().image("mtoon-outline.depth").clone();
        executor.store().clear();
    }

    double focal() const { return (kSize / 2.0) / std::tan(glm::radians(kFovDegrees) / 2.0); }
    /** Pixels from the image centre to the silhouette of a sphere of `radius` at the origin. */
    double silhouetteOf(double radius) const { return focal() * std::tan(std::asin(radius / kDistance)); }
    /** Window depth (reversed-Z) of a point `distance` in front of the eye. */
    double windowDepthAt(double distance) const {
        const glm::dvec4 clip = glm::dmat4(frame.clipFromView()) * glm::dvec4(0.0, 0.0, -distance, 1.0);
        return clip.z / clip.w;
    }
    /** The pixel `radius` pixels from the centre in direction `angle` (counter-clockwise from +x, y up). */
    static cv::Point pixelAt(double radius, double angle) {
        return cv::Point(int(std::floor(kSize / 2.0 + radius * std::cos(angle))),
                         int(std::floor(kSize / 2.0 - radius * std::sin(angle))));
    }
    /** The outermost radius (in steps of 1/8 pixel) along `angle` at which `image`'s alpha is not 0. */
    static double outerRadius(const cv::Mat& image, double angle) {
        double found = 0.0;
        for (double radius = 0.0; radius < kSize / 2.0 - 1.0; radius += 0.125)
            if (image.at<cv::Vec4b>(pixelAt(radius, angle))[3] != 0) found = radius;
        return found;
    }

    cv::Mat color, layer, depth;
};

TEST_F(MToonOutline, WorldWidthShellIsTheClosedFormCircleWithinAPixel) {
    constexpr double kWidth = 0.15;
    useSphere(float(kWidth));
    MToonOutlinePass outline(kMToonOutlinePass, shaders, *gpuScene, frame);
    run(outline);
    const double inner = silhouetteOf(1.0);
    const double outer = silhouetteOf(1.0 + kWidth);
    ASSERT_GT(outer - inner, 4.0); // a ring wide enough to sample its middle
    int checked = 0;
    for (int step = 0; step < 64; ++step) {
        const double angle = step * 2.0 * kPi / 64.0;
        // The layer: the shell's disc, out to its silhouette.
        EXPECT_NEAR(outerRadius(layer, angle), outer, 1.0) << "angle " << angle;
        // The shading: the outline colour halfway across the ring, nothing beyond it.
        EXPECT_EQ(color.at<cv::Vec4b>(pixelAt((inner + outer) / 2.0, angle)), cv::Vec4b(255, 0, 0, 255));
        EXPECT_NEAR(outerRadius(color, angle), outer, 1.0) << "angle " << angle;
        ++checked;
    }
    EXPECT_EQ(checked, 64);
    // Inside the sphere the surface wins (white, lit from the eye).
    const cv::Point centre(kSize / 2, kSize / 2);
    for (int c = 0; c < 4; ++c) EXPECT_GE(color.at<cv::Vec4b>(centre)[c], 254) << "channel " << c;
    // In the ring the layer holds the shell's far side (its back faces): the ray's second hit of radius 1 + w.
    const cv::Point inRing = pixelAt((inner + outer) / 2.0, 0.0);
    EXPECT_EQ(layer.at<cv::Vec4b>(inRing), cv::Vec4b(255, 0, 0, 255));
    const double tanHalf = std::tan(glm::radians(kFovDegrees) / 2.0);
    const glm::dvec3 ray = glm::normalize(glm::dvec3((2.0 * (inRing.x + 0.5) / kSize - 1.0) * tanHalf,
                                                     (1.0 - 2.0 * (inRing.y + 0.5) / kSize) * tanHalf, -1.0));
    const double b = glm::dot(ray, glm::dvec3(0.0, 0.0, -kDistance));
    const double farHit = b + std::sqrt(b * b - (kDistance * kDistance - (1.0 + kWidth) * (1.0 + kWidth)));
    const double farDepth = -(ray * farHit).z;
    const float ringDepth = depth.at<float>(inRing);
    // The tessellated shell lies within 0.01 of the round one along the ray here; reversed-Z: nearer is greater.
    EXPECT_LT(ringDepth, windowDepthAt(farDepth - 0.01));
    EXPECT_GT(ringDepth, windowDepthAt(farDepth + 0.01));
    // Off the shell: cleared, transparent and at the far plane.
    EXPECT_EQ(layer.at<cv::Vec4b>(0, 0), cv::Vec4b(0, 0, 0, 0));
    EXPECT_EQ(depth.at<float>(0, 0), 0.0f);

    nlohmann::ordered_json report;
    outline.describe(report);
    EXPECT_EQ(report["shells"], 1);
    EXPECT_EQ(report["triangles"], scene.triangleCount());
}

TEST_F(MToonOutline, TheShellOfAMeshTheEyeIsInsideIsNotDrawn) {
    // The eye at the centre of one sphere (a camera in a character's head), looking at a second one: every back face
    // of the first's shell faces the eye and would fill the layer; only the second's shell is drawn, its ring as
    // from outside.
    useSphere(0.15f);
    Mesh around = scene.meshes.front();
    scene.meshes.push_back(std::move(around));
    for (glm::vec3& position : scene.meshes.back().positions) position.z += float(kDistance);
    frame.camera = test::lookingAt(scene, glm::dvec3(0.0, 0.0, kDistance), glm::dvec3(0.0), kFovDegrees, kSize, kSize);
    gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    MToonOutlinePass outline(kMToonOutlinePass, shaders, *gpuScene, frame);
    run(outline);
    nlohmann::ordered_json report;
    outline.describe(report);
    EXPECT_EQ(report["shells"], 1);
    EXPECT_EQ(report["shells_skipped_eye_inside"], 1);
    // The far sphere's shell is the closed-form ring, and the corners, off both shells, stay clear.
    const double outer = silhouetteOf(1.0 + 0.15);
    for (int step = 0; step < 16; ++step) {
        const double angle = step * 2.0 * kPi / 16.0;
        EXPECT_NEAR(outerRadius(layer, angle), outer, 1.0) << "angle " << angle;
    }
    EXPECT_EQ(layer.at<cv::Vec4b>(0, 0), cv::Vec4b(0, 0, 0, 0));
    EXPECT_EQ(layer.at<cv::Vec4b>(kSize - 1, kSize - 1), cv::Vec4b(0, 0, 0, 0));
}

TEST_F(MToonOutline, WithFourSamplesTheShellsEdgesAreAntiAliasedOnBothSides) {
    // The ring's outer edge meets nothing: a share of red over transparent (premultiplied). Its inner edge meets the
    // white sphere: the layer laid in sample by sample gives a pixel of red and white samples, pink, at full alpha.
    // With one sample neither exists.
    useSphere(0.15f);
    const auto edges = [](const cv::Mat& image, int& outer, int& inner) {
        outer = inner = 0;
        for (int y = 0; y < image.rows; ++y)
            for (int x = 0; x < image.cols; ++x) {
                const cv::Vec4b pixel = image.at<cv::Vec4b>(y, x); // RGBA
                if (pixel[3] > 0 && pixel[3] < 255) {
                    ++outer;
                    EXPECT_NEAR(pixel[0], pixel[3], 1) << "(" << x << ", " << y << ")"; // premultiplied red
                    EXPECT_EQ(pixel[1], 0) << "(" << x << ", " << y << ")";
                    EXPECT_EQ(pixel[2], 0) << "(" << x << ", " << y << ")";
                }
                if (pixel[3] == 255 && pixel[0] == 255 && pixel[1] > 2 && pixel[1] < 252) ++inner;
            }
    };
    int outer = 0;
    int inner = 0;
    MToonOutlinePass single(kMToonOutlinePass, shaders, *gpuScene, frame);
    run(single);
    edges(color, outer, inner);
    EXPECT_EQ(outer, 0);
    EXPECT_EQ(inner, 0);
    // The ring's edges, circles of radius 52 and 61 px, cross about 330 and 380 pixels; most have 1 to 3 of their 4
    // samples on each side.
    MToonOutlinePass multi(kMToonOutlinePass, shaders, *gpuScene, frame, 4);
    run(multi, 4);
    edges(color, outer, inner);
    EXPECT_GT(outer, 200);
    EXPECT_GT(inner, 200);
    // The layer read back is resolved: its own silhouette is anti-aliased too, and its middle is the outline colour.
    int layerEdge = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            if (const int alpha = layer.at<cv::Vec4b>(y, x)[3]; alpha > 0 && alpha < 255) ++layerEdge;
    EXPECT_GT(layerEdge, 200);
    EXPECT_EQ(layer.at<cv::Vec4b>(pixelAt((silhouetteOf(1.0) + silhouetteOf(1.15)) / 2.0, 0.0)),
              cv::Vec4b(255, 0, 0, 255));
}

TEST_F(MToonOutline, ALayerOfOtherSamplesThanTheShadingIsRefused) {
    useSphere(0.15f);
    MToonOutlinePass outline(kMToonOutlinePass, shaders, *gpuScene, frame, 4);
    try {
        run(outline, 2);
        FAIL() << "a 4-sample layer laid into 2-sample shading was accepted";
    } catch (const std::exception& error) {
        EXPECT_NE(std::string(error.what()).find("'mtoon-outline.color' has 4 samples per pixel, the shading 2"),
                  std::string::npos)
            << error.what();
    }
    executor.store().clear();
}

TEST_F(MToonOutline, ANearerSurfaceHidesTheOutlineBehindIt) {
    // A second, outline-free sphere in front of the first's rim: where it covers the ring, it wins, as a shell fragment
    // behind it would have lost the depth test.
    useSphere(0.15f);
    // Its centre projects to the middle of the ring, two units from the eye.
    const double ring = (silhouetteOf(1.0) + silhouetteOf(1.15)) / 2.0;
    const glm::dvec3 blockerView(ring * 2.0 / focal(), 0.0, -2.0);
    Mesh blocker = makeUvSphere({float(blockerView.x), 0.0f, float(kDistance + blockerView.z)}, 0.2f, 64, 32);
    blocker.material.baseColorFactor = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
    blocker.material.unlit = true; // pure green: lit, a dielectric's white specular would add some red
    scene.meshes.push_back(std::move(blocker));
    // Near and far fitted again: the blocker is nearer than the first sphere's near plane.
    frame.camera = test::lookingAt(scene, glm::dvec3(0.0, 0.0, kDistance), glm::dvec3(0.0), kFovDegrees, kSize, kSize);
    gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    MToonOutlinePass outline(kMToonOutlinePass, shaders, *gpuScene, frame);
    run(outline);
    const cv::Point onBlocker(int(kSize / 2.0 + ring), kSize / 2);
    ASSERT_EQ(layer.at<cv::Vec4b>(onBlocker), cv::Vec4b(255, 0, 0, 255)) << "the layer has the shell there";
    const cv::Vec4b seen = color.at<cv::Vec4b>(onBlocker);
    EXPECT_EQ(seen[0], 0) << "no outline red over the nearer surface";
    EXPECT_GT(seen[1], 0);
    nlohmann::ordered_json report;
    outline.describe(report);
    EXPECT_EQ(report["shells"], 1) << "the blocker's material asks for no outline";
}

} // namespace
} // namespace inkgraph::mtoon_outline_gl_test
