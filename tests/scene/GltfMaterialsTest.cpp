/** @file The glTF reader's surface data: materials (factors, textures with their set, sampler and
 *  KHR_texture_transform, emissive, unlit, alpha, double-sidedness), TEXCOORD_n and COLOR_0 attributes, images kept
 *  encoded, and the accessor forms KHR_mesh_quantization and sparse accessors bring. Every file is written here with
 *  known values. */

#include "scene/Scene.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace inkgraph {
namespace {

using test::TempFile;

/** Buffer views of any bytes and accessors written by hand, for component types and sparse forms that
 *  test::GltfWriter (float VEC3 and indices only) does not write. One buffer, embedded as a data: URI. */
class RawGltf {
public:
    /** A buffer view holding `values` as they lie in memory (little-endian, like glTF); returns its index. */
    template <typename T>
    int view(const std::vector<T>& values, int byteStride = 0) {
        while (mBinary.size() % 4 != 0) mBinary += '\0';
        mViews.push_back("{\"buffer\": 0, \"byteOffset\": " + std::to_string(mBinary.size()) +
                         ", \"byteLength\": " + std::to_string(values.size() * sizeof(T)) +
                         (byteStride > 0 ? ", \"byteStride\": " + std::to_string(byteStride) : std::string()) + "}");
        mBinary.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
        return int(mViews.size() - 1);
    }

    /** An accessor from its JSON members, e.g. "\"bufferView\": 0, \"componentType\": 5126, ..."; returns its index. */
    int accessor(const std::string& members) {
        mAccessors.push_back("{" + members + "}");
        return int(mAccessors.size() - 1);
    }

    /** A float accessor of `type` ("VEC2", "VEC3", ...) over a new view of `values`. */
    int floats(const std::vector<float>& values, const std::string& type, std::size_t count) {
        return accessor("\"bufferView\": " + std::to_string(view(values)) + ", \"componentType\": 5126, \"count\": " +
                        std::to_string(count) + ", \"type\": \"" + type + "\"");
    }

    /** The .gltf text: the buffer, views and accessors, then `body` (meshes, nodes, materials, ...). */
    std::string gltf(const std::string& body) const {
        std::string views;
        for (const std::string& view : mViews) views += (views.empty() ? "" : ", ") + view;
        std::string accessors;
        for (const std::string& accessor : mAccessors) accessors += (accessors.empty() ? "" : ", ") + accessor;
        return "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"uri\": \"data:application/octet-stream;base64," +
               test::base64(mBinary) + "\", \"byteLength\": " + std::to_string(mBinary.size()) +
               "}], \"bufferViews\": [" + views + "], \"accessors\": [" + accessors + "], " + body + "}";
    }

private:
    std::string mBinary;
    std::vector<std::string> mViews;
    std::vector<std::string> mAccessors;
};

/** The triangle (0,0,0), (1,0,0), (0,1,0) as float POSITION; returns the accessor. */
int addTrianglePositions(RawGltf& gltf) { return gltf.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3); }

/** One node, one mesh, one primitive with `attributes` (JSON members) and `primitiveExtra` members. */
std::string singlePrimitive(const std::string& attributes, const std::string& primitiveExtra = "",
                            const std::string& nodeExtra = "") {
    return "\"meshes\": [{\"primitives\": [{\"attributes\": {" + attributes + "}" + primitiveExtra +
           "}]}], \"nodes\": [{\"mesh\": 0" + nodeExtra + "}], \"scenes\": [{\"nodes\": [0]}], \"scene\": 0";
}

/** World positions of a mesh, sorted, for comparisons that do not depend on the welder's vertex order. */
std::vector<glm::dvec3> sortedWorldPositions(const Scene& scene, const Mesh& mesh) {
    std::vector<glm::dvec3> world;
    for (const glm::vec3& position : mesh.positions) world.push_back(test::worldPosition(scene, position));
    std::ranges::sort(world, [](const glm::dvec3& a, const glm::dvec3& b) {
        return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
    });
    return world;
}

/** The index of the vertex at world position `where` (within 1e-6), or -1. */
int vertexAt(const Scene& scene, const Mesh& mesh, glm::dvec3 where) {
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        if (glm::length(test::worldPosition(scene, mesh.positions[i]) - where) < 1e-6) return int(i);
    return -1;
}

void expectNear(const glm::mat3& actual, const glm::mat3& expected) {
    for (int column = 0; column < 3; ++column)
        for (int row = 0; row < 3; ++row)
            EXPECT_NEAR(actual[column][row], expected[column][row], 1e-6) << "column " << column << " row " << row;
}

const std::string kImageBytesA = std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR-a", 18);
const std::string kImageBytesB = std::string("\xff\xd8\xff\xe0\0\x10JFIF-b", 12);

std::string imagesOfTwoDataUris() {
    return "\"images\": [{\"uri\": \"data:image/png;base64," + test::base64(kImageBytesA) +
           "\"}, {\"uri\": \"data:image/jpeg;base64," + test::base64(kImageBytesB) + "\", \"name\": \"second\"}]";
}

