// The post-stage line types end to end: the GL G-buffer of a mesh, read back, through the postfx kernels, stroked.
// Analytic expectations: a sphere's contour lies on its silhouette circle (image radius f R / sqrt(d^2 - R^2)), a
// sphere has no suggestive contours, a torus has them on its inner side, and runs repeat exactly.
#include "graph/GraphCompiler.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/lines/LineLayerPass.h"
#include "passes/lines/StrokesPass.h"
#include "passes/lines/types/ImageEdgeLines.h"
#include "passes/lines/types/SuggestiveLines.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/AnalyticSphere.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/PassHarness.h"
#include "tests/support/TestCamera.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <memory>
#include <vector>

namespace inkgraph {
namespace {

constexpr int kSize = 512;
constexpr double kFovDegrees = 35.0;

enum class Source { Contour, Suggestive, SuggestiveObject, HiddenSuggestiveObject, DepthEdge, NormalEdge };

/** Which kernel a layer runs, with the suggestive settings both suggestive kernels take. */
struct LineSettings {
    Source source = Source::Contour;
    SuggestiveSettings suggestive;
};

LineSettings withSource(Source source) { return {source, {}}; }

std::unique_ptr<LineKernel> kernelFor(const LineSettings& settings, GpuScene& scene, const FrameParams& frame) {
    switch (settings.source) {
    case Source::Contour: return std::make_unique<ContourKernel>("gbuffer", ContourSettings{});
    // No smoothing (the kernels' own defaults): these tests hold the unsmoothed lines to the analytic ones.
    case Source::Suggestive: return std::make_unique<SuggestiveKernel>("gbuffer", settings.suggestive, frame);
    case Source::SuggestiveObject:
        return std::make_unique<ObjectSuggestiveKernel>("gbuffer", settings.suggestive, 0.0, scene, frame);
    case Source::HiddenSuggestiveObject:
        return std::make_unique<ObjectSuggestiveKernel>("gbuffer", settings.suggestive, 0.0, scene, frame,
                                                        SegmentVisibility::Hidden);
    case Source::DepthEdge: return std::make_unique<DepthEdgeKernel>("gbuffer", DepthEdgeSettings{});
    case Source::NormalEdge: return std::make_unique<NormalEdgeKernel>("gbuffer", NormalEdgeSettings{});
    }
    return nullptr;
}

/** What the object-space kernel of a layer found beyond its skeleton. */
const ObjectSuggestiveReport& objectReport(const LineLayerPass& pass) {
    return static_cast<const ObjectSuggestiveKernel&>(pass.kernel()).report();
}

class LineLayers : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override { test::sharedGlContext(); }

    void look(Mesh mesh, const glm::dvec3& eye, int size = kSize) {
        scene = makeScene(std::move(mesh));
        frame.camera = test::lookingAt(scene, eye, glm::dvec3(0.0), kFovDegrees, size, size);
        frame.worldOrigin = glm::dvec3(0.0);
        frameSize = size;
    }

    /** Runs the G-buffer, one line pass and the stroke stage (keeping every stroke, so the layer is the whole
     *  skeleton stroked); returns the line pass for its report. The lines stay in the store. */
    LineLayerPass& draw(const LineSettings& settings, int supersample = 1) {
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
        gbuffer = std::make_unique<GBufferPass>("gbuffer", shaders, *gpuScene, frame, supersample);
        lines = std::make_unique<LineLayerPass>("lines-under-test", kernelFor(settings, *gpuScene, frame), supersample);
        StrokesPassSettings strokeSettings;
        strokeSettings.supersample = supersample;
        strokeSettings.inputs = {{"lines-under-test", "lines-under-test.skeleton", true, 2.0f, 0.0, 0.0f}};
        strokes = std::make_unique<StrokesPass>("strokes", strokeSettings);
        const std::vector<const Pass*> passes = {gbuffer.get(), lines.get(), strokes.get()};
        const Plan plan = compile(passes, {"strokes.lines-under-test", "gbuffer.depth", "lines-under-test.skeleton"});
        executor.run(plan, {gbuffer.get(), lines.get(), strokes.get()}, {frameSize, frameSize, false});
        return *lines;
    }

