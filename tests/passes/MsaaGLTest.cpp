// Multisampled shading (ShadeSettings::msaa, --msaa): a lit sphere drawn with 1 and 4 samples per pixel. With 4 the
// silhouette's pixels take a share of the surface between nothing and all of it (premultiplied: the colour scaled
// with the alpha), with 1 every pixel is all or nothing; off the edge both agree, since the fragment shader runs at
// the pixel's centre either way. Also multisampled graph textures themselves: GL's resolve on read-back and the
// texture pool's key. Needs a GL context (llvmpipe in CI).
#include "gl/GlObjects.h"
#include "gl/Readback.h"
#include "graph/GraphCompiler.h"
#include "passes/shade/ShadePass.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/PassHarness.h"
#include "tests/support/TestCamera.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <cmath>
#include <cstdlib>
#include <string>

namespace inkgraph {
namespace {

constexpr int kSize = 96;

class MsaaShading : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override { test::sharedGlContext(); }

    /** A unit sphere of base colour `color`, blending or opaque, seen from (0, 0, 4) and lit from the eye. */
    void useSphere(const glm::vec4& color, AlphaMode alphaMode) {
        Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 64, 32);
        sphere.material.baseColorFactor = color;
        sphere.material.alphaMode = alphaMode;
        scene = makeScene(std::move(sphere));
        frame.camera = test::lookingAt(scene, glm::dvec3(0.0, 0.0, 4.0), glm::dvec3(0.0), 35.0, kSize, kSize);
        frame.worldOrigin = glm::dvec3(0.0);
        frame.towardLightWorld = glm::dvec3(0.3, 0.4, 1.0);
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    }

    /** shade.color of a lambert pass with `msaa` samples per pixel. */
    cv::Mat shade(int msaa) {
        ShadeSettings settings;
        settings.model = ShadingModel::Lambert;
        settings.msaa = msaa;
        ShadePass pass("shade", shaders, *gpuScene, frame, settings, std::nullopt);
        const Plan plan = compile({&pass}, {"shade.color"});
        executor.run(plan, {&pass}, {kSize, kSize, false});
        cv::Mat color = executor.store().image("shade.color").clone();
        executor.store().clear();
        return color;
    }

    /** Pixels whose alpha lies strictly between 0 and `full`. */
    static int partlyCovered(const cv::Mat& color, int full) {
        int count = 0;
        for (int y = 0; y < color.rows; ++y)
            for (int x = 0; x < color.cols; ++x) {
                const int alpha = color.at<cv::Vec4b>(y, x)[3];
                if (alpha > 0 && alpha < full) ++count;
            }
        return count;
    }
};

TEST_F(MsaaShading, FourSamplesGiveTheSilhouetteIntermediateCoverageAndOneSampleNone) {
    useSphere(glm::vec4(0.8f, 0.6f, 0.4f, 1.0f), AlphaMode::Opaque);
    const cv::Mat single = shade(1);
    const cv::Mat multi = shade(4);
    EXPECT_EQ(partlyCovered(single, 255), 0);
    // The silhouette, a circle of radius 39 px (focal 152 px x tan(asin(1/4))), crosses about 250 pixels; most take 1
    // to 3 of their 4 samples.
    EXPECT_GT(partlyCovered(multi, 255), 150);
    int edge = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const cv::Vec4b pixel = multi.at<cv::Vec4b>(y, x);
            if (pixel[3] == 0 || pixel[3] == 255) continue;
            ++edge;
            // A share of the samples: 64, 128 or 191 of 255 with 4 samples, however GL rounds the average.
            const double quarters = pixel[3] / 63.75;
            EXPECT_NEAR(quarters, std::round(quarters), 1.0 / 63.75)
                << "(" << x << ", " << y << ") alpha " << int(pixel[3]);
            // Premultiplied: no channel exceeds the coverage (the surface's colours are below 1).
            for (int c = 0; c < 3; ++c) EXPECT_LE(pixel[c], pixel[3]) << "(" << x << ", " << y << ") channel " << c;
        }
    EXPECT_GT(edge, 0);
}

TEST_F(MsaaShading, InsideTheSurfaceFourSamplesShadeAsOne) {
    useSphere(glm::vec4(0.8f, 0.6f, 0.4f, 1.0f), AlphaMode::Opaque);
    const cv::Mat single = shade(1);
    const cv::Mat multi = shade(4);
    int inside = 0;
    for (int y = 1; y + 1 < kSize; ++y)
        for (int x = 1; x + 1 < kSize; ++x) {
            // Inside: the pixel and its neighbours fully covered in both, so no sample of it is off the surface.
            bool covered = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    covered = covered && single.at<cv::Vec4b>(y + dy, x + dx)[3] == 255 &&
                              multi.at<cv::Vec4b>(y + dy, x + dx)[3] == 255;
            if (!covered) continue;
            ++inside;
            // Where two triangles share a pixel, each shades it at the pixel's centre: up to a code apart.
            for (int c = 0; c < 4; ++c)
                EXPECT_NEAR(multi.at<cv::Vec4b>(y, x)[c], single.at<cv::Vec4b>(y, x)[c], 1)
                    << "(" << x << ", " << y << ") channel " << c;
        }
    EXPECT_GT(inside, 4000); // the disc of radius 39 px (4800 pixels), less its rim
    // Off the surface both are transparent black.
    EXPECT_EQ(multi.at<cv::Vec4b>(0, 0), cv::Vec4b(0, 0, 0, 0));
    EXPECT_EQ(single.at<cv::Vec4b>(0, 0), cv::Vec4b(0, 0, 0, 0));
}