TEST(GltfMaterials, EveryFieldOfACoreMaterialIsRead) {
    RawGltf gltf;
    const int position = addTrianglePositions(gltf);
    const int uv0 = gltf.floats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
    const int uv1 = gltf.floats({0, 0, 0.5f, 0, 0, 0.5f}, "VEC2", 3);
    const std::string body =
        singlePrimitive("\"POSITION\": " + std::to_string(position) + ", \"TEXCOORD_0\": " + std::to_string(uv0) +
                            ", \"TEXCOORD_1\": " + std::to_string(uv1),
                        ", \"material\": 0") +
        ", \"materials\": [{\"name\": \"skin\", \"pbrMetallicRoughness\": {\"baseColorFactor\": [0.1, 0.2, 0.3, 0.4],"
        " \"baseColorTexture\": {\"index\": 0, \"texCoord\": 1}},"
        " \"emissiveFactor\": [0.5, 0.25, 0.0],"
        " \"emissiveTexture\": {\"index\": 1, \"extensions\": {\"KHR_texture_transform\":"
        " {\"offset\": [0.5, 0.25], \"rotation\": " +
        std::to_string(glm::half_pi<double>()) +
        ", \"scale\": [2, 3], \"texCoord\": 1}}},"
        " \"alphaMode\": \"MASK\", \"alphaCutoff\": 0.3, \"doubleSided\": true}],"
        " \"textures\": [{\"sampler\": 0, \"source\": 1}, {\"source\": 0}],"
        " \"samplers\": [{\"magFilter\": 9728, \"minFilter\": 9729, \"wrapS\": 33071, \"wrapT\": 33648}], " +
        imagesOfTwoDataUris() + ", \"extensionsUsed\": [\"KHR_texture_transform\"]";
    const TempFile file("material.gltf", gltf.gltf(body));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Material& material = scene.meshes[0].material;
    EXPECT_EQ(material.name, "skin");
    EXPECT_EQ(material.baseColorFactor, glm::vec4(0.1f, 0.2f, 0.3f, 0.4f));
    EXPECT_EQ(material.baseColorTexture.image, 1);
    EXPECT_EQ(material.baseColorTexture.texCoord, 1);
    EXPECT_EQ(material.baseColorTexture.sampler.magFilter, TextureFilter::Nearest);
    EXPECT_EQ(material.baseColorTexture.sampler.minFilter, TextureFilter::Linear);
    EXPECT_EQ(material.baseColorTexture.sampler.wrapS, TextureWrap::ClampToEdge);
    EXPECT_EQ(material.baseColorTexture.sampler.wrapT, TextureWrap::MirroredRepeat);
    EXPECT_EQ(material.baseColorTexture.transform, glm::mat3(1.0f));
    EXPECT_EQ(material.emissiveFactor, glm::vec3(0.5f, 0.25f, 0.0f));
    EXPECT_EQ(material.emissiveTexture.image, 0);
    EXPECT_EQ(material.emissiveTexture.texCoord, 1);               // the transform's override of the default 0
    EXPECT_EQ(material.emissiveTexture.sampler, TextureSampler{}); // no sampler: repeat, trilinear
    // T * R * S with offset (0.5, 0.25), a quarter turn counter-clockwise in UV space (v down) and scale (2, 3): u
    // maps to (0, -2), v to (3, 0).
    expectNear(material.emissiveTexture.transform, glm::mat3(0, -2, 0, 3, 0, 0, 0.5f, 0.25f, 1));
    const glm::vec3 corner = material.emissiveTexture.transform * glm::vec3(1, 1, 1);
    EXPECT_NEAR(corner.x, 3.5, 1e-6);
    EXPECT_NEAR(corner.y, -1.75, 1e-6);
    EXPECT_FALSE(material.unlit);
    EXPECT_EQ(material.alphaMode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(material.alphaCutoff, 0.3f);
    EXPECT_TRUE(material.doubleSided);
    EXPECT_TRUE(material.textured());

    ASSERT_EQ(scene.meshes[0].texcoords[0].size(), 3u);
    ASSERT_EQ(scene.meshes[0].texcoords[1].size(), 3u);
    const int right = vertexAt(scene, scene.meshes[0], {1, 0, 0});
    ASSERT_GE(right, 0);
    EXPECT_EQ(scene.meshes[0].texcoords[0][std::size_t(right)], glm::vec2(1, 0));
    EXPECT_EQ(scene.meshes[0].texcoords[1][std::size_t(right)], glm::vec2(0.5f, 0));
}

/** A material whose base colour texture (clamped to its edges) carries `transformJson` as its KHR_texture_transform;
 *  its transform, loaded. */
glm::mat3 loadedTextureTransform(const std::string& transformJson) {
    RawGltf gltf;
    const int position = addTrianglePositions(gltf);
    const int uv0 = gltf.floats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
    const std::string body =
        singlePrimitive("\"POSITION\": " + std::to_string(position) + ", \"TEXCOORD_0\": " + std::to_string(uv0),
                        ", \"material\": 0") +
        ", \"materials\": [{\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0, \"extensions\":"
        " {\"KHR_texture_transform\": " +
        transformJson +
        "}}}}], \"textures\": [{\"source\": 0, \"sampler\": 0}],"
        // Clamped, as the sample's textures are: a repeating wrap would reduce the offset modulo 1 (ShaderValues.h).
        " \"samplers\": [{\"wrapS\": 33071, \"wrapT\": 33071}], " +
        imagesOfTwoDataUris() + ", \"extensionsUsed\": [\"KHR_texture_transform\"]";
    const TempFile file("transform.gltf", gltf.gltf(body));
    return loadScene(file.path()).meshes.at(0).material.baseColorTexture.transform;
}

TEST(GltfMaterials, TextureTransformRotationFollowsTheExtensionsExample) {
    // KHR_texture_transform's example: offset [0, 1], rotation pi/2, scale [0.5, 0.5] "utilizes only the lower left
    // quadrant of the source image, rotated clockwise 90 degrees". By hand, (u, v) -> (0.5 v, 1 - 0.5 u): u in [0, 0.5]
    // (left), v in [0.5, 1] (lower: glTF's v = 0 is the image's top row).
    const glm::mat3 transform =
        loadedTextureTransform("{\"offset\": [0, 1], \"rotation\": 1.57079632679, \"scale\": [0.5, 0.5]}");
    const std::vector<std::pair<glm::vec2, glm::vec2>> expected = {{{0, 0}, {0, 1}},
                                                                   {{1, 0}, {0, 0.5f}},
                                                                   {{0, 1}, {0.5f, 1}},
                                                                   {{1, 1}, {0.5f, 0.5f}},
                                                                   {{0.5f, 0.25f}, {0.125f, 0.75f}}};
    for (const auto& [uv, mapped] : expected) {
        const glm::vec3 actual = transform * glm::vec3(uv, 1.0f);
        EXPECT_NEAR(actual.x, mapped.x, 1e-6) << "uv " << uv.x << ", " << uv.y;
        EXPECT_NEAR(actual.y, mapped.y, 1e-6) << "uv " << uv.x << ", " << uv.y;
    }
    // TextureTransformTest's Rotation tile: 22.5 degrees alone; (1, 0) turns toward -v, (0, 1) toward +u.
    const double angle = glm::pi<double>() / 8.0;
    const glm::mat3 tile = loadedTextureTransform("{\"rotation\": 0.39269908169872414}");
    expectNear(tile, glm::mat3(float(std::cos(angle)), float(-std::sin(angle)), 0, float(std::sin(angle)),
                               float(std::cos(angle)), 0, 0, 0, 1));
}

TEST(GltfMaterials, UnlitBlendAndEmissiveStrength) {
    RawGltf gltf;
    const int position = addTrianglePositions(gltf);
    const std::string body = singlePrimitive("\"POSITION\": " + std::to_string(position), ", \"material\": 0") +
                             ", \"materials\": [{\"alphaMode\": \"BLEND\", \"emissiveFactor\": [0.5, 0.25, 1],"
                             " \"extensions\": {\"KHR_materials_unlit\": {}, \"KHR_materials_emissive_strength\": "
                             "{\"emissiveStrength\": 4}}}],"
                             " \"extensionsUsed\": [\"KHR_materials_unlit\", \"KHR_materials_emissive_strength\"],"
                             " \"extensionsRequired\": [\"KHR_materials_unlit\"]";
    const TempFile file("unlit.gltf", gltf.gltf(body));
    const Scene scene = loadScene(file.path());
    const Material& material = scene.meshes.at(0).material;
    EXPECT_TRUE(material.unlit);
    EXPECT_EQ(material.alphaMode, AlphaMode::Blend);
    EXPECT_FLOAT_EQ(material.alphaCutoff, 0.5f);
    EXPECT_EQ(material.emissiveFactor, glm::vec3(2.0f, 1.0f, 4.0f));
    EXPECT_FALSE(material.doubleSided);
    EXPECT_FALSE(material.textured());
    EXPECT_TRUE(scene.images.empty());
}

TEST(GltfMaterials, MetallicRoughnessIsReadWithGltfsDefaultsAndClamped) {
    RawGltf gltf;
    const int position = addTrianglePositions(gltf);
    const int uv0 = gltf.floats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
    // Four primitives: factors and a texture; no pbrMetallicRoughness; factors outside [0, 1]; no material at all.
    std::string primitives;
    for (const char* material : {", \"material\": 0", ", \"material\": 1", ", \"material\": 2", ""})
        primitives += std::string(primitives.empty() ? "" : ", ") +
                      "{\"attributes\": {\"POSITION\": " + std::to_string(position) +
                      ", \"TEXCOORD_0\": " + std::to_string(uv0) + "}" + material + "}";
    const std::string body =
        "\"meshes\": [{\"primitives\": [" + primitives +
        "]}], \"nodes\": [{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}], \"scene\": 0,"
        " \"materials\": [{\"pbrMetallicRoughness\": {\"metallicFactor\": 0.25, \"roughnessFactor\": 0.75,"
        " \"metallicRoughnessTexture\": {\"index\": 0}}}, {\"name\": \"plain\"},"
        " {\"name\": \"wild\", \"pbrMetallicRoughness\": {\"metallicFactor\": 2, \"roughnessFactor\": -1}}],"
        " \"textures\": [{\"source\": 1}], " +
        imagesOfTwoDataUris();
    const TempFile file("metallic.gltf", gltf.gltf(body));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 4u);
    // Materials 0 and "none" are unnamed: material 0 is the one with the texture.
    auto materialWhere = [&](auto&& predicate) -> const Material& {
        const auto found =
            std::ranges::find_if(scene.meshes, [&](const Mesh& mesh) { return predicate(mesh.material); });
        EXPECT_NE(found, scene.meshes.end());
        return found == scene.meshes.end() ? scene.meshes[0].material : found->material;
    };
    auto named = [&](const std::string& name) {
        return materialWhere([&](const Material& material) { return material.name == name; });
    };
    const Material& textured =
        materialWhere([](const Material& material) { return material.metallicRoughnessTexture.present(); });
    EXPECT_FLOAT_EQ(textured.metallicFactor, 0.25f);
    EXPECT_FLOAT_EQ(textured.roughnessFactor, 0.75f);
    EXPECT_EQ(textured.metallicRoughnessTexture.image, 1);
    EXPECT_EQ(textured.metallicRoughnessTexture.texCoord, 0);
    // glTF's defaults when the material leaves them out: metallic 1, roughness 1.
    const Material& plain = named("plain");
    EXPECT_EQ(plain.metallicFactor, 1.0f);
    EXPECT_EQ(plain.roughnessFactor, 1.0f);
    EXPECT_FALSE(plain.metallicRoughnessTexture.present());
    const Material& wild = named("wild");
    EXPECT_EQ(wild.metallicFactor, 1.0f);
    EXPECT_EQ(wild.roughnessFactor, 0.0f);
    EXPECT_EQ(scene.report.warnings.size(), 2u) << ::testing::PrintToString(scene.report.warnings);
    for (const char* factor : {"metallicFactor 2 is outside [0, 1]", "roughnessFactor -1 is outside [0, 1]"})
        EXPECT_TRUE(std::ranges::any_of(scene.report.warnings, [&](const Warning& warning) {
            return warning.message.find(factor) != std::string::npos;
        })) << factor;
    // A primitive without a material is drawn with inkgraph's own default, a dielectric, not glTF's default material.
    const Material& none = materialWhere(
        [](const Material& material) { return material.name.empty() && !material.metallicRoughnessTexture.present(); });
    EXPECT_EQ(none.metallicFactor, 0.0f);
    EXPECT_EQ(none.roughnessFactor, 1.0f);
}

