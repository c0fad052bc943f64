// A model far from the world origin (georeferenced exports: 1e7 units out) must load to the same float positions,
// relative to Scene::origin, as the same model at the origin, and be seen the same way by every camera. Before the
// loaders kept positions in double until re-centred, float32 world coordinates at 3e7 had a spacing of 2 units: a
// unit sphere became a blocky polyhedron.

#include "scene/Camera.h"
#include "scene/mesh/Procedural.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace inkgraph {
namespace {

using test::GltfWriter;
using test::TempFile;

const glm::dvec3 kFarOffset(1e7, -3e7, 2e7);

/** A unit sphere: curved everywhere, so any rounding of its positions shows. Radius 1, so "relative to the size"
 *  and absolute tolerances agree up to a factor of 2. */
const Mesh& unitSphere() {
    static const Mesh sphere = makeUvSphere({0, 0, 0}, 1.0f, 24, 12);
    return sphere;
}

/** `value` with enough digits to read back exactly. */
std::string exact(double value) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}

std::string sphereObj(const glm::dvec3& offset) {
    std::string text;
    for (const glm::vec3& p : unitSphere().positions) {
        const glm::dvec3 world = offset + glm::dvec3(p); // exact in double: 1e7 leaves 29 bits for the float's fraction
        text += "v " + exact(world.x) + " " + exact(world.y) + " " + exact(world.z) + "\n";
    }
    for (const glm::uvec3& t : unitSphere().triangles) {
        text += "f " + std::to_string(t.x + 1) + " " + std::to_string(t.y + 1) + " " + std::to_string(t.z + 1) + "\n";
    }
    return text;
}

std::string sphereAsciiStl(const glm::dvec3& offset) {
    std::string text = "solid sphere\n";
    for (const glm::uvec3& t : unitSphere().triangles) {
        text += "facet normal 0 0 0\nouter loop\n";
        for (int corner = 0; corner < 3; ++corner) {
            const glm::dvec3 world = offset + glm::dvec3(unitSphere().positions[t[corner]]);
            text += "vertex " + exact(world.x) + " " + exact(world.y) + " " + exact(world.z) + "\n";
        }
        text += "endloop\nendfacet\n";
    }
    return text + "endsolid sphere\n";
}

/** The sphere in a buffer at the origin, moved by its node's translation: the offset comes from the transform. */
std::string sphereGltf(const glm::dvec3& offset) {
    GltfWriter writer;
    const int positions = writer.addVec3(unitSphere().positions);
    std::vector<std::uint32_t> indices;
    for (const glm::uvec3& t : unitSphere().triangles) {
        indices.insert(indices.end(), {t.x, t.y, t.z});
    }
    const int triangles = writer.addIndices(indices, 4);
    return writer.gltf("\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                       "}, \"indices\": " + std::to_string(triangles) +
                       "}]}], \"nodes\": [{\"mesh\": 0, \"translation\": [" + exact(offset.x) + ", " + exact(offset.y) +
                       ", " + exact(offset.z) + "]}], \"scenes\": [{\"nodes\": [0]}]");
}

Scene loadText(const std::string& fileName, const std::string& content) {
    const TempFile file(fileName, content);
    return loadScene(file.path());
}

/** Same meshes, same triangles, stored positions equal within 1e-6 of the sphere's radius. */
void expectSameStoredMeshes(const Scene& near, const Scene& far) {
    ASSERT_EQ(near.meshes.size(), far.meshes.size());
    for (std::size_t m = 0; m < near.meshes.size(); ++m) {
        const Mesh& a = near.meshes[m];
        const Mesh& b = far.meshes[m];
        ASSERT_EQ(a.positions.size(), b.positions.size());
        EXPECT_EQ(a.triangles, b.triangles);
        double worst = 0.0;
        for (std::size_t i = 0; i < a.positions.size(); ++i) {
            worst = std::max(worst, glm::length(glm::dvec3(a.positions[i]) - glm::dvec3(b.positions[i])));
        }
        EXPECT_LT(worst, 1e-6) << "stored positions differ by up to " << worst << " (radius 1)";
    }
}

