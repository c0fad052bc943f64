#include "scene/Camera.h"
#include "scene/Scene.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <utility>

namespace inkgraph {
namespace {

using test::GltfWriter;
using test::TempFile;

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance = 1e-6) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

/** One mesh with one primitive on one node, in the default scene. */
std::string singleNode(const std::string& primitive, const std::string& nodeExtras = "") {
    return "\"meshes\": [{\"name\": \"shape\", \"primitives\": [" + primitive +
           "]}], "
           "\"nodes\": [{\"mesh\": 0" +
           nodeExtras + "}], \"scenes\": [{\"nodes\": [0]}], \"scene\": 0";
}

const std::vector<glm::vec3> kUnitTriangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

TEST(GltfLoader, TriangleStripKeepsItsWinding) {
    // A zig-zag strip of 5 vertices in the z=0 plane: triangles 0-1-2, 1-3-2 (odd: last two swapped), 2-3-4, all +z.
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}});
    const TempFile file(
        "strip.gltf",
        writer.gltf(singleNode("{\"attributes\": {\"POSITION\": " + std::to_string(positions) + "}, \"mode\": 5}")));
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.report.format, "gltf");
    EXPECT_EQ(scene.report.trianglesRead, 3u);
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    EXPECT_EQ(mesh.triangleCount(), 3u);
    EXPECT_EQ(mesh.positions.size(), 5u);
    EXPECT_EQ(mesh.name, "shape");
    for (const glm::uvec3& triangle : mesh.triangles) {
        EXPECT_NEAR(test::triangleCross(mesh, triangle).z, 1.0, 1e-9); // each has area 1/2, facing +z
    }
    for (const glm::vec3& normal : mesh.normals) {
        EXPECT_EQ(normal, glm::vec3(0, 0, 1));
    }
}

TEST(GltfLoader, IndexedTriangleFanWithByteIndices) {
    // A hexagon: centre plus six rim vertices counter-clockwise; the fan closes by repeating the first rim vertex.
    std::vector<glm::vec3> hexagon = {{0, 0, 0}};
    for (int i = 0; i < 6; ++i) {
        const float angle = float(i) * glm::pi<float>() / 3.0f;
        hexagon.emplace_back(std::cos(angle), std::sin(angle), 0.0f);
    }
    GltfWriter writer;
    const int positions = writer.addVec3(hexagon);
    const int indices = writer.addIndices({0, 1, 2, 3, 4, 5, 6, 1}, 1);
    const TempFile file("fan.glb",
                        writer.glb(singleNode("{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                                              "}, \"indices\": " + std::to_string(indices) + ", \"mode\": 6}")));
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.report.format, "glb");
    const Mesh& mesh = scene.meshes.at(0);
    EXPECT_EQ(mesh.triangleCount(), 6u);
    EXPECT_EQ(mesh.positions.size(), 7u);
    for (const glm::uvec3& triangle : mesh.triangles) {
        EXPECT_GT(test::triangleCross(mesh, triangle).z, 0.0);
    }
}

TEST(GltfLoader, ShortAndIntIndicesGiveTheSameMesh) {
    for (int bytes : {2, 4}) {
        GltfWriter writer;
        const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
        const int indices = writer.addIndices({0, 1, 2, 0, 2, 3}, bytes);
        const TempFile file("quad.gltf",
                            writer.gltf(singleNode("{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                                                   "}, \"indices\": " + std::to_string(indices) + "}")));
        const Mesh mesh = loadScene(file.path()).meshes.at(0);
        EXPECT_EQ(mesh.triangles, (std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}})) << bytes << "-byte indices";
    }
}

TEST(GltfLoader, NodeTransformsAreBakedIntoWorldSpace) {
    // Parent translates by (10, 0, 0); child scales by 2 and translates by (0, 1, 0) in the parent's frame.
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    const std::string body =
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
        "}}]}], "
        "\"nodes\": [{\"name\": \"parent\", \"translation\": [10, 0, 0], \"children\": [1]},"
        "            {\"name\": \"child\", \"mesh\": 0, \"translation\": [0, 1, 0], \"scale\": [2, 2, 2]}], "
        "\"scenes\": [{\"nodes\": [0]}]";
    const TempFile file("transform.gltf", writer.gltf(body));
    const Scene scene = loadScene(file.path());
    const Mesh& mesh = scene.meshes.at(0);
    EXPECT_EQ(mesh.name, "child");
    ASSERT_EQ(mesh.positions.size(), 3u);
    EXPECT_EQ(test::worldPosition(scene, mesh.positions[0]), glm::dvec3(10, 1, 0));
    EXPECT_EQ(test::worldPosition(scene, mesh.positions[1]), glm::dvec3(12, 1, 0));
    EXPECT_EQ(test::worldPosition(scene, mesh.positions[2]), glm::dvec3(10, 3, 0));
}

TEST(GltfLoader, ANodeRotationOfAnyLengthTurnsAsItsUnitOneAndOneOfNoLengthIsAnError) {
    // glTF asks for unit quaternions; a file's may be scaled. Lengths whose squares overflow or underflow a double
    // (1e300, 1e-200) turn the mesh as the unit quaternion does: half a turn about x takes (0, 1, 0) to (0, -1, 0).
    // Before, they were drawn unturned, silently.
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    const std::string primitive = "{\"attributes\": {\"POSITION\": " + std::to_string(positions) + "}}";
    for (const std::string rotation : {"1, 0, 0, 0", "1e300, 0, 0, 0", "1e-200, 0, 0, 0", "-3, 0, 0, 0"}) {
        SCOPED_TRACE("rotation [" + rotation + "]");
        const TempFile file("rotated.gltf", writer.gltf(singleNode(primitive, ", \"rotation\": [" + rotation + "]")));
        const Scene scene = loadScene(file.path());
        const Mesh& mesh = scene.meshes.at(0);
        ASSERT_EQ(mesh.positions.size(), 3u);
        expectNear(test::worldPosition(scene, mesh.positions[1]), glm::dvec3(1, 0, 0));
        expectNear(test::worldPosition(scene, mesh.positions[2]), glm::dvec3(0, -1, 0));
    }
    const TempFile file("norotation.gltf", writer.gltf(singleNode(primitive, ", \"rotation\": [0, 0, 0, 0]")));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
    EXPECT_NE(message.find("node 0: rotation [0, 0, 0, 0] must be finite and of non-zero length"), std::string::npos)
        << message;
}

