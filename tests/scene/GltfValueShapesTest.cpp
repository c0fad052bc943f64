/** The shapes of glTF's core values, judged before tinygltf reads the file (GltfValueShapes.h): tinygltf takes a
 *  value of the wrong type or length for absent, so each case here loaded as the default without a word. */

#include "scene/Scene.h"
#include "scene/mesh/MeshOps.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>

namespace inkgraph {
namespace {

using test::GltfWriter;
using test::TempFile;

/** A unit quad (two triangles) on a node whose members are `nodeMembers` ("\"scale\": [1, 2, 3], "), with material
 *  members `materialMembers` and, when `morph` is set, one morph target and the mesh members `meshMembers`. */
class Quad {
public:
    Quad() {
        mPositions = mWriter.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
        mIndices = mWriter.addIndices({0, 1, 2, 2, 1, 3}, 2);
        mOffsets = mWriter.addVec3({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    }

    std::string body(const std::string& nodeMembers, const std::string& materialMembers = "",
                     const std::string& meshMembers = "", bool morph = false) const {
        return "\"materials\": [{\"name\": \"paint\"" + materialMembers +
               "}], \"meshes\": [{\"name\": \"quad\", \"primitives\": [{\"attributes\": {\"POSITION\": " +
               std::to_string(mPositions) + "}, \"indices\": " + std::to_string(mIndices) + ", \"material\": 0" +
               (morph ? ", \"targets\": [{\"POSITION\": " + std::to_string(mOffsets) + "}]" : std::string()) + "}]" +
               meshMembers + "}], \"nodes\": [{" + nodeMembers +
               "\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}], \"scene\": 0";
    }

    const GltfWriter& writer() const { return mWriter; }

private:
    GltfWriter mWriter;
    int mPositions = 0;
    int mIndices = 0;
    int mOffsets = 0;
};

std::string refusal(const std::string& fileName, const std::string& content) {
    const TempFile file(fileName, content);
    return test::sceneErrorMessage([&] { loadScene(file.path()); });
}

bool warned(const Scene& scene, WarningKind kind, const std::string& text) {
    return std::ranges::any_of(scene.report.warnings, [&](const Warning& warning) {
        return warning.code == warningCode(kind) && warning.message.find(text) != std::string::npos;
    });
}

TEST(GltfValueShapes, ANodeTransformOfTheWrongShapeIsRefusedNamingIt) {
    const Quad quad;
    // Each was taken for absent: the node drawn untransformed.
    const std::pair<std::string, std::string> cases[] = {
        {"\"matrix\": [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0], ",
         "nodes[0].matrix has 15 values, not 16 numbers"},
        {"\"translation\": [1, 2], ", "nodes[0].translation has 2 values, not 3 numbers"},
        {"\"rotation\": \"none\", ", "nodes[0].rotation is the string 'none', not 4 numbers"},
        {"\"scale\": [1, true, 1], ", "nodes[0].scale[1] is true, not a number"},
        {"\"matrix\": [1, 0, 0, 0.5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], ",
         "nodes[0].matrix is projective: its bottom row is [0.5, 0, 0, 1] (elements 3, 7, 11, 15), where glTF's "
         "affine nodes have [0, 0, 0, 1]"},
    };
    for (const auto& [members, expected] : cases) {
        const std::string message = refusal("node.gltf", quad.writer().gltf(quad.body(members)));
        EXPECT_NE(message.find("node.gltf': " + expected), std::string::npos) << message;
    }
    // Within float rounding of affine, and of the right shapes, a node loads as written.
    const Scene scene = loadScene(
        TempFile("affine.gltf", quad.writer().gltf(quad.body("\"matrix\": [2, 0, 0, 1e-7, 0, 2, 0, 0, 0, 0, 2, 0, 0, "
                                                             "0, 0, 1.000001], ")))
            .path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    const BoundingBox box = computeBoundingBox(scene.meshes[0].positions);
    EXPECT_NEAR(box.max.x - box.min.x, 2.0, 1e-6) << "the matrix's scale of 2 applied";
    EXPECT_TRUE(scene.report.warnings.empty()) << scene.report.warnings.front();
}

TEST(GltfValueShapes, AnotherVersionOrAnExtensionListOfTheWrongTypeIsRefused) {
    const Quad quad;
    const std::string file = quad.writer().gltf(quad.body(""));
    const auto withAsset = [&](const std::string& asset) {
        std::string text = file;
        const std::string written = "\"asset\": {\"version\": \"2.0\"}";
        text.replace(text.find(written), written.size(), "\"asset\": {" + asset + "}");
        return text;
    };
    EXPECT_NE(refusal("v3.gltf", withAsset("\"version\": \"3.0\""))
                  .find("asset.version is '3.0': this reader reads glTF 2.0"),
              std::string::npos);
    EXPECT_NE(refusal("v1.gltf", withAsset("\"version\": \"1.0\"")).find("asset.version is '1.0'"), std::string::npos);
    EXPECT_NE(refusal("min.gltf", withAsset("\"version\": \"2.1\", \"minVersion\": \"2.1\""))
                  .find("asset.minVersion is '2.1'"),
              std::string::npos);
    EXPECT_NE(refusal("word.gltf", withAsset("\"version\": \"two\"")).find("asset.version is 'two', not a version"),
              std::string::npos);
    // tinygltf told a number as "asset object not found".
    EXPECT_NE(
        refusal("number.gltf", withAsset("\"version\": 2.0")).find("asset.version is 2.0, not a string such as '2.0'"),
        std::string::npos);
    // A version longer than the 4 KiB at which data: URIs are cut before the file is judged is quoted as written:
    // it was told as '' (every long string was cut to its first printable ASCII bytes, none here).
    std::string escaped;
    for (int i = 0; i < 1200; ++i) escaped += "\\u0041";
    const std::string longVersion = refusal("long.gltf", withAsset("\"version\": \"" + escaped + "\""));
    EXPECT_NE(longVersion.find("asset.version is 'AAAA"), std::string::npos) << longVersion;
    EXPECT_NE(longVersion.find("(1200 bytes)"), std::string::npos) << longVersion;
    // A later minor version reads as 2.0: glTF keeps them compatible.
    const Scene later = loadScene(TempFile("later.gltf", withAsset("\"version\": \"2.1\"")).path());
    EXPECT_EQ(later.meshes.size(), 1u);
    EXPECT_TRUE(later.report.warnings.empty());

    // tinygltf took an object for an empty array: "material index 0 out of range (file has 0 materials)".
    std::string objectFile = quad.writer().gltf(quad.body(""));
    const std::string materials = "\"materials\": [{\"name\": \"paint\"}]";
    objectFile.replace(objectFile.find(materials), materials.size(), "\"materials\": {\"paint\": {}}");
    const std::string object = refusal("object.gltf", objectFile);
    EXPECT_NE(object.find("object.gltf': materials is {\"paint\":{}}, not an array"), std::string::npos) << object;

    const std::string required =
        refusal("required.gltf",
                quad.writer().gltf("\"extensionsRequired\": \"KHR_draco_mesh_compression\", " + quad.body("")));
    EXPECT_NE(required.find("extensionsRequired is the string 'KHR_draco_mesh_compression', not an array of "
                            "extension names"),
              std::string::npos)
        << required;

    // glTF 1.0's binary form is version 1 and laid out otherwise: it was read as a 2.0 GLB.
    std::string glb = quad.writer().glb(quad.body(""));
    const std::uint32_t one = 1;
    std::memcpy(glb.data() + 4, &one, sizeof one);
    const std::string header = refusal("one.glb", glb);
    EXPECT_NE(header.find("one.glb': GLB header version 1, not 2"), std::string::npos) << header;
}

TEST(GltfValueShapes, AStrideOrADataUriLengthTinygltfMisnamesIsToldAsItIs) {
    const Quad quad;
    std::string strided = quad.writer().gltf(quad.body(""));
    const std::string view = "\"byteOffset\": 0, ";
    strided.insert(strided.find(view), "\"byteStride\": 512, ");
    const std::string stride = refusal("stride.gltf", strided);
    // tinygltf: "`byteStride' must be the multiple of 4 : 512".
    EXPECT_NE(stride.find("stride.gltf': bufferViews[0].byteStride is 512, not a multiple of 4 from 4 to 252"),
              std::string::npos)
        << stride;

    // tinygltf: "Failed to decode 'uri'", as for a URI that is not base64.
    std::string longer = quad.writer().gltf(quad.body(""));
    const std::string length = "\"byteLength\": " + std::to_string(quad.writer().binary().size()) + "}]";
    longer.replace(longer.find(length), length.size(),
                   "\"byteLength\": " + std::to_string(quad.writer().binary().size() + 8) + "}]");
    const std::string message = refusal("long.gltf", longer);
    EXPECT_NE(message.find("long.gltf': invalid glTF: buffers[0].byteLength is " +
                           std::to_string(quad.writer().binary().size() + 8) + ", but its data: URI holds " +
                           std::to_string(quad.writer().binary().size()) + " bytes"),
              std::string::npos)
        << message;
    std::string broken = quad.writer().gltf(quad.body(""));
    broken.insert(broken.find(";base64,") + 8, "!");
    const std::string brokenMessage = refusal("broken.gltf", broken);
    EXPECT_NE(brokenMessage.find("buffers[0].uri's data: URI is not valid base64"), std::string::npos) << brokenMessage;
    // Taken by tinygltf for file names: "File not found", quoting the URI's decoded bytes.
    std::string typeless = quad.writer().gltf(quad.body(""));
    typeless.replace(typeless.find("data:application/octet-stream;"), 30, "data:;");
    const std::string typelessMessage = refusal("typeless.gltf", typeless);
    EXPECT_NE(typelessMessage.find("buffers[0].uri's data: URI has the media type '', where a glTF buffer's is "
                                   "'application/octet-stream' or 'application/gltf-buffer'"),
              std::string::npos)
        << typelessMessage;
    const std::string percent =
        refusal("percent.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"byteLength\": 4, \"uri\": "
                                "\"data:application/octet-stream,%00%00%80%BF\"}]}");
    EXPECT_NE(percent.find("buffers[0].uri is a data: URI without ';base64,'"), std::string::npos) << percent;
}

TEST(GltfValueShapes, AMaterialValueOfTheWrongTypeIsSaidAndItsDefaultUsed) {
    const Quad quad;
    const Scene scene = loadScene(
        TempFile("paint.gltf",
                 quad.writer().gltf(quad.body("", ", \"pbrMetallicRoughness\": {\"baseColorFactor\": [1, 0, 0]}, "
                                                  "\"doubleSided\": \"yes\", \"emissiveFactor\": [1, 0], "
                                                  "\"alphaMode\": 1, \"normalTexture\": {\"index\": 0, \"scale\": "
                                                  "\"deep\"}")))
            .path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].material.baseColorFactor, glm::vec4(1.0f));
    EXPECT_FALSE(scene.meshes[0].material.doubleSided);
    for (const std::string& expected :
         {std::string("materials[0].pbrMetallicRoughness.baseColorFactor has 3 values, not 4 numbers; the default "
                      "[1, 1, 1, 1] is used"),
          std::string("materials[0].doubleSided is the string 'yes', not true or false; the default false is used"),
          std::string("materials[0].emissiveFactor has 2 values, not 3 numbers; the default [0, 0, 0] is used"),
          std::string("materials[0].alphaMode is 1, not a string; the default OPAQUE is used"),
          std::string("materials[0].normalTexture.scale is the string 'deep', not a number")}) {
        EXPECT_TRUE(warned(scene, WarningKind::MaterialValueInvalid, expected)) << expected;
    }
    // Dropped before tinygltf reads the file, which warned of the base colour's length and refused the emissive's.
    EXPECT_FALSE(std::ranges::any_of(
        scene.report.warnings, [](const Warning& w) { return w.code == warningCode(WarningKind::GltfParserMessage); }));

    const Scene empty =
        loadScene(TempFile("null.gltf", quad.writer().gltf(quad.body("", ", \"normalTexture\": null"))).path());
    EXPECT_TRUE(warned(empty, WarningKind::MaterialValueInvalid,
                       "materials[0].normalTexture is null, not an object; its defaults are used"));
    EXPECT_EQ(empty.report.warnings.size(), 1u) << "tinygltf's \"'index' property is missing\" is not said too";

    const Scene object = loadScene(
        TempFile("shiny.gltf", quad.writer().gltf(quad.body("", ", \"pbrMetallicRoughness\": \"shiny\""))).path());
    EXPECT_TRUE(
        warned(object, WarningKind::MaterialValueInvalid,
               "materials[0].pbrMetallicRoughness is the string 'shiny', not an object; its defaults are used"));
    EXPECT_EQ(object.report.warnings.size(), 1u);
}

TEST(GltfValueShapes, MorphWeightsOtherThanOnePerTargetAreSaid) {
    const Quad quad;
    // One target: the mesh's two weights, and a node's none, differ from it; a weight per target is not warned.
    const Scene extra = loadScene(
        TempFile("extra.gltf", quad.writer().gltf(quad.body("", "", ", \"weights\": [1, 0.5]", true))).path());
    EXPECT_TRUE(warned(extra, WarningKind::MorphWeightsMismatched,
                       "meshes[0].weights has 2 weights for 1 morph targets; the extra weights are ignored"));
    const BoundingBox box = computeBoundingBox(extra.meshes[0].positions);
    EXPECT_NEAR(box.max.z - box.min.z, 0.0, 1e-6) << "the one target's weight of 1 moves the whole quad";
    const Scene fewer =
        loadScene(TempFile("fewer.gltf", quad.writer().gltf(quad.body("\"weights\": [], ", "", "", true))).path());
    EXPECT_TRUE(warned(fewer, WarningKind::MorphWeightsMismatched,
                       "nodes[0].weights has 0 weights for 1 morph targets; the targets without one are not applied"));
    const Scene text =
        loadScene(TempFile("text.gltf", quad.writer().gltf(quad.body("", "", ", \"weights\": \"0.5\"", true))).path());
    EXPECT_TRUE(warned(text, WarningKind::MorphWeightsMismatched,
                       "meshes[0].weights is the string '0.5', not an array of numbers; read as no weights"));
    const Scene none =
        loadScene(TempFile("none.gltf", quad.writer().gltf(quad.body("", "", ", \"weights\": \"0.5\"", false))).path());
    EXPECT_TRUE(warned(none, WarningKind::MorphWeightsMismatched,
                       "meshes[0].weights is the string '0.5', not an array of numbers; ignored"));
    const Scene one =
        loadScene(TempFile("one.gltf", quad.writer().gltf(quad.body("", "", ", \"weights\": [1]", true))).path());
    EXPECT_TRUE(one.report.warnings.empty()) << one.report.warnings.front();
}

TEST(GltfValueShapes, AChannelWhoseTargetNamesNoNodeIsSaidAsItself) {
    // KHR_animation_pointer's channels name their target by a pointer, not a node: tinygltf skips them saying only
    // "'node' property is missing." and "`node` field is missing in animation.channels.target".
    const Quad quad;
    GltfWriter writer = quad.writer();
    const int times = writer.addFloats({0.0f, 1.0f}, "SCALAR", 1);
    const int values = writer.addVec3({{0, 0, 0}, {1, 0, 0}});
    const std::string sampler =
        "\"samplers\": [{\"input\": " + std::to_string(times) + ", \"output\": " + std::to_string(values) + "}]";
    const std::string animations =
        ", \"animations\": [{\"channels\": [{\"sampler\": 0, \"target\": {\"node\": 0, \"path\": "
        "\"translation\"}}, {\"sampler\": 0, \"target\": {\"path\": \"pointer\", \"extensions\": "
        "{\"KHR_animation_pointer\": {\"pointer\": \"/nodes/0/translation\"}}}}], " +
        sampler + "}, {\"channels\": [{\"sampler\": 0, \"target\": {\"path\": \"translation\"}}], " + sampler + "}]";
    const Scene scene = loadScene(TempFile("pointer.gltf", writer.gltf(quad.body("") + animations)).path());
    EXPECT_TRUE(warned(scene, WarningKind::AnimationChannelIgnored,
                       "animations[0].channels[1]: its target names no node (a KHR_animation_pointer channel, which "
                       "this reader does not read); ignored"))
        << ::testing::PrintToString(scene.report.warnings);
    EXPECT_TRUE(warned(scene, WarningKind::AnimationChannelIgnored,
                       "animations[1].channels[0]: its target names no node (another extension's channel); ignored"));
    EXPECT_EQ(scene.report.warnings.size(), 2u)
        << "tinygltf's words are not said again: " << ::testing::PrintToString(scene.report.warnings);
}

} // namespace
} // namespace inkgraph
