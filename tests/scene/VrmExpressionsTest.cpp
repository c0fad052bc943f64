/** VRM expressions and look-at (scene/formats/gltf/VrmExpressions.h, VrmLookAt.h) through loadScene(): small .vrm
 *  files the tests write, whose morph targets, colours, texture transforms and bones give known answers, and the
 *  specification's isBinary/override samples in models/characters. */

#include "scene/Scene.h"

#include "SceneTestSupport.h"

#include <glm/gtc/constants.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::GltfWriter;
using test::TempFile;

/** The world positions of the mesh named `name` (its node's name). */
std::vector<glm::dvec3> worldPositions(const Scene& scene, const std::string& name) {
    for (const Mesh& mesh : scene.meshes) {
        if (mesh.name != name) continue;
        std::vector<glm::dvec3> world;
        for (const glm::vec3& p : mesh.positions) world.push_back(scene.origin + glm::dvec3(p));
        return world;
    }
    ADD_FAILURE() << "no mesh '" << name << "'";
    return {};
}

/** Whether some position of mesh `name` lies within 1e-5 of `expected`. */
::testing::AssertionResult hasVertex(const Scene& scene, const std::string& name, const glm::dvec3& expected) {
    std::string seen;
    for (const glm::dvec3& p : worldPositions(scene, name)) {
        if (glm::length(p - expected) < 1e-5) return ::testing::AssertionSuccess();
        seen += " (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")";
    }
    return ::testing::AssertionFailure() << "no vertex at (" << expected.x << ", " << expected.y << ", " << expected.z
                                         << "); the mesh has" << seen;
}

const Material& materialNamed(const Scene& scene, const std::string& name) {
    for (const Mesh& mesh : scene.meshes)
        if (mesh.material.name == name) return mesh.material;
    ADD_FAILURE() << "no material '" << name << "'";
    static const Material none;
    return none;
}

/** A face: one triangle (0,0,0), (1,0,0), (0,1,0) on node "Face" with two morph targets (0 lifts vertex 2 by z 1,
 *  1 lifts vertex 1 by z 2), material 0 "Skin" (base colour 0.2, 0.4, 0.6, 1, a texture; MToon shade colour 0, 0.5,
 *  1) and `extensions`, the root extensions' members. */
std::string faceVrm(const std::string& extensions, const std::string& extensionsUsed = "\"VRMC_vrm\"") {
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const int texcoords = writer.addVec2({{0, 0}, {1, 0}, {0, 1}});
    const int lift2 = writer.addVec3({{0, 0, 0}, {0, 0, 0}, {0, 0, 1}});
    const int lift1 = writer.addVec3({{0, 0, 0}, {0, 0, 2}, {0, 0, 0}});
    const std::string body =
        "\"extensionsUsed\": [" + extensionsUsed + ", \"VRMC_materials_mtoon\"], \"extensions\": {" + extensions +
        "}, \"images\": [{\"uri\": \"a.png\"}], \"textures\": [{\"source\": 0}], "
        "\"materials\": [{\"name\": \"Skin\", \"pbrMetallicRoughness\": {\"baseColorFactor\": [0.2, 0.4, 0.6, 1], "
        "\"baseColorTexture\": {\"index\": 0}}, \"extensions\": {\"VRMC_materials_mtoon\": {\"specVersion\": \"1.0\", "
        "\"shadeColorFactor\": [0, 0.5, 1]}}}], "
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " +
        std::to_string(positions) + ", \"TEXCOORD_0\": " + std::to_string(texcoords) +
        "}, \"material\": 0, \"targets\": [{\"POSITION\": " + std::to_string(lift2) +
        "}, {\"POSITION\": " + std::to_string(lift1) +
        "}]}]}], \"nodes\": [{\"name\": \"Face\", \"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}]";
    return writer.glb(body);
}

/** VRM 1.0 expressions over faceVrm(): happy lifts vertex 2 fully and turns the skin red at alpha 0.5 and its shade
 *  white, blocking blink; sad lifts vertex 2 by half and blends blink; blink lifts vertex 1; the custom binary wink
 *  lifts vertex 1 by half; surprised scales the skin's textures 2x and offsets them (0.5, 0.25). */