TEST(GltfLoader, MatrixTransformAndMirroringKeepFrontFaces) {
    // A column-major matrix mirroring x and translating by (0, 0, 5); the file's +z normals must stay +z and the
    // triangle must still face them.
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    const int normals = writer.addVec3({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const std::string primitive = "{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                                  ", \"NORMAL\": " + std::to_string(normals) + "}}";
    const TempFile file("mirror.gltf",
                        writer.gltf(singleNode(primitive, ", \"matrix\": [-1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1]")));
    const Scene scene = loadScene(file.path());
    const Mesh& mesh = scene.meshes.at(0);
    EXPECT_FALSE(scene.report.normalsComputed);
    EXPECT_EQ(test::worldPosition(scene, mesh.positions[1]), glm::dvec3(-1, 0, 5));
    for (const glm::vec3& normal : mesh.normals) {
        EXPECT_EQ(normal, glm::vec3(0, 0, 1));
    }
    EXPECT_GT(test::triangleCross(mesh, mesh.triangles.at(0)).z, 0.0);
    // Its last two corners swapped to keep it so: marked, so the barycentric weights can be given in the file's order.
    EXPECT_EQ(mesh.cornersSwapped, std::vector<std::uint8_t>{1});
}

TEST(GltfLoader, NonUniformScaleUsesInverseTransposeForNormals) {
    // A 45-degree slope scaled by 2 in x: the transformed normal of (1, 1, 0)/sqrt2 is (1/2, 1, 0) normalised.
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {0, 0, 1}, {1, -1, 0}}); // wound to face the normal
    const glm::vec3 n = glm::normalize(glm::vec3(1, 1, 0));
    const int normals = writer.addVec3({n, n, n});
    const std::string primitive = "{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                                  ", \"NORMAL\": " + std::to_string(normals) + "}}";
    const TempFile file("scaled_normals.gltf", writer.gltf(singleNode(primitive, ", \"scale\": [2, 1, 1]")));
    const Mesh mesh = loadScene(file.path()).meshes.at(0);
    expectNear(glm::dvec3(mesh.normals.at(0)), glm::normalize(glm::dvec3(0.5, 1.0, 0.0)));
}

TEST(GltfLoader, BaseColorFactorIsRead) {
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    const std::string primitive = "{\"attributes\": {\"POSITION\": " + std::to_string(positions) + "}";
    const std::string body =
        "\"materials\": [{\"pbrMetallicRoughness\": {\"baseColorFactor\": [0.1, 0.2, 0.3, 0.4]}}], "
        "\"meshes\": [{\"primitives\": [" +
        primitive + ", \"material\": 0}, " + primitive +
        "}]}], "
        "\"nodes\": [{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}]";
    const TempFile file("material.gltf", writer.gltf(body));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 2u);
    EXPECT_EQ(scene.meshes[0].material.baseColorFactor, glm::vec4(0.1f, 0.2f, 0.3f, 0.4f));
    EXPECT_EQ(scene.meshes[1].material.baseColorFactor,
              glm::vec4(0.8f, 0.8f, 0.8f, 1.0f)); // no material: the default grey
}

/** Indices, offsets and counts written as whole numbers with a fraction (3.0, as numpy-based writers write them, and
 *  as JSON Schema counts integers) read as the integers: tinygltf took them for absent, so the indices were dropped
 *  (a soup of the vertices) and the material too (grey), without a word. Anything else there is refused by name. */
TEST(GltfLoader, IntegersWrittenAsWholeNumbersAreTheIntegersAndOtherValuesAreRefused) {
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
    const int indices = writer.addIndices({0, 1, 2, 2, 1, 3}, 2);
    const auto body = [&](const std::string& index, const std::string& material, const std::string& node) {
        return "\"materials\": [{\"pbrMetallicRoughness\": {\"baseColorFactor\": [0.1, 0.2, 0.3, 1.0]}}], "
               "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " +
               std::to_string(positions) + ".0}, \"indices\": " + index + ", \"mode\": 4.0, \"material\": " + material +
               "}]}], \"nodes\": [{\"mesh\": 0.0}], \"scenes\": [{\"nodes\": [" + node + "]}], \"scene\": 0.0";
    };
    writer.addVec3(std::vector<glm::vec3>(400)); // unused: makes the .gltf's data URI long (judged without it)
    const std::string wholeBody = body(std::to_string(indices) + ".0", "0.0", "0.0");
    for (const TempFile& whole :
         {TempFile("whole.glb", writer.glb(wholeBody)), TempFile("whole.gltf", writer.gltf(wholeBody))}) {
        const Scene scene = loadScene(whole.path());
        ASSERT_EQ(scene.meshes.size(), 1u) << whole.fileName();
        EXPECT_EQ(scene.meshes[0].triangles.size(), 2u) << "indexed: two triangles on four vertices";
        EXPECT_EQ(scene.meshes[0].positions.size(), 4u);
        EXPECT_EQ(scene.meshes[0].material.baseColorFactor, glm::vec4(0.1f, 0.2f, 0.3f, 1.0f));
    }

    const TempFile text("text.gltf", writer.gltf(body("\"1\"", "0", "0")));
    const std::string message = test::sceneErrorMessage([&] { loadScene(text.path()); });
    EXPECT_NE(message.find(text.fileName() + "': meshes[0].primitives[0].indices is the string '1', not an integer"),
              std::string::npos)
        << message;
    const TempFile fraction("fraction.gltf", writer.gltf(body(std::to_string(indices), "0.5", "true")));
    const std::string fractionMessage = test::sceneErrorMessage([&] { loadScene(fraction.path()); });
    EXPECT_NE(fractionMessage.find("meshes[0].primitives[0].material is 0.5, not an integer"), std::string::npos)
        << fractionMessage;
    const TempFile flag("flag.gltf", writer.gltf(body(std::to_string(indices), "0", "true")));
    const std::string flagMessage = test::sceneErrorMessage([&] { loadScene(flag.path()); });
    EXPECT_NE(flagMessage.find("scenes[0].nodes[0] is true, not an integer"), std::string::npos) << flagMessage;
    // An index tinygltf's int cannot hold wrapped (4294967299 read as accessor 3), and -1 read as absent (a soup).
    const std::pair<std::string, std::string> outOfRange[] = {
        {"4294967299.0", "4294967299.0, over 2147483647, the largest index glTF's reader can hold"},
        {"4294967299", "4294967299, over 2147483647, the largest index glTF's reader can hold"},
        {"-1", "-1, negative: glTF's indices and enums are 0 or more"},
        {"-1.0", "-1.0, negative: glTF's indices and enums are 0 or more"}};
    for (const auto& [index, expected] : outOfRange) {
        const TempFile wide("wide.gltf", writer.gltf(body(index, "0", "0")));
        const std::string wideMessage = test::sceneErrorMessage([&] { loadScene(wide.path()); });
        EXPECT_NE(wideMessage.find("meshes[0].primitives[0].indices is " + expected), std::string::npos) << wideMessage;
    }
    // A size below 0 is told as negative, not as outside a range of 2^53 (which only a size over it is).
    std::string negativeStride = writer.gltf(body(std::to_string(indices), "0", "0"));
    const std::string firstView = "\"bufferViews\": [{";
    ASSERT_NE(negativeStride.find(firstView), std::string::npos);
    negativeStride.insert(negativeStride.find(firstView) + firstView.size(), "\"byteStride\": -12, ");
    const TempFile stride("stride.gltf", negativeStride);
    const std::string strideMessage = test::sceneErrorMessage([&] { loadScene(stride.path()); });
    EXPECT_NE(strideMessage.find("stride.gltf': bufferViews[0].byteStride is -12, negative: glTF's offsets, lengths, "
                                 "strides and counts are 0 or more"),
              std::string::npos)
        << strideMessage;
}

