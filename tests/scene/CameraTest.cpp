#include "scene/Camera.h"

#include "scene/mesh/Procedural.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <cmath>

namespace inkgraph::camera_test {
namespace {

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance = 1e-9) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

Scene sphereScene(glm::vec3 center = {3, -2, 5}, float radius = 2.0f) {
    return makeScene(makeUvSphere(center, radius, 48, 24));
}

glm::dvec4 toClip(const Camera& camera, const glm::dvec3& point) {
    return camera.projectionMatrix() * camera.viewMatrix() * glm::dvec4(point, 1.0);
}

/** Points of the sphere that bound its image: the 6 axis extremes and the silhouette circle seen from the eye. */
std::vector<glm::dvec3> outlinePoints(const BoundingSphere& sphere, const glm::dvec3& eye) {
    std::vector<glm::dvec3> points;
    for (int axis = 0; axis < 3; ++axis) {
        glm::dvec3 offset(0.0);
        offset[axis] = sphere.radius;
        points.push_back(sphere.center + offset);
        points.push_back(sphere.center - offset);
    }
    const double distance = glm::length(sphere.center - eye);
    const glm::dvec3 w = (sphere.center - eye) / distance;
    const glm::dvec3 u = glm::normalize(glm::cross(w, std::abs(w.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0)));
    const glm::dvec3 v = glm::cross(w, u);
    const glm::dvec3 circleCenter = sphere.center - w * (sphere.radius * sphere.radius / distance);
    const double circleRadius =
        sphere.radius * std::sqrt(distance * distance - sphere.radius * sphere.radius) / distance;
    for (int i = 0; i < 72; ++i) {
        const double angle = 2.0 * glm::pi<double>() * i / 72.0;
        points.push_back(circleCenter + circleRadius * (std::cos(angle) * u + std::sin(angle) * v));
    }
    return points;
}

template <typename Function>
std::string invalidArgumentMessage(Function&& function) {
    try {
        function();
    } catch (const std::invalid_argument& error) {
        return error.what();
    }
    ADD_FAILURE() << "expected std::invalid_argument";
    return {};
}

/** Every outline point of the bounding sphere projects inside the image and the depth range; returns the largest
 *  |x| or |y| they reach in normalised device coordinates. */
double expectSphereInsideTheFrustum(const Camera& camera, const BoundingSphere& sphere) {
    double largest = 0.0;
    for (const glm::dvec3& point : outlinePoints(sphere, camera.eye)) {
        const glm::dvec4 clip = toClip(camera, point);
        EXPECT_GT(clip.w, 0.0);
        const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
        EXPECT_LE(std::abs(ndc.x), 1.0);
        EXPECT_LE(std::abs(ndc.y), 1.0);
        EXPECT_LE(std::abs(ndc.z), 1.0);
        largest = std::max({largest, std::abs(ndc.x), std::abs(ndc.y)});
    }
    return largest;
}

TEST(Camera, AutoFramingFitsTheWholeBoundingSphere) {
    const Scene scene = sphereScene();
    const BoundingSphere sphere = computeBoundingSphere(scene);
    for (const glm::ivec2 size : {glm::ivec2(1024, 1024), glm::ivec2(1920, 1080), glm::ivec2(600, 1000)}) {
        for (const double fov : {20.0, 35.0, 70.0}) {
            CameraRequest request;
            request.width = size.x;
            request.height = size.y;
            request.fovYDegrees = fov;
            const Camera camera = resolveCamera(request, scene);
            SCOPED_TRACE(testing::Message() << size.x << "x" << size.y << ", fov " << fov);

            EXPECT_EQ(camera.source, "auto-framed");
            expectNear(camera.target, sphere.center);
            expectNear(glm::normalize(camera.eye - camera.target), glm::normalize(glm::dvec3(0.0, 0.25, 1.0)));

            const double largest = expectSphereInsideTheFrustum(camera, sphere);
            // The 5% margin: the sphere fills about 1/1.05 of the narrower half-extent, not much less.
            EXPECT_GT(largest, 0.9);
            EXPECT_LT(largest, 0.99);
        }
    }
}

TEST(Camera, ClipPlanesEncloseTheSphere) {
    const Scene scene = sphereScene();
    const BoundingSphere sphere = computeBoundingSphere(scene);
    const Camera camera = resolveCamera({}, scene);
    const double distance = glm::length(camera.eye - sphere.center);
    EXPECT_GT(camera.zNear, 0.0);
    EXPECT_LT(camera.zNear, distance - sphere.radius);
    EXPECT_GT(camera.zFar, distance + sphere.radius);
    EXPECT_NEAR(camera.zFar, (distance + sphere.radius) * 1.01, 1e-9);
    EXPECT_NEAR(camera.zNear, (distance - sphere.radius) * 0.99, 1e-9);
}

TEST(Camera, NearPlaneFollowsTheDepthAlongTheViewAxisWhenTheModelIsOffAxis) {
    // The eye 4 from the centre, looking 0.8 beside it: the centre lies at depth 16/sqrt(16.64) = 3.92 along the view
    // axis, so the sphere's front is at depth 2.92, in front of the 2.97 the centre's distance (4 - 1) x 0.99 gave.
    const Scene scene = sphereScene({0, 0, 0}, 1.0f);
    const BoundingSphere sphere = computeBoundingSphere(scene);
    CameraRequest request;
    request.eye = glm::dvec3(0, 0, 4);
    request.target = glm::dvec3(0.8, 0, 0);
    const Camera camera = resolveCamera(request, scene);
    const glm::dvec3 axis = glm::normalize(*request.target - *request.eye);
    const double frontDepth = glm::dot(sphere.center - camera.eye, axis) - sphere.radius;
    EXPECT_NEAR(camera.zNear, frontDepth * 0.99, 1e-9);
    EXPECT_LT(camera.zNear, frontDepth);
    EXPECT_GT(camera.zFar, glm::length(camera.eye - sphere.center) + sphere.radius);
    // A sphere beside the eye (its front behind the eye plane) gets the smallest near plane.
    request.target = glm::dvec3(0, 0, 8);
    request.eye = glm::dvec3(1.5, 0, 0.5);
    const Camera beside = resolveCamera(request, scene);
    EXPECT_DOUBLE_EQ(beside.zNear, beside.zFar * 1e-4);
}

TEST(Camera, EyeInsideTheSphereGetsATinyNearPlane) {
    const Scene scene = sphereScene({0, 0, 0}, 10.0f);
    CameraRequest request;
    request.eye = glm::dvec3(1, 0, 0);
    request.target = glm::dvec3(1, 0, -1);
    const Camera camera = resolveCamera(request, scene);
    EXPECT_NEAR(camera.zFar, (1.0 + 10.0) * 1.01, 1e-5);
    EXPECT_DOUBLE_EQ(camera.zNear, camera.zFar * 1e-4);
}

TEST(Camera, AModelSeenUnderAPixelIsOutsideTheView) {
    // A unit sphere 10,000 radii away at 128 px: about 0.05 px across, so no pixel shows it. It drew blank paper
    // without the warning, which judged only the view's planes.
    const Scene scene = sphereScene({0, 0, 0}, 1.0f);
    CameraRequest request;
    request.width = request.height = 128;
    request.eye = glm::dvec3(0, 0, 1e4);
    const std::optional<Warning> far = modelOutsideView(resolveCamera(request, scene), scene);
    ASSERT_TRUE(far.has_value());
    EXPECT_EQ(far->code, "model-outside-view");
    EXPECT_NE(far->message.find("the model spans 0.0"), std::string::npos) << far->message;
    EXPECT_NE(far->message.find("pixels, under a pixel (move the eye nearer or narrow --fov)"), std::string::npos);
    // Not "only the background": an outline or silhouette band drawn round the speck may leave a dot of ink.
    EXPECT_NE(far->message.find("no pixel shows its surface (its lines may leave a dot)"), std::string::npos)
        << far->message;
    // A few pixels across is drawn, and not warned about: 100 radii away it spans about 4 pixels, 1,000 about 0.4.
    request.eye = glm::dvec3(0, 0, 100);
    EXPECT_FALSE(modelOutsideView(resolveCamera(request, scene), scene).has_value());
    request.eye = glm::dvec3(0, 0, 1e3);
    EXPECT_TRUE(modelOutsideView(resolveCamera(request, scene), scene).has_value());
    // Under a pixel but over a pixel centre: a 1 x 1 picture of the model, or the far sphere in a picture of odd size
    // (its centre a pixel's centre), draws that pixel.
    CameraRequest tiny;
    tiny.width = tiny.height = 1;
    EXPECT_FALSE(modelOutsideView(resolveCamera(tiny, scene), scene).has_value());
    request.width = request.height = 127;
    request.eye = glm::dvec3(0, 0, 1e4);
    EXPECT_FALSE(modelOutsideView(resolveCamera(request, scene), scene).has_value());
    // An orbit is named as one, not as the --orbit flag: --views places its views as orbits too.
    CameraRequest orbit;
    orbit.width = orbit.height = 128;
    orbit.orbit = Orbit{0.0, 0.0, 1e4, 1.0};
    const std::optional<Warning> orbited = modelOutsideView(resolveCamera(orbit, scene), scene);
    ASSERT_TRUE(orbited.has_value());
    EXPECT_EQ(orbited->message.rfind("the orbit camera (--orbit or a --views view) sees none of the model: ", 0), 0u)
        << orbited->message;
}

TEST(Camera, ASliverBetweenTwoColumnsOfPixelCentresIsOutsideTheView) {
    // 0.6 x 10 units 10 away at --fov 90 in 16 x 16 pixels (0.8 px a unit): 0.48 x 8 pixels, from x 7.76 to 8.24,
    // between the centres 7.5 and 8.5. It drew blank paper without a word: only a model under a pixel both ways was
    // judged.
    Mesh sliver;
    sliver.positions = {{-0.3f, -5, 0}, {0.3f, -5, 0}, {0.3f, 5, 0}, {-0.3f, 5, 0}};
    sliver.normals.assign(4, {0, 0, 1});
    sliver.triangles = {{0, 1, 2}, {0, 2, 3}};
    const Scene scene = makeScene(sliver);
    CameraRequest request;
    request.width = request.height = 16;
    request.fovYDegrees = 90.0;
    request.eye = glm::dvec3(0, 0, 10);
    request.target = glm::dvec3(0, 0, 0);
    const std::optional<Warning> between = modelOutsideView(resolveCamera(request, scene), scene);
    ASSERT_TRUE(between.has_value());
    EXPECT_EQ(between->code, "model-outside-view");
    EXPECT_NE(between->message.find("the model spans 0.48 x 8 pixels, between pixel centres (move the eye nearer"),
              std::string::npos)
        << between->message;
    // Three times the pixels each way (--supersample 3) sample it at x 7.83 and 8.17, and --msaa's sample positions
    // at 1/16 pixel steps: either draws it. Twice (centres 7.75 and 8.25) still misses it.
    const Camera camera = resolveCamera(request, scene);
    EXPECT_FALSE(modelOutsideView(camera, scene, {.supersample = 3}).has_value());
    EXPECT_TRUE(modelOutsideView(camera, scene, {.supersample = 2}).has_value());
    EXPECT_FALSE(modelOutsideView(camera, scene, {.msaaSamples = 4}).has_value());
    // An outline or silhouette draws the sliver as a line 8 pixels long: nothing to warn of. A speck under a pixel
    // both ways is still judged by its samples.
    EXPECT_FALSE(modelOutsideView(camera, scene, {.linesDrawTheMesh = true}).has_value());
    CameraRequest far = request;
    far.eye = glm::dvec3(0, 0, 100);
    EXPECT_TRUE(modelOutsideView(resolveCamera(far, scene), scene, {.linesDrawTheMesh = true}).has_value());
    // Beside the picture: the eye 0.2 in front of the sliver's middle looking along it (+x) through a narrow view,
    // what lies before the eye over 50 pixels left of the picture; with a card behind the eye on its right, no one
    // side of the view holds every vertex. The warning names neither a size nor a sliver.
    Scene withCardBehind = scene;
    Mesh card = sliver;
    for (glm::vec3& position : card.positions) position += glm::vec3(-5, 0, 5);
    withCardBehind.meshes.push_back(card);
    CameraRequest away = request;
    away.eye = glm::dvec3(0, 0, 0.2);
    away.target = glm::dvec3(1, 0, 0.2);
    away.fovYDegrees = 10.0;
    const std::optional<Warning> beside = modelOutsideView(resolveCamera(away, withCardBehind), withCardBehind);
    ASSERT_TRUE(beside.has_value());
    EXPECT_NE(beside->message.find("sees none of the model: what lies before the eye falls beside the picture (aim the "
                                   "view at the model: --target)"),
              std::string::npos)
        << beside->message;
    // Half a pixel to the side it covers the centres at x 8.5, and is drawn.
    request.eye = glm::dvec3(0.5 / 0.8, 0, 10);
    request.target = glm::dvec3(0.5 / 0.8, 0, 0);
    EXPECT_FALSE(modelOutsideView(resolveCamera(request, scene), scene).has_value());
}

TEST(Camera, AModelSeenUnderAPixelWithTheRestBehindTheEyeIsOutsideTheView) {
    // --fov 179 puts the eye 1.05 radii from the framed part: under a pixel at 16 px. With another mesh behind the eye
    // (--frame of one part; here an eye given), some vertex is nearer than the near plane, and the check said nothing
    // of the blank paper, which it judged only when every vertex lay beyond that plane.
    Scene scene = makeScene(makeUvSphere({0, 0, 0}, 0.5f, 48, 24));
    CameraRequest request;
    request.width = request.height = 16;
    request.fovYDegrees = 179.0;
    request.target = glm::dvec3(0, 0, 0);
    request.eye = glm::dvec3(0, 0, 1.05 * 0.5 / std::sin(glm::radians(89.5)));
    const std::optional<Warning> alone = modelOutsideView(resolveCamera(request, scene), scene);
    ASSERT_TRUE(alone.has_value());
    EXPECT_NE(alone->message.find("under a pixel"), std::string::npos) << alone->message;
    scene.meshes.push_back(makeUvSphere({0, 0, 50}, 5.0f, 16, 8));
    const Camera camera = resolveCamera(request, scene);
    ASSERT_LT(camera.zNear, 0.01); // the eye is inside the whole scene's sphere
    const std::optional<Warning> behind = modelOutsideView(camera, scene);
    ASSERT_TRUE(behind.has_value());
    EXPECT_EQ(behind->code, "model-outside-view");
    EXPECT_NE(behind->message.find("the model spans 0.4"), std::string::npos) << behind->message;
    // A triangle from behind the eye to the speck's side is cut by the near plane and drawn across the picture's lower
    // half: its cut corners count, not its one vertex beyond the plane.
    Mesh across;
    across.positions = {{-100, -1, 10}, {100, -1, 10}, {0, -0.01f, -10}};
    across.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
    across.triangles = {{0, 1, 2}};
    scene.meshes.push_back(across);
    EXPECT_FALSE(modelOutsideView(resolveCamera(request, scene), scene).has_value());
}

TEST(Camera, RequestedEyeAndTargetAreHonoured) {
    const Scene scene = sphereScene();
    const BoundingSphere sphere = computeBoundingSphere(scene);

    CameraRequest both;
    both.eye = glm::dvec3(20, 1, 2);
    both.target = glm::dvec3(0, 1, 0);
    both.up = glm::dvec3(0, 0, 1);
    both.fovYDegrees = 50.0;
    both.width = 640;
    both.height = 480;
    const Camera camera = resolveCamera(both, scene);
    EXPECT_EQ(camera.source, "flags");
    EXPECT_EQ(camera.eye, *both.eye);
    EXPECT_EQ(camera.target, *both.target);
    EXPECT_EQ(camera.up, *both.up);
    EXPECT_EQ(camera.fovYDegrees, 50.0);
    EXPECT_EQ(camera.width, 640);
    EXPECT_EQ(camera.height, 480);

    CameraRequest eyeOnly;
    eyeOnly.eye = glm::dvec3(0, 0, 30);
    const Camera aimed = resolveCamera(eyeOnly, scene);
    EXPECT_EQ(aimed.source, "flags");
    expectNear(aimed.target, sphere.center);
    EXPECT_EQ(aimed.fovYDegrees, 35.0);

    CameraRequest targetOnly;
    targetOnly.target = glm::dvec3(1, 1, 1);
    const Camera placed = resolveCamera(targetOnly, scene);
    EXPECT_EQ(placed.source, "auto-framed");
    EXPECT_EQ(placed.target, *targetOnly.target);
    const Camera framed = resolveCamera({}, scene);
    expectNear(placed.eye - placed.target, framed.eye - framed.target); // the same offset as auto-framing
}

TEST(Camera, AutoCameraIgnoresTheFilesCamera) {
    Scene scene = sphereScene({0, 0, 0}, 1.0f);
    SceneCamera fileCamera;
    fileCamera.eye = glm::dvec3(0, 0, 8);
    fileCamera.up = glm::dvec3(1, 0, 0);
    fileCamera.fovYDegrees = 18.0;
    scene.camera = fileCamera;
    CameraRequest automatic;
    automatic.ignoreFileCamera = true;
    const Camera framed = resolveCamera(automatic, scene);
    const Camera unfiled = resolveCamera({}, sphereScene({0, 0, 0}, 1.0f));
    EXPECT_EQ(framed.source, "auto-framed");
    EXPECT_EQ(framed.fovYDegrees, 35.0) << "the file's lens goes with its camera";
    EXPECT_EQ(framed.up, glm::dvec3(0, 1, 0));
    EXPECT_EQ(framed.eye, unfiled.eye) << "the same view as a file without a camera";
    // With --eye too: the flags' placement and the default lens, not the file's 18 degrees.
    automatic.eye = glm::dvec3(3, 0, 3);
    const Camera placed = resolveCamera(automatic, scene);
    EXPECT_EQ(placed.source, "flags");
    EXPECT_EQ(placed.fovYDegrees, 35.0);
}

TEST(Camera, GltfCameraIsUsedWithoutFlags) {
    Scene scene = sphereScene({0, 0, 0}, 1.0f);
    SceneCamera fileCamera;
    fileCamera.eye = glm::dvec3(0, 0, 8);
    fileCamera.forward = glm::normalize(glm::dvec3(0.1, 0, -1));
    fileCamera.up = glm::dvec3(1, 0, 0); // rolled 90 degrees
    fileCamera.fovYDegrees = 22.0;
    scene.camera = fileCamera;

    const Camera camera = resolveCamera({}, scene);
    EXPECT_EQ(camera.source, "gltf");
    EXPECT_EQ(camera.eye, fileCamera.eye);
    expectNear(glm::normalize(camera.target - camera.eye), fileCamera.forward);
    EXPECT_EQ(camera.up, fileCamera.up);
    EXPECT_EQ(camera.fovYDegrees, 22.0);

    CameraRequest fovOnly;
    fovOnly.fovYDegrees = 40.0;
    const Camera widened = resolveCamera(fovOnly, scene);
    EXPECT_EQ(widened.source, "gltf");
    EXPECT_EQ(widened.fovYDegrees, 40.0);

    // An explicit eye replaces the file's camera: its placement, up and lens (CameraAimTest has the lens rule).
    CameraRequest eye;
    eye.eye = glm::dvec3(5, 0, 0);
    const Camera moved = resolveCamera(eye, scene);
    EXPECT_EQ(moved.source, "flags");
    EXPECT_EQ(moved.up, glm::dvec3(0, 1, 0));
    expectNear(moved.target, glm::dvec3(0.0), 1e-6);
    EXPECT_EQ(moved.fovYDegrees, 35.0);
}

TEST(Camera, InvalidRequestsThrow) {
    const Scene scene = sphereScene();
    const auto expectInvalid = [&](const CameraRequest& request, const char* what) {
        const std::string message = invalidArgumentMessage([&] { resolveCamera(request, scene); });
        EXPECT_EQ(message.rfind("resolveCamera():", 0), 0u) << what << ": " << message;
    };
    CameraRequest same;
    same.eye = glm::dvec3(1, 2, 3);
    same.target = glm::dvec3(1, 2, 3);
    expectInvalid(same, "eye == target");

    CameraRequest parallel;
    parallel.eye = glm::dvec3(0, 10, 0);
    parallel.target = glm::dvec3(0, 0, 0);
    expectInvalid(parallel, "up parallel to the view");

    CameraRequest zeroUp;
    zeroUp.up = glm::dvec3(0.0);
    expectInvalid(zeroUp, "zero up");

    for (const double fov : {0.0, -10.0, 180.0, 200.0, std::nan("")}) {
        CameraRequest badFov;
        badFov.fovYDegrees = fov;
        expectInvalid(badFov, "fov");
    }
    CameraRequest noWidth;
    noWidth.width = 0;
    expectInvalid(noWidth, "width");
    CameraRequest negativeHeight;
    negativeHeight.height = -4;
    expectInvalid(negativeHeight, "height");

    EXPECT_THROW(resolveCamera({}, Scene{}), SceneError);
}

TEST(Camera, AutoFramingWithTheDefaultUpKeepsItsDirection) {
    const Scene scene = sphereScene();
    const glm::dvec3 expected = glm::normalize(glm::dvec3(0.0, 0.25, 1.0));
    CameraRequest explicitUp;
    explicitUp.up = glm::dvec3(0, 1, 0);
    for (const CameraRequest& request : {CameraRequest{}, explicitUp}) {
        const Camera camera = resolveCamera(request, scene);
        EXPECT_EQ(camera.up, glm::dvec3(0, 1, 0));
        expectNear(glm::normalize(camera.eye - camera.target), expected, 1e-12);
    }
    // A scaled up vector means the same up.
    CameraRequest scaledUp;
    scaledUp.up = glm::dvec3(0, 7, 0);
    const Camera scaled = resolveCamera(scaledUp, scene);
    expectNear(glm::normalize(scaled.eye - scaled.target), expected, 1e-12);
}

TEST(Camera, AutoFramingWithZUpLooksFromTheFront) {
    // Z-up models (CAD, STL) are seen from -Y, raised a little toward +Z, like Blender's front view.
    const Scene scene = sphereScene();
    const BoundingSphere sphere = computeBoundingSphere(scene);
    CameraRequest request;
    request.up = glm::dvec3(0, 0, 1);
    const Camera camera = resolveCamera(request, scene);
    EXPECT_EQ(camera.source, "auto-framed");
    EXPECT_EQ(camera.up, glm::dvec3(0, 0, 1));
    expectNear(camera.target, sphere.center);
    expectNear(glm::normalize(camera.eye - sphere.center), glm::normalize(glm::dvec3(0.0, -1.0, 0.25)), 1e-12);
    // Up stays up in the image: the model's top (+Z) is above its centre on screen.
    const glm::dvec4 top = toClip(camera, sphere.center + glm::dvec3(0, 0, sphere.radius));
    EXPECT_GT(top.y / top.w, 0.0);
}

TEST(Camera, AutoFramingFitsTheSphereForAnyUp) {
    const Scene scene = sphereScene();
    const BoundingSphere sphere = computeBoundingSphere(scene);
    for (const glm::dvec3 up :
         {glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0), glm::dvec3(1, 1, 0), glm::dvec3(0, 0.25, 1),
          glm::dvec3(0, -1, 0), glm::dvec3(0, 0, -1), glm::dvec3(-2, 3, 0.5), glm::dvec3(0.3, 0, 1)}) {
        SCOPED_TRACE(testing::Message() << "up " << up.x << "," << up.y << "," << up.z);
        CameraRequest request;
        request.up = up;
        request.width = 1280;
        request.height = 720;
        const Camera camera = resolveCamera(request, scene); // never "parallel"
        EXPECT_EQ(camera.source, "auto-framed");
        EXPECT_EQ(camera.up, up);
        // The same slight elevation as the default framing: 0.25 along up before normalising.
        const glm::dvec3 direction = glm::normalize(camera.eye - sphere.center);
        EXPECT_NEAR(glm::dot(direction, glm::normalize(up)), 0.25 / std::sqrt(1.0625), 1e-9);
        expectSphereInsideTheFrustum(camera, sphere);
    }
}

