// FrameParams::boundScene() and scenePixels(): where the scene's triangles can cover the frame, from the projection of
// its vertices, against the pinhole's closed form. No GL.
#include "passes/FrameParams.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/TestCamera.h"

#include <gtest/gtest.h>

#include <cmath>

namespace inkgraph {
namespace {

/** Two triangles at depth `depth` in front of an eye at the origin looking down -z, spanning [x0, x1] x [y0, y1]. */
Scene quadAt(double x0, double x1, double y0, double y1, double depth) {
    Mesh mesh;
    const float z = float(-depth);
    mesh.positions = {
        {float(x0), float(y0), z}, {float(x1), float(y0), z}, {float(x1), float(y1), z}, {float(x0), float(y1), z}};
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    return makeScene(mesh);
}

/** The frame of a 90-degree, width x height camera at the origin looking down -z, positions relative to the origin. */
FrameParams frameOf(const Scene& scene, int width, int height) {
    FrameParams frame;
    frame.camera = test::lookingAt(scene, glm::dvec3(0.0), glm::dvec3(0.0, 0.0, -1.0), 90.0, width, height);
    return frame;
}

TEST(SceneBounds, AreTheProjectionOfTheVertices) {
    // A 90-degree vertical field of view: y_ndc = y / depth, x_ndc = y_ndc's scale over the aspect (2 here).
    const Scene scene = quadAt(-1.0, 3.0, -0.5, 1.5, 4.0);
    FrameParams frame = frameOf(scene, 200, 100);
    frame.boundScene(scene);
    EXPECT_NEAR(frame.sceneLow.x, -1.0 / 4.0 / 2.0, 1e-6);
    EXPECT_NEAR(frame.sceneHigh.x, 3.0 / 4.0 / 2.0, 1e-6);
    EXPECT_NEAR(frame.sceneLow.y, -0.5 / 4.0, 1e-6);
    EXPECT_NEAR(frame.sceneHigh.y, 1.5 / 4.0, 1e-6);
    // NDC [-0.125, 0.375] x [-0.125, 0.375] -> window x [87.5, 137.5], y [43.75, 68.75]; one pixel more each side.
    EXPECT_EQ(frame.scenePixels(200, 100), (PixelRect{86, 42, 53, 28}));
    // At twice the size (a supersampled field) the same bounds cover twice the pixels.
    EXPECT_EQ(frame.scenePixels(400, 200), (PixelRect{174, 86, 102, 53}));
}

TEST(SceneBounds, AreTheWholeFrameUntilBoundAndWhenAVertexIsBehindTheEye) {
    const Scene scene = quadAt(-1.0, 1.0, -1.0, 1.0, 4.0);
    FrameParams frame = frameOf(scene, 64, 48);
    EXPECT_EQ(frame.scenePixels(64, 48), (PixelRect{0, 0, 64, 48}));
    Scene behind = scene;
    behind.meshes[0].positions[2].z = 0.5f; // behind the eye: its image is no bound
    frame.boundScene(behind);
    EXPECT_EQ(frame.scenePixels(64, 48), (PixelRect{0, 0, 64, 48}));
    Scene atTheEye = scene;
    atTheEye.meshes[0].positions[1] = glm::vec3(0.0f);
    frame.boundScene(atTheEye);
    EXPECT_EQ(frame.scenePixels(64, 48), (PixelRect{0, 0, 64, 48}));
}

TEST(SceneBounds, ClampToTheFrameAndAreEmptyForAModelOutsideItOrNone) {
    FrameParams frame = frameOf(quadAt(-1.0, 1.0, -1.0, 1.0, 4.0), 64, 64);
    // Half off the right edge: clamped there.
    Scene right = quadAt(2.0, 40.0, -1.0, 1.0, 4.0);
    frame.boundScene(right);
    const PixelRect clamped = frame.scenePixels(64, 64);
    EXPECT_EQ(clamped.x + clamped.width, 64);
    EXPECT_EQ(clamped.x, 47); // x_ndc = 2 / 4 -> window (1.5 / 2) 64 = 48, less the pixel for rounding
    // Wholly beyond the left edge, and no vertex at all: nothing to shade or read back.
    Scene left = quadAt(-400.0, -300.0, -1.0, 1.0, 4.0);
    frame.boundScene(left);
    EXPECT_EQ(frame.scenePixels(64, 64).width, 0);
    Scene empty;
    frame.boundScene(empty);
    const PixelRect none = frame.scenePixels(64, 64);
    EXPECT_EQ(none.width * none.height, 0);
}

} // namespace
} // namespace inkgraph
