/** Skins, morph targets and animation sampling in the glTF reader, with known answers from files the tests write. */

#include "scene/formats/gltf/GltfPose.h"
#include "scene/Scene.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::TempFile;

/** A glTF whose accessors are any type and component type (SceneTestSupport's GltfWriter writes float VEC3 and
 *  indices only): one buffer as a data: URI, one view per accessor. */
class PoseGltfWriter {
public:
    /** Float components, `type` "SCALAR", "VEC3", "VEC4" or "MAT4"; returns the accessor's index. */
    int addFloats(const std::vector<float>& values, const std::string& type) {
        const std::size_t components = type == "SCALAR" ? 1 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : 16;
        return add(bytesOf(values.data(), values.size() * sizeof(float)), values.size() / components, type, 5126);
    }
    /** VEC4 unsigned byte components (JOINTS_0). */
    int addJoints(const std::vector<std::uint8_t>& joints) {
        return add(bytesOf(joints.data(), joints.size()), joints.size() / 4, "VEC4", 5121);
    }
    int addIndices(const std::vector<std::uint16_t>& indices) {
        return add(bytesOf(indices.data(), indices.size() * 2), indices.size(), "SCALAR", 5123);
    }
    /** A sparse float VEC3 accessor of `count` elements without a buffer view (zeros), `values` at `indices`. */
    int addSparseVec3(std::size_t count, const std::vector<std::uint16_t>& indices, const std::vector<float>& values) {
        const int indexView = addView(bytesOf(indices.data(), indices.size() * 2));
        const int valueView = addView(bytesOf(values.data(), values.size() * sizeof(float)));
        mAccessors.push_back(
            "{\"count\": " + std::to_string(count) +
            ", \"type\": \"VEC3\", \"componentType\": 5126, \"sparse\": {\"count\": " + std::to_string(indices.size()) +
            ", \"indices\": {\"bufferView\": " + std::to_string(indexView) +
            ", \"componentType\": 5123}, \"values\": {\"bufferView\": " + std::to_string(valueView) + "}}}");
        return int(mAccessors.size() - 1);
    }

    std::string gltf(const std::string& body) const {
        std::string views;
        std::string accessors;
        for (std::size_t i = 0; i < mViews.size(); ++i) views += (i ? ", " : "") + mViews[i];
        for (std::size_t i = 0; i < mAccessors.size(); ++i) accessors += (i ? ", " : "") + mAccessors[i];
        return "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"uri\": \"data:application/octet-stream;base64," +
               test::base64(mBinary) + "\", \"byteLength\": " + std::to_string(mBinary.size()) +
               "}], \"bufferViews\": [" + views + "], \"accessors\": [" + accessors + "], " + body + "}";
    }

private:
    static std::string bytesOf(const void* data, std::size_t size) {
        return std::string(static_cast<const char*>(data), size);
    }

    int addView(const std::string& bytes) {
        while (mBinary.size() % 4 != 0) mBinary += '\0';
        mViews.push_back("{\"buffer\": 0, \"byteOffset\": " + std::to_string(mBinary.size()) +
                         ", \"byteLength\": " + std::to_string(bytes.size()) + "}");
        mBinary += bytes;
        return int(mViews.size() - 1);
    }

    int add(const std::string& bytes, std::size_t count, const std::string& type, int componentType) {
        const int view = addView(bytes);
        mAccessors.push_back("{\"bufferView\": " + std::to_string(view) + ", \"count\": " + std::to_string(count) +
                             ", \"type\": \"" + type + "\", \"componentType\": " + std::to_string(componentType) + "}");
        return int(mAccessors.size() - 1);
    }

    std::string mBinary;
    std::vector<std::string> mViews;
    std::vector<std::string> mAccessors;
};

std::string quaternionAboutZ(double degrees) {
    const double half = degrees * std::acos(-1.0) / 360.0;
    return "[0, 0, " + std::to_string(std::sin(half)) + ", " + std::to_string(std::cos(half)) + "]";
}