TEST(Camera, RequestedUpWinsOverTheGltfCameraUp) {
    Scene scene = sphereScene({0, 0, 0}, 1.0f);
    SceneCamera fileCamera;
    fileCamera.eye = glm::dvec3(0, 0, 8);
    fileCamera.forward = glm::dvec3(0, 0, -1);
    fileCamera.up = glm::dvec3(1, 0, 0); // rolled 90 degrees
    scene.camera = fileCamera;

    EXPECT_EQ(resolveCamera({}, scene).up, fileCamera.up); // unset: the file's up

    CameraRequest upright;
    upright.up = glm::dvec3(0, 1, 0);
    const Camera camera = resolveCamera(upright, scene);
    EXPECT_EQ(camera.source, "gltf");
    EXPECT_EQ(camera.eye, fileCamera.eye);
    expectNear(glm::normalize(camera.target - camera.eye), fileCamera.forward);
    EXPECT_EQ(camera.up, glm::dvec3(0, 1, 0));
    // The view is not rolled any more: world +y is image up.
    EXPECT_GT((camera.viewMatrix() * glm::dvec4(0, 1, 0, 1)).y, 0.0);

    CameraRequest alongForward;
    alongForward.up = glm::dvec3(0, 0, 1);
    const std::string message = invalidArgumentMessage([&] { resolveCamera(alongForward, scene); });
    EXPECT_NE(message.find("--up 0,0,1"), std::string::npos) << message;
    EXPECT_NE(message.find("parallel"), std::string::npos) << message;
    EXPECT_NE(message.find("glTF camera's forward"), std::string::npos) << message;
}