const std::string kExpressions = R"("VRMC_vrm": {"specVersion": "1.0", "expressions": {
    "preset": {
        "happy": {"morphTargetBinds": [{"node": 0, "index": 0, "weight": 1}],
                  "materialColorBinds": [{"material": 0, "type": "color", "targetValue": [1, 0, 0, 0.5]},
                                         {"material": 0, "type": "shadeColor", "targetValue": [1, 1, 1, 1]}],
                  "overrideBlink": "block"},
        "sad": {"morphTargetBinds": [{"node": 0, "index": 0, "weight": 0.5}], "overrideBlink": "blend"},
        "blink": {"morphTargetBinds": [{"node": 0, "index": 1, "weight": 1}], "overrideBlink": "block"},
        "surprised": {"textureTransformBinds": [{"material": 0, "scale": [2, 2], "offset": [0.5, 0.25]}]}},
    "custom": {
        "wink": {"isBinary": true, "morphTargetBinds": [{"node": 0, "index": 1, "weight": 0.5}]}}}})";

Scene loadFace(const std::vector<ExpressionWeight>& expressions, const std::string& extensions = kExpressions) {
    const TempFile file("face.vrm", faceVrm(extensions));
    LoadOptions options;
    options.expressions = expressions;
    return loadScene(file.path(), options);
}

TEST(VrmExpressions, WithoutExpressionsTheFaceKeepsItsRestPose) {
    const Scene scene = loadFace({});
    EXPECT_TRUE(hasVertex(scene, "Face", {0, 1, 0}));
    EXPECT_TRUE(hasVertex(scene, "Face", {1, 0, 0}));
    EXPECT_EQ(materialNamed(scene, "Skin").baseColorFactor, glm::vec4(0.2f, 0.4f, 0.6f, 1.0f));
}

TEST(VrmExpressions, AWeightMovesTheMorphTargetAndLerpsTheColours) {
    const Scene scene = loadFace({{"happy", 0.5}});
    EXPECT_TRUE(hasVertex(scene, "Face", {0, 1, 0.5})) << "morph target 0 at weight 1 x 0.5";
    EXPECT_TRUE(hasVertex(scene, "Face", {1, 0, 0}));
    const Material& skin = materialNamed(scene, "Skin");
    // base + (target - base) x 0.5, alpha included.
    EXPECT_NEAR(skin.baseColorFactor.r, 0.6f, 1e-6f);
    EXPECT_NEAR(skin.baseColorFactor.g, 0.2f, 1e-6f);
    EXPECT_NEAR(skin.baseColorFactor.b, 0.3f, 1e-6f);
    EXPECT_NEAR(skin.baseColorFactor.a, 0.75f, 1e-6f);
    ASSERT_TRUE(skin.mtoon.has_value());
    EXPECT_NEAR(skin.mtoon->shadeColorFactor.r, 0.5f, 1e-6f);
    EXPECT_NEAR(skin.mtoon->shadeColorFactor.g, 0.75f, 1e-6f);
    EXPECT_NEAR(skin.mtoon->shadeColorFactor.b, 1.0f, 1e-6f);
}

TEST(VrmExpressions, ExpressionsOnOneTargetAddUp) {
    const Scene scene = loadFace({{"happy", 0.5}, {"sad", 0.5}});
    EXPECT_TRUE(hasVertex(scene, "Face", {0, 1, 0.75})) << "1 x 0.5 + 0.5 x 0.5";
}

TEST(VrmExpressions, ABlockingExpressionZeroesBlinkWhileItShowsAtAll) {
    const Scene scene = loadFace({{"happy", 0.1}, {"blink", 1.0}});
    EXPECT_TRUE(hasVertex(scene, "Face", {1, 0, 0})) << "blink blocked";
    EXPECT_TRUE(hasVertex(scene, "Face", {0, 1, 0.1}));
    EXPECT_TRUE(hasVertex(loadFace({{"happy", 0.0}, {"blink", 1.0}}), "Face", {1, 0, 2})) << "happy at 0 blocks none";
}

TEST(VrmExpressions, ABlendingExpressionScalesBlinkByOneMinusItsWeight) {
    const Scene scene = loadFace({{"sad", 0.25}, {"blink", 0.8}});
    EXPECT_TRUE(hasVertex(scene, "Face", {1, 0, 2 * 0.8 * 0.75}));
    EXPECT_TRUE(hasVertex(scene, "Face", {0, 1, 0.5 * 0.25}));
}

TEST(VrmExpressions, AnOverrideOfItsOwnKindIsIgnored) {
    // blink's own overrideBlink "block" must not suppress blink.
    EXPECT_TRUE(hasVertex(loadFace({{"blink", 0.5}}), "Face", {1, 0, 1}));
}

