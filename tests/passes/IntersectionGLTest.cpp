// The intersection line types end to end, through the line-type registry and the still graph as the app builds it.
// Two spheres (R 0.8 at x = +-0.45) cross on the circle x = 0, radius sqrt(0.8^2 - 0.45^2); seen obliquely, its near
// arc shows in the crease between them and its far arc lies behind them. Analytic expectation: each point of the exact
// circle is visible when the ray from the eye reaches it before entering either sphere; the `intersection` skeleton
// lies on the projected visible arc and covers it (F1 >= 0.95 at 1.5 px), the `hidden-intersection` skeleton on the
// hidden arc (F1 >= 0.90 at 1.5 px). Two boxes touching face to face draw no intersection point.
#include "graph/GraphCompiler.h"
#include "passes/StillGraph.h"
#include "passes/lines/LineLayerPass.h"
#include "passes/lines/LineTypes.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/PassHarness.h"
#include "tests/support/TestCamera.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace inkgraph::intersection_gl_test {
namespace {

constexpr int kSize = 256;
constexpr double kRadius = 0.8;
constexpr double kOffset = 0.45;
constexpr double kTolerancePixels = 1.5;

class Intersection : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override { test::sharedGlContext(); }

    /** Renders `meshes` with the two intersection types (or only `lines`, then fills nothing); fills the skeletons'
     *  points (output pixels). */
    void render(std::vector<Mesh> meshes, std::vector<std::string> lines = {"intersection", "hidden-intersection"}) {
        scene = Scene{};
        scene.meshes = std::move(meshes);
        frame.camera = test::lookingAt(scene, eye, glm::dvec3(0.0), 35.0, kSize, kSize);
        frame.worldOrigin = glm::dvec3(0.0);
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
        Look look;
        look.shading = ShadingModel::None;
        look.lines = lines;
        const bool intersections = lines.size() == 2 && lines[0] == "intersection";
        StillGraphSetup setup{look, shaders, scene, computeBoundingSphere(scene), *gpuScene, frame, std::nullopt};
        const StillGraph graph = buildStillGraph(setup);
        const Plan plan =
            intersections
                ? compile(graph.view(), {graph.finalResource, "intersection.skeleton", "hidden-intersection.skeleton"})
                : compile(graph.view(), {graph.finalResource});
        executor.run(plan, graph.mutableView(), {kSize, kSize, false});
        if (!intersections) return;
        visible = pointsOf("intersection.skeleton");
        hidden = pointsOf("hidden-intersection.skeleton");
    }

    std::vector<cv::Point2d> pointsOf(const std::string& resource) {
        std::vector<cv::Point2d> points;
        for (const LinePoint& point : executor.store().object<LineSkeleton>(resource).points)
            points.push_back({point.position.x, point.position.y});
        return points;
    }

    /** A world point in output pixels (x right, y down, pixel centres at integers). */
    cv::Point2d project(const glm::dvec3& world) const {
        const glm::dvec4 clip = frame.camera.projectionMatrix() * frame.camera.viewMatrix() * glm::dvec4(world, 1.0);
        return {(clip.x / clip.w + 1.0) * 0.5 * kSize - 0.5, (1.0 - clip.y / clip.w) * 0.5 * kSize - 0.5};
    }

    /** Whether the eye sees `point`, on both spheres' surfaces: the ray from the eye meets each sphere at t = 1 (the
     *  point) and at t = C / A (the product of the roots of |e + t d - c|^2 = R^2); the point is hidden when that
     *  other meeting comes first, the ray then entering the sphere before it. */
    bool analyticallyVisible(const glm::dvec3& point) const {
        const glm::dvec3 direction = point - frame.camera.eye;
        for (const double centre : {kOffset, -kOffset}) {
            const glm::dvec3 fromCentre = frame.camera.eye - glm::dvec3(centre, 0.0, 0.0);
            const double other =
                (glm::dot(fromCentre, fromCentre) - kRadius * kRadius) / glm::dot(direction, direction);
            if (other < 1.0 - 1e-9) return false;
        }
        return true;
    }

    glm::dvec3 eye{1.6, 1.2, 3.4};
    std::vector<cv::Point2d> visible, hidden;
};

double nearest(const cv::Point2d& point, const std::vector<cv::Point2d>& set) {
    double best = std::numeric_limits<double>::infinity();
    for (const cv::Point2d& other : set) best = std::min(best, std::hypot(point.x - other.x, point.y - other.y));
    return best;
}

/** F1 of `drawn` against `expected` (dense samples of the analytic curve) at `tolerance` pixels: precision, the share
 *  of drawn points within it of the curve; recall, the share of the curve's samples within it of a drawn point. */