/** Pixel position of a stored point, through the camera resolved for its scene. */
glm::dvec2 pixelOf(const Camera& camera, const glm::vec3& stored) {
    const glm::dvec4 clip = camera.projectionMatrix() * camera.viewMatrix() * glm::dvec4(glm::dvec3(stored), 1.0);
    return (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * glm::dvec2(camera.width, camera.height);
}

/** Every vertex of the first mesh lands on the same pixel (within 1e-3 px of a 1024 px image). */
void expectSameView(const Camera& nearCamera, const Scene& near, const Camera& farCamera, const Scene& far) {
    const Mesh& a = near.meshes.at(0);
    const Mesh& b = far.meshes.at(0);
    double worst = 0.0;
    for (std::size_t i = 0; i < a.positions.size(); ++i) {
        worst = std::max(worst, glm::length(pixelOf(nearCamera, a.positions[i]) - pixelOf(farCamera, b.positions[i])));
    }
    EXPECT_LT(worst, 1e-3) << "vertices land up to " << worst << " px apart";
}

void expectFarModelLoadsAndLooksTheSame(const std::string& fileName, std::string (*write)(const glm::dvec3&)) {
    const Scene near = loadText(fileName, write(glm::dvec3(0.0)));
    const Scene far = loadText(fileName, write(kFarOffset));
    expectSameStoredMeshes(near, far);
    // The origins differ by the offset (each is its model's bounding-box centre).
    const glm::dvec3 originShift = far.origin - near.origin;
    EXPECT_NEAR(originShift.x, kFarOffset.x, 1e-6);
    EXPECT_NEAR(originShift.y, kFarOffset.y, 1e-6);
    EXPECT_NEAR(originShift.z, kFarOffset.z, 1e-6);

    // Auto-framed: the same local view; world values carry the offset.
    const Camera nearAuto = resolveCamera({}, near);
    const Camera farAuto = resolveCamera({}, far);
    expectSameView(nearAuto, near, farAuto, far);
    EXPECT_NEAR(glm::length(farAuto.worldEye() - nearAuto.worldEye() - kFarOffset), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(farAuto.worldTarget() - nearAuto.worldTarget() - kFarOffset), 0.0, 1e-6);

    // --eye and --target are world coordinates: the same point relative to each model gives the same picture.
    CameraRequest nearRequest;
    nearRequest.eye = glm::dvec3(0.3, 0.5, 4.0);
    nearRequest.target = glm::dvec3(0.1, 0.0, -0.2);
    CameraRequest farRequest = nearRequest;
    farRequest.eye = *nearRequest.eye + kFarOffset;
    farRequest.target = *nearRequest.target + kFarOffset;
    const Camera nearFlags = resolveCamera(nearRequest, near);
    const Camera farFlags = resolveCamera(farRequest, far);
    expectSameView(nearFlags, near, farFlags, far);
    EXPECT_EQ(farFlags.worldEye(), *farRequest.eye);
    // worldViewMatrix() takes world points: a world vertex lands where viewMatrix() puts the stored one.
    const glm::vec3 stored = far.meshes[0].positions[5];
    const glm::dvec4 viaWorld = farFlags.worldViewMatrix() * glm::dvec4(test::worldPosition(far, stored), 1.0);
    const glm::dvec4 viaLocal = farFlags.viewMatrix() * glm::dvec4(glm::dvec3(stored), 1.0);
    EXPECT_NEAR(glm::length(glm::dvec3(viaWorld) - glm::dvec3(viaLocal)), 0.0, 1e-7);
}

TEST(SceneOrigin, ObjFarFromTheOriginKeepsItsShape) { expectFarModelLoadsAndLooksTheSame("sphere.obj", &sphereObj); }

TEST(SceneOrigin, AsciiStlFarFromTheOriginKeepsItsShape) {
    expectFarModelLoadsAndLooksTheSame("sphere.stl", &sphereAsciiStl);
}

TEST(SceneOrigin, GltfNodeTranslationFarFromTheOriginKeepsItsShape) {
    expectFarModelLoadsAndLooksTheSame("sphere.gltf", &sphereGltf);
}

TEST(SceneOrigin, StoredPositionsAreCentredOnTheBoundingBox) {
    // A box from (1e7, 1e7, 1e7) to (1e7 + 2, ...): origin at its centre, stored corners at +-1 exactly.
    std::string obj;
    for (const glm::vec3& corner : test::cubeCorners()) {
        const glm::dvec3 world = glm::dvec3(corner) + glm::dvec3(1e7 + 1.0);
        obj += "v " + exact(world.x) + " " + exact(world.y) + " " + exact(world.z) + "\n";
    }
    for (const glm::uvec4& quad : test::cubeQuads()) {
        obj += "f " + std::to_string(quad.x) + " " + std::to_string(quad.y) + " " + std::to_string(quad.z) + " " +
               std::to_string(quad.w) + "\n";
    }
    const Scene scene = loadText("box.obj", obj);
    EXPECT_EQ(scene.origin, glm::dvec3(1e7 + 1.0));
    for (const glm::vec3& p : scene.meshes.at(0).positions) {
        EXPECT_EQ(glm::abs(p), glm::vec3(1.0f));
    }
    const BoundingSphere sphere = computeBoundingSphere(scene);
    EXPECT_EQ(sphere.center, glm::dvec3(0.0));
    EXPECT_DOUBLE_EQ(sphere.radius, std::sqrt(3.0));
}

TEST(SceneOrigin, GltfCameraEyeIsInTheSceneFrame) {
    // The file's camera sits 10 units in front of a model 1e7 units out: its stored eye is local, its world eye exact.
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const std::string body =
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
        "}}]}], \"cameras\": [{\"type\": \"perspective\", \"perspective\": {\"yfov\": 0.5, \"znear\": 0.1}}], "
        "\"nodes\": [{\"mesh\": 0, \"translation\": [1e7, 0, 0]}, "
        "{\"camera\": 0, \"translation\": [10000000, 0, 10]}], "
        "\"scenes\": [{\"nodes\": [0, 1]}]";
    const Scene scene = loadText("camera.gltf", writer.gltf(body));
    ASSERT_TRUE(scene.camera.has_value());
    EXPECT_EQ(scene.origin, glm::dvec3(1e7 + 0.5, 0.5, 0.0));
    EXPECT_EQ(scene.camera->eye, glm::dvec3(-0.5, -0.5, 10.0));
    const Camera camera = resolveCamera({}, scene);
    EXPECT_EQ(camera.source, "gltf");
    EXPECT_EQ(camera.worldEye(), glm::dvec3(1e7, 0, 10));
}

} // namespace
} // namespace inkgraph