TEST(VrmExpressions, IsBinarySnapsAtOneHalf) {
    EXPECT_TRUE(hasVertex(loadFace({{"wink", 0.6}}), "Face", {1, 0, 1})) << "0.6 -> 1, x bind weight 0.5 x 2";
    EXPECT_TRUE(hasVertex(loadFace({{"wink", 0.5}}), "Face", {1, 0, 0})) << "0.5 -> 0";
}

TEST(VrmExpressions, ATextureTransformBindMovesEveryUvTextureOfTheMaterial) {
    const Scene scene = loadFace({{"surprised", 0.5}});
    const glm::mat3& transform = materialNamed(scene, "Skin").baseColorTexture.transform;
    // Own scale 1, offset 0: halfway to scale 2, offset (0.5, 0.25).
    EXPECT_NEAR(transform[0][0], 1.5f, 1e-6f);
    EXPECT_NEAR(transform[1][1], 1.5f, 1e-6f);
    EXPECT_NEAR(transform[0][1], 0.0f, 1e-6f);
    EXPECT_NEAR(transform[2][0], 0.25f, 1e-6f);
    EXPECT_NEAR(transform[2][1], 0.125f, 1e-6f);
}

/** The messages of the warnings of `code`. */
std::vector<std::string> warningsOf(const Scene& scene, const std::string& code) {
    std::vector<std::string> messages;
    for (const Warning& warning : scene.report.warnings)
        if (warning.code == code) messages.push_back(warning.message);
    return messages;
}

TEST(VrmExpressions, BindValuesBeyondTheirRangeAreTreatedAsTheFilesOwn) {
    // A texture transform bind is reduced by the texture's wrap and one float cannot resolve is left out, as a file's
    // KHR_texture_transform is; a colour bind is clamped into [0, 1]. Both were used as given without a word: a scale
    // of 1e300 drew the textures black, an offset of 1e7 + 0.875 one flat colour.
    const std::string extensions = R"("VRMC_vrm": {"specVersion": "1.0", "expressions": {"preset": {
        "happy": {"textureTransformBinds": [{"material": 0, "scale": [1e300, 1], "offset": [0, 0]}]},
        "sad": {"textureTransformBinds": [{"material": 0, "scale": [1, 1], "offset": [10000000.875, -3.25]}]},
        "angry": {"materialColorBinds": [{"material": 0, "type": "color", "targetValue": [1e300, -2, 0.5, 1]}]}}}})";
    const Scene stretched = loadFace({{"happy", 1.0}}, extensions);
    EXPECT_EQ(materialNamed(stretched, "Skin").baseColorTexture.transform, glm::mat3(1.0f)) << "left as it was";
    EXPECT_EQ(
        warningsOf(stretched, "texture-transform-dropped"),
        std::vector<std::string>{"the expressions' texture transform on material 'Skin': its scale and rotation "
                                 "stretch texture coordinates 1e+300 times, beyond the 10000 at which float still "
                                 "resolves a texel of the image; the textures are drawn without it"});

    const Scene moved = loadFace({{"sad", 1.0}}, extensions);
    const glm::mat3& transform = materialNamed(moved, "Skin").baseColorTexture.transform;
    EXPECT_FLOAT_EQ(transform[2][0], 0.875f) << "whole repeats of the default wrap (repeat) taken off";
    EXPECT_FLOAT_EQ(transform[2][1], -0.25f);
    EXPECT_TRUE(warningsOf(moved, "texture-transform-dropped").empty());

    const Scene coloured = loadFace({{"angry", 0.5}}, extensions);
    const glm::vec4 color = materialNamed(coloured, "Skin").baseColorFactor;
    EXPECT_NEAR(color.r, 0.6f, 1e-6f) << "halfway from 0.2 to 1";
    EXPECT_NEAR(color.g, 0.2f, 1e-6f) << "halfway from 0.4 to 0";
    EXPECT_NEAR(color.b, 0.55f, 1e-6f);
    EXPECT_EQ(warningsOf(coloured, "value-out-of-range").size(), 2u);
}

TEST(VrmExpressions, ANameTheFileLacksIsRefusedWithTheNamesItHas) {
    try {
        loadFace({{"Happy", 1.0}});
        FAIL() << "expected a SceneError";
    } catch (const SceneError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("face.vrm': --expression: no expression 'Happy' (names are case-sensitive; the file "
                               "has 'blink', 'happy', 'sad', 'surprised', 'wink')"),
                  std::string::npos)
            << message;
    }
}

