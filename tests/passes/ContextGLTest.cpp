// The GL layer on a real headless context: both EGL platforms, the one flip point, the texture pool, shader errors.
#include "gl/GlObjects.h"
#include "gl/HeadlessContext.h"
#include "gl/Readback.h"
#include "gl/ShaderLibrary.h"
#include "gl/TexturePool.h"
#include "tests/support/GlTestContext.h"

#include <gtest/gtest.h>

#include <epoxy/egl.h>

#include <filesystem>
#include <fstream>
#include <future>
#include <string>
#include <thread>

namespace inkgraph {
namespace {

TEST(HeadlessContext, DevicePlatformGivesCore45) {
    test::releaseSharedGlContext();
    HeadlessContext context({EglPlatform::Device, false});
    EXPECT_EQ(context.platform(), "device");
    GLint major = 0, minor = 0, profile = 0, flags = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    EXPECT_GE(major * 10 + minor, 45);
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
    EXPECT_FALSE(flags & GL_CONTEXT_FLAG_FORWARD_COMPATIBLE_BIT) << "wide lines need a non-forward-compatible context";
}

TEST(HeadlessContext, SurfacelessPlatformGivesCore45) {
    test::releaseSharedGlContext();
    HeadlessContext context({EglPlatform::Surfaceless, false});
    EXPECT_EQ(context.platform(), "surfaceless");
    EXPECT_GE(epoxy_gl_version(), 45);
    EXPECT_NE(context.describe().find("surfaceless"), std::string::npos);
}

/** A fresh 4 x 4 float texture cleared to `value` and read back on this thread's context: one of its texels. */
float clearedAndReadBack(float value) {
    GlTexture texture(Format::R32F, 4, 4, "thread test");
    glClearTexImage(texture.id(), 0, GL_RED, GL_FLOAT, &value);
    return readTexture(texture, ReadbackFlip::Cpu).at<float>(2, 1);
}

TEST(HeadlessContext, SeveralLiveAtOnceEachOnItsThreadAndTheLastOneEndsTheDisplay) {
    // A batch's drawing threads (--draw-threads) each hold a context on the one display EGL gives the process: the
    // first context to go must leave the display to the others (eglTerminate() would end it for all of them).
    test::releaseSharedGlContext();
    std::promise<void> firstMade, secondMade, firstGone;
    std::string secondFailure;
    float secondBefore = 0.0f, secondAfter = 0.0f;
    std::thread second([&] {
        try {
            firstMade.get_future().wait();
            HeadlessContext context;
            secondBefore = clearedAndReadBack(2.0f);
            secondMade.set_value();
            firstGone.get_future().wait(); // the first context is destroyed meanwhile, on its own thread
            context.releaseThread();
            context.makeCurrent(); // eglMakeCurrent() fails on a terminated display
            EXPECT_NE(eglQueryString(eglGetCurrentDisplay(), EGL_VERSION), nullptr);
            secondAfter = clearedAndReadBack(3.0f);
        } catch (const std::exception& error) {
            secondFailure = error.what();
        }
    });
    {
        HeadlessContext context;
        EXPECT_EQ(clearedAndReadBack(1.0f), 1.0f);
        firstMade.set_value();
        secondMade.get_future().wait();
        EXPECT_EQ(clearedAndReadBack(4.0f), 4.0f); // both current at once, each on its own thread
    }
    firstGone.set_value();
    second.join();
    EXPECT_EQ(secondFailure, "");
    EXPECT_EQ(secondBefore, 2.0f);
    EXPECT_EQ(secondAfter, 3.0f) << "the first context's end must not end the display the second one still uses";
    HeadlessContext again; // the last one ended the display; a new context starts it again
    EXPECT_EQ(clearedAndReadBack(5.0f), 5.0f);
}

TEST(Readback, RowZeroIsTheTopOfTheImage) {
    test::sharedGlContext();
    cv::Mat image(3, 2, CV_32FC1);
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 2; ++col) image.at<float>(row, col) = float(10 * row + col);
    GlTexture texture(Format::R32F, 2, 3, "readback test");
    uploadImage(texture, image);
    // GL stores the bottom row first: our top row (row 0) must be GL's last row.
    float raw[6] = {};
    glGetTextureImage(texture.id(), 0, GL_RED, GL_FLOAT, sizeof raw, raw);
    EXPECT_EQ(raw[0], 20.0f);
    EXPECT_EQ(raw[4], 0.0f);
    // The driver's flip (GL_MESA_pack_invert, here on Mesa) and the CPU's give the same image; 3 rows, so the middle
    // row of the in-place swap stays put.
    for (const ReadbackFlip flip : {ReadbackFlip::Fastest, ReadbackFlip::Cpu}) {
        const cv::Mat back = readTexture(texture, flip);
        EXPECT_EQ(cv::norm(back, image, cv::NORM_INF), 0.0);
    }
    EXPECT_THROW(uploadImage(texture, cv::Mat(2, 2, CV_32FC1)), std::invalid_argument);
}

TEST(Readback, ARegionReadsItsPixelsIntoTheirPlaces) {
    test::sharedGlContext();
    // 7 x 5 texels, value 10 row + column (row 0 at the top); GL window rows count from the bottom.
    cv::Mat image(5, 7, CV_32FC1);
    for (int row = 0; row < image.rows; ++row)
        for (int col = 0; col < image.cols; ++col) image.at<float>(row, col) = float(10 * row + col);
    GlTexture texture(Format::R32F, image.cols, image.rows, "region test");
    uploadImage(texture, image);
    // Window x 2..5, y 1..3: image columns 2..5, rows 5 - 1 - 3 = 1 .. 3.
    const PixelRect region{2, 1, 4, 3};
    const cv::Rect inImage(2, 1, 4, 3);
    for (const ReadbackFlip flip : {ReadbackFlip::Fastest, ReadbackFlip::Cpu}) {
        const cv::Mat back = readTexture(texture, flip, region);
        ASSERT_EQ(back.size(), image.size());
        EXPECT_EQ(cv::norm(back(inImage), image(inImage), cv::NORM_INF), 0.0) << int(flip);
        // (Outside the region the result holds whatever its memory held.) A whole read after it is whole again.
        const cv::Mat whole = readTexture(texture, flip);
        EXPECT_EQ(cv::norm(whole, image, cv::NORM_INF), 0.0) << "the row length is GL's default again";
    }
    EXPECT_EQ(readTexture(texture, ReadbackFlip::Fastest, PixelRect{3, 2, 0, 0}).size(), image.size())
        << "an empty region reads nothing";
    // A region outside is refused by both reads, each naming itself, the region and the texture.
    for (const PixelRect outside : {PixelRect{5, 0, 3, 1}, PixelRect{0, 4, 1, 2}, PixelRect{-1, 0, 1, 1}}) {
        for (const bool pending : {false, true}) {
            try {
                if (pending)
                    PendingReadback(texture, GlBuffer(readbackBytesOf(texture), GL_MAP_READ_BIT, "region buffer"),
                                    outside);
                else
                    readTexture(texture, ReadbackFlip::Fastest, outside);
                ADD_FAILURE() << "no refusal of (" << outside.x << ", " << outside.y << ")";
            } catch (const std::invalid_argument& error) {
                const std::string message = error.what();
                EXPECT_EQ(message.rfind(pending ? "PendingReadback(): the region (" : "readTexture(): the region (", 0),
                          0u)
                    << message;
                EXPECT_NE(message.find("'region test'"), std::string::npos) << message;
            }
        }
    }
    GLint rowLength = -1;
    glGetIntegerv(GL_PACK_ROW_LENGTH, &rowLength);
    EXPECT_EQ(rowLength, 0);
}

TEST(Readback, FloatValuesAreUnclamped) {
    test::sharedGlContext();
    cv::Mat image(1, 1, CV_32FC4, cv::Scalar(-3.5, 1e6, 0.125, 42.0));
    GlTexture texture(Format::RGBA32F, 1, 1, "unclamped");
    uploadImage(texture, image);
    EXPECT_EQ(readTexture(texture).at<cv::Vec4f>(0, 0), cv::Vec4f(-3.5f, 1e6f, 0.125f, 42.0f));
}

TEST(TexturePool, ReusesOnlyMatchingTextures) {
    test::sharedGlContext();
    TexturePool pool;
    GlTexture first = pool.acquire(Format::R32F, 8, 8, "a");
    const GLuint firstId = first.id();
    pool.release(std::move(first));
    GlTexture other = pool.acquire(Format::RGBA32F, 8, 8, "b"); // different format: new texture
    GlTexture again = pool.acquire(Format::R32F, 8, 8, "c");    // same key: reused and relabelled
    EXPECT_EQ(again.id(), firstId);
    EXPECT_EQ(again.label(), "c");
    EXPECT_EQ(pool.createdCount(), 2u);
    EXPECT_EQ(pool.reusedCount(), 1u);
}

TEST(GlObjects, EveryObjectCarriesItsLabel) {
    test::sharedGlContext();
    auto labelOf = [](GLenum identifier, GLuint id) {
        char label[256] = {};
        GLsizei length = 0;
        glGetObjectLabel(identifier, id, sizeof label, &length, label);
        return std::string(label, std::size_t(length));
    };
    GlTexture texture(Format::RGBA32F, 4, 4, "gbuffer.normal");
    GlDepthTexture depth(4, 4, "gbuffer depth test");
    GlFramebuffer framebuffer("gbuffer");
    const float data[3] = {0, 0, 0};
    GlBuffer buffer(data, sizeof data, "mesh 'spot' positions");
    GlVertexArray vertexArray("mesh 'spot'");
    EXPECT_EQ(labelOf(GL_TEXTURE, texture.id()), "gbuffer.normal");
    EXPECT_EQ(labelOf(GL_TEXTURE, depth.id()), "gbuffer depth test");
    EXPECT_EQ(labelOf(GL_FRAMEBUFFER, framebuffer.id()), "gbuffer");
    EXPECT_EQ(labelOf(GL_BUFFER, buffer.id()), "mesh 'spot' positions");
    EXPECT_EQ(labelOf(GL_VERTEX_ARRAY, vertexArray.id()), "mesh 'spot'");
}

TEST(GlHandle, MoveTransfersOwnership) {
    test::sharedGlContext();
    GlTexture texture(Format::R8, 4, 4, "moved");
    const GLuint id = texture.id();
    GlTexture moved = std::move(texture);
    EXPECT_EQ(moved.id(), id);
    EXPECT_EQ(texture.id(), 0u); // NOLINT(bugprone-use-after-move): the moved-from state is what is tested
    EXPECT_TRUE(glIsTexture(id));
}

TEST(ShaderLibrary, CompileErrorNamesFileAndDefines) {
    test::sharedGlContext();
    const std::filesystem::path directory =
        std::filesystem::temp_directory_path() / ("inkgraph-shader-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(directory / "broken");
    std::ofstream(directory / "broken" / "ok.vert") << "void main() { gl_Position = vec4(0.0); }\n";
    std::ofstream(directory / "broken" / "bad.frag") << "out vec4 color;\nvoid main() { color = undefinedThing; }\n";
    ShaderLibrary library(directory);
    try {
        library.build({"broken", "broken/ok.vert", "broken/bad.frag", {"FLAVOUR 2"}, {}});
        FAIL() << "a broken shader must throw";
    } catch (const std::runtime_error& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("ShaderLibrary::build()"), std::string::npos) << message;
        EXPECT_NE(message.find("/broken/bad.frag'"), std::string::npos) << message;
        EXPECT_NE(message.find("FLAVOUR 2"), std::string::npos) << message;
    }
    EXPECT_THROW(library.build({"missing", "broken/none.vert", "broken/bad.frag", {}, {}}), std::runtime_error);
    std::filesystem::remove_all(directory);
}

TEST(ShaderLibrary, GeometryStageIsOptionalAndGetsItsDefine) {
    test::sharedGlContext();
    const std::filesystem::path directory =
        std::filesystem::temp_directory_path() / ("inkgraph-geometry-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(directory / "geo");
    // The snippet defines its function only in the geometry stage: the program links only if that stage got
    // INKGRAPH_GEOMETRY_STAGE and the others did not (two definitions would be a compile error elsewhere).
    std::ofstream(directory / "geo" / "corner.glsl")
        << "#ifdef INKGRAPH_GEOMETRY_STAGE\nvec4 corner(int i) { return vec4(i == 1 ? 3.0 : -1.0, i == 2 ? 3.0 : "
           "-1.0, 0.0, 1.0); }\n#endif\n#ifdef INKGRAPH_FRAGMENT_STAGE\nconst float kValue = 1.0;\n#endif\n";
    std::ofstream(directory / "geo" / "point.vert") << "void main() { gl_Position = vec4(0.0, 0.0, 0.0, 1.0); }\n";
    std::ofstream(directory / "geo" / "cover.geom")
        << "layout(points) in;\nlayout(triangle_strip, max_vertices = 3) out;\n"
           "void main() { for (int i = 0; i < 3; ++i) { gl_Position = corner(i); EmitVertex(); } EndPrimitive(); }\n";
    std::ofstream(directory / "geo" / "bad.geom") << "layout(points) in;\nvoid main() { EmitVertex(undefined); }\n";
    std::ofstream(directory / "geo" / "one.frag") << "out float value;\nvoid main() { value = kValue; }\n";
    ShaderLibrary library(directory);
    // A single point only becomes a full-screen triangle through the geometry stage.
    GlProgram program =
        library.build({"geo", "geo/point.vert", "geo/one.frag", {}, {"geo/corner.glsl"}, "geo/cover.geom"});
    GlTexture target(Format::R8, 8, 8, "geometry target");
    GlFramebuffer framebuffer("geometry test");
    framebuffer.attachColor(0, target);
    framebuffer.finish({0});
    framebuffer.bind();
    glViewport(0, 0, 8, 8);
    program.use();
    GlVertexArray empty("geometry test points");
    empty.bind();
    glDrawArrays(GL_POINTS, 0, 1);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    const cv::Mat image = readTexture(target);
    EXPECT_EQ(cv::countNonZero(image == 255), 64);

    try {
        library.build({"geo bad", "geo/point.vert", "geo/one.frag", {}, {"geo/corner.glsl"}, "geo/bad.geom"});
        FAIL() << "a broken geometry shader must throw";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("/geo/bad.geom'"), std::string::npos) << error.what();
    }
    std::filesystem::remove_all(directory);
}

TEST(ShaderLibrary, MissingDirectoryIsAnErrorOnFirstBuild) {
    test::sharedGlContext();
    ShaderLibrary library("/nonexistent/inkgraph/shaders");
    try {
        library.build({"x", "a/a.vert", "a/a.frag", {}, {}});
        FAIL() << "a missing shader folder must throw";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("/nonexistent/inkgraph/shaders/a/a.vert"), std::string::npos);
        EXPECT_NE(std::string(error.what()).find("INKGRAPH_SHADER_DIR"), std::string::npos);
    }
}