    const cv::Mat& lineImage() { return executor.store().image("strokes.lines-under-test"); }
    /** The skeleton the line pass handed on, as the graph holds it. */
    const LineSkeleton& skeleton() { return executor.store().object<LineSkeleton>("lines-under-test.skeleton"); }

    int frameSize = kSize;
    std::unique_ptr<GBufferPass> gbuffer;
    std::unique_ptr<LineLayerPass> lines;
    std::unique_ptr<StrokesPass> strokes;
};

TEST_F(LineLayers, SphereContourLiesOnTheAnalyticSilhouetteCircle) {
    // 512 x 256 segments: the polygon lies inside the sphere by at most rho pi^2 / (2 N^2) = 0.004 px here.
    look(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 512, 256), {0.0, 0.0, 4.0});
    const test::AnalyticSphereView sphere{kSize, 1.0, 4.0, kFovDegrees};
    for (const int supersample : {1, 2}) {
        SCOPED_TRACE("supersample " + std::to_string(supersample));
        draw(withSource(Source::Contour), supersample);
        const cv::Mat& image = lineImage();
        ASSERT_EQ(image.size(), cv::Size(kSize, kSize));
        // Every drawn pixel with full coverage lies within half the width (1 px) plus 1 px of the circle, and the
        // line goes all the way round: each 1-degree sector has a full-coverage pixel.
        std::vector<int> sectors(360, 0);
        double worst = 0.0;
        int fullPixels = 0;
        for (int row = 0; row < kSize; ++row)
            for (int col = 0; col < kSize; ++col) {
                if (image.at<uchar>(row, col) < 250) continue;
                ++fullPixels;
                worst = std::max(worst, sphere.pixelsFromSilhouette(col, row));
                const double angle = std::atan2(row + 0.5 - kSize / 2.0, col + 0.5 - kSize / 2.0);
                ++sectors[int(std::floor((angle + glm::pi<double>()) / (2.0 * glm::pi<double>()) * 360.0)) % 360];
            }
        EXPECT_LT(worst, 2.0) << "full-coverage line pixel this far from the silhouette circle";
        for (int sector = 0; sector < 360; ++sector) EXPECT_GT(sectors[sector], 0) << "gap at " << sector << " deg";
        // A 2-px ring of radius 209.6 px: about 2 pi rho x 2 pixels of coverage in all.
        const double circle = sphere.focalPixels() / std::sqrt(15.0);
        EXPECT_NEAR(cv::sum(image)[0] / 255.0, 2.0 * glm::pi<double>() * circle * 2.0,
                    0.1 * 2.0 * glm::pi<double>() * circle * 2.0);
        RecordProperty("full_pixels_s" + std::to_string(supersample), fullPixels);
    }
}

TEST_F(LineLayers, SphereContourSkeletonPointsAreWithinOnePixel) {
    look(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 512, 256), {0.3, -0.2, 4.0});
    // The off-axis sphere's silhouette is the image of the tangent cone: a pixel ray x lies on it iff
    // (x.c)^2 = (|c|^2 - R^2)|x|^2 (docs/accuracy.md). Every skeleton point must have the cone within 1 px.
    draw(withSource(Source::Contour));
    ASSERT_GT(skeleton().points.size(), 1000u);
    const glm::dmat4 view = frame.camera.viewMatrix();
    const glm::dvec3 center = glm::dvec3(view * glm::dvec4(0.0, 0.0, 0.0, 1.0));
    const double focal = (kSize / 2.0) / std::tan(glm::radians(kFovDegrees) / 2.0);
    auto coneResidual = [&](double x, double y) { // x, y: image point, origin top-left
        const glm::dvec3 ray((x - kSize / 2.0) / focal, -(y - kSize / 2.0) / focal, -1.0);
        return glm::dot(ray, center) * glm::dot(ray, center) - (glm::dot(center, center) - 1.0) * glm::dot(ray, ray);
    };
    int outside = 0;
    for (const LinePoint& point : skeleton().points) {
        // Skeleton points put pixel centres at integers; the image point of a pixel centre is col + 0.5.
        const double x = point.position.x + 0.5, y = point.position.y + 0.5;
        const bool positive = coneResidual(x, y) > 0;
        bool crosses = false;
        for (int step = 0; step < 32 && !crosses; ++step) {
            const double angle = step * glm::pi<double>() / 16.0;
            crosses = (coneResidual(x + std::cos(angle), y + std::sin(angle)) > 0) != positive;
        }
        outside += !crosses;
    }
    EXPECT_EQ(outside, 0) << "skeleton points more than 1 px from the analytic silhouette";
}