TEST(VrmExpressions, AFileWithoutExpressionsIsRefused) {
    try {
        loadFace({{"happy", 1.0}}, R"("VRMC_vrm": {"specVersion": "1.0"})");
        FAIL() << "expected a SceneError";
    } catch (const SceneError& error) {
        EXPECT_NE(std::string(error.what()).find("--expression: the file has no VRM expressions"), std::string::npos)
            << error.what();
    }
    const TempFile obj("face.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    LoadOptions options;
    options.expressions = {{"happy", 1.0}};
    EXPECT_THROW(loadScene(obj.path(), options), SceneError);
}

TEST(VrmExpressions, ABindToAMissingMorphTargetIsLeftOutWithAWarning) {
    const Scene scene = loadFace({{"happy", 1.0}}, R"("VRMC_vrm": {"specVersion": "1.0", "expressions": {"preset": {
        "happy": {"morphTargetBinds": [{"node": 0, "index": 7, "weight": 1}, {"node": 0, "index": 0, "weight": 1}]}}}})");
    EXPECT_TRUE(hasVertex(scene, "Face", {0, 1, 1}));
    bool warned = false;
    for (const Warning& warning : scene.report.warnings)
        warned |= warning.message.find("preset.happy.morphTargetBinds[0]: node 0's mesh has 2 morph targets") !=
                  std::string::npos;
    EXPECT_TRUE(warned);
}

/** VRM 0.x: Joy binds mesh 0's target 0 at 50 (of 100) and the skin's _Color to sRGB 0.5 grey; Blink_L is binary. */
const std::string kVrm0Groups = R"("VRM": {"blendShapeMaster": {"blendShapeGroups": [
    {"name": "Joy", "presetName": "joy", "binds": [{"mesh": 0, "index": 0, "weight": 50}],
     "materialValues": [{"materialName": "Skin", "propertyName": "_Color", "targetValue": [0.5, 0.5, 0.5, 1]}]},
    {"name": "Blink_L", "presetName": "blink_l", "isBinary": true, "binds": [{"mesh": 0, "index": 1, "weight": 100}]},
    {"name": "Smirk", "presetName": "unknown", "binds": [{"mesh": 0, "index": 1, "weight": 25}]}]}})";

Scene loadVrm0Face(const std::vector<ExpressionWeight>& expressions) {
    const TempFile file("face0.vrm", faceVrm(kVrm0Groups, "\"VRM\""));
    LoadOptions options;
    options.expressions = expressions;
    return loadScene(file.path(), options);
}

TEST(VrmExpressions, Vrm0GroupsAnswerToTheirPresetAndTheirOwnNames) {
    for (const char* name : {"happy", "Joy"}) {
        const Scene scene = loadVrm0Face({{name, 1.0}});
        EXPECT_TRUE(hasVertex(scene, "Face", {0, 1, 0.5})) << name << ": weight 50 of 100";
        // sRGB 0.5 is linear 0.2140411; the 0.x material's own _Color is absent, so the glTF factor is the base.
        EXPECT_NEAR(materialNamed(scene, "Skin").baseColorFactor.r, 0.2140411f, 1e-6f) << name;
    }
    EXPECT_TRUE(hasVertex(loadVrm0Face({{"blinkLeft", 0.7}}), "Face", {1, 0, 2})) << "isBinary: 0.7 -> 1";
    EXPECT_TRUE(hasVertex(loadVrm0Face({{"Smirk", 1.0}}), "Face", {1, 0, 0.5})) << "a custom group by its name";
    EXPECT_THROW(loadVrm0Face({{"joy", 1.0}}), SceneError) << "the 0.x preset name is not a name";
}

TEST(VrmExpressions, AWeightOrIsBinaryOfTheWrongTypeIsReadAsItsDefaultAndSaid) {
    // Both were taken without a word: a weight "50" as the default, isBinary "yes" as false.
    const std::string vrm1 = R"("VRMC_vrm": {"specVersion": "1.0", "expressions": {"preset": {
        "happy": {"isBinary": "yes", "morphTargetBinds": [{"node": 0, "index": 0, "weight": "0.5"}]}}}})";
    const Scene scene = loadFace({{"happy", 0.4}}, vrm1);
    EXPECT_TRUE(hasVertex(scene, "Face", {0, 1, 0.4})) << "weight 1, and not snapped as a binary expression";
    EXPECT_EQ(warningsOf(scene, "vrm-property-invalid"),
              (std::vector<std::string>{
                  "VRMC_vrm.expressions.preset.happy.isBinary: a string, not true or false; read as false",
                  "VRMC_vrm.expressions.preset.happy.morphTargetBinds[0].weight: a string, not a number; read as 1"}));

    const std::string vrm0 = R"("VRM": {"blendShapeMaster": {"blendShapeGroups": [
        {"name": "Joy", "presetName": "joy", "isBinary": 1, "binds": [{"mesh": 0, "index": 0, "weight": [50]}]}]}})";
    const TempFile file("face0.vrm", faceVrm(vrm0, "\"VRM\""));
    LoadOptions options;
    options.expressions = {{"happy", 0.4}};
    const Scene scene0 = loadScene(file.path(), options);
    EXPECT_TRUE(hasVertex(scene0, "Face", {0, 1, 0.4})) << "weight 100 of 100";
    EXPECT_EQ(warningsOf(scene0, "vrm-property-invalid"),
              (std::vector<std::string>{
                  "VRM.blendShapeMaster.blendShapeGroups[0].isBinary: a number, not true or false; read as false",
                  "VRM.blendShapeMaster.blendShapeGroups[0].binds[0].weight: an array, not a number; read as 100"}));
}