/** Meshes "a", "b", "c" (one triangle each, one node each), using the materials given as JSON (empty: none). */
std::string threeMeshesWithMaterials(GltfWriter& writer, const std::string& materials,
                                     const std::vector<int>& materialOfMesh) {
    const int positions = writer.addVec3(kUnitTriangle);
    std::string meshes;
    std::string nodes;
    const char* names[] = {"a", "b", "c"};
    for (std::size_t i = 0; i < materialOfMesh.size(); ++i) {
        const std::string material =
            materialOfMesh[i] >= 0 ? ", \"material\": " + std::to_string(materialOfMesh[i]) : "";
        meshes += std::string(i ? ", " : "") + "{\"name\": \"" + names[i] +
                  "\", \"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) + "}" + material +
                  "}]}";
        nodes += std::string(i ? ", " : "") + "{\"mesh\": " + std::to_string(i) + "}";
    }
    std::string roots;
    for (std::size_t i = 0; i < materialOfMesh.size(); ++i) roots += std::string(i ? ", " : "") + std::to_string(i);
    return "\"materials\": [" + materials + "], \"meshes\": [" + meshes + "], \"nodes\": [" + nodes +
           "], \"scenes\": [{\"nodes\": [" + roots + "]}]";
}

TEST(GltfLoader, MaterialShadeMapIsResolvedAgainstTheFilesFolder) {
    // Material 0: a relative path with a detour, resolved next to the .gltf (the temp folder) and normalised;
    // material 1: an absolute path, kept; material 2: extras of another tool only. Mesh "c" has no material.
    GltfWriter writer;
    const std::string materials =
        "{\"name\": \"Warm\", \"extras\": {\"inkgraph\": {\"shademap\": \"maps/../maps/./warm.png\"}}}, "
        "{\"extras\": {\"inkgraph\": {\"shademap\": \"/srv/maps/cool.png\"}, \"blender\": 1}}, "
        "{\"name\": \"Plain\", \"extras\": {\"blender\": {\"shademap\": 5}}}";
    const TempFile file("shademaps.gltf", writer.gltf(threeMeshesWithMaterials(writer, materials, {0, 1, 2})));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 3u);
    const std::filesystem::path folder = std::filesystem::path(file.path()).parent_path();
    EXPECT_EQ(scene.meshes[0].material.shadeMapPath, (folder / "maps" / "warm.png").string());
    EXPECT_EQ(scene.meshes[1].material.shadeMapPath, "/srv/maps/cool.png");
    EXPECT_EQ(scene.meshes[2].material.shadeMapPath, "");
    EXPECT_EQ(scene.meshes[0].material.name, "Warm");
    EXPECT_EQ(scene.meshes[1].material.name, "");
    EXPECT_EQ(scene.meshes[2].material.name, "Plain");
    EXPECT_TRUE(scene.report.warnings.empty()) << scene.report.warnings.front();

    GltfWriter noMaterialWriter;
    const TempFile plain("no_material.gltf",
                         noMaterialWriter.gltf(threeMeshesWithMaterials(noMaterialWriter, "", {-1})));
    EXPECT_EQ(loadScene(plain.path()).meshes.at(0).material.shadeMapPath, "");
}

TEST(GltfLoader, MaterialShadeMapSharedByPrimitivesWarnsOnceAboutUnknownKeys) {
    // Two meshes use material 0, whose inkgraph extras hold a typo next to the map: one warning naming the key and
    // the material, and both meshes get the map.
    GltfWriter writer;
    const std::string materials =
        "{\"name\": \"Metal\", \"extras\": {\"inkgraph\": {\"shademap\": \"metal.png\", \"shadeMap\": \"x.png\"}}}";
    const TempFile file("typo.gltf", writer.gltf(threeMeshesWithMaterials(writer, materials, {0, 0})));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 2u);
    const std::string expected = (std::filesystem::path(file.path()).parent_path() / "metal.png").string();
    EXPECT_EQ(scene.meshes[0].material.shadeMapPath, expected);
    EXPECT_EQ(scene.meshes[1].material.shadeMapPath, expected);
    ASSERT_EQ(scene.report.warnings.size(), 1u);
    EXPECT_EQ(scene.report.warnings[0].message,
              "material 0 'Metal': extras.inkgraph key 'shadeMap' ignored (known: 'shademap')");
}

