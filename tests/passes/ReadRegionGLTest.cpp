// A pass that covers only part of its target may have its read-backs kept to that part (GlPassContext::
// limitReadback()): allowed only when every reader reads the texture where covered (ReadExtent::CoveredPixels), and
// then the pixels inside come back as drawn, read back late (when the reader asks) or early (a pixel-pack buffer
// from the pool, begun after the writer ran). Needs a GL context (llvmpipe in CI).
#include "gl/GlPass.h"
#include "gl/GraphExecutor.h"
#include "gl/TexturePool.h"
#include "graph/GraphCompiler.h"
#include "tests/support/GlTestContext.h"

#include <gtest/gtest.h>

#include <optional>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

constexpr int kWidth = 12;
constexpr int kHeight = 8;
const PixelRect kCovered{3, 2, 5, 4}; // GL window coordinates: image columns 3..7, rows 8 - 2 - 4 = 2 .. 5

/** Clears `cover.field` (r32f) to 0, then to 7 inside kCovered, and limits its read-backs to kCovered. */
class CoverPass : public GlPass {
public:
    std::string_view name() const override { return "cover"; }
    void declare(PassBuilder& builder) const override { builder.write("field", {Format::R32F}); }
    void execute(GlPassContext& gl) override {
        GlFramebuffer framebuffer("cover");
        framebuffer.attachColor(0, gl.outputTexture("field"));
        framebuffer.finish({0});
        framebuffer.bind();
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearBufferfv(GL_COLOR, 0, zero); // what a whole read sees outside the covered pixels
        glEnable(GL_SCISSOR_TEST);
        glScissor(kCovered.x, kCovered.y, kCovered.width, kCovered.height);
        const float seven[4] = {7.0f, 0.0f, 0.0f, 0.0f};
        glClearBufferfv(GL_COLOR, 0, seven);
        glDisable(GL_SCISSOR_TEST);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        try {
            gl.limitReadback("field", kCovered);
            limited = true;
        } catch (const std::logic_error& error) {
            refusal = error.what();
        }
    }
    bool limited = false;
    std::string refusal;
};

/** Reads `cover.field` with `extent` on the CPU (a host pass: an early read-back begins for it) and keeps a copy. */
class ReaderPass : public GlPass {
public:
    explicit ReaderPass(ReadExtent extent) : mExtent(extent) {}
    std::string_view name() const override { return "reader"; }
    void declare(PassBuilder& builder) const override {
        builder.read("cover.field", mExtent);
        builder.write("out", {Format::R8});
        builder.runsOnHost();
    }
    void execute(GlPassContext& gl) override {
        seen = gl.inputImage("cover.field").clone();
        gl.outputImage("out");
    }
    cv::Mat seen;

private:
    ReadExtent mExtent;
};

/** What CoverPass and a ReaderPass reading with `extent` leave after `runs` runs of the two over one pool. */
struct CoverAndRead {
    explicit CoverAndRead(ReadExtent extent, bool readBackEarly = false, int runs = 1) : reader(extent) {
        test::sharedGlContext();
        for (int run = 0; run < runs; ++run) {
            GraphExecutor executor{pool};
            executor.run(compile({&cover, &reader}, {"reader.out"}), {&cover, &reader},
                         {kWidth, kHeight, readBackEarly});
        }
    }
    TexturePool pool;
    CoverPass cover;
    ReaderPass reader;
};

class ReadRegionTiming : public ::testing::TestWithParam<bool> {};

TEST_P(ReadRegionTiming, AFieldReadOnlyWhereCoveredComesBackInsideItsRegion) {
    const CoverAndRead run(ReadExtent::CoveredPixels, GetParam());
    ASSERT_TRUE(run.cover.limited) << run.cover.refusal;
    ASSERT_EQ(run.reader.seen.size(), cv::Size(kWidth, kHeight));
    const cv::Mat inside = run.reader.seen(cv::Rect(3, 2, 5, 4));
    EXPECT_EQ(cv::countNonZero(inside != 7.0f), 0) << "the covered pixels, in their places (row 0 at the top)";
}

TEST_P(ReadRegionTiming, AWholeFieldComesBackWhole) {
    const CoverAndRead run(ReadExtent::WholeImage, GetParam());
    ASSERT_EQ(run.reader.seen.size(), cv::Size(kWidth, kHeight));
    EXPECT_EQ(cv::countNonZero(run.reader.seen(cv::Rect(3, 2, 5, 4)) != 7.0f), 0);
    cv::Mat outside = run.reader.seen.clone();
    outside(cv::Rect(3, 2, 5, 4)).setTo(0.0f);
    EXPECT_EQ(cv::countNonZero(outside), 0) << "the cleared pixels around the covered ones";
}

INSTANTIATE_TEST_SUITE_P(LateAndEarly, ReadRegionTiming, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& timing) { return timing.param ? "Early" : "Late"; });

TEST(ReadRegion, EarlyReadbacksReuseThePoolsBuffer) {
    const CoverAndRead run(ReadExtent::CoveredPixels, true, 3);
    EXPECT_EQ(run.pool.readbackBuffersCreated(), 1u) << "one buffer, made for the first run and reused by the others";
    EXPECT_EQ(cv::countNonZero(run.reader.seen(cv::Rect(3, 2, 5, 4)) != 7.0f), 0);
}

TEST(ReadRegion, IsRefusedForAFieldReadWhole) {
    const CoverAndRead run(ReadExtent::WholeImage);
    EXPECT_FALSE(run.cover.limited);
    EXPECT_NE(run.cover.refusal.find("GlPassContext::limitReadback(): 'cover.field'"), std::string::npos)
        << run.cover.refusal;
}

} // namespace
} // namespace inkgraph