TEST(Camera, ErrorMessagesNameTheFlags) {
    const Scene scene = sphereScene();
    const BoundingSphere sphere = computeBoundingSphere(scene);

    CameraRequest eyeOnCentre;
    eyeOnCentre.eye = sphere.center;
    std::string message = invalidArgumentMessage([&] { resolveCamera(eyeOnCentre, scene); });
    EXPECT_EQ(message.rfind("resolveCamera(): the eye (--eye ", 0), 0u) << message;
    EXPECT_NE(message.find("without --target"), std::string::npos) << message;
    EXPECT_NE(message.find("bounding-sphere centre (3,-2,5)"), std::string::npos) << message;

    CameraRequest same;
    same.eye = glm::dvec3(1, 2, 3);
    same.target = glm::dvec3(1, 2, 3);
    message = invalidArgumentMessage([&] { resolveCamera(same, scene); });
    EXPECT_NE(message.find("--eye 1,2,3"), std::string::npos) << message;
    EXPECT_NE(message.find("--target 1,2,3"), std::string::npos) << message;
    EXPECT_NE(message.find("coincide"), std::string::npos) << message;

    CameraRequest lookingDown; // the default up is parallel to a view straight down
    lookingDown.eye = glm::dvec3(0, 10, 0);
    lookingDown.target = glm::dvec3(0, 0, 0);
    message = invalidArgumentMessage([&] { resolveCamera(lookingDown, scene); });
    EXPECT_NE(message.find("--up"), std::string::npos) << message;
    EXPECT_NE(message.find("parallel to the view direction (from --eye to --target)"), std::string::npos) << message;
    EXPECT_NE(message.find("; give an --up across the view (for an eye straight above, --up 0,0,-1)"),
              std::string::npos)
        << message;

    // Nearly straight down: a target 1e-5 to either side of the eye's foot turned the picture 180 degrees.
    lookingDown.target = glm::dvec3(1e-5, 0, 0);
    message = invalidArgumentMessage([&] { resolveCamera(lookingDown, scene); });
    EXPECT_NE(message.find("parallel to the view direction (from --eye to --target), 5.7"), std::string::npos)
        << message;
    EXPECT_NE(
        message.find("degrees off: within 0.05 degrees the picture's turn about the view would follow its slightest "
                     "tilt"),
        std::string::npos)
        << message;
    lookingDown.target = glm::dvec3(0.01, 0, 0); // 0.057 degrees off: taken
    EXPECT_NO_THROW(resolveCamera(lookingDown, scene));
    // Every orbit passes: its elevation stops 0.1 degrees short of up.
    CameraRequest steepest;
    steepest.orbit = Orbit{30.0, 89.9, std::nullopt, 1.0};
    EXPECT_NO_THROW(resolveCamera(steepest, scene));
    steepest.orbit->elevationDegrees = -89.9;
    EXPECT_NO_THROW(resolveCamera(steepest, scene));

    CameraRequest parallelUp;
    parallelUp.eye = glm::dvec3(3, -2, 20);
    parallelUp.up = glm::dvec3(0, 0, -2);
    message = invalidArgumentMessage([&] { resolveCamera(parallelUp, scene); });
    EXPECT_NE(message.find("(--up 0,0,-2)"), std::string::npos) << message;
    EXPECT_NE(message.find("parallel"), std::string::npos) << message;

    CameraRequest zeroUp;
    zeroUp.up = glm::dvec3(0.0);
    message = invalidArgumentMessage([&] { resolveCamera(zeroUp, scene); });
    EXPECT_NE(message.find("--up 0,0,0"), std::string::npos) << message;
    EXPECT_NE(message.find("zero"), std::string::npos) << message;

    CameraRequest wideFov;
    wideFov.fovYDegrees = 200.0;
    message = invalidArgumentMessage([&] { resolveCamera(wideFov, scene); });
    EXPECT_NE(message.find("--fov 200"), std::string::npos) << message;

    CameraRequest nanEye;
    nanEye.eye = glm::dvec3(0, std::nan(""), 0);
    message = invalidArgumentMessage([&] { resolveCamera(nanEye, scene); });
    EXPECT_NE(message.find("--eye"), std::string::npos) << message;
    EXPECT_NE(message.find("finite"), std::string::npos) << message;
}