TEST_F(LineLayers, SphereHasNoSuggestiveContours) {
    for (const glm::dvec3 eye : {glm::dvec3(0.0, 0.0, 4.0), glm::dvec3(1.5, 1.0, 2.5), glm::dvec3(0.0, 0.0, 1.6)}) {
        look(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 512, 256), eye);
        LineSettings settings = withSource(Source::Suggestive);
        settings.suggestive.featureSize = 0.05f;
        const LineLayerPass& pass = draw(settings);
        EXPECT_EQ(pass.report().points, 0u) << "eye " << eye.x << "," << eye.y << "," << eye.z;
        EXPECT_EQ(cv::countNonZero(lineImage()), 0);
    }
}

TEST_F(LineLayers, TorusHasSuggestiveContoursOnItsInnerSide) {
    // Ring radius 1, tube 0.35, around z; seen from 30 degrees above the ring's plane.
    const double ringRadius = 1.0, tubeRadius = 0.35;
    const double elevation = glm::radians(30.0);
    const glm::dvec3 eye = 4.0 * glm::dvec3(std::cos(elevation), 0.0, std::sin(elevation));
    look(makeTorus(float(ringRadius), float(tubeRadius), 512, 256), eye);
    LineSettings settings = withSource(Source::Suggestive);
    settings.suggestive.featureSize = float(0.05 * (ringRadius + tubeRadius));
    const LineLayerPass& pass = draw(settings);
    ASSERT_GT(pass.report().points, 100u);
    // Back-project every line pixel through the depth buffer and ask where on the torus it is: the inner half
    // (negative Gaussian curvature, distance from the axis below the ring radius) is the only place kappa_r can be 0.
    const cv::Mat& depth = executor.store().image("gbuffer.depth");
    const cv::Mat& image = lineImage();
    const glm::dmat4 worldFromView = glm::inverse(frame.camera.viewMatrix());
    const double focal = (kSize / 2.0) / std::tan(glm::radians(kFovDegrees) / 2.0);
    int inner = 0, outer = 0;
    for (int row = 0; row < kSize; ++row)
        for (int col = 0; col < kSize; ++col) {
            // Lines fade with their strength (rtsc's fade), so any coverage counts.
            if (image.at<uchar>(row, col) == 0 || depth.at<float>(row, col) <= 0.0f) continue;
            const double z = depth.at<float>(row, col);
            const glm::dvec3 view((col + 0.5 - kSize / 2.0) / focal * z, -(row + 0.5 - kSize / 2.0) / focal * z, -z);
            const glm::dvec3 world = glm::dvec3(worldFromView * glm::dvec4(view, 1.0));
            (std::hypot(world.x, world.y) < ringRadius ? inner : outer)++;
        }
    EXPECT_GT(inner, 200);
    // The stroke reaches 1.5 px from its points, and the line ends where the inner side meets the outer: allow 2%.
    EXPECT_LT(outer, inner / 50) << "suggestive-contour pixels on the torus's outer (convex) half";
    RecordProperty("inner_pixels", inner);
    RecordProperty("outer_pixels", outer);
}

/** The share of `points` with one of `reference` within `radius` (brute force: a few thousand points). */
double shareNear(const std::vector<LinePoint>& points, const std::vector<LinePoint>& reference, double radius) {
    if (points.empty()) return 0.0;
    int near = 0;
    for (const LinePoint& point : points)
        for (const LinePoint& other : reference)
            if (cv::norm(point.position - other.position) <= radius) {
                ++near;
                break;
            }
    return double(near) / double(points.size());
}