/** Whether some vertex of the scene lies within `tolerance` of `expected` (world coordinates). */
bool hasVertexNear(const Scene& scene, const glm::dvec3& expected, double tolerance = 1e-5) {
    for (const Mesh& mesh : scene.meshes) {
        for (const glm::vec3& position : mesh.positions) {
            if (glm::length(test::worldPosition(scene, position) - expected) <= tolerance) return true;
        }
    }
    return false;
}

std::string describeVertices(const Scene& scene) {
    std::string text;
    for (const Mesh& mesh : scene.meshes) {
        for (const glm::vec3& position : mesh.positions) {
            const glm::dvec3 world = test::worldPosition(scene, position);
            // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "(" + a temporary string.
            text += "(";
            text += std::to_string(world.x) + ", " + std::to_string(world.y) + ", " + std::to_string(world.z) + ") ";
        }
    }
    return text;
}

/** A strip of two unit squares along +Y from y=0 to y=2: the vertices at y <= 1 follow bone 0 (the root, at the
 *  origin), those at y = 2 bone 1 (at y = 1, a child of bone 0). `bone1Extra` adds members to bone 1's node (a
 *  rotation), `animations` the top-level "animations" member with its leading comma. The mesh node's own translation
 *  (5, 0, 0) must be ignored: glTF places a skinned mesh by its joints only. */
struct TwoBoneStrip {
    PoseGltfWriter writer;
    int positions = 0;
    int indices = 0;
    int joints = 0;
    int weights = 0;
    int inverseBind = 0;
    int normals = -1; ///< a NORMAL attribute when set (withNormals())

    explicit TwoBoneStrip(std::vector<std::uint8_t> jointIndices = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                                                    0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0},
                          const std::vector<float>& weightValues = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0,
                                                                    1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}) {
        positions = writer.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0, 1, 2, 0}, "VEC3");
        indices = writer.addIndices({0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4});
        joints = writer.addJoints(jointIndices);
        weights = writer.addFloats(weightValues, "VEC4");
        // Bone 0 binds at the origin (identity), bone 1 at y = 1 (its inverse: a translation by -1 along Y).
        inverseBind = writer.addFloats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1, // column-major
                                        1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1},
                                       "MAT4");
    }

    /** Every vertex's normal (1, 0, 0), which a skin turns like the vertex. */
    void withNormals() { normals = writer.addFloats({1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0}, "VEC3"); }

    std::string gltf(const std::string& bone1Extra, const std::string& animations = "",
                     const std::string& skinJoints = "[1, 2]") {
        return writer.gltf(
            "\"meshes\": [{\"name\": \"strip\", \"primitives\": [{\"attributes\": {\"POSITION\": " +
            std::to_string(positions) + (normals >= 0 ? ", \"NORMAL\": " + std::to_string(normals) : "") +
            ", \"JOINTS_0\": " + std::to_string(joints) + ", \"WEIGHTS_0\": " + std::to_string(weights) +
            "}, \"indices\": " + std::to_string(indices) +
            "}]}], "
            "\"skins\": [{\"joints\": " +
            skinJoints + ", \"inverseBindMatrices\": " + std::to_string(inverseBind) +
            "}], "
            "\"nodes\": [{\"mesh\": 0, \"skin\": 0, \"translation\": [5, 0, 0]}, {\"name\": \"bone0\", \"children\": "
            "[2]}, {\"name\": \"bone1\", \"translation\": [0, 1, 0]" +
            bone1Extra + "}], \"scenes\": [{\"nodes\": [0, 1]}], \"scene\": 0" + animations);
    }
};

/** The strip's top vertices (0, 2, 0) and (1, 2, 0) turned by `degrees` about Z around the joint at (0, 1, 0). */
void expectTopTurnedBy(const Scene& scene, double degrees) {
    const double angle = degrees * std::acos(-1.0) / 180.0;
    const auto turned = [&](glm::dvec2 offset) { // offset from the joint
        return glm::dvec3(offset.x * std::cos(angle) - offset.y * std::sin(angle),
                          1.0 + offset.x * std::sin(angle) + offset.y * std::cos(angle), 0.0);
    };
    EXPECT_TRUE(hasVertexNear(scene, turned({0.0, 1.0}))) << describeVertices(scene);
    EXPECT_TRUE(hasVertexNear(scene, turned({1.0, 1.0}))) << describeVertices(scene);
    // The lower vertices follow bone 0, which has not moved (and the mesh node's translation is ignored).
    EXPECT_TRUE(hasVertexNear(scene, {0, 0, 0})) << describeVertices(scene);
    EXPECT_TRUE(hasVertexNear(scene, {1, 1, 0})) << describeVertices(scene);
}

