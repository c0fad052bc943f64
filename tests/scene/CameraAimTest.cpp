/** @file Aiming the camera: --orbit's angles and distance, the lens of a view the flags place, --frame's node
 *  selection, and the node paths the loaders give each mesh (which --frame selects by). */

#include "scene/Camera.h"

#include "scene/mesh/Procedural.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::GltfWriter;
using test::TempFile;

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance = 1e-9) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

std::string invalidArgumentMessage(const CameraRequest& request, const Scene& scene) {
    try {
        resolveCamera(request, scene);
    } catch (const std::invalid_argument& error) {
        return error.what();
    }
    ADD_FAILURE() << "expected std::invalid_argument";
    return {};
}

/** The SceneError of a --frame name the model lacks (a batch fails that model alone). */
std::string modelMismatchMessage(const CameraRequest& request, const Scene& scene) {
    try {
        resolveCamera(request, scene);
    } catch (const SceneError& error) {
        return error.what();
    }
    ADD_FAILURE() << "expected SceneError";
    return {};
}

CameraRequest orbitRequest(double azimuth, double elevation, std::optional<double> distance = std::nullopt) {
    CameraRequest request;
    request.orbit = Orbit{azimuth, elevation, distance};
    return request;
}

Scene unitSphereScene() { return makeScene(makeUvSphere({0, 0, 0}, 1.0f, 48, 24)); }

/** The distance auto-framing puts the eye from the target. */
double fittedDistance(const Scene& scene, CameraRequest request = {}) {
    request.orbit.reset();
    const Camera framed = resolveCamera(request, scene);
    return glm::length(framed.eye - framed.target);
}

glm::dvec3 ndcOf(const Camera& camera, const glm::dvec3& point) {
    const glm::dvec4 clip = camera.projectionMatrix() * camera.viewMatrix() * glm::dvec4(point, 1.0);
    return glm::dvec3(clip) / clip.w;
}

TEST(CameraAim, OrbitNinetyLooksFromTheFrontViewsRight) {
    const Scene scene = unitSphereScene();
    const double distance = fittedDistance(scene);
    const Camera camera = resolveCamera(orbitRequest(90.0, 0.0), scene);
    EXPECT_EQ(camera.source, "orbit");
    // Up +Y, front +Z: the front view's right is +X (a point there shows right of centre), and 90 puts the eye there.
    EXPECT_GT(ndcOf(resolveCamera({}, scene), glm::dvec3(1, 0, 0)).x, 0.5);
    expectNear(camera.eye, glm::dvec3(distance, 0.0, 0.0));
    expectNear(camera.target, glm::dvec3(0.0));
    expectNear(resolveCamera(orbitRequest(-90.0, 0.0), scene).eye, glm::dvec3(-distance, 0.0, 0.0));
    expectNear(resolveCamera(orbitRequest(0.0, 0.0), scene).eye, glm::dvec3(0.0, 0.0, distance));
    expectNear(resolveCamera(orbitRequest(180.0, 0.0), scene).eye, glm::dvec3(0.0, 0.0, -distance));
}

TEST(CameraAim, OrbitTurnsFromTheModelsFront) {
    // A VRM 0.x character faces -Z: azimuth 0 looks from -Z, and the front view's right is then -X.
    Scene scene = unitSphereScene();
    scene.front = glm::dvec3(0, 0, -1);
    const double distance = fittedDistance(scene);
    expectNear(resolveCamera(orbitRequest(0.0, 0.0), scene).eye, glm::dvec3(0.0, 0.0, -distance));
    expectNear(resolveCamera(orbitRequest(90.0, 0.0), scene).eye, glm::dvec3(-distance, 0.0, 0.0));

    // Z-up (--up 0,0,1): the front view looks from -Y (Blender's), 180 from +Y, 90 from +X.
    CameraRequest zUp = orbitRequest(0.0, 0.0);
    zUp.up = glm::dvec3(0, 0, 1);
    const Scene plain = unitSphereScene();
    const double zUpDistance = fittedDistance(plain, zUp);
    expectNear(resolveCamera(zUp, plain).eye, glm::dvec3(0.0, -zUpDistance, 0.0));
    zUp.orbit->azimuthDegrees = 180.0;
    expectNear(resolveCamera(zUp, plain).eye, glm::dvec3(0.0, zUpDistance, 0.0));
    zUp.orbit->azimuthDegrees = 90.0;
    expectNear(resolveCamera(zUp, plain).eye, glm::dvec3(zUpDistance, 0.0, 0.0));
}