TEST_F(LineLayers, ObjectSpaceSuggestiveContoursMatchTheImageSpaceOnes) {
    // The torus of TorusHasSuggestiveContoursOnItsInnerSide; both types with the app's settings.
    const double ringRadius = 1.0, tubeRadius = 0.35;
    const double elevation = glm::radians(30.0);
    const glm::dvec3 eye = 4.0 * glm::dvec3(std::cos(elevation), 0.0, std::sin(elevation));
    for (const int supersample : {1, 2}) {
        SCOPED_TRACE("supersample " + std::to_string(supersample));
        look(makeTorus(float(ringRadius), float(tubeRadius), 256, 96), eye, 384);
        LineSettings settings = withSource(Source::Suggestive);
        settings.suggestive.featureSize = float(0.05 * (ringRadius + tubeRadius));
        const std::vector<LinePoint> imageSpace = (draw(settings, supersample), skeleton().points);
        settings.source = Source::SuggestiveObject;
        const LineLayerPass& pass = draw(settings, supersample);
        const std::vector<LinePoint> objectSpace = skeleton().points;
        ASSERT_GT(imageSpace.size(), 50u);
        ASSERT_GT(objectSpace.size(), 100u);
        EXPECT_GT(objectReport(pass).segments, 40u);
        EXPECT_EQ(skeleton().mask.size(), cv::Size(384 * supersample, 384 * supersample));
        EXPECT_GT(cv::countNonZero(lineImage()), 0);
        // Data pixels: the lines are the same set seen two ways, so they lie within a couple of pixels of each other.
        const double radius = 2.0 * supersample;
        const double objectNearImage = shareNear(objectSpace, imageSpace, radius);
        const double imageNearObject = shareNear(imageSpace, objectSpace, radius);
        // Measured at 384^2: 98% (S = 1) and 100% (S = 2) of the object-space points lie within 2 output pixels of an
        // image-space point, and 100% and 86% the other way. The 14% at S = 2 continue each line past its analytic
        // end: where the line turns over the top of the tube, the analytic q falls below T (at u = 1.17, v = 1.64,
        // exactly where the object-space line stops) and then below 0 (u > 1.28), but the image-space kernel keeps
        // ~60 points there with strengths up to 0.5.
        EXPECT_GT(objectNearImage, 0.95);
        EXPECT_GT(imageNearObject, supersample == 1 ? 0.95 : 0.8);
        RecordProperty("object_near_image_s" + std::to_string(supersample), std::to_string(objectNearImage));
        RecordProperty("image_near_object_s" + std::to_string(supersample), std::to_string(imageNearObject));
        RecordProperty("points_s" + std::to_string(supersample),
                       std::to_string(objectSpace.size()) + " vs " + std::to_string(imageSpace.size()));
        for (const LinePoint& point : objectSpace) {
            ASSERT_GT(point.strength, 0.0f);
            ASSERT_LE(point.strength, 1.0f);
        }
    }
}

TEST_F(LineLayers, ObjectSpaceSuggestiveContoursAreHiddenBehindNearerSurfaces) {
    // The torus from 30 degrees up, then the same torus with a ball between the eye and one of its two lines (the
    // one at u = +1.1): that line is hidden and the other is not. The ball, convex, adds no segments.
    const glm::dvec3 eye = 4.0 * glm::dvec3(std::cos(glm::radians(30.0)), 0.0, std::sin(glm::radians(30.0)));
    const Mesh torus = makeTorus(1.0f, 0.35f, 256, 96);
    LineSettings settings = withSource(Source::SuggestiveObject);
    settings.suggestive.featureSize = 0.0675f;
    look(torus, eye, 256);
    const LineLayerPass& alone = draw(settings);
    const std::size_t segments = objectReport(alone).segments;
    const std::vector<LinePoint> unoccluded = skeleton().points;

    Mesh occluded = torus;
    const Mesh ball = makeUvSphere({1.9f, 0.38f, 1.14f}, 0.3f, 48, 24);
    const auto offset = std::uint32_t(occluded.positions.size());
    occluded.positions.insert(occluded.positions.end(), ball.positions.begin(), ball.positions.end());
    occluded.normals.insert(occluded.normals.end(), ball.normals.begin(), ball.normals.end());
    for (const glm::uvec3& triangle : ball.triangles) occluded.triangles.push_back(triangle + offset);
    look(occluded, eye, 256);
    const LineLayerPass& behind = draw(settings);
    EXPECT_EQ(objectReport(behind).segments, segments);
    const std::vector<LinePoint> visible = skeleton().points;
    // Measured: 273 points alone, 132 behind the ball. Every one kept is one of the unoccluded ones.
    EXPECT_GT(unoccluded.size(), 100u);
    EXPECT_LT(double(visible.size()), 0.7 * double(unoccluded.size()));
    EXPECT_GT(double(visible.size()), 0.3 * double(unoccluded.size()));
    EXPECT_EQ(shareNear(visible, unoccluded, 0.01), 1.0);
    RecordProperty("points_alone", int(unoccluded.size()));
    RecordProperty("points_behind_ball", int(visible.size()));
}

