// strokeRecords() (passes/lines/StrokePoints.h) on hand-made strokes, without GL: image-space points on the camera ray
// at the nearer surface's depth, mapped from the supersampled data pixels to output pixels; object-space points from
// their skeleton's own 3-D points with global triangle numbers; mesh-edge points from a point image, bridges between.
#include "passes/lines/StrokePoints.h"

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <numeric>

namespace inkgraph {
namespace {

Camera testCamera() {
    Camera camera;
    camera.origin = {100.0, -20.0, 5.0}; // world = origin + local
    camera.eye = {0.0, 0.0, 5.0};
    camera.target = {0.0, 0.0, 0.0};
    camera.fovYDegrees = 40.0;
    camera.zNear = 0.1;
    camera.zFar = 50.0;
    camera.width = 32;
    camera.height = 24;
    return camera;
}

glm::dvec2 project(const Camera& camera, const glm::dvec3& world) {
    const glm::dmat3 K = camera.openCvIntrinsics();
    const glm::dmat4x3 Rt = camera.openCvExtrinsics();
    const glm::dvec3 x = K * (glm::dmat3(Rt[0], Rt[1], Rt[2]) * world + Rt[3]);
    return glm::dvec2(x) / x.z;
}

/** The view-space point at linear depth `depth` that pixel (col, row)'s centre sees. */
cv::Vec4f viewPointAt(const Camera& camera, double col, double row, double depth, float triangleId) {
    const glm::dmat3 K = camera.openCvIntrinsics();
    return {float((col - K[2][0]) / K[0][0] * depth), float(-(row - K[2][1]) / K[1][1] * depth), float(-depth),
            triangleId};
}

/** A scene of meshes with these numbers of triangles (indices only: the numbering reads nothing else). */
Scene sceneOfTriangleCounts(const std::vector<std::size_t>& counts) {
    Scene scene;
    for (const std::size_t count : counts) {
        Mesh mesh;
        mesh.triangles.assign(count, glm::uvec3(0, 1, 2));
        scene.meshes.push_back(std::move(mesh));
    }
    return scene;
}

Stroke strokeOf(int layer, const std::vector<cv::Point2f>& positions, const std::vector<cv::Point>& pixels) {
    Stroke stroke;
    stroke.layer = layer;
    stroke.kept = true;
    for (const cv::Point2f& position : positions) stroke.points.push_back({position, 1.0f});
    stroke.pixels = pixels;
    return stroke;
}

TEST(StrokePointsTest, ImageSpacePointsLieOnTheirRayAtTheNearerSurfacesDepth) {
    const Camera camera = testCamera();
    const int scale = 2; // --supersample 2: data pixels 64 x 48
    DrawnStrokes drawn;
    drawn.supersample = scale;
    drawn.inputs = {StrokeInput{"contour", "contour.skeleton"}};
    // Depth 4 on the left half, 6 (farther) on the right, background in the bottom rows.
    cv::Mat depth(48, 64, CV_32FC1, cv::Scalar(4.0f));
    depth.colRange(32, 64).setTo(6.0f);
    depth.rowRange(40, 48).setTo(0.0f);
    // On the left surface; on the edge between the two (the nearer wins); on the model's lower rim; off the model.
    drawn.strokes.strokes.push_back(strokeOf(0, {{10.25f, 12.5f}, {31.5f, 20.0f}, {20.0f, 39.5f}, {20.0f, 45.0f}},
                                             {{10, 13}, {32, 20}, {20, 40}, {20, 45}}));
    StrokePointSetup setup;
    setup.drawn = &drawn;
    setup.inputs = {StrokePointInput{}};
    setup.depth = depth;
    setup.camera = &camera;
    const std::vector<StrokeRecord> records = strokeRecords(setup);
    ASSERT_EQ(records.size(), 1u);
    const StrokeRecord& stroke = records[0];
    EXPECT_EQ(stroke.type, "contour");
    EXPECT_TRUE(stroke.visible);
    ASSERT_EQ(stroke.points.size(), 4u);
    // Data pixel p maps to output pixel (p + 0.5) / 2 - 0.5.
    EXPECT_DOUBLE_EQ(stroke.points[0].x, (10.25 + 0.5) / 2 - 0.5);
    EXPECT_DOUBLE_EQ(stroke.points[0].y, (12.5 + 0.5) / 2 - 0.5);
    const double expectedDepth[3] = {4.0, 4.0, 4.0};
    for (int index = 0; index < 3; ++index) {
        const StrokePointRecord& point = stroke.points[std::size_t(index)];
        ASSERT_TRUE(point.world.has_value()) << index;
        const glm::dvec2 pixel = project(camera, *point.world);
        EXPECT_NEAR(pixel.x, point.x, 1e-4) << index; // on the ray through (x, y), up to the 7-digit rounding
        EXPECT_NEAR(pixel.y, point.y, 1e-4) << index;
        // The linear view depth: the distance along the view axis (-z) from the eye.
        const glm::dvec3 view = glm::dvec3(camera.worldViewMatrix() * glm::dvec4(*point.world, 1.0));
        EXPECT_NEAR(-view.z, expectedDepth[index], 1e-5) << index;
        EXPECT_EQ(point.mesh, 0);      // no triangle ids given
        EXPECT_EQ(point.triangle, -1); // no triangle ids given
    }
    EXPECT_FALSE(stroke.points[3].world.has_value()); // nothing under it within a pixel
}

TEST(StrokePointsTest, TriangleIdsNameTheTriangleAndItsMesh) {
    const Camera camera = testCamera();
    DrawnStrokes drawn;
    drawn.inputs = {StrokeInput{"depth-edge", "depth-edge.skeleton"}};
    drawn.strokes.strokes.push_back(strokeOf(0, {{5.0f, 5.0f}}, {{5, 5}}));
    StrokePointSetup setup;
    setup.drawn = &drawn;
    setup.inputs = {StrokePointInput{}};
    setup.depth = cv::Mat(24, 32, CV_32FC1, cv::Scalar(3.0f));
    setup.triangleIds = cv::Mat(24, 32, CV_32FC1, cv::Scalar(0.0f));
    setup.triangleIds.at<float>(5, 5) = 1500.0f + 1.0f; // global triangle 1500 (id = index + 1)
    setup.camera = &camera;
    // The file gave the first mesh 1000 triangles, of which the loader dropped one: its numbers still end at 999, so
    // 1500 lies in the second mesh.
    Scene scene = sceneOfTriangleCounts({999, 1000, 5});
    scene.meshes[0].fileTriangleCount = 1000;
    scene.meshes[0].fileTriangles.resize(999);
    std::iota(scene.meshes[0].fileTriangles.begin(), scene.meshes[0].fileTriangles.end(), 1u);
    const TriangleNumbering numbering(scene);
    setup.numbering = &numbering;
    const StrokePointRecord point = strokeRecords(setup).at(0).points.at(0);
    EXPECT_EQ(point.triangle, 1500);
    EXPECT_EQ(point.mesh, 2);
}

TEST(StrokePointsTest, ObjectSpaceAndMeshEdgePointsAreTheirOwn3DPoints) {
    const Camera camera = testCamera();
    DrawnStrokes drawn;
    StrokeInput hidden{"hidden-intersection", "hidden-intersection.skeleton"};
    hidden.dashed = true;
    drawn.inputs = {hidden, StrokeInput{"crease", "crease.skeleton"}};
    // The object-space skeleton: two samples with their 3-D points (local frame) on mesh 1, triangles 7 and 8.
    LineSkeleton skeleton;
    skeleton.mask = cv::Mat::zeros(24, 32, CV_8UC1);
    skeleton.points = {{{4.2f, 6.1f}, 1.0f}, {{5.1f, 6.3f}, 1.0f}};
    skeleton.surface = {{{0.1, 0.2, 0.3}, 1, 7}, {{0.2, 0.2, 0.3}, 1, 8}};
    drawn.strokes.strokes.push_back(strokeOf(0, {{4.2f, 6.1f}, {5.1f, 6.3f}}, {{4, 6}, {5, 6}}));
    // The mesh-edge point image: view positions and triangle id + 1 at two pixels; the point between them is a bridge.
    cv::Mat image(24, 32, CV_32FC4, cv::Scalar(0, 0, 0, 0));
    image.at<cv::Vec4f>(10, 10) = viewPointAt(camera, 10, 10, 4.0, 3.0f);
    image.at<cv::Vec4f>(10, 14) = viewPointAt(camera, 14, 10, 4.0, 3.0f);
    drawn.strokes.strokes.push_back(
        strokeOf(1, {{10.0f, 10.0f}, {12.0f, 10.0f}, {14.0f, 10.0f}}, {{10, 10}, {-1, -1}, {14, 10}}));
    StrokePointSetup setup;
    setup.drawn = &drawn;
    StrokePointInput object;
    object.source = StrokePointSource::Skeleton;
    object.skeleton = &skeleton;
    object.visible = false;
    StrokePointInput edges;
    edges.source = StrokePointSource::Image;
    edges.image = image;
    setup.inputs = {object, edges};
    setup.depth = cv::Mat(24, 32, CV_32FC1, cv::Scalar(0.0f));
    setup.camera = &camera;
    // The file gave mesh 1 eleven triangles, of which the loader dropped 2 and 5: its triangle 7 is the file's 9.
    Scene scene = sceneOfTriangleCounts({100, 9});
    scene.meshes[1].fileTriangles = {0, 1, 3, 4, 6, 7, 8, 9, 10};
    scene.meshes[1].fileTriangleCount = 11;
    const TriangleNumbering numbering(scene);
    setup.numbering = &numbering;
    const std::vector<StrokeRecord> records = strokeRecords(setup);
    ASSERT_EQ(records.size(), 2u);
    EXPECT_FALSE(records[0].visible);
    ASSERT_TRUE(records[0].points[1].world.has_value());
    const glm::dvec3 world = *records[0].points[1].world;
    EXPECT_NEAR(world.x, 100.2, 1e-4); // the local point plus the origin
    EXPECT_NEAR(world.y, -19.8, 1e-4);
    EXPECT_NEAR(world.z, 5.3, 1e-4);
    EXPECT_EQ(records[0].points[0].triangle, 109); // mesh 1's triangle 7 (the file's 9), after mesh 0's 100
    EXPECT_EQ(records[0].points[1].triangle, 110); // its 8 (the file's 10)
    EXPECT_EQ(records[0].points[1].mesh, 2);
    // The crease: the image's view positions back in the world, the bridge halfway between them.
    const glm::dmat4 worldFromView = glm::inverse(camera.worldViewMatrix());
    const cv::Vec4f firstView = image.at<cv::Vec4f>(10, 10), lastView = image.at<cv::Vec4f>(10, 14);
    const glm::dvec3 first = glm::dvec3(worldFromView * glm::dvec4(firstView[0], firstView[1], firstView[2], 1.0));
    const glm::dvec3 last = glm::dvec3(worldFromView * glm::dvec4(lastView[0], lastView[1], lastView[2], 1.0));
    const std::vector<StrokePointRecord>& crease = records[1].points;
    ASSERT_EQ(crease.size(), 3u);
    EXPECT_TRUE(records[1].visible);
    EXPECT_NEAR(glm::length(*crease[0].world - first), 0.0, 1e-4);
    EXPECT_NEAR(glm::length(*crease[2].world - last), 0.0, 1e-4);
    EXPECT_NEAR(glm::length(*crease[1].world - 0.5 * (first + last)), 0.0, 1e-4);
    EXPECT_EQ(crease[1].triangle, 2);
    EXPECT_EQ(crease[1].mesh, 1);
}

/** strokeRecords() of `strokes` of one object-space type (intersection) whose skeleton has the samples `points` at the
 *  3-D points `surface`, on a scene of one mesh of 9 triangles. */
std::vector<StrokeRecord> objectSpaceStrokeRecords(std::vector<Stroke> strokes, std::vector<LinePoint> points,
                                                   std::vector<SurfacePoint> surface) {
    const Camera camera = testCamera();
    DrawnStrokes drawn;
    drawn.inputs = {StrokeInput{"intersection", "intersection.skeleton"}};
    drawn.strokes.strokes = std::move(strokes);
    LineSkeleton skeleton;
    skeleton.mask = cv::Mat::zeros(24, 32, CV_8UC1);
    skeleton.points = std::move(points);
    skeleton.surface = std::move(surface);
    StrokePointSetup setup;
    setup.drawn = &drawn;
    StrokePointInput object;
    object.source = StrokePointSource::Skeleton;
    object.skeleton = &skeleton;
    setup.inputs = {object};
    setup.depth = cv::Mat(24, 32, CV_32FC1, cv::Scalar(0.0f));
    setup.camera = &camera;
    const Scene scene = sceneOfTriangleCounts({9});
    const TriangleNumbering numbering(scene);
    setup.numbering = &numbering;
    return strokeRecords(setup);
}

TEST(StrokePointsTest, APointTheStrokeStagePlacedTwiceIsWrittenOnce) {
    // Two of the stroke stage's points at one spot: written twice, a segment of no length, on which a reader's tangent
    // divides by zero (870 such places in a hostile pass's strokes files).
    const std::vector<StrokeRecord> records = objectSpaceStrokeRecords(
        {strokeOf(0, {{4.2f, 6.1f}, {4.2f, 6.1f}, {5.1f, 6.3f}, {4.2f, 6.1f}}, {{4, 6}, {4, 6}, {5, 6}, {4, 6}})},
        {{{4.2f, 6.1f}, 1.0f}, {{5.1f, 6.3f}, 1.0f}}, {{{0.1, 0.2, 0.3}, 0, 7}, {{0.2, 0.2, 0.3}, 0, 8}});
    ASSERT_EQ(records.size(), 1u);
    const std::vector<StrokePointRecord>& points = records[0].points;
    ASSERT_EQ(points.size(), 3u) << "the repeated point once; the same spot again after another is kept";
    EXPECT_EQ(points[0].triangle, 7);
    EXPECT_EQ(points[1].triangle, 8);
    EXPECT_EQ(points[2].triangle, 7);
}

TEST(StrokePointsTest, AClosedStrokeNeverRepeatsItsFirstPointAndEnclosesSomething) {
    // Closed strokes as the stroke stage may leave them at tiny sizes: a loop whose last point came out on its first,
    // and loops of two and of one distinct point. Written closed only where three points or more remain.
    const std::vector<std::vector<cv::Point2f>> loops = {{{4.0f, 6.0f}, {5.0f, 6.0f}, {5.0f, 7.0f}, {4.0f, 6.0f}},
                                                         {{4.0f, 6.0f}, {5.0f, 6.0f}, {4.0f, 6.0f}},
                                                         {{4.0f, 6.0f}, {5.0f, 6.0f}},
                                                         {{4.0f, 6.0f}}};
    std::vector<Stroke> strokes;
    for (const std::vector<cv::Point2f>& loop : loops) {
        std::vector<cv::Point> pixels;
        for (const cv::Point2f& point : loop) pixels.emplace_back(int(point.x), int(point.y));
        strokes.push_back(strokeOf(0, loop, pixels));
        strokes.back().closed = true;
    }
    const std::vector<StrokeRecord> records =
        objectSpaceStrokeRecords(strokes, {{{4.0f, 6.0f}, 1.0f}, {{5.0f, 6.0f}, 1.0f}, {{5.0f, 7.0f}, 1.0f}},
                                 {{{0.1, 0.2, 0.3}, 0, 1}, {{0.2, 0.2, 0.3}, 0, 2}, {{0.2, 0.3, 0.3}, 0, 3}});
    ASSERT_EQ(records.size(), 4u);
    EXPECT_TRUE(records[0].closed);
    EXPECT_EQ(records[0].points.size(), 3u) << "the first point once";
    for (std::size_t index = 1; index < 4; ++index) {
        EXPECT_FALSE(records[index].closed) << index;
        EXPECT_EQ(records[index].points.size(), index == 3 ? 1u : 2u) << index;
    }
}

TEST(StrokePointsTest, RefusesMissingInputs) {
    const Camera camera = testCamera();
    DrawnStrokes drawn;
    drawn.inputs = {StrokeInput{"intersection", "intersection.skeleton"}};
    StrokePointSetup setup;
    setup.drawn = &drawn;
    setup.camera = &camera;
    setup.depth = cv::Mat(24, 32, CV_32FC1, cv::Scalar(0.0f));
    setup.inputs = {StrokePointInput{StrokePointSource::Skeleton}};
    EXPECT_THROW(strokeRecords(setup), std::invalid_argument); // no skeleton
    setup.inputs = {StrokePointInput{}};
    setup.depth = cv::Mat(12, 16, CV_32FC1, cv::Scalar(0.0f));
    EXPECT_THROW(strokeRecords(setup), std::invalid_argument); // the depth is not at the data size
    setup.drawn = nullptr;
    EXPECT_THROW(strokeRecords(setup), std::invalid_argument);
}

} // namespace
} // namespace inkgraph