TEST(CameraAim, OrbitElevationAndDistance) {
    const Scene scene = makeScene(makeUvSphere({3, -2, 5}, 2.0f, 48, 24));
    const BoundingSphere sphere = computeBoundingSphere(scene);
    const Camera raised = resolveCamera(orbitRequest(0.0, 30.0), scene);
    const glm::dvec3 offset = raised.eye - raised.target;
    expectNear(raised.target, sphere.center);
    EXPECT_NEAR(std::asin(offset.y / glm::length(offset)), glm::radians(30.0), 1e-12) << "30 degrees above";
    EXPECT_NEAR(offset.x, 0.0, 1e-9);
    EXPECT_GT(offset.z, 0.0);
    EXPECT_NEAR(glm::length(offset), fittedDistance(scene), 1e-9);
    const Camera below = resolveCamera(orbitRequest(0.0, -45.0), scene);
    EXPECT_NEAR(below.eye.y - below.target.y, -std::sqrt(0.5) * fittedDistance(scene), 1e-9);

    const Camera far = resolveCamera(orbitRequest(45.0, 10.0, 40.0), scene);
    EXPECT_NEAR(glm::length(far.eye - sphere.center), 40.0, 1e-9);
    EXPECT_GT(far.zFar, 40.0 + sphere.radius) << "the clip planes follow the eye";
    EXPECT_LT(far.zNear, 40.0 - sphere.radius);

    CameraRequest aimed = orbitRequest(0.0, 0.0, 10.0);
    aimed.target = glm::dvec3(1, 1, 1);
    expectNear(resolveCamera(aimed, scene).eye, glm::dvec3(1, 1, 11));
}

TEST(CameraAim, DefaultViewIsTheOrbitAtAtanAQuarter) {
    const Scene scene = makeScene(makeUvSphere({3, -2, 5}, 2.0f, 48, 24));
    const Camera framed = resolveCamera({}, scene);
    const Camera orbit = resolveCamera(orbitRequest(0.0, glm::degrees(std::atan(0.25))), scene);
    EXPECT_EQ(framed.source, "auto-framed");
    expectNear(orbit.eye, framed.eye, 1e-12);
    EXPECT_NEAR(glm::degrees(std::atan(0.25)), 14.04, 0.005);
}

TEST(CameraAim, OrbitRefusals) {
    const Scene scene = unitSphereScene();
    for (const double elevation : {90.0, -90.0, 89.95, 120.0}) {
        const std::string message = invalidArgumentMessage(orbitRequest(0.0, elevation), scene);
        EXPECT_EQ(message.rfind("resolveCamera(): --orbit 0,", 0), 0u) << message;
        EXPECT_NE(message.find("[-89.9, 89.9]"), std::string::npos) << message;
    }
    EXPECT_NO_THROW(resolveCamera(orbitRequest(0.0, 89.9), scene));
    EXPECT_NO_THROW(resolveCamera(orbitRequest(720.0, -89.9), scene));

    CameraRequest withEye = orbitRequest(10.0, 0.0);
    withEye.eye = glm::dvec3(0, 0, 5);
    const std::string both = invalidArgumentMessage(withEye, scene);
    EXPECT_NE(both.find("--orbit 10,0 and --eye both place the eye"), std::string::npos) << both;

    for (const double distance : {0.0, -1.0, HUGE_VAL}) {
        const std::string message = invalidArgumentMessage(orbitRequest(0.0, 0.0, distance), scene);
        EXPECT_NE(message.find("distance must be finite and above 0"), std::string::npos) << message;
    }
    EXPECT_NE(invalidArgumentMessage(orbitRequest(std::nan(""), 0.0), scene).find("finite"), std::string::npos);

    // A scale so small that the eye meets the target: the scale is named, not the model's size.
    CameraRequest scaled = orbitRequest(0.0, 0.0);
    scaled.orbit->distanceScale = 1e-15;
    scaled.target = glm::dvec3(0.0, 1.0, 0.0);
    const std::string tiny = invalidArgumentMessage(scaled, scene);
    EXPECT_NE(tiny.find("coincide: the orbit's scale x1e-15 puts the eye too near the target"), std::string::npos)
        << tiny;
}

TEST(CameraAim, AViewTheFlagsPlaceTakesTheirLensNotTheFiles) {
    Scene scene = unitSphereScene();
    SceneCamera fileCamera;
    fileCamera.eye = glm::dvec3(0, 0, 8);
    fileCamera.fovYDegrees = 18.0;
    scene.camera = fileCamera;
    EXPECT_EQ(resolveCamera({}, scene).fovYDegrees, 18.0) << "the file camera's view keeps its lens";

    CameraRequest eye;
    eye.eye = glm::dvec3(5, 0, 0);
    EXPECT_EQ(resolveCamera(eye, scene).fovYDegrees, 35.0);
    eye.fovYDegrees = 50.0;
    const Camera widened = resolveCamera(eye, scene);
    EXPECT_EQ(widened.source, "flags");
    EXPECT_EQ(widened.fovYDegrees, 50.0);

    const Camera orbit = resolveCamera(orbitRequest(30.0, 10.0), scene);
    EXPECT_EQ(orbit.source, "orbit");
    EXPECT_EQ(orbit.fovYDegrees, 35.0);
    // The orbit's distance is fitted for the lens it uses (35 degrees), as auto-framing's.
    CameraRequest automatic;
    automatic.ignoreFileCamera = true;
    EXPECT_NEAR(glm::length(orbit.eye - orbit.target), fittedDistance(scene, automatic), 1e-9);
}