TEST_F(MsaaShading, ABlendedSurfaceStaysPremultipliedAtItsEdge) {
    // Alpha 0.5, both sides drawn (the sphere is double-sided): inside, the far and near side over nothing leave
    // 1 - 0.5^2 = 0.75; every covered pixel has at least one side's 0.5 with one sample, and an edge pixel a share
    // of it with four, its colour scaled alike.
    useSphere(glm::vec4(0.8f, 0.6f, 0.4f, 0.5f), AlphaMode::Blend);
    const cv::Mat single = shade(1);
    const cv::Mat multi = shade(4);
    const cv::Vec4b centre = multi.at<cv::Vec4b>(kSize / 2, kSize / 2);
    EXPECT_NEAR(centre[3], 0.75 * 255, 1);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(centre[c], single.at<cv::Vec4b>(kSize / 2, kSize / 2)[c], 1);
    EXPECT_EQ(partlyCovered(single, 127), 0);
    int edge = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const cv::Vec4b pixel = multi.at<cv::Vec4b>(y, x);
            if (pixel[3] == 0 || pixel[3] >= 127) continue;
            ++edge;
            for (int c = 0; c < 3; ++c) EXPECT_LE(pixel[c], pixel[3]) << "(" << x << ", " << y << ") channel " << c;
        }
    EXPECT_GT(edge, 60);
}

TEST(MsaaTexture, ReadBackResolvesColourAndDepthAndUploadIsRefused) {
    test::sharedGlContext();
    if (maxSamples() < 4) GTEST_SKIP() << "the driver draws fewer than 4 samples";
    // The averaging itself is the shading tests' (shares of 4 at the silhouette); here every sample holds one value,
    // which the read-back must give whatever the driver's resolve, for colour and for depth.
    GlTexture color(Format::RGBA8, 3, 2, "msaa colour", 4);
    GlTexture depth(Format::Depth32F, 3, 2, "msaa depth", 4);
    ASSERT_EQ(color.samples(), 4);
    GLint samples = 0;
    glGetTextureLevelParameteriv(color.id(), 0, GL_TEXTURE_SAMPLES, &samples);
    EXPECT_GE(samples, 4);
    GlFramebuffer framebuffer("msaa test");
    framebuffer.attachColor(0, color);
    framebuffer.attachDepth(depth);
    framebuffer.finish({0});
    framebuffer.bind();
    const float value[4] = {1.0f, 0.5f, 0.25f, 1.0f};
    glClearBufferfv(GL_COLOR, 0, value);
    const float far = 0.375f;
    glClearBufferfv(GL_DEPTH, 0, &far);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    const cv::Mat colorImage = readTexture(color);
    const cv::Mat depthImage = readTexture(depth);
    ASSERT_EQ(colorImage.type(), CV_8UC4);
    ASSERT_EQ(depthImage.type(), CV_32FC1);
    ASSERT_EQ(colorImage.size(), cv::Size(3, 2));
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
            EXPECT_EQ(colorImage.at<cv::Vec4b>(y, x), cv::Vec4b(255, 128, 64, 255));
            EXPECT_EQ(depthImage.at<float>(y, x), far);
        }
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    cv::Mat upload(2, 3, CV_8UC4, cv::Scalar::all(0));
    EXPECT_THROW(uploadImage(color, upload), std::invalid_argument);
}

TEST(MsaaTexture, ThePoolKeysOnTheSampleCount) {
    test::sharedGlContext();
    if (maxSamples() < 4) GTEST_SKIP() << "the driver draws fewer than 4 samples";
    TexturePool pool;
    GlTexture multi = pool.acquire(Format::RGBA8, 8, 8, "a", 4);
    pool.release(std::move(multi));
    GlTexture single = pool.acquire(Format::RGBA8, 8, 8, "b"); // one sample: not the released one
    EXPECT_EQ(single.samples(), 1);
    GlTexture again = pool.acquire(Format::RGBA8, 8, 8, "c", 4); // four: reused
    EXPECT_EQ(again.samples(), 4);
    EXPECT_EQ(pool.createdCount(), 2u);
    EXPECT_EQ(pool.reusedCount(), 1u);
}

} // namespace
} // namespace inkgraph