TEST(VrmExpressions, AVersionOtherThanOnePointZeroIsReadAsItAndSaid) {
    const auto versionWarnings = [](const std::string& vrm) {
        std::vector<std::string> said;
        for (const std::string& message : warningsOf(loadFace({}, vrm), "vrm-property-invalid"))
            if (message.find("specVersion") != std::string::npos) said.push_back(message);
        return said;
    };
    EXPECT_TRUE(versionWarnings(R"("VRMC_vrm": {"specVersion": "1.0"})").empty());
    EXPECT_TRUE(versionWarnings(R"("VRMC_vrm": {"specVersion": "1.0-beta"})").empty());
    EXPECT_EQ(
        versionWarnings(R"("VRMC_vrm": {"specVersion": "2.0"})"),
        std::vector<std::string>{"VRMC_vrm.specVersion: '2.0' is not a version this reader knows; read as VRM 1.0"});
    EXPECT_EQ(versionWarnings(R"("VRMC_vrm": {"specVersion": 1})"),
              std::vector<std::string>{"VRMC_vrm.specVersion: not a string; read as VRM 1.0"});
    EXPECT_EQ(versionWarnings(R"("VRMC_vrm": {"humanoid": {}})"),
              std::vector<std::string>{"VRMC_vrm.specVersion: missing; read as VRM 1.0"});
}

// The specification's samples: textureTransformBinds move a validation window's texture and two meters.
std::string sample(const std::string& file) { return test::sourcePath("models/characters/" + file); }

Scene loadSample(const std::string& file, const std::vector<ExpressionWeight>& expressions) {
    LoadOptions options;
    options.expressions = expressions;
    return loadScene(sample(file), options);
}

glm::vec2 offsetOf(const Scene& scene, const std::string& material) {
    const glm::mat3& transform = materialNamed(scene, material).baseColorTexture.transform;
    return {transform[2][0], transform[2][1]};
}

// The meters' own offset is 0.5009765625 (empty); an expression at weight w moves it to 0.5009765625 - 0.5 w.
constexpr float kMeterEmpty = 0.5009765625f;

TEST(VrmExpressions, BinaryHappyBlendsBlinkAwayOnlyOnceItShows) {
    // expressions-binary-overrides: happy isBinary with overrideBlink "blend", blink plain.
    const Scene shown = loadSample("expressions-binary-overrides.vrm", {{"happy", 0.6}, {"blink", 1.0}});
    EXPECT_NEAR(offsetOf(shown, "Meter Happy").x, kMeterEmpty - 0.5f, 1e-6f) << "happy's binary output 1";
    EXPECT_NEAR(offsetOf(shown, "Meter Blink").x, kMeterEmpty, 1e-6f) << "blink blended away by 1";
    EXPECT_NEAR(offsetOf(shown, "Validation Window").x, 0.875f, 1e-6f);
    EXPECT_NEAR(offsetOf(shown, "Validation Window").y, 0.0f, 1e-6f);

    const Scene hidden = loadSample("expressions-binary-overrides.vrm", {{"happy", 0.4}, {"blink", 0.7}});
    EXPECT_NEAR(offsetOf(hidden, "Meter Happy").x, kMeterEmpty, 1e-6f) << "happy's binary output 0";
    EXPECT_NEAR(offsetOf(hidden, "Meter Blink").x, kMeterEmpty - 0.5f * 0.7f, 1e-6f) << "blink untouched";
    EXPECT_NEAR(offsetOf(hidden, "Validation Window").y, 0.875f * 0.7f, 1e-6f);
}