/** A small sphere (a character) under "root"/"character" standing on a huge box (the ground) under "root"/"ground". */
Scene characterOnGround() {
    Mesh character = makeUvSphere({3, 1, 2}, 0.5f, 32, 16);
    character.nodePath = {"root", "character"};
    Mesh ground = makeCube({0, -50, 0}, 50.0f);
    ground.nodePath = {"root", "ground"};
    Scene scene = makeScene(std::move(character));
    scene.meshes.push_back(std::move(ground));
    return scene;
}

TEST(CameraAim, FrameFitsTheNamedNodesAndClipsToTheWholeScene) {
    const Scene scene = characterOnGround();
    Scene characterAlone;
    characterAlone.meshes.push_back(scene.meshes[0]);
    const BoundingSphere small = computeBoundingSphere(characterAlone);
    const BoundingSphere whole = computeBoundingSphere(scene);
    ASSERT_GT(whole.radius, 50.0 * small.radius);

    CameraRequest request;
    request.frameNodes = {"character"};
    const Camera camera = resolveCamera(request, scene);
    const Camera alone = resolveCamera({}, characterAlone);
    EXPECT_EQ(camera.source, "auto-framed");
    expectNear(camera.target, small.center);
    expectNear(camera.eye, alone.eye);
    // The ground is not clipped: every corner in front of the eye lies between the planes.
    const glm::dvec3 axis = glm::normalize(camera.target - camera.eye);
    EXPECT_GE(camera.zFar, glm::length(camera.eye - whole.center) + whole.radius);
    for (const glm::vec3& corner : scene.meshes[1].positions) {
        const double depth = glm::dot(glm::dvec3(corner) - camera.eye, axis);
        if (depth > 0.0) {
            EXPECT_GE(depth, camera.zNear);
            EXPECT_LE(depth, camera.zFar);
        }
    }

    // --orbit frames the same part: its distance is the small sphere's fit.
    request.orbit = Orbit{90.0, 0.0, std::nullopt};
    const Camera orbit = resolveCamera(request, scene);
    expectNear(orbit.eye, small.center + glm::dvec3(glm::length(alone.eye - alone.target), 0.0, 0.0));

    // A name higher up selects everything below it; the default target with --eye is the framed centre.
    CameraRequest everything;
    everything.frameNodes = {"root"};
    expectNear(resolveCamera(everything, scene).eye, resolveCamera({}, scene).eye);
    CameraRequest eye;
    eye.eye = glm::dvec3(3, 1, 10);
    eye.frameNodes = {"character"};
    expectNear(resolveCamera(eye, scene).target, small.center);
}

TEST(CameraAim, FrameTakesThePlaceOfTheFilesCamera) {
    Scene scene = characterOnGround();
    SceneCamera fileCamera;
    fileCamera.eye = glm::dvec3(0, 0, 300);
    fileCamera.fovYDegrees = 18.0;
    scene.camera = fileCamera;
    CameraRequest request;
    request.frameNodes = {"character"};
    const Camera camera = resolveCamera(request, scene);
    EXPECT_EQ(camera.source, "auto-framed");
    EXPECT_EQ(camera.fovYDegrees, 35.0);
}