TEST(GltfPose, PreciseTransformsHoldWhatDoubleRoundsAway) {
    // In double 1e17 + 0.5 is 1e17 (its doubles lie 16 apart); composed to 32 digits and made relative to 1e17 before
    // rounding, the half is kept exactly, and so is the quarter a rotated child adds under it.
    const glm::dmat4 far = glm::translate(glm::dmat4(1.0), glm::dvec3(1e17, -3e17, 0.0));
    const glm::dmat4 half = glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, 0.0, 0.25));
    ASSERT_EQ((far * half)[3][0], 1e17);
    const detail::PreciseTransform precise = detail::PreciseTransform(far) * half;
    EXPECT_EQ(precise.relativeTo(glm::dvec3(1e17, -3e17, 0.0))[3], glm::dvec4(0.5, 0.0, 0.25, 1.0));
    const glm::dmat4 turned = glm::rotate(glm::dmat4(1.0), glm::radians(90.0), glm::dvec3(0.0, 0.0, 1.0));
    const glm::dvec4 child = (precise * turned * half).relativeTo(glm::dvec3(1e17, -3e17, 0.0))[3];
    EXPECT_NEAR(child.x, 0.5, 1e-15);
    EXPECT_NEAR(child.y, 0.5, 1e-15);
    EXPECT_EQ(child.z, 0.5);
    EXPECT_EQ(precise.magnitude(), 3e17) << "the largest term summed into a translation";
    EXPECT_EQ((precise * turned).steps(), 2u);
}

TEST(GltfPose, SkinRestPoseTurnsTheUpperBone) {
    TwoBoneStrip strip;
    const TempFile file("skin.gltf", strip.gltf(", \"rotation\": " + quaternionAboutZ(90)));
    const Scene scene = loadScene(file.path());
    expectTopTurnedBy(scene, 90.0);
    EXPECT_TRUE(hasVertexNear(scene, {-1, 1, 0})) << describeVertices(scene);
    EXPECT_TRUE(hasVertexNear(scene, {-1, 2, 0})) << describeVertices(scene);
}

TEST(GltfPose, ASkinWithoutInverseBindMatricesIsNotWarnedAbout) {
    // glTF makes them optional (identity); tinygltf reports them missing, which was passed on as a warning.
    TwoBoneStrip strip;
    std::string text = strip.gltf("");
    const std::string member = ", \"inverseBindMatrices\": " + std::to_string(strip.inverseBind);
    ASSERT_NE(text.find(member), std::string::npos);
    text.erase(text.find(member), member.size());
    const TempFile file("no-inverse-binds.gltf", text);
    const Scene scene = loadScene(file.path());
    EXPECT_TRUE(scene.report.warnings.empty()) << ::testing::PrintToString(scene.report.warnings);
    // Both bones bind at the origin, so the upper bone's rest translation moves its vertices up by one.
    EXPECT_TRUE(hasVertexNear(scene, {0, 3, 0})) << describeVertices(scene);
}