/** One triangle with TEXCOORD_0 and _1 whose material 0 is `material` (JSON), with the two images of
 *  imagesOfTwoDataUris() as textures 0 (image 1) and 1 (image 0), and `extensionsRequired`. */
std::string triangleWithMaterial(const std::string& material, const std::string& extensionsRequired) {
    RawGltf gltf;
    const int position = addTrianglePositions(gltf);
    const int uv0 = gltf.floats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
    const int uv1 = gltf.floats({0, 0, 0.5f, 0, 0, 0.5f}, "VEC2", 3);
    return gltf.gltf(singlePrimitive("\"POSITION\": " + std::to_string(position) + ", \"TEXCOORD_0\": " +
                                         std::to_string(uv0) + ", \"TEXCOORD_1\": " + std::to_string(uv1),
                                     ", \"material\": 0") +
                     ", \"materials\": [" + material + "], \"textures\": [{\"source\": 1}, {\"source\": 0}], " +
                     imagesOfTwoDataUris() + ", \"extensionsUsed\": [" + extensionsRequired +
                     "], \"extensionsRequired\": [" + extensionsRequired + "]");
}

TEST(GltfMaterials, SpecularGlossinessDiffuseIsTheBaseColour) {
    // The extension required, with a metallic-roughness fallback that must not be read: the diffuse factor and
    // texture (its coordinate set and KHR_texture_transform read as a core texture's) become the base colour and
    // alpha; a non-metal whose roughness is 1 - glossiness.
    const TempFile file(
        "specular-glossiness.gltf",
        triangleWithMaterial(
            "{\"name\": \"leather\", \"pbrMetallicRoughness\": {\"baseColorFactor\": [1, 0, 0, 1],"
            " \"baseColorTexture\": {\"index\": 1}, \"metallicFactor\": 1, \"metallicRoughnessTexture\": {\"index\": "
            "1}},"
            " \"extensions\": {\"KHR_materials_pbrSpecularGlossiness\": {\"diffuseFactor\": [0.5, 0.25, 0.125, 0.75],"
            " \"diffuseTexture\": {\"index\": 0, \"texCoord\": 1, \"extensions\": {\"KHR_texture_transform\":"
            " {\"offset\": [0.5, 0.25]}}}, \"specularFactor\": [0.2, 0.2, 0.2], \"glossinessFactor\": 0.75}}}",
            "\"KHR_materials_pbrSpecularGlossiness\", \"KHR_texture_transform\""));
    const Scene scene = loadScene(file.path());
    const Material& material = scene.meshes.at(0).material;
    EXPECT_EQ(material.name, "leather");
    EXPECT_EQ(material.baseColorFactor, glm::vec4(0.5f, 0.25f, 0.125f, 0.75f));
    EXPECT_EQ(material.baseColorTexture.image, 1); // texture 0's source
    EXPECT_EQ(material.baseColorTexture.texCoord, 1);
    expectNear(material.baseColorTexture.transform, glm::mat3(1, 0, 0, 0, 1, 0, 0.5f, 0.25f, 1));
    EXPECT_EQ(material.metallicFactor, 0.0f);
    EXPECT_FLOAT_EQ(material.roughnessFactor, 0.25f);
    EXPECT_FALSE(material.metallicRoughnessTexture.present());
    EXPECT_TRUE(scene.report.warnings.empty()) << ::testing::PrintToString(scene.report.warnings);

    // Without factors or texture: the extension's defaults, white and fully glossy.
    const TempFile defaults("specular-glossiness-defaults.gltf",
                            triangleWithMaterial("{\"extensions\": {\"KHR_materials_pbrSpecularGlossiness\": {}}}",
                                                 "\"KHR_materials_pbrSpecularGlossiness\""));
    const Material plain = loadScene(defaults.path()).meshes.at(0).material; // a copy: the scene is a temporary
    EXPECT_EQ(plain.baseColorFactor, glm::vec4(1.0f));
    EXPECT_FALSE(plain.baseColorTexture.present());
    EXPECT_EQ(plain.metallicFactor, 0.0f);
    EXPECT_EQ(plain.roughnessFactor, 0.0f);
}