TEST(GltfLoader, MaterialShadeMapOfTheWrongTypeIsAnError) {
    // What the file holds -> the end of the message; the material is named by index and name (or index alone).
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"{\"inkgraph\": 5}", "extras.inkgraph must be an object, got number"},
        {"{\"inkgraph\": \"metal.png\"}", "extras.inkgraph must be an object, got string"},
        {"{\"inkgraph\": []}", "extras.inkgraph must be an object, got array"},
        {"{\"inkgraph\": null}", "extras.inkgraph must be an object, got null"},
        {"{\"inkgraph\": {\"shademap\": 3}}",
         "extras.inkgraph.shademap must be a non-empty string (a PNG path), got number"},
        {"{\"inkgraph\": {\"shademap\": \"\"}}",
         "extras.inkgraph.shademap must be a non-empty string (a PNG path), got an empty string"},
        {"{\"inkgraph\": {\"shademap\": null}}",
         "extras.inkgraph.shademap must be a non-empty string (a PNG path), got null"},
        {"{\"inkgraph\": {\"shademap\": {}}}",
         "extras.inkgraph.shademap must be a non-empty string (a PNG path), got object"},
    };
    for (const auto& [extras, problem] : cases) {
        for (const bool named : {true, false}) {
            GltfWriter writer;
            const std::string material =
                std::string("{") + (named ? "\"name\": \"Metal\", " : "") + "\"extras\": " + extras + "}";
            const TempFile file("bad_extras.gltf",
                                writer.gltf(threeMeshesWithMaterials(writer, "{}, " + material, {-1, 1})));
            const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
            EXPECT_EQ(message,
                      "loadScene(): '" + file.path() + "': material 1" + (named ? " 'Metal'" : "") + ": " + problem)
                << extras;
        }
    }
}

TEST(GltfLoader, PerspectiveCameraIsRead) {
    // Camera at (1, 2, 10) turned 90 degrees about +y: it looks down -x, up stays +y.
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    const double s = std::sqrt(0.5);
    const std::string body =
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
        "}}]}], "
        "\"cameras\": [{\"type\": \"orthographic\", \"orthographic\": {\"xmag\": 1, \"ymag\": 1, \"znear\": 0.1, "
        "\"zfar\": 10}}, {\"type\": \"perspective\", \"perspective\": {\"yfov\": 0.5, \"aspectRatio\": 1.5, "
        "\"znear\": 0.1}}], "
        "\"nodes\": [{\"mesh\": 0}, {\"camera\": 0}, {\"camera\": 1, \"translation\": [1, 2, 10], "
        "\"rotation\": [0, " +
        std::to_string(s) + ", 0, " + std::to_string(s) +
        "]}], "
        "\"scenes\": [{\"nodes\": [0, 1, 2]}]";
    const TempFile file("camera.gltf", writer.gltf(body));
    const Scene scene = loadScene(file.path());
    ASSERT_TRUE(scene.camera.has_value());
    expectNear(scene.origin + scene.camera->eye, {1, 2, 10});
    expectNear(scene.camera->forward, {-1, 0, 0});
    expectNear(scene.camera->up, {0, 1, 0});
    EXPECT_NEAR(scene.camera->fovYDegrees, 0.5 * 180.0 / glm::pi<double>(), 1e-9);
    ASSERT_TRUE(scene.camera->aspectRatio.has_value());
    EXPECT_DOUBLE_EQ(*scene.camera->aspectRatio, 1.5);
    const bool warnedAboutOrthographic =
        std::any_of(scene.report.warnings.begin(), scene.report.warnings.end(),
                    [](const Warning& warning) { return warning.message.find("orthographic") != std::string::npos; });
    EXPECT_TRUE(warnedAboutOrthographic);

    const Camera camera = resolveCamera({}, scene);
    EXPECT_EQ(camera.source, "gltf");
    expectNear(camera.worldEye(), {1, 2, 10});
    expectNear(glm::normalize(camera.target - camera.eye), {-1, 0, 0});
}

TEST(GltfLoader, DirectionalLightPointsTowardTheLight) {
    // The light node is turned -90 degrees about +x, so it shines along -y: toward the light is +y.
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    const double s = std::sqrt(0.5);
    const std::string body = "\"extensionsUsed\": [\"KHR_lights_punctual\"], "
                             "\"extensions\": {\"KHR_lights_punctual\": {\"lights\": [{\"type\": \"point\"}, "
                             "{\"type\": \"directional\", \"color\": [1, 0.5, 0.25], \"intensity\": 3}]}}, "
                             "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " +
                             std::to_string(positions) +
                             "}}]}], "
                             "\"nodes\": [{\"mesh\": 0}, {\"extensions\": {\"KHR_lights_punctual\": {\"light\": 0}}}, "
                             "{\"rotation\": [" +
                             std::to_string(-s) + ", 0, 0, " + std::to_string(s) +
                             "], "
                             "\"extensions\": {\"KHR_lights_punctual\": {\"light\": 1}}}], "
                             "\"scenes\": [{\"nodes\": [0, 1, 2]}]";
    const TempFile file("light.glb", writer.glb(body));
    const Scene scene = loadScene(file.path());
    ASSERT_TRUE(scene.light.has_value());
    expectNear(scene.light->towardLight, {0, 1, 0});
    expectNear(scene.light->color, {1, 0.5, 0.25});
    EXPECT_DOUBLE_EQ(scene.light->intensity, 3.0);
}

TEST(GltfLoader, DefaultSceneSelectsTheRoots) {
    GltfWriter writer;
    const int small = writer.addVec3(kUnitTriangle);
    const int large = writer.addVec3({{0, 0, 0}, {5, 0, 0}, {0, 5, 0}});
    const std::string body =
        "\"meshes\": [{\"name\": \"small\", \"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(small) +
        "}}]}, {\"name\": \"large\", \"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(large) +
        "}}]}], "
        "\"nodes\": [{\"mesh\": 0}, {\"mesh\": 1}], \"scenes\": [{\"nodes\": [0]}, {\"nodes\": [1]}], \"scene\": 1";
    const TempFile file("scenes.gltf", writer.gltf(body));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].name, "large");
}