TEST_F(LineLayers, HiddenObjectSpaceSuggestiveContoursAreTheSamplesTheVisibleOnesDrop) {
    // The torus and ball of the test above: the hidden layer (hidden-suggestive-object) keeps exactly the samples in
    // the frame the visible one drops, so with the ball the line behind it moves from one layer to the other.
    const glm::dvec3 eye = 4.0 * glm::dvec3(std::cos(glm::radians(30.0)), 0.0, std::sin(glm::radians(30.0)));
    const Mesh torus = makeTorus(1.0f, 0.35f, 256, 96);
    LineSettings settings = withSource(Source::SuggestiveObject);
    settings.suggestive.featureSize = 0.0675f;
    LineSettings hiddenSettings = settings;
    hiddenSettings.source = Source::HiddenSuggestiveObject;
    look(torus, eye, 256);
    draw(settings);
    const std::vector<LinePoint> visibleAlone = skeleton().points;
    draw(hiddenSettings);
    const std::vector<LinePoint> hiddenAlone = skeleton().points;

    Mesh occluded = torus;
    const Mesh ball = makeUvSphere({1.9f, 0.38f, 1.14f}, 0.3f, 48, 24);
    const auto offset = std::uint32_t(occluded.positions.size());
    occluded.positions.insert(occluded.positions.end(), ball.positions.begin(), ball.positions.end());
    occluded.normals.insert(occluded.normals.end(), ball.normals.begin(), ball.normals.end());
    for (const glm::uvec3& triangle : ball.triangles) occluded.triangles.push_back(triangle + offset);
    look(occluded, eye, 256);
    draw(settings);
    const std::vector<LinePoint> visible = skeleton().points;
    draw(hiddenSettings);
    const std::vector<LinePoint> hidden = skeleton().points;

    // The same samples, split otherwise: the two layers together are the same points with and without the ball.
    EXPECT_EQ(visible.size() + hidden.size(), visibleAlone.size() + hiddenAlone.size());
    // The line behind the ball went over: at least 30% of the points (the test above measured 273 -> 132).
    EXPECT_GE(double(hidden.size()) - double(hiddenAlone.size()), 0.3 * double(visibleAlone.size()));
    // Every hidden point is one of the lines' points, and none is also drawn visible.
    std::vector<LinePoint> all = visibleAlone;
    all.insert(all.end(), hiddenAlone.begin(), hiddenAlone.end());
    EXPECT_EQ(shareNear(hidden, all, 0.01), 1.0);
    EXPECT_EQ(shareNear(hidden, visible, 0.001), 0.0);
    RecordProperty("hidden_alone", int(hiddenAlone.size()));
    RecordProperty("hidden_behind_ball", int(hidden.size()));
}