TEST(GltfMaterials, AMaterialThatDrawsNothingIsSaid) {
    // A model of such materials alone was blank paper with exit 0, --strict included. MASK cuts out every fragment
    // when the factor's alpha is under the cutoff (the texture's alpha only multiplies it down); BLEND under half a
    // level of 8-bit colour changes no pixel. OPAQUE ignores alpha.
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"("alphaMode": "MASK", "alphaCutoff": 0.5, "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 0.2]})",
         "material 0 'm': alphaMode MASK with a base colour alpha of 0.2, under its alphaCutoff 0.5, cuts out every "
         "fragment: its faces are not drawn"},
        {R"("alphaMode": "MASK", "alphaCutoff": 0.5, "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 0.5]})", ""},
        {R"("alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 0]})",
         "material 0 'm': alphaMode BLEND with a base colour alpha of 0, under half a level of 8-bit colour (1/510), "
         "changes no pixel: its faces are not drawn"},
        {R"("alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 0.002]})", ""},
        {R"("pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 0]})", ""}};
    for (const auto& [material, expected] : cases) {
        const TempFile file("invisible.gltf", triangleWithMaterial("{\"name\": \"m\", " + material + "}", ""));
        const Scene scene = loadScene(file.path());
        std::vector<std::string> said;
        for (const Warning& warning : scene.report.warnings)
            if (warning.code == "material-invisible") said.push_back(warning.message);
        EXPECT_EQ(said, expected.empty() ? std::vector<std::string>{} : std::vector<std::string>{expected}) << material;
    }
}

TEST(GltfMaterials, SpecularGlossinessOutOfRangeIsClampedAndBrokenIsRefused) {
    const TempFile clamped("gloss-clamped.gltf",
                           triangleWithMaterial("{\"extensions\": {\"KHR_materials_pbrSpecularGlossiness\": "
                                                "{\"diffuseFactor\": [2, 0.5, 0.5, 1], \"glossinessFactor\": -1}}}",
                                                "\"KHR_materials_pbrSpecularGlossiness\""));
    const Scene scene = loadScene(clamped.path());
    EXPECT_EQ(scene.meshes.at(0).material.baseColorFactor, glm::vec4(1.0f, 0.5f, 0.5f, 1.0f));
    EXPECT_EQ(scene.meshes.at(0).material.roughnessFactor, 1.0f);
    EXPECT_EQ(scene.report.warnings.size(), 2u) << ::testing::PrintToString(scene.report.warnings);

    const std::vector<std::pair<std::string, std::string>> broken = {
        {"{\"diffuseFactor\": [1, 1, 1]}",
         "material 0 KHR_materials_pbrSpecularGlossiness: 'diffuseFactor' must be an array of 4 numbers"},
        {"{\"diffuseTexture\": {\"texCoord\": 0}}",
         "material 0 KHR_materials_pbrSpecularGlossiness diffuseTexture has no 'index'"},
        {"{\"diffuseTexture\": {\"index\": 1.5}}",
         "material 0 KHR_materials_pbrSpecularGlossiness diffuseTexture: 'index' 1.5 is not a whole number >= 0"},
        {"{\"diffuseTexture\": {\"index\": 7}}",
         "material 0 KHR_materials_pbrSpecularGlossiness diffuseTexture: texture index 7 out of range (file has 2 "
         "textures)"},
    };
    for (const auto& [extension, expected] : broken) {
        const TempFile file(
            "gloss-broken.gltf",
            triangleWithMaterial("{\"extensions\": {\"KHR_materials_pbrSpecularGlossiness\": " + extension + "}}",
                                 "\"KHR_materials_pbrSpecularGlossiness\""));
        const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
        EXPECT_NE(message.find(expected), std::string::npos) << extension << ": " << message;
        EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
    }
}

