// The host tail (gl/GraphExecutor.h runUntilHostTail(), runHostTail()): the GPU part of a plan on the context's
// thread, then its host passes on a thread that holds no context, as a pipelined batch runs them; the result is the
// one run() gives, and the tail finds every texture it reads moved to the CPU.
#include "passes/_template/TemplatePass.h"

#include "gl/GraphExecutor.h"
#include "gl/ShaderLibrary.h"
#include "gl/TexturePool.h"
#include "graph/GraphCompiler.h"
#include "tests/support/GlTestContext.h"

#include <gtest/gtest.h>

#include <exception>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace inkgraph::host_tail_gl_test {
namespace {

/** Writes `source.color` (rgba8) on the CPU: a distinct colour per pixel. Not host-only: it runs with the GPU part. */
class SourcePass : public GlPass {
public:
    std::string_view name() const override { return "source"; }
    void declare(PassBuilder& builder) const override { builder.write("color", {Format::RGBA8}); }
    void execute(GlPassContext& gl) override {
        cv::Mat& image = gl.outputImage("color");
        for (int row = 0; row < image.rows; ++row)
            for (int col = 0; col < image.cols; ++col)
                image.at<cv::Vec4b>(row, col) = cv::Vec4b(uchar(10 * col), uchar(20 * row), uchar(3 * row), 255);
    }
};

/** A host pass: `invert.color` = 255 - `template.color` in its colour channels; records whether the texture it reads
 *  had a GPU side while it ran (it must not). */
class InvertPass : public GlPass {
public:
    std::string_view name() const override { return "invert"; }
    void declare(PassBuilder& builder) const override {
        builder.runsOnHost();
        builder.read("template.color");
        builder.write("color", {Format::RGBA8});
    }
    void execute(GlPassContext& gl) override {
        const cv::Mat& input = gl.inputImage("template.color");
        cv::Mat& output = gl.outputImage("color");
        cv::subtract(cv::Scalar(255, 255, 255, 0), input, output);
        ranOn = std::this_thread::get_id();
    }
    std::thread::id ranOn;
};

class HostTailTest : public ::testing::Test {
protected:
    void SetUp() override { test::sharedGlContext(); }

    ShaderLibrary shaders;
    TexturePool pool;
    SourcePass source;
    TemplatePass copy{"template", shaders, "source.color"};
    InvertPass invert;
};

TEST_F(HostTailTest, TheTailRunsOnAThreadWithoutTheContextAndGivesWhatOneRunGives) {
    const Plan plan = compile({&source, &copy, &invert}, {"invert.color"});
    ASSERT_EQ(plan.hostTailStart(), 2u) << plan.describe();
    const ExecuteOptions options{9, 6, false};

    GraphExecutor whole{pool};
    whole.run(plan, {&source, &copy, &invert}, options);
    const cv::Mat expected = whole.store().image("invert.color").clone();
    ASSERT_EQ(expected.at<cv::Vec4b>(1, 2), cv::Vec4b(255 - 20, 255 - 20, 255 - 3, 0)) << "alpha: 0 - 255, saturated";

    GraphExecutor halves{pool};
    halves.runUntilHostTail(plan, {&source, &copy, &invert}, options);
    EXPECT_FALSE(halves.store().holdsTexture("template.color")) << "the hand-off moves the tail's reads to the CPU";
    std::exception_ptr failure;
    std::thread worker([&] {
        try {
            halves.runHostTail();
        } catch (...) {
            failure = std::current_exception();
        }
    });
    const std::thread::id workerId = worker.get_id();
    worker.join();
    if (failure) std::rethrow_exception(failure);
    EXPECT_EQ(invert.ranOn, workerId);
    EXPECT_EQ(cv::norm(halves.store().image("invert.color"), expected, cv::NORM_INF), 0.0);
    EXPECT_FALSE(halves.store().contains("template.color")) << "released after its last reader, on the worker";
}

TEST_F(HostTailTest, ATailWithoutABeginningIsALogicError) {
    GraphExecutor executor{pool};
    EXPECT_THROW(executor.runHostTail(), std::logic_error);
}

} // namespace
} // namespace inkgraph::host_tail_gl_test