TEST(GltfPose, WeightsThatDoNotSumToOneAreNormalisedAndSaid) {
    // glTF asks that a vertex's weights sum to 1. The top vertices' sum 0.5 and vertex 0's 0 were used without a
    // word (normalised, and the node's world for all-zero), so a program skinning the file's weights itself placed
    // them elsewhere than the picture.
    TwoBoneStrip strip({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0},
                       {0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1.005f, 0, 0, 0, 0.5f, 0, 0, 0, 0.5f, 0, 0, 0});
    const TempFile file("half.gltf", strip.gltf(", \"rotation\": " + quaternionAboutZ(90)));
    const Scene scene = loadScene(file.path());
    EXPECT_TRUE(hasVertexNear(scene, {-1, 2, 0})) << "0.5 of bone 1 is all of it: " << describeVertices(scene);
    EXPECT_TRUE(hasVertexNear(scene, {5, 0, 0})) << "all 0: the mesh node's world: " << describeVertices(scene);
    std::vector<std::string> said;
    for (const Warning& warning : scene.report.warnings)
        if (warning.code == "skin-weights-unnormalised") said.push_back(warning.message);
    ASSERT_EQ(said.size(), 1u) << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(said[0], "'strip': 2 vertices' joint weights do not sum to 1 (glTF asks that they do); each vertex's are "
                       "scaled to sum 1; 1 vertex's weights are all 0: it follows the mesh's node, unskinned "
                       "(first: vertex 0, weights summing to 0)")
        << "vertex 3's 1.005 is within the tolerance";
    EXPECT_TRUE(loadScene(TempFile("whole.gltf", TwoBoneStrip().gltf("")).path()).report.warnings.empty());
}

TEST(GltfPose, SkinTurnsNormalsWithTheirVertices) {
    TwoBoneStrip strip;
    strip.withNormals();
    const TempFile file("normals.gltf", strip.gltf(", \"rotation\": " + quaternionAboutZ(90)));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    std::size_t checked = 0;
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        const glm::dvec3 world = test::worldPosition(scene, mesh.positions[v]);
        // Bone 1's vertices (now at x = -1) turned 90 degrees about Z: +X becomes +Y; bone 0's keep +X.
        const glm::dvec3 expected = world.x < -0.5 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
        EXPECT_LT(glm::length(glm::dvec3(mesh.normals[v]) - expected), 1e-5)
            << "vertex at " << world.x << ", " << world.y;
        ++checked;
    }
    EXPECT_EQ(checked, 6u);
}

TEST(GltfPose, SkinWithoutRotationStaysInBindPose) {
    TwoBoneStrip strip;
    const TempFile file("skin.gltf", strip.gltf(""));
    const Scene scene = loadScene(file.path());
    EXPECT_TRUE(hasVertexNear(scene, {0, 2, 0})) << describeVertices(scene);
    EXPECT_TRUE(hasVertexNear(scene, {1, 2, 0})) << describeVertices(scene);
}

/** An animation "bend" turning bone 1 (node 2): keyframes at `times`, `rotations` their quaternions x, y, z, w (for
 *  CUBICSPLINE in-tangent, value, out-tangent per keyframe). */
std::string rotationAnimation(PoseGltfWriter& writer, const std::vector<float>& times,
                              const std::vector<float>& rotations, const std::string& interpolation) {
    const int input = writer.addFloats(times, "SCALAR");
    const int output = writer.addFloats(rotations, "VEC4");
    return ", \"animations\": [{\"name\": \"bend\", \"samplers\": [{\"input\": " + std::to_string(input) +
           ", \"output\": " + std::to_string(output) + ", \"interpolation\": \"" + interpolation +
           "\"}], \"channels\": [{\"sampler\": 0, \"target\": {\"node\": 2, \"path\": \"rotation\"}}]}]";
}

/** rotationAnimation() about Z: keyframes at `times`, rotations in degrees. */
std::string bendAnimation(PoseGltfWriter& writer, const std::vector<float>& times, const std::vector<double>& degrees,
                          const std::string& interpolation) {
    std::vector<float> rotations;
    for (const double angle : degrees) {
        const double half = angle * std::acos(-1.0) / 360.0;
        rotations.insert(rotations.end(), {0.0f, 0.0f, float(std::sin(half)), float(std::cos(half))});
    }
    return rotationAnimation(writer, times, rotations, interpolation);
}

TEST(GltfPose, LinearRotationChannelSlerpsHalfway) {
    TwoBoneStrip strip;
    const std::string animation = bendAnimation(strip.writer, {0.0f, 2.0f}, {0.0, 90.0}, "LINEAR");
    const TempFile file("bend.gltf", strip.gltf("", animation));
    LoadOptions options;
    options.animation = "bend";
    options.time = 1.0;
    expectTopTurnedBy(loadScene(file.path(), options), 45.0);
    // Without --animation the file's rest pose: unbent.
    EXPECT_TRUE(hasVertexNear(loadScene(file.path()), {0, 2, 0}));
    // By index, and clamped past the last keyframe.
    options.animation = "0";
    options.time = 7.5;
    expectTopTurnedBy(loadScene(file.path(), options), 90.0);
}