TEST(GltfMaterials, SupportedExtensionsListTheMaterialAndGeometryOnes) {
    for (const char* name :
         {"KHR_lights_punctual", "KHR_mesh_quantization", "KHR_draco_mesh_compression", "KHR_texture_transform",
          "KHR_materials_unlit", "KHR_materials_emissive_strength", "KHR_materials_pbrSpecularGlossiness"})
        EXPECT_NE(std::ranges::find(supportedGltfExtensions(), std::string(name)), supportedGltfExtensions().end())
            << name;
}

TEST(GltfMaterials, NormalizedUnsignedShortTexcoordsBecomeFractions) {
    RawGltf gltf;
    const int position = addTrianglePositions(gltf);
    const int uvView = gltf.view(std::vector<std::uint16_t>{0, 0, 65535, 0, 0, 32768});
    const int uv = gltf.accessor("\"bufferView\": " + std::to_string(uvView) +
                                 ", \"componentType\": 5123, \"normalized\": true, \"count\": 3, \"type\": \"VEC2\"");
    const TempFile file("uv16.gltf", gltf.gltf(singlePrimitive("\"POSITION\": " + std::to_string(position) +
                                                               ", \"TEXCOORD_0\": " + std::to_string(uv))));
    const Scene scene = loadScene(file.path());
    const Mesh& mesh = scene.meshes.at(0);
    ASSERT_EQ(mesh.texcoords[0].size(), 3u);
    EXPECT_TRUE(mesh.texcoords[1].empty());
    EXPECT_EQ(mesh.texcoords[0][std::size_t(vertexAt(scene, mesh, {0, 0, 0}))], glm::vec2(0, 0));
    EXPECT_EQ(mesh.texcoords[0][std::size_t(vertexAt(scene, mesh, {1, 0, 0}))], glm::vec2(1, 0));
    EXPECT_EQ(mesh.texcoords[0][std::size_t(vertexAt(scene, mesh, {0, 1, 0}))], glm::vec2(0, 32768.0f / 65535.0f));
}

TEST(GltfMaterials, NormalizedByteRgbColoursGetAlphaOne) {
    // Unmarked (the file breaks glTF's rule that integer colours are normalized), 255 was read as 255 times white;
    // now as the exporter meant, with a warning.
    for (const bool normalized : {true, false}) {
        RawGltf gltf;
        const int position = addTrianglePositions(gltf);
        // VEC3 of unsigned bytes, each element padded to 4 bytes as glTF requires of vertex attributes.
        const int colorView = gltf.view(std::vector<std::uint8_t>{255, 0, 0, 0, 0, 51, 0, 0, 0, 0, 255, 0}, 4);
        const int color =
            gltf.accessor("\"bufferView\": " + std::to_string(colorView) +
                          ", \"componentType\": 5121, \"normalized\": " + (normalized ? "true" : "false") +
                          ", \"count\": 3, \"type\": \"VEC3\"");
        const TempFile file("colour.gltf", gltf.gltf(singlePrimitive("\"POSITION\": " + std::to_string(position) +
                                                                     ", \"COLOR_0\": " + std::to_string(color))));
        const Scene scene = loadScene(file.path());
        const Mesh& mesh = scene.meshes.at(0);
        ASSERT_EQ(mesh.colors.size(), 3u);
        EXPECT_EQ(mesh.colors[std::size_t(vertexAt(scene, mesh, {0, 0, 0}))], glm::vec4(1, 0, 0, 1));
        EXPECT_EQ(mesh.colors[std::size_t(vertexAt(scene, mesh, {1, 0, 0}))], glm::vec4(0, 0.2f, 0, 1));
        EXPECT_EQ(mesh.colors[std::size_t(vertexAt(scene, mesh, {0, 1, 0}))], glm::vec4(0, 0, 1, 1));
        ASSERT_EQ(scene.report.warnings.size(), normalized ? 0u : 1u)
            << ::testing::PrintToString(scene.report.warnings);
        if (!normalized)
            EXPECT_NE(scene.report.warnings[0].message.find(
                          "COLOR_0: unsigned bytes not marked normalized, as glTF requires of integer colours; read "
                          "as normalized (255 is white)"),
                      std::string::npos)
                << scene.report.warnings[0].message;
    }
}

TEST(GltfMaterials, AttributeCountDifferentFromPositionsIsRefused) {
    RawGltf gltf;
    const int position = addTrianglePositions(gltf);
    const int uv = gltf.floats({0, 0, 1, 0}, "VEC2", 2);
    const TempFile file("short-uv.gltf", gltf.gltf(singlePrimitive("\"POSITION\": " + std::to_string(position) +
                                                                   ", \"TEXCOORD_0\": " + std::to_string(uv))));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("TEXCOORD_0 has 2 elements but POSITION has 3"), std::string::npos) << message;
    EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
}

/** Six corners and a primitive of three indices 0 1 2 over a view of 0 1 2 3 4 5 with `byteStride` (0: none), of
 *  unsigned short (5123) or int (5125) components. */
std::string stridedIndicesGltf(int byteStride, std::uint32_t componentType) {
    RawGltf gltf;
    const int position = gltf.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 0, 0, 0, 2, 0}, "VEC3", 6);
    const int view = componentType == 5123 ? gltf.view(std::vector<std::uint16_t>{0, 1, 2, 3, 4, 5}, byteStride)
                                           : gltf.view(std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5}, byteStride);
    const int indices = gltf.accessor("\"bufferView\": " + std::to_string(view) + ", \"componentType\": " +
                                      std::to_string(componentType) + ", \"count\": 3, \"type\": \"SCALAR\"");
    return gltf.gltf(
        singlePrimitive("\"POSITION\": " + std::to_string(position), ", \"indices\": " + std::to_string(indices)));
}