TEST_F(LineLayers, CurvatureIsDerivedOnlyWhenObjectSpaceLinesRun) {
    look(makeTorus(1.0f, 0.35f, 96, 48), 4.0 * glm::dvec3(std::cos(glm::radians(30.0)), 0.0, 0.5), 128);
    gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    GBufferPass gbufferPass("gbuffer", shaders, *gpuScene, frame);
    LineLayerPass contour("contour", kernelFor(withSource(Source::Contour), *gpuScene, frame), 1);
    LineSettings objectSettings = withSource(Source::SuggestiveObject);
    objectSettings.suggestive.featureSize = 0.0675f;
    LineLayerPass object("suggestive-object", kernelFor(objectSettings, *gpuScene, frame), 1);
    const std::vector<const Pass*> passes = {&gbufferPass, &contour, &object};

    const Plan contourOnly = compile(passes, {"contour.skeleton"});
    EXPECT_FALSE(contourOnly.findPass("suggestive-object"));
    executor.run(contourOnly, {&gbufferPass, &contour, &object}, {128, 128, false});
    EXPECT_FALSE(gpuScene->meshCurvatureComputed()) << "a culled pass derived the curvature";

    const Plan both = compile(passes, {"contour.skeleton", "suggestive-object.skeleton"});
    // The object-space lines read only the depth from the G-buffer.
    EXPECT_EQ(both.findPass("gbuffer")->liveWrites, (std::vector<std::string>{"gbuffer.nDotV", "gbuffer.depth"}));
    executor.run(both, {&gbufferPass, &contour, &object}, {128, 128, false});
    EXPECT_TRUE(gpuScene->meshCurvatureComputed());
    EXPECT_TRUE(objectReport(object).curvatureDerived);
    EXPECT_GT(objectReport(object).curvatureMilliseconds, 0.0);
    EXPECT_GT(objectReport(object).segments, 0u);
    // Derived once per scene: the next frame reuses it.
    executor.run(both, {&gbufferPass, &contour, &object}, {128, 128, false});
    EXPECT_FALSE(objectReport(object).curvatureDerived);
    EXPECT_EQ(objectReport(object).curvatureMilliseconds, 0.0);

    EXPECT_THROW(LineLayerPass("no-kernel", nullptr, 1), std::invalid_argument);
    EXPECT_THROW(LineLayerPass("no-scale", kernelFor(objectSettings, *gpuScene, frame), 0), std::invalid_argument);
}

TEST_F(LineLayers, EveryKernelRepeatsExactly) {
    for (const Source source :
         {Source::Contour, Source::Suggestive, Source::SuggestiveObject, Source::DepthEdge, Source::NormalEdge}) {
        // A smooth torus has contours, suggestive contours and depth breaks; normal creases need a cube.
        if (source == Source::NormalEdge)
            look(makeCube({0.0f, 0.0f, 0.0f}, 1.0f), {2.5, 1.8, 2.0});
        else
            look(makeTorus(1.0f, 0.35f, 96, 48), {2.5, 1.0, 2.5});
        draw(withSource(source));
        const cv::Mat first = lineImage().clone();
        draw(withSource(source));
        EXPECT_EQ(cv::norm(first, lineImage(), cv::NORM_INF), 0.0) << "source " << int(source);
        EXPECT_GT(cv::countNonZero(first), 0) << "source " << int(source) << " found nothing on a torus";
    }
}

TEST_F(LineLayers, ReadsOnlyWhatItsKernelNeeds) {
    look(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 32, 16), {0.0, 0.0, 4.0});
    GpuScene scene2(scene, frame.worldOrigin);
    GBufferPass gbufferPass("gbuffer", shaders, scene2, frame);
    LineLayerPass depthEdges("depth-edge", kernelFor(withSource(Source::DepthEdge), scene2, frame), 1);
    const Plan plan = compile({&gbufferPass, &depthEdges}, {"depth-edge.skeleton"});
    EXPECT_EQ(plan.findPass("gbuffer")->liveWrites, std::vector<std::string>{"gbuffer.depth"});
    LineLayerPass suggestive("suggestive", kernelFor(withSource(Source::Suggestive), scene2, frame), 1);
    const Plan plan2 = compile({&gbufferPass, &suggestive}, {"suggestive.skeleton"});
    EXPECT_EQ(plan2.findPass("gbuffer")->liveWrites, (std::vector<std::string>{"gbuffer.depth", "gbuffer.radial"}));
}

} // namespace
} // namespace inkgraph
