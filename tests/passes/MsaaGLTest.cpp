// Multisampled graph textures (TextureDesc::samples): GL's resolve on read-back and the texture pool's key. Needs a
// GL context (llvmpipe in CI).
#include "gl/GlObjects.h"
#include "gl/Readback.h"
#include "gl/TexturePool.h"
#include "tests/support/GlTestContext.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

namespace inkgraph {
namespace {

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
