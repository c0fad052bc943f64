// The copy-me pass (passes/_template/) on llvmpipe, run through GraphExecutor as the app runs passes: a CPU pass
// writes a small rgba8 image, the template pass copies it on the GPU, and the read-back is the same image, also when
// the input is supersampled (the scale comes from the plan: GlPassContext::scaleOf()).
#include "passes/_template/TemplatePass.h"

#include "gl/GraphExecutor.h"
#include "gl/ShaderLibrary.h"
#include "gl/TexturePool.h"
#include "graph/GraphCompiler.h"
#include "tests/support/GlTestContext.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace inkgraph {
namespace {

/** A CPU pass writing `source.color` (rgba8, `scale` times the frame): a distinct colour per pixel. */
class SourcePass : public GlPass {
public:
    explicit SourcePass(int scale) : mScale(scale) {}
    std::string_view name() const override { return "source"; }
    void declare(PassBuilder& builder) const override { builder.write("color", {Format::RGBA8, mScale}); }
    void execute(GlPassContext& gl) override {
        cv::Mat& image = gl.outputImage("color");
        for (int row = 0; row < image.rows; ++row)
            for (int col = 0; col < image.cols; ++col)
                image.at<cv::Vec4b>(row, col) =
                    cv::Vec4b(uchar(10 * col), uchar(20 * row), uchar(7 * (row + col)), 255);
    }

private:
    int mScale;
};

class TemplatePassTest : public ::testing::Test {
protected:
    void SetUp() override { test::sharedGlContext(); }

    /** Runs source (at `scale`) and template on a width x height frame; returns both images. */
    void run(int scale, int width, int height) {
        SourcePass source(scale);
        TemplatePass copy("template", shaders, "source.color");
        const Plan plan = compile({&source, &copy}, {"template.color", "source.color"});
        executor.run(plan, {&copy, &source}, {width, height, false});
        input = executor.store().image("source.color").clone();
        output = executor.store().image("template.color").clone();
    }

    ShaderLibrary shaders;
    TexturePool pool;
    GraphExecutor executor{pool};
    cv::Mat input;
    cv::Mat output;
};

TEST_F(TemplatePassTest, CopiesItsInputTexelExact) {
    run(1, 7, 5);
    ASSERT_EQ(output.size(), cv::Size(7, 5));
    ASSERT_EQ(output.type(), CV_8UC4);
    EXPECT_EQ(cv::norm(output, input, cv::NORM_INF), 0.0);
    EXPECT_EQ(output.at<cv::Vec4b>(0, 6), cv::Vec4b(60, 0, 42, 255)) << "row 0 is the top, as the source wrote it";
}

TEST_F(TemplatePassTest, ReadsASupersampledInputAtThePlannedScale) {
    run(2, 6, 4);
    ASSERT_EQ(input.size(), cv::Size(12, 8));
    ASSERT_EQ(output.size(), cv::Size(6, 4));
    // GL's origin is the bottom-left: from each 2 x 2 block the pass takes its lower-left texel, image row 2r + 1.
    for (int row = 0; row < output.rows; ++row)
        for (int col = 0; col < output.cols; ++col)
            ASSERT_EQ(output.at<cv::Vec4b>(row, col), input.at<cv::Vec4b>(2 * row + 1, 2 * col))
                << "row " << row << ", col " << col;
}

TEST_F(TemplatePassTest, AMissingInputIsAGraphError) {
    TemplatePass copy("template", shaders, "nobody.color");
    EXPECT_THROW(compile({&copy}, {"template.color"}), GraphError);
}

} // namespace
} // namespace inkgraph