TEST(GltfMaterials, IndicesOnAStridedViewAreRefusedUnlessTheStrideIsTheIndexSize) {
    // glTF forbids byteStride on index data. Read with it, a stride of 4 over 16-bit indices took every other one
    // (0 2 4 of 0 1 2 3 4 5): another triangle than any reader draws, with no word.
    const TempFile strided("strided-indices.gltf", stridedIndicesGltf(4, 5123));
    const std::string message = test::sceneErrorMessage([&] { loadScene(strided.path()); });
    EXPECT_NE(message.find("index accessor 1: buffer view 1 has byteStride 4, but glTF forbids a stride on indices "
                           "(they lie packed, 2 bytes each)"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find(strided.fileName()), std::string::npos) << message;
    // A stride of the index's own size reads the same, as does none: the first three corners, the unit triangle.
    for (const auto& [byteStride, componentType] : {std::pair<int, std::uint32_t>{4, 5125}, {0, 5123}}) {
        const TempFile file("packed-indices.gltf", stridedIndicesGltf(byteStride, componentType));
        const Scene scene = loadScene(file.path());
        ASSERT_EQ(scene.meshes.size(), 1u);
        EXPECT_EQ(sortedWorldPositions(scene, scene.meshes[0]),
                  (std::vector<glm::dvec3>{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}))
            << "byteStride " << byteStride;
    }
}

TEST(GltfMaterials, SparsePositionsAreSubstituted) {
    RawGltf gltf;
    const int base = gltf.view(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int indices = gltf.view(std::vector<std::uint8_t>{2});
    const int values = gltf.view(std::vector<float>{0, 2, 0});
    const int position = gltf.accessor(
        "\"bufferView\": " + std::to_string(base) +
        ", \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\", \"sparse\": {\"count\": 1, \"indices\": "
        "{\"bufferView\": " +
        std::to_string(indices) + ", \"componentType\": 5121}, \"values\": {\"bufferView\": " + std::to_string(values) +
        "}}");
    const TempFile file("sparse.gltf", gltf.gltf(singlePrimitive("\"POSITION\": " + std::to_string(position))));
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(sortedWorldPositions(scene, scene.meshes.at(0)),
              (std::vector<glm::dvec3>{{0, 0, 0}, {0, 2, 0}, {1, 0, 0}}));
}

TEST(GltfMaterials, SparseValuesBetweenTheirComponentsAreRefused) {
    // glTF's data alignment holds for the sparse part too: values 2 bytes into their view are refused by name.
    RawGltf gltf;
    const int base = gltf.view(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int indices = gltf.view(std::vector<std::uint8_t>{2});
    const int values = gltf.view(std::vector<float>{0, 2, 0, 0});
    const int position = gltf.accessor(
        "\"bufferView\": " + std::to_string(base) +
        ", \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\", \"sparse\": {\"count\": 1, \"indices\": "
        "{\"bufferView\": " +
        std::to_string(indices) + ", \"componentType\": 5121}, \"values\": {\"bufferView\": " + std::to_string(values) +
        ", \"byteOffset\": 2}}");
    const TempFile file("sparse.gltf", gltf.gltf(singlePrimitive("\"POSITION\": " + std::to_string(position))));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("sparse values: byteOffset 2 is not a multiple of its component size (4 bytes)"),
              std::string::npos)
        << message;
}

TEST(GltfMaterials, SparseAccessorWithoutBufferViewStartsFromZeros) {
    RawGltf gltf;
    const int indices = gltf.view(std::vector<std::uint16_t>{1, 2});
    const int values = gltf.view(std::vector<float>{3, 0, 0, 0, 4, 0});
    const int position =
        gltf.accessor("\"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\", \"sparse\": {\"count\": 2, "
                      "\"indices\": {\"bufferView\": " +
                      std::to_string(indices) +
                      ", \"componentType\": 5123}, \"values\": {\"bufferView\": " + std::to_string(values) + "}}");
    const TempFile file("sparse-zeros.gltf", gltf.gltf(singlePrimitive("\"POSITION\": " + std::to_string(position))));
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(sortedWorldPositions(scene, scene.meshes.at(0)),
              (std::vector<glm::dvec3>{{0, 0, 0}, {0, 4, 0}, {3, 0, 0}}));
}

TEST(GltfMaterials, SparseIndexOutOfRangeIsRefused) {
    RawGltf gltf;
    const int base = gltf.view(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int indices = gltf.view(std::vector<std::uint8_t>{7});
    const int values = gltf.view(std::vector<float>{0, 2, 0});
    const int position = gltf.accessor(
        "\"bufferView\": " + std::to_string(base) +
        ", \"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\", \"sparse\": {\"count\": 1, \"indices\": "
        "{\"bufferView\": " +
        std::to_string(indices) + ", \"componentType\": 5121}, \"values\": {\"bufferView\": " + std::to_string(values) +
        "}}");
    const TempFile file("sparse-bad.gltf", gltf.gltf(singlePrimitive("\"POSITION\": " + std::to_string(position))));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("POSITION accessor 0: sparse index 7"), std::string::npos) << message;
}

TEST(GltfMaterials, QuantizedShortPositionsTakeTheNodeScale) {
    RawGltf gltf;
    // Signed shorts, not normalized (KHR_mesh_quantization), each VEC3 padded to 8 bytes.
    const int view = gltf.view(std::vector<std::int16_t>{0, 0, 0, 0, 100, 0, 0, 0, 0, -200, 0, 0}, 8);
    const int position = gltf.accessor("\"bufferView\": " + std::to_string(view) +
                                       ", \"componentType\": 5122, \"count\": 3, \"type\": \"VEC3\"");
    const TempFile file("quantized.gltf", gltf.gltf(singlePrimitive("\"POSITION\": " + std::to_string(position), "",
                                                                    ", \"scale\": [0.01, 0.01, 0.01]") +
                                                    ", \"extensionsUsed\": [\"KHR_mesh_quantization\"],"
                                                    " \"extensionsRequired\": [\"KHR_mesh_quantization\"]"));
    const Scene scene = loadScene(file.path());
    const std::vector<glm::dvec3> world = sortedWorldPositions(scene, scene.meshes.at(0));
    const std::vector<glm::dvec3> expected = {{0, -2, 0}, {0, 0, 0}, {1, 0, 0}};
    ASSERT_EQ(world.size(), expected.size());
    for (std::size_t i = 0; i < world.size(); ++i) EXPECT_LT(glm::length(world[i] - expected[i]), 1e-6) << i;
}

TEST(GltfMaterials, EmbeddedImagesKeepTheirBytesInFileOrder) {
    RawGltf gltf;
    const int position = addTrianglePositions(gltf);
    const int imageView = gltf.view(std::vector<char>(kImageBytesB.begin(), kImageBytesB.end()));
    const std::string body = singlePrimitive("\"POSITION\": " + std::to_string(position)) +
                             ", \"images\": [{\"uri\": \"data:image/png;base64," + test::base64(kImageBytesA) +
                             "\"}, {\"bufferView\": " + std::to_string(imageView) +
                             ", \"mimeType\": \"image/jpeg\", \"name\": \"face\"}]";
    const TempFile file("embedded.gltf", gltf.gltf(body));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.images.size(), 2u);
    ASSERT_TRUE(scene.images[0].encoded);
    EXPECT_EQ(std::string(scene.images[0].encoded->begin(), scene.images[0].encoded->end()), kImageBytesA);
    EXPECT_EQ(scene.images[0].mimeType, "image/png");
    EXPECT_TRUE(scene.images[0].path.empty());
    ASSERT_TRUE(scene.images[1].encoded);
    EXPECT_EQ(std::string(scene.images[1].encoded->begin(), scene.images[1].encoded->end()), kImageBytesB);
    EXPECT_EQ(scene.images[1].mimeType, "image/jpeg");
    EXPECT_EQ(scene.images[1].name, "face");
}

TEST(GltfMaterials, ATextureOnACoordinateSetTheMeshLacksIsDroppedWithAWarning) {
    // TEXCOORD_1 named, only TEXCOORD_0 present: sampled, it would paint one texel everywhere.
    RawGltf gltf;
    const int position = addTrianglePositions(gltf);
    const int uv = gltf.floats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
    const std::string body =
        singlePrimitive("\"POSITION\": " + std::to_string(position) + ", \"TEXCOORD_0\": " + std::to_string(uv),
                        ", \"material\": 0") +
        ", \"materials\": [{\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0, \"texCoord\": 1}}}],"
        " \"textures\": [{\"source\": 0}], \"images\": [{\"uri\": \"skin.png\"}]";
    const TempFile file("second-set.gltf", gltf.gltf(body));
    const Scene scene = loadScene(file.path());
    EXPECT_FALSE(scene.meshes.at(0).material.baseColorTexture.present());
    ASSERT_EQ(scene.report.warnings.size(), 1u);
    EXPECT_NE(scene.report.warnings[0].message.find("reads TEXCOORD_1, which the mesh does not have"),
              std::string::npos)
        << scene.report.warnings[0];
}

TEST(GltfMaterials, ExternalImageIsResolvedBesideTheModelAndNotRead) {
    RawGltf gltf;
    const int position = addTrianglePositions(gltf);
    const int uv = gltf.floats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
    const std::string body =
        singlePrimitive("\"POSITION\": " + std::to_string(position) + ", \"TEXCOORD_0\": " + std::to_string(uv),
                        ", \"material\": 0") +
        ", \"materials\": [{\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0}}}],"
        " \"textures\": [{\"source\": 0}],"
        " \"images\": [{\"uri\": \"textures/no%20such.png\"}]";
    const TempFile file("external-image.gltf", gltf.gltf(body));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.images.size(), 1u);
    const std::string expected =
        (std::filesystem::path(file.path()).parent_path() / "textures" / "no such.png").string();
    EXPECT_EQ(scene.images[0].path, expected);
    EXPECT_FALSE(scene.images[0].encoded);
    EXPECT_EQ(scene.meshes.at(0).material.baseColorTexture.image, 0);
    EXPECT_NE(std::ranges::find(scene.report.inputFiles, expected), scene.report.inputFiles.end());
    const std::vector<std::string> referenced = referencedFiles(file.path());
    EXPECT_NE(std::ranges::find(referenced, expected), referenced.end());
}