double f1Score(const std::vector<cv::Point2d>& drawn, const std::vector<cv::Point2d>& expected, double tolerance,
               double* precisionOut = nullptr, double* recallOut = nullptr) {
    if (drawn.empty() || expected.empty()) return 0.0;
    std::size_t near = 0, covered = 0;
    for (const cv::Point2d& point : drawn)
        if (nearest(point, expected) <= tolerance) ++near;
    for (const cv::Point2d& point : expected)
        if (nearest(point, drawn) <= tolerance) ++covered;
    const double precision = double(near) / double(drawn.size());
    const double recall = double(covered) / double(expected.size());
    if (precisionOut) *precisionOut = precision;
    if (recallOut) *recallOut = recall;
    return precision + recall > 0.0 ? 2.0 * precision * recall / (precision + recall) : 0.0;
}

TEST_F(Intersection, TheSpheresCircleIsDrawnWhereVisibleAndHiddenWhereNot) {
    render({makeUvSphere({float(kOffset), 0.0f, 0.0f}, float(kRadius), 64, 32),
            makeUvSphere({float(-kOffset), 0.0f, 0.0f}, float(kRadius), 64, 32)});
    ASSERT_TRUE(gpuScene->meshIntersectionsComputed());
    EXPECT_GT(gpuScene->meshIntersections().segments.size(), 100u);

    // The exact circle, split by analytic visibility, in output pixels.
    const double circleRadius = std::sqrt(kRadius * kRadius - kOffset * kOffset);
    std::vector<cv::Point2d> visibleArc, hiddenArc;
    constexpr int kSamples = 4000;
    for (int i = 0; i < kSamples; ++i) {
        const double angle = 2.0 * glm::pi<double>() * i / kSamples;
        const glm::dvec3 point(0.0, circleRadius * std::cos(angle), circleRadius * std::sin(angle));
        (analyticallyVisible(point) ? visibleArc : hiddenArc).push_back(project(point));
    }
    // The view shows a real part of each.
    ASSERT_GT(visibleArc.size(), kSamples / 5);
    ASSERT_GT(hiddenArc.size(), kSamples / 5);

    double precision = 0.0, recall = 0.0;
    const double visibleF1 = f1Score(visible, visibleArc, kTolerancePixels, &precision, &recall);
    EXPECT_GE(visibleF1, 0.95) << "precision " << precision << ", recall " << recall;
    RecordProperty("visible_f1", std::to_string(visibleF1));
    RecordProperty("visible_precision", std::to_string(precision));
    RecordProperty("visible_recall", std::to_string(recall));
    const double hiddenF1 = f1Score(hidden, hiddenArc, kTolerancePixels, &precision, &recall);
    EXPECT_GE(hiddenF1, 0.90) << "precision " << precision << ", recall " << recall;
    RecordProperty("hidden_f1", std::to_string(hiddenF1));
    RecordProperty("hidden_precision", std::to_string(precision));
    RecordProperty("hidden_recall", std::to_string(recall));
    // A negative control for the metric: the visible line does not match the hidden arc.
    EXPECT_LT(f1Score(visible, hiddenArc, kTolerancePixels), 0.5);
}

TEST_F(Intersection, BoxesTouchingWithoutCrossingDrawNone) {
    render({makeCube({-0.5f, 0.0f, 0.0f}, 0.5f), makeCube({0.5f, 0.0f, 0.0f}, 0.5f)});
    EXPECT_TRUE(gpuScene->meshIntersections().segments.empty());
    EXPECT_GT(gpuScene->meshIntersections().report.pairsTested, 0u);
    EXPECT_TRUE(visible.empty());
    EXPECT_TRUE(hidden.empty());
}

TEST_F(Intersection, TheSegmentsAreDerivedOnlyWhenAnIntersectionTypeRuns) {
    render({makeCube({-0.5f, 0.0f, 0.0f}, 0.5f), makeCube({0.2f, 0.1f, 0.0f}, 0.5f)}, {"contour"});
    EXPECT_FALSE(gpuScene->meshIntersectionsComputed());
    render({makeCube({-0.5f, 0.0f, 0.0f}, 0.5f), makeCube({0.2f, 0.1f, 0.0f}, 0.5f)});
    EXPECT_TRUE(gpuScene->meshIntersectionsComputed());
    // Crossing boxes: their segments are drawn.
    EXPECT_FALSE(gpuScene->meshIntersections().segments.empty());
    EXPECT_FALSE(visible.empty());
}

TEST_F(Intersection, TheTypesAreRegisteredAsObjectSpaceWithTheirHiddenTwin) {
    const LineType* intersection = findLineType("intersection");
    const LineType* hiddenIntersection = findLineType("hidden-intersection");
    const LineType* hiddenSuggestive = findLineType("hidden-suggestive-object");
    ASSERT_TRUE(intersection && hiddenIntersection && hiddenSuggestive);
    EXPECT_EQ(intersection->family, LineFamily::ObjectSpace);
    EXPECT_FALSE(intersection->hiddenLines);
    EXPECT_TRUE(hiddenIntersection->hiddenLines);
    EXPECT_TRUE(hiddenSuggestive->hiddenLines);
}

} // namespace
} // namespace inkgraph::intersection_gl_test