TEST(Camera, FocalLengthInPixels) {
    Camera camera;
    camera.height = 1000;
    camera.fovYDegrees = 90.0;
    EXPECT_NEAR(camera.focalPixels(), 500.0, 1e-9);
    camera.height = 1024;
    camera.fovYDegrees = 35.0;
    EXPECT_NEAR(camera.focalPixels(), 512.0 / std::tan(glm::radians(17.5)), 1e-9);
}

TEST(Camera, ViewMatrixPutsTheEyeAtTheOriginLookingDownMinusZ) {
    CameraRequest request;
    request.eye = glm::dvec3(4, 5, 6);
    request.target = glm::dvec3(-1, 2, 0);
    const Camera camera = resolveCamera(request, sphereScene());
    const glm::dmat4 view = camera.viewMatrix();
    expectNear(glm::dvec3(view * glm::dvec4(camera.eye, 1.0)), glm::dvec3(0.0));
    const double distance = glm::length(camera.target - camera.eye);
    expectNear(glm::dvec3(view * glm::dvec4(camera.target, 1.0)), glm::dvec3(0.0, 0.0, -distance));
    // Up stays up: a point above the eye along world +y lands in the upper half of view space.
    EXPECT_GT((view * glm::dvec4(camera.eye + glm::dvec3(0, 1, 0), 1.0)).y, 0.0);
}