TEST(GltfPose, StepRotationChannelHoldsUntilTheNextKeyframe) {
    TwoBoneStrip strip;
    const std::string animation = bendAnimation(strip.writer, {0.0f, 1.0f}, {0.0, 90.0}, "STEP");
    const TempFile file("step.gltf", strip.gltf("", animation));
    LoadOptions options;
    options.animation = "bend";
    options.time = 0.99;
    expectTopTurnedBy(loadScene(file.path(), options), 0.0);
    options.time = 1.0;
    expectTopTurnedBy(loadScene(file.path(), options), 90.0);
}

TEST(GltfPose, ARotationOfZeroLengthIsRefusedNamingItsKeyframe) {
    // A keyframe [0, 0, 0, 0] was drawn as the identity without a word (a node's rotation so is refused), at any
    // time the curve reached it; a CUBICSPLINE whose tangents cancel its values passes through zero between keys.
    TwoBoneStrip strip;
    const std::string linear = rotationAnimation(strip.writer, {0.0f, 1.0f}, {0, 0, 0, 1, 0, 0, 0, 0}, "LINEAR");
    const TempFile file("zero.gltf", strip.gltf("", linear));
    LoadOptions options;
    options.animation = "bend";
    options.time = 0.0;
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(file.path(), options); })
                  .find("zero.gltf': animation 0 'bend' sampler 0: keyframe 1 rotation [0, 0, 0, 0] must be finite "
                        "and of non-zero length"),
              std::string::npos);

    TwoBoneStrip cubicStrip;
    // From w = 1 to w = -1 with no tangents: w = 0 and no other component halfway.
    const std::string cubic =
        rotationAnimation(cubicStrip.writer, {0.0f, 1.0f},
                          {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, -1, 0, 0, 0, 0}, "CUBICSPLINE");
    const TempFile cubicFile("cubic-zero.gltf", cubicStrip.gltf("", cubic));
    options.time = 0.5;
    EXPECT_NE(test::sceneErrorMessage([&] {
                  loadScene(cubicFile.path(), options);
              }).find("animation 0 'bend' sampler 0: its CUBICSPLINE rotation passes through zero at --time 0.5"),
              std::string::npos);
    options.time = 0.25; // w = 0.5 there: the identity, as the file says
    expectTopTurnedBy(loadScene(cubicFile.path(), options), 0.0);
}

TEST(GltfPose, UnknownAnimationIsRefusedWithTheList) {
    TwoBoneStrip strip;
    const std::string animation = bendAnimation(strip.writer, {0.0f, 1.0f}, {0.0, 90.0}, "LINEAR");
    const TempFile file("named.gltf", strip.gltf("", animation));
    LoadOptions options;
    options.animation = "run";
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path(), options); });
    EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
    EXPECT_NE(message.find("no animation 'run' (the file has 0 'bend')"), std::string::npos) << message;
    options.animation = "1";
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(file.path(), options); }).find("no animation '1'"),
              std::string::npos);
}

TEST(GltfPose, AnimationOnAFileWithoutAnimationsIsRefused) {
    TwoBoneStrip strip;
    const TempFile file("still.gltf", strip.gltf(""));
    LoadOptions options;
    options.animation = "walk";
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path(), options); });
    EXPECT_NE(message.find("no animation 'walk' (the file has no animations)"), std::string::npos) << message;
    // A name written as a VRM Animation file that is not there, or not a file, says so too (it read as a name only).
    options.animation = file.path() + ".missing.vrma";
    EXPECT_NE(test::sceneErrorMessage([&] {
                  loadScene(file.path(), options);
              }).find("(the file has no animations); no VRM Animation file is there either"),
              std::string::npos);
    options.animation = file.path() + ".folder.vrma";
    std::filesystem::create_directories(options.animation);
    EXPECT_NE(test::sceneErrorMessage([&] {
                  loadScene(file.path(), options);
              }).find("; as a VRM Animation file it is not a regular file"),
              std::string::npos);
    std::filesystem::remove(options.animation);
}