TEST(GltfLoader, PointsOnlyFileHasNoTriangles) {
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    const TempFile file(
        "points.gltf",
        writer.gltf(singleNode("{\"attributes\": {\"POSITION\": " + std::to_string(positions) + "}, \"mode\": 0}")));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("no triangles"), std::string::npos) << message;
    EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
}

TEST(GltfLoader, NonTrianglePrimitivesBesideTrianglesAreSkippedWithAWarning) {
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    const std::string attributes = "{\"attributes\": {\"POSITION\": " + std::to_string(positions) + "}";
    const TempFile file("mixed.gltf", writer.gltf(singleNode(attributes + ", \"mode\": 1}, " + attributes + "}")));
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.triangleCount(), 1u);
    ASSERT_EQ(scene.report.warnings.size(), 1u);
    EXPECT_NE(scene.report.warnings[0].message.find("non-triangle primitive"), std::string::npos);
}

TEST(GltfLoader, TruncatedGlbNamesTheFile) {
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    const std::string glb =
        writer.glb(singleNode("{\"attributes\": {\"POSITION\": " + std::to_string(positions) + "}}"));
    const TempFile file("half.glb", glb.substr(0, glb.size() / 2));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_EQ(message.rfind("loadScene(): '", 0), 0u) << message;
    EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
}

TEST(GltfLoader, NonFinitePositionIsAnError) {
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {std::nanf(""), 0, 0}, {0, 1, 0}});
    const TempFile file("nan.gltf",
                        writer.gltf(singleNode("{\"attributes\": {\"POSITION\": " + std::to_string(positions) + "}}")));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("non-finite"), std::string::npos) << message;
    EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
}

TEST(GltfLoader, AccessorReadingPastItsBufferViewIsAnError) {
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    writer.setAccessorCount(positions, 4);
    const TempFile file("overrun.gltf",
                        writer.gltf(singleNode("{\"attributes\": {\"POSITION\": " + std::to_string(positions) + "}}")));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("past the end"), std::string::npos) << message;
}

/** glTF's data alignment: an accessor that starts between two of its components (its own offset or its view's) is
 *  refused naming the offset, not read as numbers made of the halves of two. The same file aligned loads, so only the
 *  offset decides. (A stride that is not a multiple of 4 tinygltf refuses itself.) */
TEST(GltfLoader, AnAccessorBetweenItsComponentsIsRefusedNamingTheOffset) {
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}});
    writer.setAccessorCount(positions, 3); // room for an offset of up to 12 bytes
    const std::string primitive = "{\"attributes\": {\"POSITION\": " + std::to_string(positions) + "}}";
    const std::string aligned = writer.gltf(singleNode(primitive));
    const std::string accessorStart = "{\"bufferView\": 0, ";
    ASSERT_NE(aligned.find(accessorStart), std::string::npos);
    const auto withAccessor = [&](const std::string& members) {
        std::string text = aligned;
        text.replace(text.find(accessorStart), accessorStart.size(), accessorStart + members);
        return text;
    };
    {
        const TempFile file("aligned.gltf", withAccessor("\"byteOffset\": 12, "));
        EXPECT_EQ(loadScene(file.path()).triangleCount(), 1u);
    }
    {
        const TempFile file("offset.gltf", withAccessor("\"byteOffset\": 2, "));
        const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
        EXPECT_NE(message.find("POSITION accessor 0: byteOffset 2 is not a multiple of its component size (4 bytes)"),
                  std::string::npos)
            << message;
        EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
    }
    {
        std::string text = aligned;
        const std::string view = "\"byteOffset\": 0, \"byteLength\": 48";
        ASSERT_NE(text.find(view), std::string::npos);
        text.replace(text.find(view), view.size(), "\"byteOffset\": 2, \"byteLength\": 46");
        const TempFile file("view.gltf", text);
        const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
        EXPECT_NE(message.find("starts at byte 2 of its buffer (buffer view 0's byteOffset 2 plus its own 0)"),
                  std::string::npos)
            << message;
    }
}

/** A double-faced card: the square's corners twice, the second sheet wound the other way with -z normals. A
 *  two-sided material draws the first sheet's back, so the second is dropped as its twin (its normals, though split,
 *  are the back's own); a one-sided material needs it to be seen from behind, so it stays. */
TEST(GltfLoader, ADoubleFacedCardOfATwoSidedMaterialKeepsItsFirstSide) {
    for (const bool doubleSided : {true, false}) {
        GltfWriter writer;
        const int positions = writer.addVec3(
            {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}});
        const int normals = writer.addVec3(
            {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, -1}, {0, 0, -1}, {0, 0, -1}, {0, 0, -1}});
        const int indices = writer.addIndices({0, 1, 2, 0, 2, 3, 7, 6, 4, 6, 5, 4}, 2);
        const std::string body =
            std::string("\"materials\": [{\"doubleSided\": ") + (doubleSided ? "true" : "false") + "}], " +
            singleNode("{\"attributes\": {\"POSITION\": " + std::to_string(positions) + ", \"NORMAL\": " +
                       std::to_string(normals) + "}, \"indices\": " + std::to_string(indices) + ", \"material\": 0}");
        const TempFile file("card.glb", writer.glb(body));
        const Scene scene = loadScene(file.path());
        ASSERT_EQ(scene.meshes.size(), 1u);
        EXPECT_EQ(scene.meshes[0].triangleCount(), doubleSided ? 2u : 4u);
        EXPECT_EQ(scene.report.backToBackDropped, doubleSided ? 2u : 0u);
        if (doubleSided)
            for (const glm::vec3& normal : scene.meshes[0].normals) EXPECT_EQ(normal, glm::vec3(0, 0, 1));
    }
}