TEST(GltfMaterials, TextureIndexOutOfRangeIsRefusedNamingTheMaterial) {
    RawGltf gltf;
    const int position = addTrianglePositions(gltf);
    const std::string body = singlePrimitive("\"POSITION\": " + std::to_string(position), ", \"material\": 0") +
                             ", \"materials\": [{\"name\": \"coat\", \"pbrMetallicRoughness\": "
                             "{\"baseColorTexture\": {\"index\": 5}}}], \"textures\": [{\"source\": 0}], " +
                             imagesOfTwoDataUris();
    const TempFile file("bad-texture.gltf", gltf.gltf(body));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("material 0 'coat' baseColorTexture: texture index 5 out of range (file has 1 textures)"),
              std::string::npos)
        << message;
}

TEST(GltfMaterials, TextureSourceOutOfRangeIsRefused) {
    RawGltf gltf;
    const int position = addTrianglePositions(gltf);
    const std::string body =
        singlePrimitive("\"POSITION\": " + std::to_string(position), ", \"material\": 0") +
        ", \"materials\": [{\"emissiveTexture\": {\"index\": 0}}], \"textures\": [{\"source\": 2}], " +
        imagesOfTwoDataUris();
    const TempFile file("bad-source.gltf", gltf.gltf(body));
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("texture 0: image index 2 out of range (file has 2 images)"), std::string::npos) << message;
}