TEST(GltfPose, NegativeOrNonFiniteTimeIsRefused) {
    TwoBoneStrip strip;
    const TempFile file("still.gltf", strip.gltf(""));
    LoadOptions options;
    for (const double time : {-1.0, std::numeric_limits<double>::quiet_NaN()}) {
        options.time = time;
        EXPECT_THROW(loadScene(file.path(), options), std::invalid_argument);
    }
}

TEST(GltfPose, SkinJointIndexOutOfRangeIsRefused) {
    // Vertex 4 names joint 5 of a two-joint skin, with weight 1.
    TwoBoneStrip strip({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 5, 0, 0, 0, 1, 0, 0, 0});
    const TempFile file("badjoint.gltf", strip.gltf(""));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
    EXPECT_NE(message.find("JOINTS_0 element 4: joint 5 out of range (the skin has 2 joints)"), std::string::npos)
        << message;
}

TEST(GltfPose, SkinJointNodeOutOfRangeIsRefused) {
    TwoBoneStrip strip;
    const TempFile file("badnode.gltf", strip.gltf("", "", "[1, 9]"));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("skin 0 joint 1: node index 9 out of range (file has 3 nodes)"), std::string::npos)
        << message;
}

/** One triangle whose morph target 0 moves vertex 0 by (0, 0, 2); `meshExtra` and `nodeExtra` add members to the
 *  mesh and its node (weights), `animations` the top-level member with its leading comma. */
std::string morphTriangle(PoseGltfWriter& writer, const std::string& meshExtra, const std::string& nodeExtra,
                          const std::string& animations = "") {
    const int positions = writer.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int offsets = writer.addFloats({0, 0, 2, 0, 0, 0, 0, 0, 0}, "VEC3");
    return writer.gltf("\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                       "}, \"targets\": [{\"POSITION\": " + std::to_string(offsets) + "}]}]" + meshExtra +
                       "}], \"nodes\": [{\"mesh\": 0" + nodeExtra + "}], \"scenes\": [{\"nodes\": [0]}]" + animations);
}

TEST(GltfPose, MorphTargetAtHalfWeightMovesHalfway) {
    PoseGltfWriter writer;
    const TempFile file("morph.gltf", morphTriangle(writer, ", \"weights\": [0.5]", ""));
    const Scene scene = loadScene(file.path());
    EXPECT_TRUE(hasVertexNear(scene, {0, 0, 1})) << describeVertices(scene);
    EXPECT_TRUE(hasVertexNear(scene, {1, 0, 0})) << describeVertices(scene);
}

TEST(GltfPose, SparseMorphTargetMovesOnlyItsVertices) {
    // Exporters write a target that moves few vertices as a sparse accessor without a buffer view.
    PoseGltfWriter writer;
    const int positions = writer.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int offsets = writer.addSparseVec3(3, {2}, {0, 0, 4});
    const TempFile file(
        "sparse.gltf",
        writer.gltf("\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                    "}, \"targets\": [{\"POSITION\": " + std::to_string(offsets) +
                    "}]}], \"weights\": [0.25]}], \"nodes\": [{\"mesh\": 0}], \"scenes\": "
                    "[{\"nodes\": [0]}]"));
    const Scene scene = loadScene(file.path());
    EXPECT_TRUE(hasVertexNear(scene, {0, 0, 0})) << describeVertices(scene);
    EXPECT_TRUE(hasVertexNear(scene, {1, 0, 0})) << describeVertices(scene);
    EXPECT_TRUE(hasVertexNear(scene, {0, 1, 1})) << describeVertices(scene);
}

TEST(GltfPose, NodeWeightsOverrideMeshWeights) {
    PoseGltfWriter writer;
    const TempFile file("morph.gltf", morphTriangle(writer, ", \"weights\": [0.5]", ", \"weights\": [1.0]"));
    const Scene scene = loadScene(file.path());
    EXPECT_TRUE(hasVertexNear(scene, {0, 0, 2})) << describeVertices(scene);
}