TEST(GltfLoader, SheetsThatLieOnEachOtherOnSharedCornersKeepTheirOwnNormals) {
    // A one-sided double-faced card on one set of corners, without normals: the two sheets' smooth normals summed to
    // nothing and each corner took one sheet's direction (the back drawn dark, or in wedges). With texture
    // coordinates the normals are the position-welded ones, which must keep the sheets apart too.
    for (const bool textured : {false, true}) {
        GltfWriter writer;
        const int positions = writer.addVec3({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}});
        const int texcoords = writer.addVec2({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
        const int indices = writer.addIndices({0, 1, 2, 0, 2, 3, 0, 2, 1, 0, 3, 2}, 2);
        const std::string body =
            "\"materials\": [{\"doubleSided\": false}], " +
            singleNode("{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                       (textured ? ", \"TEXCOORD_0\": " + std::to_string(texcoords) : std::string()) +
                       "}, \"indices\": " + std::to_string(indices) + ", \"material\": 0}");
        const Scene scene = loadScene(TempFile("card.glb", writer.glb(body)).path());
        ASSERT_EQ(scene.meshes.size(), 1u);
        EXPECT_EQ(scene.meshes[0].triangleCount(), 4u) << "a one-sided card keeps both sheets";
        test::expectCornerNormalsAlongTheirFaces(scene.meshes[0], textured ? "textured card" : "card");
    }

    // A cube whose node scales y to 0: its top and bottom lie on one plane, cut along other diagonals.
    GltfWriter writer;
    const int positions = writer.addVec3(
        {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}});
    const int indices = writer.addIndices(
        {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3},
        2);
    const std::string body =
        "\"materials\": [{}], \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " +
        std::to_string(positions) + "}, \"indices\": " + std::to_string(indices) +
        ", \"material\": 0}]}], \"nodes\": [{\"mesh\": 0, \"scale\": [1, 0, 1]}], \"scenes\": [{\"nodes\": [0]}]";
    const Scene flat = loadScene(TempFile("flat.gltf", writer.gltf(body)).path());
    ASSERT_EQ(flat.meshes.size(), 1u);
    EXPECT_EQ(flat.meshes[0].triangleCount(), 4u) << "the sides are dropped as degenerate, top and bottom kept";
    test::expectCornerNormalsAlongTheirFaces(flat.meshes[0], "flattened cube");
}

TEST(GltfLoader, SheetsThatLieOnEachOtherOnTheirOwnCornersKeepTheirOwnNormals) {
    // With texture coordinates the corners of two sheets at one place are apart (another coordinate on each side),
    // and the normals were welded by position: the sheets summed to nothing again (a textured box flattened by its
    // node drew wedges), or the back took the front's normals (a card printed on both sides was dark from behind).
    const std::vector<glm::vec3> square = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    const std::vector<glm::vec2> uv = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const std::vector<glm::vec2> mirrored = {{1, 0}, {0, 0}, {0, 1}, {1, 1}};
    const auto card = [&](const std::vector<glm::vec3>& positions, const std::vector<glm::vec2>& texcoords,
                          const std::vector<std::uint32_t>& indices, const std::string& node) {
        GltfWriter writer;
        const int position = writer.addVec3(positions);
        const int texcoord = writer.addVec2(texcoords);
        const int index = writer.addIndices(indices, 2);
        return writer.glb("\"materials\": [{\"doubleSided\": false}], \"meshes\": [{\"primitives\": "
                          "[{\"attributes\": {\"POSITION\": " +
                          std::to_string(position) + ", \"TEXCOORD_0\": " + std::to_string(texcoord) +
                          "}, \"indices\": " + std::to_string(index) +
                          ", \"material\": 0}]}], \"nodes\": [{\"mesh\": 0" + node +
                          "}], \"scenes\": [{\"nodes\": [0]}]");
    };
    std::vector<glm::vec3> twoSheets = square;
    twoSheets.insert(twoSheets.end(), square.begin(), square.end());
    std::vector<glm::vec2> bothPrints = uv;
    bothPrints.insert(bothPrints.end(), mirrored.begin(), mirrored.end());
    // The back on corners of its own; then on two of the front's and two of its own.
    const Scene separate = loadScene(
        TempFile("separate.glb", card(twoSheets, bothPrints, {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6}, "")).path());
    test::expectCornerNormalsAlongTheirFaces(separate.meshes.at(0), "a back on corners of its own");
    const Scene partly =
        loadScene(TempFile("partly.glb", card({square[0], square[1], square[2], square[3], square[1], square[3]},
                                              {uv[0], uv[1], uv[2], uv[3], mirrored[1], mirrored[3]},
                                              {0, 1, 2, 0, 2, 3, 0, 2, 4, 0, 5, 2}, ""))
                      .path());
    test::expectCornerNormalsAlongTheirFaces(partly.meshes.at(0), "a back on two corners of the front's");

    // A textured cube, four corners a face, flattened by its node's scale of 0 in y.
    std::vector<glm::vec3> corners;
    std::vector<glm::vec2> texcoords;
    std::vector<std::uint32_t> indices;
    for (const glm::uvec4& quad : test::cubeQuads()) {
        const auto first = std::uint32_t(corners.size());
        for (int k = 0; k < 4; ++k) {
            corners.push_back(test::cubeCorners()[quad[k] - 1]); // 1-based
            texcoords.push_back(uv[std::size_t(k)]);
        }
        indices.insert(indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
    }
    const Scene flat =
        loadScene(TempFile("flat.glb", card(corners, texcoords, indices, ", \"scale\": [1, 0, 1]")).path());
    ASSERT_EQ(flat.meshes.size(), 1u);
    EXPECT_EQ(flat.meshes[0].triangleCount(), 4u) << "the sides are dropped as degenerate, top and bottom kept";
    test::expectCornerNormalsAlongTheirFaces(flat.meshes[0], "a flattened textured cube");
}

TEST(GltfLoader, AFileOfNoTrianglesSaysWhatTheLoadWarned) {
    // Its only primitive spells POSITION in lower case: the refusal said "no triangles" and left out why.
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    const TempFile file("lower.gltf",
                        writer.gltf(singleNode("{\"attributes\": {\"position\": " + std::to_string(positions) + "}}")));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("no triangles in the file; what the load said: 'shape': primitive without POSITION skipped"),
              std::string::npos)
        << message;
    // Beside a primitive of lines: both said (the lines alone were "all 1 primitives are non-triangle").
    const TempFile mixed("mixed.gltf",
                         writer.gltf(singleNode("{\"attributes\": {\"position\": " + std::to_string(positions) +
                                                "}}, {\"attributes\": "
                                                "{\"POSITION\": " +
                                                std::to_string(positions) + "}, \"mode\": 1}")));
    const std::string mixedMessage = test::sceneErrorMessage([&] { loadScene(mixed.path()); });
    EXPECT_NE(mixedMessage.find("what the load said: 'shape primitive 0': primitive without POSITION skipped; 'shape "
                                "primitive 1': non-triangle primitive (mode 1, LINES) skipped"),
              std::string::npos)
        << mixedMessage;
}

