// Lander's back-face outline pass on llvmpipe: the visible ring outside a sphere's silhouette is widthPixels wide at
// several distances, fields of view and resolutions, the inner half stays hidden by the fill, the eye-inside skip,
// and near-plane clipping of edges that pass behind the eye.
#include "passes/outline/OutlinePass.h"
#include "passes/silhouette/SilhouettePass.h"

#include "LineMaskTestSupport.h"

#include <nlohmann/json.hpp>

#include <limits>
#include <sstream>

namespace inkgraph {
namespace {

using test::LineRender;
using test::OutsideRun;

class OutlineSphere : public test::LinePassFixture {
protected:
    void SetUp() override {
        LinePassFixture::SetUp();
        setScene(test::fineSphereScene());
    }
};

struct OutlineCase {
    double distance;
    double fovYDegrees;
    int width;
    int height;
    float widthPixels;
};

TEST_F(OutlineSphere, VisibleRingIsWidthPixelsWide) {
    const OutlineCase cases[] = {
        {4.0, 35.0, 256, 256, 3.0f}, {8.0, 35.0, 256, 256, 3.0f}, {4.0, 35.0, 512, 512, 3.0f},
        {8.0, 60.0, 512, 512, 3.0f}, {6.0, 20.0, 384, 256, 3.0f}, {4.0, 35.0, 512, 512, 6.0f},
    };
    std::ostringstream measured;
    for (const OutlineCase& view : cases) {
        OutlinePass pass("outline", shaders, *gpuScene, frame, view.widthPixels);
        lookFrom({0.0, 0.0, view.distance}, glm::dvec3(0.0), view.fovYDegrees, view.width, view.height);
        const LineRender render = this->render(pass);
        const std::string where = "distance " + std::to_string(view.distance) + ", fov " +
                                  std::to_string(view.fovYDegrees) + ", " + std::to_string(view.width) + "x" +
                                  std::to_string(view.height) + ", width " + std::to_string(view.widthPixels);
        SCOPED_TRACE(where);
        measured << "d" << view.distance << "/fov" << view.fovYDegrees << "/" << view.width << "x" << view.height
                 << "/w" << view.widthPixels << ":";
        for (const OutsideRun& run : test::runsFromCentre(render)) {
            EXPECT_NEAR(run.length, view.widthPixels, 1.0);
            EXPECT_EQ(run.strayBeyond, 0);
            measured << " " << run.length;
        }
        measured << ";";
        // The fill hides the inner half of every line, and no back edge shows through the front of the sphere.
        const test::SilhouetteCircle circle = test::silhouetteOf(frame.camera, 1.0, view.distance);
        int deepInside = 0, farOutside = 0, holes = 0;
        for (int row = 0; row < render.lines.rows; ++row)
            for (int col = 0; col < render.lines.cols; ++col) {
                const double distance = circle.distance(col, row);
                const bool line = render.lines.at<uchar>(row, col) == 255;
                deepInside += line && distance < -(view.widthPixels + 1.0);
                farOutside += line && distance > view.widthPixels + 1.0;
                holes += !line && distance > 1.0 && distance < view.widthPixels - 1.0;
            }
        EXPECT_EQ(deepInside, 0);
        EXPECT_EQ(farOutside, 0);
        EXPECT_EQ(holes, 0);
        EXPECT_FALSE(pass.skippedEyeInside());
    }
    RecordProperty("ring_widths_left_right_top_bottom", measured.str());
}

TEST_F(OutlineSphere, InnerHalfIsHiddenByTheFill) {
    // Measured directly: the line pixels inside the model's coverage are at most a pixel deep, not widthPixels.
    constexpr float kWidth = 4.0f;
    OutlinePass pass("outline", shaders, *gpuScene, frame, kWidth);
    lookFrom({0.0, 0.0, 4.0}, glm::dvec3(0.0), 35.0, 256, 256);
    const LineRender render = this->render(pass);
    const test::SilhouetteCircle circle = test::silhouetteOf(frame.camera, 1.0, 4.0);
    double deepest = 0.0;
    for (int row = 0; row < render.lines.rows; ++row)
        for (int col = 0; col < render.lines.cols; ++col)
            if (render.lines.at<uchar>(row, col) == 255 && render.coverage.at<uchar>(row, col) == 255)
                deepest = std::max(deepest, -circle.distance(col, row));
    EXPECT_LT(deepest, 1.5);
    RecordProperty("deepest_inner_line_pixel", std::to_string(deepest));
}

TEST_F(OutlineSphere, EyeInsideLeavesBothMasksEmpty) {
    OutlinePass outline("outline", shaders, *gpuScene, frame, 2.0f);
    SilhouettePass silhouette("silhouette", shaders, *gpuScene, frame, HullSettings{});
    lookFrom({0.1, -0.2, 0.3}, {1.0, 0.0, 0.0}, 70.0, 128, 128);
    EXPECT_EQ(cv::countNonZero(render(outline, false).lines), 0);
    EXPECT_TRUE(outline.skippedEyeInside());
    EXPECT_EQ(cv::countNonZero(render(silhouette, false).lines), 0);
    EXPECT_TRUE(silhouette.skippedEyeInside());
    nlohmann::ordered_json outlineReport, silhouetteReport;
    outline.describe(outlineReport);
    silhouette.describe(silhouetteReport);
    EXPECT_EQ(outlineReport.dump(), R"({"skipped_eye_inside":true})");
    EXPECT_EQ(silhouetteReport.dump(), R"({"skipped_eye_inside":true})");
    lookFrom({0.0, 0.0, 4.0}, glm::dvec3(0.0), 35.0, 128, 128);
    EXPECT_GT(cv::countNonZero(render(outline, false).lines), 100);
    EXPECT_FALSE(outline.skippedEyeInside());
}

TEST_F(OutlineSphere, EdgesBehindTheEyeAreClippedAtTheNearPlane) {
    // The eye 1.2 radii from the centre, looking past the sphere, which reaches behind the eye: back faces cross the
    // near plane and w = 0. Every visible point has view x > 0, so the left half of the frame must stay empty apart
    // from the line width; an edge projected without clipping would streak across it.
    constexpr float kWidth = 3.0f;
    OutlinePass pass("outline", shaders, *gpuScene, frame, kWidth);
    for (const double nearScale : {1.0, 4.0}) {
        lookFrom({-1.2, 0.0, 0.0}, {-1.2, 0.0, -1.0}, 90.0, 256, 256);
        // Also with the near plane pushed into the sphere, so the cut opens it and shows its back faces.
        frame.camera.zNear *= nearScale;
        const LineRender render = this->render(pass);
        SCOPED_TRACE("near " + std::to_string(frame.camera.zNear));
        EXPECT_FALSE(pass.skippedEyeInside());
        EXPECT_EQ(cv::countNonZero(render.coverage.colRange(0, 128)), 0);
        EXPECT_EQ(cv::countNonZero(render.lines.colRange(0, 128 - int(kWidth) - 1)), 0);
        EXPECT_GT(cv::countNonZero(render.lines), 100);
    }
}

TEST(OutlinePass, RejectsBadWidths) {
    const Scene scene = test::fineSphereScene();
    GpuScene gpuScene(scene, glm::dvec3(0.0));
    ShaderLibrary shaders;
    FrameParams frame;
    EXPECT_THROW(OutlinePass("o", shaders, gpuScene, frame, -2.0f), std::invalid_argument);
    EXPECT_THROW(OutlinePass("o", shaders, gpuScene, frame, std::numeric_limits<float>::quiet_NaN()),
                 std::invalid_argument);
}

} // namespace
} // namespace inkgraph