TEST(GltfPose, WeightsChannelAnimatesTheMorph) {
    PoseGltfWriter writer;
    const int input = writer.addFloats({0.0f, 1.0f}, "SCALAR");
    const int output = writer.addFloats({0.0f, 1.0f}, "SCALAR"); // one target: one weight per keyframe
    const std::string animation = ", \"animations\": [{\"samplers\": [{\"input\": " + std::to_string(input) +
                                  ", \"output\": " + std::to_string(output) +
                                  "}], \"channels\": [{\"sampler\": 0, \"target\": {\"node\": 0, \"path\": "
                                  "\"weights\"}}]}]";
    const TempFile file("morphanim.gltf", morphTriangle(writer, "", "", animation));
    LoadOptions options;
    options.animation = "0";
    options.time = 0.25;
    const Scene scene = loadScene(file.path(), options);
    EXPECT_TRUE(hasVertexNear(scene, {0, 0, 0.5})) << describeVertices(scene);
}

/** A unit triangle on a node animated along X: keyframes at 0 and 1 s, from x = 0 to x = 4. */
std::string movingTriangle(PoseGltfWriter& writer, const std::string& interpolation,
                           const std::vector<float>& translations) {
    const int positions = writer.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int input = writer.addFloats({0.0f, 1.0f}, "SCALAR");
    const int output = writer.addFloats(translations, "VEC3");
    return writer.gltf(
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
        "}}]}], \"nodes\": [{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}], \"animations\": [{\"name\": "
        "\"slide\", \"samplers\": [{\"input\": " +
        std::to_string(input) + ", \"output\": " + std::to_string(output) + ", \"interpolation\": \"" + interpolation +
        "\"}], \"channels\": [{\"sampler\": 0, \"target\": {\"node\": 0, \"path\": \"translation\"}}]}]");
}

TEST(GltfPose, AnimatedTranslationMovesTheMeshAndItsFraming) {
    PoseGltfWriter writer;
    const TempFile file("slide.gltf", movingTriangle(writer, "LINEAR", {0, 0, 0, 4, 0, 0}));
    LoadOptions options;
    options.animation = "slide";
    options.time = 0.25;
    const Scene scene = loadScene(file.path(), options);
    EXPECT_TRUE(hasVertexNear(scene, {1, 0, 0})) << describeVertices(scene);
    EXPECT_TRUE(hasVertexNear(scene, {2, 0, 0})) << describeVertices(scene);
    // Framing uses the posed positions: the bounding sphere moved with the mesh.
    const Scene rest = loadScene(file.path());
    const glm::dvec3 movedCentre = scene.origin + computeBoundingSphere(scene).center;
    const glm::dvec3 restCentre = rest.origin + computeBoundingSphere(rest).center;
    EXPECT_NEAR(movedCentre.x - restCentre.x, 1.0, 1e-6);
    EXPECT_NEAR(movedCentre.y - restCentre.y, 0.0, 1e-6);
}

TEST(GltfPose, CubicSplineUsesTheTangents) {
    // Keyframes (in-tangent, value, out-tangent): x = 0 then 4 with slope 4 at both ends is the line x = 4t.
    PoseGltfWriter writer;
    const TempFile file("cubic.gltf",
                        movingTriangle(writer, "CUBICSPLINE", {4, 0, 0, 0, 0, 0, 4, 0, 0, 4, 0, 0, 4, 0, 0, 4, 0, 0}));
    LoadOptions options;
    options.animation = "slide";
    options.time = 0.25;
    const Scene scene = loadScene(file.path(), options);
    EXPECT_TRUE(hasVertexNear(scene, {1, 0, 0})) << describeVertices(scene);
}

TEST(GltfPose, OutputOfTheWrongLengthIsRefused) {
    PoseGltfWriter writer;
    const TempFile file("short.gltf", movingTriangle(writer, "CUBICSPLINE", {0, 0, 0, 4, 0, 0}));
    LoadOptions options;
    options.animation = "slide";
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path(), options); });
    EXPECT_NE(message.find("has 2 elements, expected 6 (2 keyframes x 3 for CUBICSPLINE)"), std::string::npos)
        << message;
}

} // namespace
} // namespace inkgraph