TEST(GltfLoader, IndexOutOfRangeIsAnError) {
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    const int indices = writer.addIndices({0, 1, 3}, 2);
    const TempFile file("bad_index.glb",
                        writer.glb(singleNode("{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                                              "}, \"indices\": " + std::to_string(indices) + "}")));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("index 3 out of range"), std::string::npos) << message;
}

TEST(GltfLoader, ExternalBufferIsResolvedNextToTheGltf) {
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    const TempFile buffer("triangle.bin", writer.binary());
    const TempFile file(
        "external.gltf",
        writer.gltfWithExternalBuffer(singleNode("{\"attributes\": {\"POSITION\": " + std::to_string(positions) + "}}"),
                                      buffer.fileName()));
    EXPECT_EQ(loadScene(file.path()).triangleCount(), 1u);
}

// Both geometry compressions are read (GltfDracoTest, GltfMeshoptTest); a file that requires meshopt compression but
// compresses none of its views loads as it is.
TEST(GltfLoader, RequiredMeshoptCompressionWithPlainViewsLoads) {
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    const TempFile file("meshopt.gltf",
                        writer.gltf("\"extensionsUsed\": [\"EXT_meshopt_compression\"], "
                                    "\"extensionsRequired\": [\"EXT_meshopt_compression\"], " +
                                    singleNode("{\"attributes\": {\"POSITION\": " + std::to_string(positions) + "}}")));
    EXPECT_EQ(loadScene(file.path()).triangleCount(), 1u);
}

/** A triangle mesh and `nodes` (JSON objects), with node 0 the only root of the default scene. */
std::string nodeHierarchy(GltfWriter& writer, const std::vector<std::string>& nodes) {
    const int positions = writer.addVec3(kUnitTriangle);
    std::string list;
    for (const std::string& node : nodes) {
        list += (list.empty() ? "" : ", ") + node;
    }
    return writer.gltf("\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                       "}}]}], \"nodes\": [" + list + "], \"scenes\": [{\"nodes\": [0]}], \"scene\": 0");
}

TEST(GltfLoader, DeepNodeChainLoadsWithoutExhaustingTheStack) {
    // 30,000 nested nodes, each moving its subtree by +1 in x; the mesh hangs on the deepest one.
    constexpr int kDepth = 30'000;
    std::vector<std::string> nodes;
    nodes.reserve(kDepth);
    for (int i = 0; i + 1 < kDepth; ++i) {
        nodes.push_back("{\"translation\": [1, 0, 0], \"children\": [" + std::to_string(i + 1) + "]}");
    }
    nodes.push_back("{\"name\": \"deepest\", \"translation\": [1, 0, 0], \"mesh\": 0}");
    GltfWriter writer;
    const TempFile file("deep.gltf", nodeHierarchy(writer, nodes));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].name, "deepest");
    EXPECT_EQ(test::worldPosition(scene, scene.meshes[0].positions.at(0)), glm::dvec3(kDepth, 0, 0));
}

TEST(GltfLoader, SharedChildrenAreRejectedWithoutExpandingEveryPath) {
    // Node i lists node i+1 twice: 2^40 paths if every path were walked.
    std::vector<std::string> nodes;
    for (int i = 0; i + 1 < 40; ++i) {
        nodes.push_back("{\"children\": [" + std::to_string(i + 1) + ", " + std::to_string(i + 1) + "]}");
    }
    nodes.push_back("{\"mesh\": 0}");
    GltfWriter writer;
    const TempFile file("shared.gltf", nodeHierarchy(writer, nodes));
    const auto start = std::chrono::steady_clock::now();
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
    EXPECT_EQ(message.rfind("loadScene(): '" + file.path() + "'", 0), 0u) << message;
    EXPECT_NE(message.find("node 1 has more than one parent (or is in a cycle)"), std::string::npos) << message;

    // Two different parents of one node.
    GltfWriter twoParents;
    const TempFile diamond("diamond.gltf", nodeHierarchy(twoParents, {"{\"children\": [1, 2]}", "{\"children\": [3]}",
                                                                      "{\"children\": [3]}", "{\"mesh\": 0}"}));
    const std::string diamondMessage = test::sceneErrorMessage([&] { loadScene(diamond.path()); });
    EXPECT_NE(diamondMessage.find("node 3 has more than one parent"), std::string::npos) << diamondMessage;
}

TEST(GltfLoader, CyclesAreRejected) {
    GltfWriter loop;
    const TempFile file("cycle.gltf", nodeHierarchy(loop, {"{\"mesh\": 0, \"children\": [1]}", "{\"children\": [2]}",
                                                           "{\"children\": [1]}"}));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
    EXPECT_NE(message.find("node 1 has more than one parent (or is in a cycle)"), std::string::npos) << message;

    GltfWriter self;
    const TempFile selfFile("self.gltf", nodeHierarchy(self, {"{\"mesh\": 0, \"children\": [0]}"}));
    const std::string selfMessage = test::sceneErrorMessage([&] { loadScene(selfFile.path()); });
    EXPECT_NE(selfMessage.find("node 0 has more than one parent (or is in a cycle)"), std::string::npos) << selfMessage;
}

TEST(GltfLoader, ChildIndexOutOfRangeIsAnError) {
    GltfWriter writer;
    const TempFile file("bad_child.gltf", nodeHierarchy(writer, {"{\"mesh\": 0, \"children\": [7]}"}));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
    EXPECT_NE(message.find("node index 7 out of range (file has 1 nodes)"), std::string::npos) << message;
}

