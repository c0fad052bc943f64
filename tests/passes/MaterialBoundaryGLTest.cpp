// The material-boundary line type end to end, through the line-type registry and the still graph as the app builds
// it: two boxes side by side, seen from above and to the right. Analytic expectation: where their materials differ,
// one line along their shared visible edge (on the front face x = 0, z = h and the top face x = 0, y = h, projected
// by the camera), every point within 1 px of it and the whole edge covered; where the material is the same, none.
#include "graph/GraphCompiler.h"
#include "passes/StillGraph.h"
#include "passes/lines/LineLayerPass.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/PassHarness.h"
#include "tests/support/TestCamera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace inkgraph {
namespace {

constexpr int kSize = 256;
constexpr float kHalf = 0.5f; ///< half the side of each box

class MaterialBoundary : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override { test::sharedGlContext(); }

    /** Renders the two boxes (left x in [-1, 0], right x in [0, 1]) with these base colours; returns the skeleton's
     *  points in output pixels. */
    std::vector<cv::Point2d> boundaryPoints(glm::vec4 leftColor, glm::vec4 rightColor, int supersample = 1) {
        Mesh left = makeCube({-kHalf, 0.0f, 0.0f}, kHalf);
        Mesh right = makeCube({kHalf, 0.0f, 0.0f}, kHalf);
        left.material.baseColorFactor = leftColor;
        right.material.baseColorFactor = rightColor;
        scene = Scene{};
        scene.meshes = {left, right};
        frame.camera = test::lookingAt(scene, eye, glm::dvec3(0.0), 35.0, kSize, kSize);
        frame.worldOrigin = glm::dvec3(0.0);
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
        Look look;
        look.shading = ShadingModel::None;
        look.lines = {"material-boundary"};
        look.supersample = supersample;
        StillGraphSetup setup{look, shaders, scene, computeBoundingSphere(scene), *gpuScene, frame, std::nullopt};
        const StillGraph graph = buildStillGraph(setup);
        const Plan plan = compile(graph.view(), {graph.finalResource, "material-boundary.skeleton"});
        executor.run(plan, graph.mutableView(), {kSize, kSize, false});
        std::vector<cv::Point2d> points;
        for (const LinePoint& point : executor.store().object<LineSkeleton>("material-boundary.skeleton").points)
            points.push_back(
                {(point.position.x + 0.5) / supersample - 0.5, (point.position.y + 0.5) / supersample - 0.5});
        return points;
    }

    /** A world point in output pixels (x right, y down, pixel centres at integers). */
    cv::Point2d project(const glm::dvec3& world) const {
        const glm::dvec4 clip = frame.camera.projectionMatrix() * frame.camera.viewMatrix() * glm::dvec4(world, 1.0);
        return {(clip.x / clip.w + 1.0) * 0.5 * kSize - 0.5, (1.0 - clip.y / clip.w) * 0.5 * kSize - 0.5};
    }

    /** The shared visible edge: down the front face, then back across the top face. */
    std::vector<cv::Point2d> sharedEdge(int samples) const {
        std::vector<cv::Point2d> edge;
        for (int i = 0; i <= samples; ++i) {
            const double t = double(i) / samples;
            edge.push_back(project({0.0, -kHalf + t * 2 * kHalf, kHalf})); // front face, bottom to top
            edge.push_back(project({0.0, kHalf, kHalf - t * 2 * kHalf}));  // top face, front to back
        }
        return edge;
    }

    glm::dvec3 eye{1.2, 1.6, 4.0};
};

double distanceToPolyline(const cv::Point2d& point, const std::vector<cv::Point2d>& dense) {
    double best = std::numeric_limits<double>::infinity();
    for (const cv::Point2d& sample : dense) best = std::min(best, std::hypot(point.x - sample.x, point.y - sample.y));
    return best;
}

TEST_F(MaterialBoundary, DifferentMaterialsGiveOneLineAlongTheSharedVisibleEdge) {
    for (const int supersample : {1, 2}) {
        SCOPED_TRACE("supersample " + std::to_string(supersample));
        const std::vector<cv::Point2d> points =
            boundaryPoints({0.8f, 0.2f, 0.2f, 1.0f}, {0.2f, 0.2f, 0.8f, 1.0f}, supersample);
        const std::vector<cv::Point2d> edge = sharedEdge(2000);
        ASSERT_GT(points.size(), 50u);
        double worst = 0.0;
        for (const cv::Point2d& point : points) worst = std::max(worst, distanceToPolyline(point, edge));
        EXPECT_LE(worst, 1.0) << "a boundary point lies off the shared edge";
        // Covered: every point of the edge (but its very ends, where the boxes meet the background) has a line point
        // within a pixel.
        const std::vector<cv::Point2d> sparse = sharedEdge(200);
        std::size_t covered = 0, interior = 0;
        for (std::size_t i = 4; i + 4 < sparse.size(); ++i, ++interior)
            if (distanceToPolyline(sparse[i], points) <= 1.0) ++covered;
        EXPECT_EQ(covered, interior);
        RecordProperty("worst_px_s" + std::to_string(supersample), std::to_string(worst));
    }
}

TEST_F(MaterialBoundary, TheSameMaterialGivesNoLine) {
    EXPECT_TRUE(boundaryPoints({0.5f, 0.5f, 0.5f, 1.0f}, {0.5f, 0.5f, 0.5f, 1.0f}).empty());
}

} // namespace
} // namespace inkgraph
