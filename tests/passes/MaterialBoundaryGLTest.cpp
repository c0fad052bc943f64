// The material-boundary and object-boundary line types end to end, through the line-type registry and the still
// graph as the app builds it: two boxes side by side, seen from above and to the right. Analytic expectation: where
// their materials (or objects) differ, one line along their shared visible edge (on the front face x = 0, z = h and
// the top face x = 0, y = h, projected by the camera), every point within 1 px of it and the whole edge covered;
// where the material is the same, none. The G-buffer's objectId field against a ray cast per pixel.
#include "graph/GraphCompiler.h"
#include "passes/StillGraph.h"
#include "passes/lines/LineLayerPass.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/PassHarness.h"
#include "tests/support/TestCamera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <limits>
#include <vector>

namespace inkgraph::material_boundary_gl_test {
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
        render({left, right}, {"material-boundary"}, supersample, {});
        return skeletonPoints("material-boundary", supersample);
    }

    /** Runs the still graph on these meshes with these line types, computing each type's skeleton and `extra`. */
    void render(std::vector<Mesh> meshes, std::vector<std::string> lines, int supersample,
                const std::vector<std::string>& extra) {
        scene = Scene{};
        scene.meshes = std::move(meshes);
        frame.camera = test::lookingAt(scene, eye, glm::dvec3(0.0), 35.0, kSize, kSize);
        frame.worldOrigin = glm::dvec3(0.0);
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
        Look look;
        look.shading = ShadingModel::None;
        look.lines = lines;
        look.supersample = supersample;
        StillGraphSetup setup{look, shaders, scene, computeBoundingSphere(scene), *gpuScene, frame, std::nullopt};
        const StillGraph graph = buildStillGraph(setup);
        std::vector<std::string> outputs = {graph.finalResource};
        for (const std::string& type : lines) outputs.push_back(type + ".skeleton");
        outputs.insert(outputs.end(), extra.begin(), extra.end());
        const Plan plan = compile(graph.view(), outputs);
        executor.run(plan, graph.mutableView(), {kSize, kSize, false});
    }

    /** The points of `type`'s skeleton from the last render(), in output pixels. */
    std::vector<cv::Point2d> skeletonPoints(const std::string& type, int supersample) {
        std::vector<cv::Point2d> points;
        for (const LinePoint& point : executor.store().object<LineSkeleton>(type + ".skeleton").points)
            points.push_back(
                {(point.position.x + 0.5) / supersample - 0.5, (point.position.y + 0.5) / supersample - 0.5});
        return points;
    }

    /** Which box the eye ray through output pixel (x, y) (centres at integers, y down) meets first: 1 the left, 2 the
     *  right, 0 neither. Slab intersection in double against the boxes as makeCube() builds them. */
    int boxSeenAt(double x, double y) const {
        const glm::dmat4 inverse = glm::inverse(frame.camera.projectionMatrix() * frame.camera.viewMatrix());
        const glm::dvec2 ndc((x + 0.5) / kSize * 2.0 - 1.0, 1.0 - (y + 0.5) / kSize * 2.0);
        const glm::dvec4 nearPoint = inverse * glm::dvec4(ndc, -1.0, 1.0);
        const glm::dvec4 farPoint = inverse * glm::dvec4(ndc, 1.0, 1.0);
        const glm::dvec3 origin = glm::dvec3(nearPoint) / nearPoint.w;
        const glm::dvec3 direction = glm::dvec3(farPoint) / farPoint.w - origin;
        int nearest = 0;
        double nearestT = std::numeric_limits<double>::infinity();
        for (int box = 1; box <= 2; ++box) {
            const glm::dvec3 lower(box == 1 ? -2.0 * kHalf : 0.0, -kHalf, -kHalf);
            const glm::dvec3 upper(box == 1 ? 0.0 : 2.0 * kHalf, kHalf, kHalf);
            double enter = 0.0, leave = std::numeric_limits<double>::infinity();
            for (int axis = 0; axis < 3; ++axis) {
                const double t0 = (lower[axis] - origin[axis]) / direction[axis];
                const double t1 = (upper[axis] - origin[axis]) / direction[axis];
                enter = std::max(enter, std::min(t0, t1));
                leave = std::min(leave, std::max(t0, t1));
            }
            if (enter <= leave && enter < nearestT) {
                nearestT = enter;
                nearest = box;
            }
        }
        return nearest;
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

TEST_F(MaterialBoundary, TwoObjectsOfOneMaterialGiveObjectIdsAndAnObjectBoundaryButNoMaterialBoundary) {
    // Issue 36: two boxes touching face to face, one material, two nodes (unnamed siblings: equal node paths, told
    // apart by their node instance, as the glTF reader sets it).
    Mesh left = makeCube({-kHalf, 0.0f, 0.0f}, kHalf);
    Mesh right = makeCube({kHalf, 0.0f, 0.0f}, kHalf);
    left.nodePath = right.nodePath = {"root", ""};
    left.nodeInstance = 1;
    right.nodeInstance = 2;
    render({left, right}, {"object-boundary", "material-boundary"}, 1, {"gbuffer.objectId"});

    // objectId: exactly 1 on the left box, 2 on the right, 0 off the model, wherever the ray cast agrees at the pixel
    // centre and 1 px around it (away from every projected edge, where a rasterised pixel may go either way).
    const cv::Mat ids = executor.store().image("gbuffer.objectId");
    ASSERT_EQ(ids.type(), CV_32FC1);
    ASSERT_EQ(ids.size(), cv::Size(kSize, kSize));
    int counted[3] = {0, 0, 0}, wrong = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const int box = boxSeenAt(x, y);
            bool clear = true;
            for (const auto& [dx, dy] : {std::pair{-1.0, 0.0},
                                         {1.0, 0.0},
                                         {0.0, -1.0},
                                         {0.0, 1.0},
                                         {-0.7, -0.7},
                                         {0.7, -0.7},
                                         {-0.7, 0.7},
                                         {0.7, 0.7}})
                clear = clear && boxSeenAt(x + dx, y + dy) == box;
            if (!clear) continue;
            ++counted[box];
            if (ids.at<float>(y, x) != float(box)) ++wrong;
        }
    EXPECT_EQ(wrong, 0) << "pixels away from the edges whose objectId is not their box's";
    EXPECT_GT(counted[0], 1000);
    EXPECT_GT(counted[1], 1000);
    EXPECT_GT(counted[2], 1000);
    RecordProperty("checked_pixels", std::to_string(counted[0] + counted[1] + counted[2]));

    // object-boundary: the shared visible edge, within 1 px and covered; material-boundary: nothing (one material).
    const std::vector<cv::Point2d> points = skeletonPoints("object-boundary", 1);
    const std::vector<cv::Point2d> edge = sharedEdge(2000);
    ASSERT_GT(points.size(), 50u);
    double worst = 0.0;
    for (const cv::Point2d& point : points) worst = std::max(worst, distanceToPolyline(point, edge));
    EXPECT_LE(worst, 1.0) << "an object-boundary point lies off the shared edge";
    const std::vector<cv::Point2d> sparse = sharedEdge(200);
    std::size_t covered = 0, interior = 0;
    for (std::size_t i = 4; i + 4 < sparse.size(); ++i, ++interior)
        if (distanceToPolyline(sparse[i], points) <= 1.0) ++covered;
    EXPECT_EQ(covered, interior);
    EXPECT_TRUE(skeletonPoints("material-boundary", 1).empty());
    RecordProperty("object_boundary_worst_px", std::to_string(worst));
}

TEST_F(MaterialBoundary, MeshesOfOneNodeInstanceAreOneObject) {
    // Two primitives of one node: one object, so neither an object boundary nor a second id.
    Mesh left = makeCube({-kHalf, 0.0f, 0.0f}, kHalf);
    Mesh right = makeCube({kHalf, 0.0f, 0.0f}, kHalf);
    left.nodePath = right.nodePath = {"boxes"};
    render({left, right}, {"object-boundary"}, 1, {"gbuffer.objectId"});
    EXPECT_TRUE(skeletonPoints("object-boundary", 1).empty());
    double lowest = 0.0, highest = 0.0;
    cv::minMaxLoc(executor.store().image("gbuffer.objectId"), &lowest, &highest);
    EXPECT_EQ(lowest, 0.0);
    EXPECT_EQ(highest, 1.0);
}

} // namespace
} // namespace inkgraph::material_boundary_gl_test