/** A triangle at the origin and a perspective camera "lens" with the given perspective members, on node 1. */
std::string cameraFile(const std::string& perspective) {
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    return writer.gltf("\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                       "}}]}], \"cameras\": [{\"type\": \"perspective\", \"name\": \"lens\", \"perspective\": {" +
                       perspective +
                       ", \"znear\": 0.1}}], \"nodes\": [{\"mesh\": 0}, {\"camera\": 0, \"translation\": [0, 0, 5]}], "
                       "\"scenes\": [{\"nodes\": [0, 1]}]");
}

TEST(GltfLoader, CameraYfovOutsideZeroToPiIsAnError) {
    for (const char* yfov : {"0", "-0.5", "3.1416", "4", "1e300"}) {
        SCOPED_TRACE(yfov);
        const TempFile file("bad_yfov.gltf", cameraFile("\"yfov\": " + std::string(yfov)));
        const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
        EXPECT_EQ(message.rfind("loadScene(): '" + file.path() + "'", 0), 0u) << message;
        EXPECT_NE(message.find("camera 0 'lens'"), std::string::npos) << message;
        EXPECT_NE(message.find("yfov"), std::string::npos) << message;
        EXPECT_NE(message.find("(0, pi)"), std::string::npos) << message;
    }
    // JSON cannot spell infinity; an overflowing literal is rejected as a file problem too.
    const TempFile overflow("overflow_yfov.gltf", cameraFile("\"yfov\": 1e999"));
    const std::string message = test::sceneErrorMessage([&] { loadScene(overflow.path()); });
    EXPECT_NE(message.find(overflow.fileName()), std::string::npos) << message;

    const TempFile valid("good_yfov.gltf", cameraFile("\"yfov\": 3.14"));
    EXPECT_NEAR(loadScene(valid.path()).camera.value().fovYDegrees, glm::degrees(3.14), 1e-9);
}

TEST(GltfLoader, InvalidCameraAspectRatioIsIgnoredWithAWarning) {
    const TempFile file("bad_aspect.gltf", cameraFile("\"yfov\": 0.5, \"aspectRatio\": -1.5"));
    const Scene scene = loadScene(file.path());
    ASSERT_TRUE(scene.camera.has_value());
    EXPECT_FALSE(scene.camera->aspectRatio.has_value());
    const bool warned = std::any_of(scene.report.warnings.begin(), scene.report.warnings.end(), [](const auto& w) {
        return w.message.find("camera 0 'lens'") != std::string::npos &&
               w.message.find("aspectRatio -1.5 ignored") != std::string::npos;
    });
    EXPECT_TRUE(warned);

    const TempFile missing("no_aspect.gltf", cameraFile("\"yfov\": 0.5"));
    const Scene noAspect = loadScene(missing.path());
    EXPECT_FALSE(noAspect.camera.value().aspectRatio.has_value());
    EXPECT_TRUE(noAspect.report.warnings.empty());
}

TEST(GltfLoader, AbsurdlyNestedJsonIsAnErrorNotAStackOverflow) {
    // 30,000 nested arrays in "extras" overflowed tinygltf's recursive parser (SIGSEGV) before the depth check.
    const std::string nested = std::string(30000, '[') + std::string(30000, ']');
    const TempFile file("nested.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"extras\": " + nested + "}");
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("nested deeper than"), std::string::npos) << message;
    // Brackets inside strings do not count.
    const TempFile quoted("quoted.gltf",
                          "{\"asset\": {\"version\": \"2.0\", \"generator\": \"" + std::string(1000, '[') + "\"}}");
    EXPECT_EQ(test::sceneErrorMessage([&] { loadScene(quoted.path()); }).find("nested deeper"), std::string::npos);
}

TEST(GltfLoader, InvalidJsonIsAnError) {
    const TempFile file("broken.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [");
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
    EXPECT_NE(message.find("invalid glTF"), std::string::npos) << message;
}

Scene loadSceneFromTriangle() {
    GltfWriter writer;
    const int positions = writer.addVec3(kUnitTriangle);
    const TempFile file("triangle.glb",
                        writer.glb(singleNode("{\"attributes\": {\"POSITION\": " + std::to_string(positions) + "}}")));
    return loadScene(file.path());
}

TEST(GltfLoader, VrmFilesAreGlbsAndFaceTheirSpecificationsFront) {
    // A VRM file is a GLB with a .vrm name. VRM 0.x characters face -Z, VRM 1.0 ones +Z; a plain glTF names no front.
    for (const auto& [extensions, front] : std::vector<std::pair<std::string, std::optional<glm::dvec3>>>{
             {"\"extensionsUsed\": [\"VRM\"], ", glm::dvec3(0, 0, -1)},
             {"\"extensionsUsed\": [\"VRMC_vrm\"], ", glm::dvec3(0, 0, 1)},
             {"", std::nullopt}}) {
        GltfWriter writer;
        const int positions = writer.addVec3(kUnitTriangle);
        const TempFile file(
            "character.vrm",
            writer.glb(extensions + singleNode("{\"attributes\": {\"POSITION\": " + std::to_string(positions) + "}}")));
        const Scene scene = loadScene(file.path());
        EXPECT_EQ(scene.report.format, "glb");
        EXPECT_EQ(scene.triangleCount(), 1u);
        EXPECT_EQ(scene.front, front) << extensions;
    }
}

TEST(GltfLoader, AutoFramingLooksAtTheModelsFront) {
    // A VRM 0.x character (front -Z) is framed from -Z, so its face shows; a file without a front from +Z.
    Scene scene = loadSceneFromTriangle();
    const Camera defaultView = resolveCamera({}, scene);
    scene.front = glm::dvec3(0, 0, -1);
    const Camera vrmView = resolveCamera({}, scene);
    const BoundingSphere sphere = computeBoundingSphere(scene);
    EXPECT_GT(defaultView.eye.z - sphere.center.z, 0.0);
    EXPECT_LT(vrmView.eye.z - sphere.center.z, 0.0);
    EXPECT_NEAR(vrmView.eye.x - sphere.center.x, 0.0, 1e-9);
    EXPECT_GT(vrmView.eye.y - sphere.center.y, 0.0) << "still slightly above";
}

} // namespace
} // namespace inkgraph