TEST(VrmExpressions, AnOverriddenBinaryBlinkIsSuppressedByAnyOverride) {
    // expressions-binary-overridden: happy plain with overrideBlink "blend", blink isBinary.
    const Scene scene = loadSample("expressions-binary-overridden.vrm", {{"happy", 0.1}, {"blink", 1.0}});
    EXPECT_NEAR(offsetOf(scene, "Meter Happy").x, kMeterEmpty - 0.05f, 1e-6f);
    EXPECT_NEAR(offsetOf(scene, "Meter Blink").x, kMeterEmpty, 1e-6f) << "not 0.9: suppressed entirely";
    const Scene alone = loadSample("expressions-binary-overridden.vrm", {{"blink", 1.0}});
    EXPECT_NEAR(offsetOf(alone, "Meter Blink").x, kMeterEmpty - 0.5f, 1e-6f);
}

// Look-at: a head at (0, 1, 0) with two eyes, each carrying a triangle whose vertex (0, 0, 1) in the eye's frame
// shows where the eye looks, and hips at the origin. `vrmExtension` is the root's "VRMC_vrm" or "VRM" member.
std::string headVrmOf(const std::string& vrmExtension, const std::string& extensionName) {
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {0, 0, 1}, {0.1f, 0, 0}});
    const int lift = writer.addVec3({{0, 0, 0}, {0, 0, 0}, {0, 0, 1}});
    const std::string body = R"("extensionsUsed": [")" + extensionName + R"("], "extensions": {")" + extensionName +
                             R"(": )" + vrmExtension + R"(},
        "meshes": [{"primitives": [{"attributes": {"POSITION": )" +
                             std::to_string(positions) + R"(}, "targets": [{"POSITION": )" + std::to_string(lift) +
                             R"(}]}]}],
        "nodes": [{"name": "Head", "translation": [0, 1, 0], "children": [1, 2]},
                  {"name": "LeftEye", "translation": [0.03, 0.05, 0.05], "children": [3]},
                  {"name": "RightEye", "translation": [-0.03, 0.05, 0.05], "children": [4]},
                  {"name": "LeftGaze", "mesh": 0}, {"name": "RightGaze", "mesh": 0}, {"name": "Hips"}],
        "scenes": [{"nodes": [0, 5]}])";
    return writer.glb(body);
}

/** The head of headVrmOf() as VRM 1.0 with look-at settings `lookAt` and `expressions` after them. */
std::string headVrm(const std::string& lookAt, const std::string& expressions = "") {
    return headVrmOf(R"({"specVersion": "1.0",
            "humanoid": {"humanBones": {"hips": {"node": 5}, "head": {"node": 0}, "leftEye": {"node": 1},
                                        "rightEye": {"node": 2}}},
            "lookAt": )" +
                         lookAt + expressions + "}",
                     "VRMC_vrm");
}

Scene loadHeadFile(const std::string& content, const glm::dvec3& target) {
    const TempFile file("head.vrm", content);
    LoadOptions options;
    options.lookAt = target;
    return loadScene(file.path(), options);
}

Scene loadHead(const std::string& lookAt, const glm::dvec3& target, const std::string& expressions = "") {
    return loadHeadFile(headVrm(lookAt, expressions), target);
}

/** A point `degrees` to the character's left (+X, yaw > 0) of the look-at origin, or below it with `down`. */
glm::dvec3 pointAt(double degrees, bool down = false) {
    const glm::dvec3 origin(0.0, 1.06, 0.0); // the head at y 1 plus offsetFromHeadBone 0.06
    const double angle = glm::radians(degrees);
    return origin + 2.0 * (down ? glm::dvec3(0.0, -std::sin(angle), std::cos(angle))
                                : glm::dvec3(std::sin(angle), 0.0, std::cos(angle)));
}

const std::string kBoneLookAt = R"({"type": "bone", "offsetFromHeadBone": [0, 0.06, 0],
    "rangeMapHorizontalOuter": {"inputMaxValue": 20, "outputScale": 10},
    "rangeMapHorizontalInner": {"inputMaxValue": 40, "outputScale": 10},
    "rangeMapVerticalDown": {"inputMaxValue": 20, "outputScale": 10},
    "rangeMapVerticalUp": {"inputMaxValue": 90, "outputScale": 10}})";

TEST(VrmLookAt, ATarget10DegreesLeftTurnsTheEyesByTheirRangeMaps) {
    const Scene scene = loadHead(kBoneLookAt, pointAt(10.0));
    const double outer = glm::radians(5.0); // the left eye turns outward: 10 of 20 degrees -> 5 of 10
    const double inner = glm::radians(2.5); // the right eye inward: 10 of 40 -> 2.5 of 10
    EXPECT_TRUE(
        hasVertex(scene, "LeftGaze", glm::dvec3(0.03, 1.05, 0.05) + glm::dvec3(std::sin(outer), 0.0, std::cos(outer))));
    EXPECT_TRUE(hasVertex(scene, "RightGaze",
                          glm::dvec3(-0.03, 1.05, 0.05) + glm::dvec3(std::sin(inner), 0.0, std::cos(inner))));
}