TEST(Readback, LargeTexturesGoInBands) {
    test::sharedGlContext();
    // 5000 rows of 4096 RGBA32F texels (320 MiB) take several 64 MiB bands; rows must land flipped and in order.
    cv::Mat image(5000, 4096, CV_32FC4);
    for (int row = 0; row < image.rows; ++row) image.row(row).setTo(cv::Scalar(row, -row, 0.5, 1));
    GlTexture texture(Format::RGBA32F, image.cols, image.rows, "banded");
    uploadImage(texture, image);
    float bottomRow[4] = {};
    glGetTextureSubImage(texture.id(), 0, 0, 0, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, sizeof bottomRow, bottomRow);
    EXPECT_EQ(bottomRow[0], 4999.0f) << "GL row 0 is the image's last row";
    for (const ReadbackFlip flip : {ReadbackFlip::Fastest, ReadbackFlip::Cpu}) {
        const cv::Mat back = readTexture(texture, flip);
        EXPECT_EQ(cv::norm(back, image, cv::NORM_INF), 0.0);
    }
    // The driver's row order is GL's default again after a read.
    if (epoxy_has_gl_extension("GL_MESA_pack_invert")) {
        GLint invert = 1;
        glGetIntegerv(GL_PACK_INVERT_MESA, &invert);
        EXPECT_EQ(invert, 0);
    }
}

TEST(GlTexture, AllocationFailureIsAnErrorNotACrash) {
    test::sharedGlContext();
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    EXPECT_THROW(GlTexture(Format::R8, maxSize + 1, 1, "too wide"), std::runtime_error);
    // 2 GiB of RGBA32F is more than llvmpipe allocates: reported as out of memory, which the CLI maps to --size.
    // (A GPU with enough memory may allocate it; then there is nothing to report.)
    const std::string renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    bool outOfMemory = false;
    try {
        GlTexture tooBig(Format::RGBA32F, 11648, 11648, "too big");
    } catch (const GlOutOfMemoryError&) {
        outOfMemory = true;
    }
    if (renderer.find("llvmpipe") != std::string::npos) {
        EXPECT_TRUE(outOfMemory) << renderer;
    }
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << "the error was consumed by the check";
}

} // namespace
} // namespace inkgraph