TEST(CameraAim, UnknownFrameNodeNamesTheNodes) {
    const Scene scene = characterOnGround();
    CameraRequest request;
    request.frameNodes = {"character", "hero"};
    std::string message = modelMismatchMessage(request, scene);
    EXPECT_EQ(message.rfind("resolveCamera(): --frame 'hero': no mesh lies under a node of that name", 0), 0u)
        << message;
    EXPECT_NE(message.find("'root', 'character', 'ground'"), std::string::npos) << message;

    Scene crowd;
    for (int i = 0; i < 14; ++i) {
        Mesh mesh = makeUvSphere({float(i), 0, 0}, 0.25f, 8, 4);
        mesh.nodePath = {"person " + std::to_string(i)};
        crowd.meshes.push_back(std::move(mesh));
    }
    message = modelMismatchMessage(request, crowd);
    EXPECT_NE(message.find("'person 9' and 4 more"), std::string::npos) << message;
    EXPECT_EQ(message.find("'person 10'"), std::string::npos) << message;

    message = modelMismatchMessage(request, unitSphereScene());
    EXPECT_NE(message.find("the model has no named nodes"), std::string::npos) << message;

    // A mesh the load skipped (a pose scaled its node to 0) is said, so that its name does not read as a typo.
    Scene posed = characterOnGround();
    SkippedMesh hat{1, {}};
    hat.mesh.name = "hat";
    hat.mesh.nodePath = {"root", "character", "hat"};
    posed.skippedMeshes.push_back(hat);
    message = modelMismatchMessage(request, posed);
    EXPECT_NE(message.find("'root', 'character', 'ground'; meshes skipped as all degenerate (mesh-degenerate: a pose "
                           "that collapses them?): 'hat')"),
              std::string::npos)
        << message;
    // The node the user named holds it: that is the refusal's first word.
    request.frameNodes = {"hat"};
    message = modelMismatchMessage(request, posed);
    EXPECT_EQ(message.rfind("resolveCamera(): --frame 'hat': the meshes under that node draw nothing, their triangles "
                            "all degenerate (mesh-degenerate: a pose that collapses them?): 'hat' (",
                            0),
              0u)
        << message;
}

TEST(CameraAim, GltfMeshesKnowTheirNodePath) {
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const std::string body =
        "\"meshes\": [{\"name\": \"tri\", \"primitives\": [{\"attributes\": {\"POSITION\": " +
        std::to_string(positions) +
        "}}]}], "
        "\"nodes\": [{\"name\": \"root\", \"children\": [1, 3]}, {\"name\": \"body\", \"children\": [2]}, "
        "{\"name\": \"head\", \"mesh\": 0, \"translation\": [10, 0, 0]}, {\"mesh\": 0}, "
        "{\"name\": \"lone\", \"mesh\": 0, \"translation\": [0, 0, -5]}], "
        "\"scenes\": [{\"nodes\": [0, 4]}], \"scene\": 0";
    const TempFile file("nested.gltf", writer.gltf(body));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 3u);
    EXPECT_EQ(scene.meshes[0].nodePath, (std::vector<std::string>{"root", "body", "head"}));
    EXPECT_EQ(scene.meshes[1].nodePath, (std::vector<std::string>{"root", ""})) << "an unnamed node";
    EXPECT_EQ(scene.meshes[2].nodePath, (std::vector<std::string>{"lone"}));

    CameraRequest request;
    request.frameNodes = {"body"};
    const Camera camera = resolveCamera(request, scene);
    const glm::dvec3 worldTarget = camera.worldTarget();
    expectNear(worldTarget, glm::dvec3(10.5, 0.5, 0.0), 1e-5); // the head's triangle alone
}

TEST(CameraAim, DeepChainsOfMeshNodesChargeTheirPaths) {
    // 2000 nested nodes, each instancing a one-triangle mesh: the meshes' vertices take under 1 MiB, but every mesh
    // copies its path, about 2000^2 / 2 names in all (tens of MiB).
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    std::string nodes;
    constexpr int kDepth = 2000;
    for (int i = 0; i < kDepth; ++i) {
        nodes += std::string(i ? ", " : "") + "{\"name\": \"n" + std::to_string(i) + "\", \"mesh\": 0" +
                 (i + 1 < kDepth ? ", \"children\": [" + std::to_string(i + 1) + "]" : std::string()) + "}";
    }
    const TempFile file("chain.glb", writer.glb("\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " +
                                                std::to_string(positions) + "}}]}], \"nodes\": [" + nodes +
                                                "], \"scenes\": [{\"nodes\": [0]}], \"scene\": 0"));
    LoadOptions options;
    options.memoryLimitBytes = std::size_t(16) << 20;
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path(), options); });
    EXPECT_NE(message.find("node paths), above the memory limit of 16 MiB"), std::string::npos) << message;
    options.memoryLimitBytes = std::size_t(512) << 20;
    const Scene scene = loadScene(file.path(), options);
    ASSERT_EQ(scene.meshes.size(), std::size_t(kDepth));
    EXPECT_EQ(scene.meshes.back().nodePath.size(), std::size_t(kDepth));
    EXPECT_EQ(scene.meshes.back().nodePath.back(), "n1999");
}

TEST(CameraAim, ObjMeshIsNamedByItsObject) {
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const TempFile named("chair.obj", "o Chair\n" + triangle);
    EXPECT_EQ(loadScene(named.path()).meshes.at(0).nodePath, (std::vector<std::string>{"Chair"}));
    const TempFile unnamed("stool.obj", triangle);
    EXPECT_TRUE(loadScene(unnamed.path()).meshes.at(0).nodePath.empty());
}

} // namespace
} // namespace inkgraph