TEST(Camera, ProjectionMapsNearAndFarToTheDepthRange) {
    const Camera camera = resolveCamera({}, sphereScene());
    const glm::dmat4 projection = camera.projectionMatrix();
    const glm::dvec4 nearPoint = projection * glm::dvec4(0.0, 0.0, -camera.zNear, 1.0);
    const glm::dvec4 farPoint = projection * glm::dvec4(0.0, 0.0, -camera.zFar, 1.0);
    EXPECT_NEAR(nearPoint.z / nearPoint.w, -1.0, 1e-9);
    EXPECT_NEAR(farPoint.z / farPoint.w, 1.0, 1e-9);
    // Vertical extent at distance 1 is tan(fov/2).
    const glm::dvec4 top = projection * glm::dvec4(0.0, std::tan(glm::radians(camera.fovYDegrees) / 2.0), -1.0, 1.0);
    EXPECT_NEAR(top.y / top.w, 1.0, 1e-9);
}

TEST(Camera, RequestedClipRangeReplacesTheFittedOne) {
    const Scene scene = sphereScene();
    CameraRequest request;
    request.zNear = 1e-3;
    request.zFar = 1e3;
    const Camera camera = resolveCamera(request, scene);
    EXPECT_EQ(camera.zNear, 1e-3);
    EXPECT_EQ(camera.zFar, 1e3);
    EXPECT_EQ(camera.clipSource, "flags");
    EXPECT_EQ(resolveCamera({}, scene).clipSource, "fitted");
    const double nan = std::nan("");
    for (const auto& [n, f] : std::vector<std::pair<double, double>>{
             {0.0, 1.0}, {-1.0, 1.0}, {2.0, 1.0}, {1.0, 1.0}, {nan, 1.0}, {1.0, HUGE_VAL}}) {
        CameraRequest bad;
        bad.zNear = n;
        bad.zFar = f;
        const std::string message = invalidArgumentMessage([&] { resolveCamera(bad, scene); });
        EXPECT_NE(message.find("--clip"), std::string::npos) << message;
    }
}

} // namespace
} // namespace inkgraph::camera_test