TEST(VrmLookAt, ATargetBelowPitchesBothEyesDown) {
    const Scene scene = loadHead(kBoneLookAt, pointAt(10.0, true));
    const double down = glm::radians(5.0);
    EXPECT_TRUE(
        hasVertex(scene, "LeftGaze", glm::dvec3(0.03, 1.05, 0.05) + glm::dvec3(0.0, -std::sin(down), std::cos(down))));
}

TEST(VrmLookAt, ATargetBeyondTheInputRangeIsClamped) {
    const Scene scene = loadHead(kBoneLookAt, pointAt(60.0));
    const double outer = glm::radians(10.0);
    EXPECT_TRUE(
        hasVertex(scene, "LeftGaze", glm::dvec3(0.03, 1.05, 0.05) + glm::dvec3(std::sin(outer), 0.0, std::cos(outer))));
}

TEST(VrmLookAt, AnOffsetOrATurnBeyondAnyDirectionIsSaidAndItsDefaultUsed) {
    // An offset of 1e300 put the look-at space out of the world, and the eyes turned to their limit whatever the
    // target; a bone map's output of 1e300 degrees turned them by rounding noise. Both taken as the file said.
    const Scene expected = loadHead(kBoneLookAt, pointAt(10.0));
    for (const auto& [lookAt, where] : {
             std::pair{R"({"type": "bone", "offsetFromHeadBone": [0, 1e300, 0],
                 "rangeMapHorizontalOuter": {"inputMaxValue": 20, "outputScale": 10},
                 "rangeMapHorizontalInner": {"inputMaxValue": 40, "outputScale": 10}})",
                       "VRMC_vrm.lookAt.offsetFromHeadBone (0, 1e+300, 0) lies 1e+300 from the head, farther than "
                       "the hips (1); the default (0, 0.06, 0) is used"},
             std::pair{
                 R"({"type": "bone", "offsetFromHeadBone": [0, 0.06, 1.5],
                 "rangeMapHorizontalOuter": {"inputMaxValue": 20, "outputScale": 10},
                 "rangeMapHorizontalInner": {"inputMaxValue": 40, "outputScale": 10}})",
                 "VRMC_vrm.lookAt.offsetFromHeadBone (0, 0.06, 1.5) lies 1.5011995203836164 from the head, farther "
                 "than the hips (1)"},
             std::pair{R"({"type": "bone", "rangeMapHorizontalOuter": {"inputMaxValue": 20, "outputScale": 1e300},
                 "rangeMapHorizontalInner": {"inputMaxValue": 40, "outputScale": 10}})",
                       "VRMC_vrm.lookAt.rangeMapHorizontalOuter.outputScale is 1e+300 degrees of eye turn, beyond 180; "
                       "the default 10 is used"},
         }) {
        const Scene scene = loadHead(lookAt, pointAt(10.0));
        const std::vector<std::string> said = warningsOf(scene, "vrm-property-invalid");
        ASSERT_EQ(said.size(), 1u) << lookAt;
        EXPECT_NE(said[0].find(where), std::string::npos) << said[0];
        EXPECT_EQ(worldPositions(scene, "LeftGaze"), worldPositions(expected, "LeftGaze")) << lookAt;
        EXPECT_EQ(worldPositions(scene, "RightGaze"), worldPositions(expected, "RightGaze")) << lookAt;
    }
    EXPECT_TRUE(warningsOf(expected, "vrm-property-invalid").empty());
}

