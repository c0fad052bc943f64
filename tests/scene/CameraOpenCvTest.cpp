/** @file Camera::openCvIntrinsics() and openCvExtrinsics() against the OpenGL projection the renderer draws with:
 *  the same pixel for every point, the target at the image centre, a proper rotation, and no precision lost to a
 *  large scene origin. No GL: the G-buffer check is tests/app/OpenCvCameraGLTest.cpp. */
#include "scene/Camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace inkgraph {
namespace {

/** A non-square image, an origin far from zero and an up that is neither an axis nor perpendicular to the view. */
Camera skewedCamera(const glm::dvec3& origin = {2.5e5, -1.25e5, 7.5e4}) {
    Camera camera;
    camera.origin = origin;
    camera.eye = {3.0, -1.5, 2.0};
    camera.target = {-0.4, 0.7, 0.2};
    camera.up = {0.3, 0.2, 1.0};
    camera.fovYDegrees = 40.0;
    camera.zNear = 0.1;
    camera.zFar = 50.0;
    camera.width = 640;
    camera.height = 360;
    return camera;
}

/** Where OpenGL draws world point `world`: its window position with row 0 at the top, less half a pixel so that the
 *  centre of pixel (col, row) is (col, row), as OpenCV counts. */
glm::dvec2 openGlPixel(const Camera& camera, const glm::dvec3& world) {
    const glm::dvec4 clip = camera.projectionMatrix() * camera.viewMatrix() * glm::dvec4(world - camera.origin, 1.0);
    const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
    return {(ndc.x + 1.0) / 2.0 * camera.width - 0.5, (1.0 - ndc.y) / 2.0 * camera.height - 0.5};
}

glm::dvec3 openCvCameraPoint(const Camera& camera, const glm::dvec3& world) {
    const glm::dmat4x3 extrinsics = camera.openCvExtrinsics();
    return glm::dmat3(extrinsics[0], extrinsics[1], extrinsics[2]) * world + extrinsics[3];
}

glm::dvec2 openCvPixel(const Camera& camera, const glm::dvec3& world) {
    const glm::dvec3 image = camera.openCvIntrinsics() * openCvCameraPoint(camera, world);
    return glm::dvec2(image) / image.z;
}

TEST(OpenCvCamera, IntrinsicsAreTheFocalLengthAndTheCentreLessHalfAPixel) {
    const Camera camera = skewedCamera();
    const glm::dmat3 k = camera.openCvIntrinsics();
    // Column-major: k[column][row].
    EXPECT_EQ(k[0][0], camera.focalPixels());
    EXPECT_EQ(k[1][1], camera.focalPixels());
    EXPECT_EQ(k[2][0], 319.5);
    EXPECT_EQ(k[2][1], 179.5);
    EXPECT_EQ(k[2][2], 1.0);
    EXPECT_EQ(k[1][0], 0.0); // no skew
    EXPECT_EQ(k[0][1], 0.0);
    EXPECT_EQ(k[0][2], 0.0);
    EXPECT_EQ(k[1][2], 0.0);
}

TEST(OpenCvCamera, ExtrinsicsAreAProperRotationAndPutTheEyeAtZero) {
    const Camera camera = skewedCamera();
    const glm::dmat4x3 extrinsics = camera.openCvExtrinsics();
    const glm::dmat3 rotation(extrinsics[0], extrinsics[1], extrinsics[2]);
    const glm::dmat3 product = glm::transpose(rotation) * rotation;
    for (int column = 0; column < 3; ++column)
        for (int row = 0; row < 3; ++row) EXPECT_NEAR(product[column][row], column == row ? 1.0 : 0.0, 1e-14);
    EXPECT_NEAR(glm::determinant(rotation), 1.0, 1e-14);
    // The eye is the camera centre; the target lies straight ahead (+z) at its distance.
    const glm::dvec3 eye = openCvCameraPoint(camera, camera.worldEye());
    EXPECT_NEAR(glm::length(eye), 0.0, 1e-9);
    const glm::dvec3 target = openCvCameraPoint(camera, camera.worldTarget());
    EXPECT_NEAR(target.x, 0.0, 1e-9);
    EXPECT_NEAR(target.y, 0.0, 1e-9);
    EXPECT_NEAR(target.z, glm::length(camera.target - camera.eye), 1e-9);
    // y is down: the world up, seen from the eye, points to -y (up is not perpendicular to the view here, so only its
    // component across the view is compared).
    const glm::dvec3 up = glm::dmat3(extrinsics[0], extrinsics[1], extrinsics[2]) * glm::normalize(camera.up);
    EXPECT_LT(up.y, -0.5);
    EXPECT_NEAR(up.x, 0.0, 1e-12);
}

TEST(OpenCvCamera, ProjectsEveryPointWhereOpenGlDrawsIt) {
    const Camera camera = skewedCamera();
    const glm::dvec2 centre = openCvPixel(camera, camera.worldTarget());
    EXPECT_NEAR(centre.x, 319.5, 1e-6);
    EXPECT_NEAR(centre.y, 179.5, 1e-6);

    // Points around the target, near and far, in every direction of the view; every one must land on the pixel
    // OpenGL's projection * view gives it, and OpenCV's depth z must be OpenGL's view depth -z_view.
    int inFront = 0;
    for (double dx : {-1.3, 0.0, 0.9})
        for (double dy : {-0.8, 0.0, 1.1})
            for (double dz : {-1.7, 0.0, 0.6}) {
                const glm::dvec3 world = camera.worldTarget() + glm::dvec3(dx, dy, dz);
                const glm::dvec3 cameraPoint = openCvCameraPoint(camera, world);
                const double viewDepth = -(camera.viewMatrix() * glm::dvec4(world - camera.origin, 1.0)).z;
                EXPECT_NEAR(cameraPoint.z, viewDepth, 1e-9);
                if (viewDepth <= camera.zNear) continue;
                ++inFront;
                const glm::dvec2 gl = openGlPixel(camera, world);
                const glm::dvec2 cv = openCvPixel(camera, world);
                EXPECT_NEAR(cv.x, gl.x, 1e-6) << dx << "," << dy << "," << dz;
                EXPECT_NEAR(cv.y, gl.y, 1e-6) << dx << "," << dy << "," << dz;
            }
    EXPECT_GT(inFront, 20);

    // And back: depth x K^-1 (u, v, 1) is the camera point, R^T (that - t) the world point.
    const glm::dvec3 world = camera.worldTarget() + glm::dvec3(0.4, -0.3, 0.2);
    const glm::dvec2 pixel = openCvPixel(camera, world);
    const double depth = openCvCameraPoint(camera, world).z;
    const glm::dmat4x3 extrinsics = camera.openCvExtrinsics();
    const glm::dmat3 rotation(extrinsics[0], extrinsics[1], extrinsics[2]);
    const glm::dvec3 back =
        glm::transpose(rotation) *
        (depth * (glm::inverse(camera.openCvIntrinsics()) * glm::dvec3(pixel, 1.0)) - extrinsics[3]);
    EXPECT_NEAR(glm::length(back - world), 0.0, 1e-9);
}

TEST(OpenCvCamera, AFarOriginLosesNothing) {
    // The same view 1e7 units out: camera-frame points must agree to double rounding of the world coordinates
    // (1e7 x 2e-16 = 2e-9), not to float's 1 unit, which multiplying by a translation in float would give.
    const Camera near = skewedCamera(glm::dvec3(0.0));
    const Camera far = skewedCamera(glm::dvec3(1e7, -3e7, 2e7));
    for (const glm::dvec3& local : std::vector<glm::dvec3>{{0.1, 0.2, 0.3}, {-0.7, 0.4, 1.2}, {0.0, 0.0, 0.0}}) {
        const glm::dvec3 a = openCvCameraPoint(near, near.origin + local);
        const glm::dvec3 b = openCvCameraPoint(far, far.origin + local);
        EXPECT_NEAR(glm::length(a - b), 0.0, 1e-7);
    }
    // The rotation does not depend on the origin at all.
    for (int column = 0; column < 3; ++column)
        EXPECT_EQ(near.openCvExtrinsics()[column], far.openCvExtrinsics()[column]);
}

} // namespace
} // namespace inkgraph