TEST(GltfMaterials, KtxOnlyTextureIsARecordNamingTheModelTheMaterialAndTheTexture) {
    // A texture whose only source is KHR_texture_basisu's KTX2 image: nothing the renderer decodes.
    RawGltf gltf;
    const int position = addTrianglePositions(gltf);
    const std::string body =
        singlePrimitive("\"POSITION\": " + std::to_string(position), ", \"material\": 0") +
        ", \"materials\": [{\"name\": \"coat\", \"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0}}}],"
        " \"textures\": [{\"name\": \"skin\", \"extensions\": {\"KHR_texture_basisu\": {\"source\": 0}}}], \"images\": "
        "[{\"uri\": \"skin.ktx2\", \"mimeType\": \"image/ktx2\"}], \"extensionsUsed\": [\"KHR_texture_basisu\"]";
    const TempFile file("basisu.gltf", gltf.gltf(body));
    const Scene scene = loadScene(file.path());
    EXPECT_FALSE(scene.meshes.at(0).material.textured());
    const Warning expected{"texture-without-core-image",
                           "material 0 'coat' baseColorTexture: texture 0 'skin' has no PNG, JPEG or WebP source (it "
                           "has only 'KHR_texture_basisu'); drawn untextured",
                           file.path(), "texture 0 'skin'"};
    EXPECT_EQ(scene.report.warnings, std::vector<Warning>{expected});

    // With a PNG fallback as the texture's own source (and texture coordinates to draw it with): that image,
    // silently (docs/materials.md).
    RawGltf withUvs;
    const int corners = addTrianglePositions(withUvs);
    const int uvs = withUvs.floats({0, 0, 1, 0, 0, 1}, "VEC2", 3);
    const std::string textures =
        ", \"materials\": [{\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0}}}], \"textures\": "
        "[{\"source\": 1, \"extensions\": {\"KHR_texture_basisu\": {\"source\": 0}}}], \"images\": [{\"uri\": "
        "\"skin.ktx2\", \"mimeType\": \"image/ktx2\"}, {\"uri\": \"skin.png\"}], \"extensionsUsed\": "
        "[\"KHR_texture_basisu\"]";
    const std::string primitive = singlePrimitive(
        "\"POSITION\": " + std::to_string(corners) + ", \"TEXCOORD_0\": " + std::to_string(uvs), ", \"material\": 0");
    const TempFile fallback("basisu-fallback.gltf", withUvs.gltf(primitive + textures));
    const Scene fallbackScene = loadScene(fallback.path());
    EXPECT_EQ(fallbackScene.meshes.at(0).material.baseColorTexture.image, 1);
    EXPECT_TRUE(fallbackScene.report.warnings.empty()) << ::testing::PrintToString(fallbackScene.report.warnings);

    // Required: refused, with the list of what is supported.
    const TempFile required("basisu-required.gltf",
                            withUvs.gltf(primitive + textures + ", \"extensionsRequired\": [\"KHR_texture_basisu\"]"));
    const std::string message = test::sceneErrorMessage([&] { loadScene(required.path()); });
    EXPECT_NE(message.find("'KHR_texture_basisu'"), std::string::npos) << message;
    EXPECT_NE(message.find("unsupported"), std::string::npos) << message;
    EXPECT_NE(message.find("'EXT_texture_webp'"), std::string::npos) << message;
}

TEST(GltfMaterials, TextureWithOnlyAnExtensionImageIsDrawnUntexturedWithAWarning) {
    RawGltf gltf;
    const int position = addTrianglePositions(gltf);
    const std::string body = singlePrimitive("\"POSITION\": " + std::to_string(position), ", \"material\": 0") +
                             ", \"materials\": [{\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0}}}],"
                             " \"textures\": [{\"extensions\": {\"EXT_texture_avif\": {\"source\": 0}}}], " +
                             imagesOfTwoDataUris() + ", \"extensionsUsed\": [\"EXT_texture_avif\"]";
    const TempFile file("avif.gltf", gltf.gltf(body));
    const Scene scene = loadScene(file.path());
    EXPECT_FALSE(scene.meshes.at(0).material.textured());
    const auto& warnings = scene.report.warnings;
    EXPECT_TRUE(std::ranges::any_of(warnings, [](const Warning& warning) {
        return warning.message.find("texture 0 has no PNG, JPEG or WebP source (it has only 'EXT_texture_avif')") !=
               std::string::npos;
    })) << ::testing::PrintToString(warnings);
}

/** A unit quad as two non-indexed triangles (6 vertices): corners (0,0) and (1,1) appear in both. `secondUvs` are the
 *  second triangle's texture coordinates for (1,1), (0,1), (0,0). */
std::string quadWithUvs(const std::vector<float>& secondUvs) {
    RawGltf gltf;
    const int position = gltf.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 1, 1, 0, 0, 1, 0, 0, 0, 0}, "VEC3", 6);
    std::vector<float> uvs = {0, 0, 1, 0, 1, 1};
    uvs.insert(uvs.end(), secondUvs.begin(), secondUvs.end());
    const int uv = gltf.floats(uvs, "VEC2", 6);
    return gltf.gltf(
        singlePrimitive("\"POSITION\": " + std::to_string(position) + ", \"TEXCOORD_0\": " + std::to_string(uv)));
}

TEST(GltfMaterials, TextureSeamsKeepTheirSplitVertices) {
    const TempFile continuous("quad-continuous.gltf", quadWithUvs({1, 1, 0, 1, 0, 0}));
    const Scene joined = loadScene(continuous.path());
    EXPECT_EQ(joined.meshes.at(0).positions.size(), 4u); // equal coordinates at the shared corners: welded

    const TempFile seam("quad-seam.gltf", quadWithUvs({0.5f, 0.5f, 0, 1, 0.25f, 0.25f}));
    const Scene split = loadScene(seam.path());
    const Mesh& mesh = split.meshes.at(0);
    EXPECT_EQ(mesh.positions.size(), 6u); // both shared corners differ in their coordinates: a seam
    ASSERT_EQ(mesh.texcoords[0].size(), 6u);
    std::vector<glm::vec2> atOrigin;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        if (glm::length(test::worldPosition(split, mesh.positions[i])) < 1e-9) atOrigin.push_back(mesh.texcoords[0][i]);
    std::ranges::sort(atOrigin, [](glm::vec2 a, glm::vec2 b) { return a.x < b.x; });
    EXPECT_EQ(atOrigin, (std::vector<glm::vec2>{{0, 0}, {0.25f, 0.25f}}));
}

} // namespace
} // namespace inkgraph