TEST(VrmLookAt, AVrm0FirstPersonBoneOffsetBeyondTheHipsIsSaidAndItsDefaultUsed) {
    const auto vrm0Head = [](const std::string& offset) {
        return headVrmOf(R"({"humanoid": {"humanBones": [{"bone": "hips", "node": 5}, {"bone": "head", "node": 0},
                {"bone": "leftEye", "node": 1}, {"bone": "rightEye", "node": 2}]},
            "firstPerson": {"lookAtTypeName": "Bone", "firstPersonBoneOffset": )" +
                             offset + R"(,
                "lookAtHorizontalOuter": {"xRange": 20, "yRange": 10},
                "lookAtHorizontalInner": {"xRange": 40, "yRange": 10}}})",
                         "VRM");
    };
    // A 0.x character faces -Z: the target 10 degrees to its left.
    const glm::dvec3 target = glm::dvec3(0.0, 1.06, 0.0) +
                              2.0 * glm::dvec3(-std::sin(glm::radians(10.0)), 0.0, -std::cos(glm::radians(10.0)));
    const Scene expected = loadHeadFile(vrm0Head(R"({"x": 0, "y": 0.06, "z": 0})"), target);
    EXPECT_TRUE(warningsOf(expected, "vrm-property-invalid").empty());
    const Scene scene = loadHeadFile(vrm0Head(R"({"x": 0, "y": 1e300, "z": 0})"), target);
    const std::vector<std::string> said = warningsOf(scene, "vrm-property-invalid");
    ASSERT_EQ(said.size(), 1u);
    EXPECT_NE(said[0].find("VRM.firstPerson.firstPersonBoneOffset (0, 1e+300, 0) lies 1e+300 from the head"),
              std::string::npos)
        << said[0];
    EXPECT_EQ(worldPositions(scene, "LeftGaze"), worldPositions(expected, "LeftGaze"));
    // The left eye turned outward by 5 degrees (10 of 20 -> 5 of 10), away from its rest direction.
    const double outer = glm::radians(5.0);
    EXPECT_TRUE(
        hasVertex(scene, "LeftGaze", glm::dvec3(0.03, 1.05, 0.05) + glm::dvec3(std::sin(outer), 0.0, std::cos(outer))));
}

TEST(VrmLookAt, TheExpressionTypeWeightsLookLeft) {
    const std::string lookAt = R"({"type": "expression", "offsetFromHeadBone": [0, 0.06, 0],
        "rangeMapHorizontalOuter": {"inputMaxValue": 20, "outputScale": 1}})";
    const std::string expressions = R"(, "expressions": {"preset": {
        "lookLeft": {"morphTargetBinds": [{"node": 3, "index": 0, "weight": 1}]},
        "lookRight": {"morphTargetBinds": [{"node": 4, "index": 0, "weight": 1}]}}})";
    const Scene scene = loadHead(lookAt, pointAt(10.0), expressions);
    // lookLeft at 0.5 lifts LeftGaze's third vertex by 0.5; lookRight stays 0; the eyes do not turn.
    EXPECT_TRUE(hasVertex(scene, "LeftGaze", {0.03 + 0.1, 1.05, 0.05 + 0.5}));
    EXPECT_TRUE(hasVertex(scene, "RightGaze", {-0.03 + 0.1, 1.05, 0.05}));
    EXPECT_TRUE(hasVertex(scene, "LeftGaze", {0.03, 1.05, 1.05}));
}

TEST(VrmLookAt, ALookExpressionGivenBesideAnExpressionTypeLookAtIsRefused) {
    const TempFile file("head.vrm", headVrm(R"({"type": "expression"})", R"(, "expressions": {"preset": {
        "lookLeft": {"morphTargetBinds": [{"node": 3, "index": 0, "weight": 1}]}}})"));
    LoadOptions options;
    options.lookAt = pointAt(10.0);
    options.expressions = {{"lookLeft", 1.0}};
    try {
        loadScene(file.path(), options);
        FAIL() << "expected a SceneError";
    } catch (const SceneError& error) {
        EXPECT_NE(std::string(error.what()).find("--expression 'lookLeft' and --look-at both set it"),
                  std::string::npos)
            << error.what();
    }
}

TEST(VrmLookAt, TheExpressionTypeWithoutLookExpressionsIsRefused) {
    try {
        loadHead(R"({"type": "expression"})", pointAt(10.0));
        FAIL() << "expected a SceneError";
    } catch (const SceneError& error) {
        EXPECT_NE(std::string(error.what())
                      .find("--look-at: the file's look-at moves the eyes by expressions, but it "
                            "has none of lookUp, lookDown, lookLeft, lookRight"),
                  std::string::npos)
            << error.what();
    }
}

TEST(VrmLookAt, AFileWithoutLookAtSettingsIsRefused) {
    const TempFile file("face.vrm", faceVrm(kExpressions));
    LoadOptions options;
    options.lookAt = glm::dvec3(0.0, 0.0, 1.0);
    try {
        loadScene(file.path(), options);
        FAIL() << "expected a SceneError";
    } catch (const SceneError& error) {
        EXPECT_NE(std::string(error.what()).find("face.vrm': --look-at: the file has no VRM look-at settings"),
                  std::string::npos)
            << error.what();
    }
}

} // namespace
} // namespace inkgraph
