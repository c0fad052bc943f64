/** VRM MToon materials (scene/formats/gltf/VrmMaterials.h) through loadScene(): VRM 1.0's VRMC_materials_mtoon read as
 * written, VRM 0.x's materialProperties converted to it, known answers from small .vrm files the tests write. */

#include "scene/Scene.h"
#include "scene/formats/gltf/VrmMaterials.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace inkgraph::vrm_materials_test {
namespace {

using test::GltfWriter;
using test::TempFile;
using OutlineWidthMode = MToonMaterial::OutlineWidthMode;

/** A .vrm with one triangle per material (primitive i uses material i), three textures (texture t shows image t),
 *  and `extra` top-level members (the VRM 0.x root extension, extensionsRequired). */
Scene loadVrm(const std::vector<std::string>& materials, const std::string& extra = "",
              std::size_t primitivesPerMaterial = 1) {
    GltfWriter writer;
    const int positions = writer.addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    // Both texture-coordinate sets, so every texture the materials name has the set it reads.
    const int texcoords = writer.addVec2({{0, 0}, {1, 0}, {0, 1}});
    std::string primitives;
    std::string materialList;
    for (std::size_t i = 0; i < materials.size(); ++i) {
        for (std::size_t copy = 0; copy < primitivesPerMaterial; ++copy) {
            primitives += std::string(primitives.empty() ? "" : ", ") +
                          "{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
                          ", \"TEXCOORD_0\": " + std::to_string(texcoords) +
                          ", \"TEXCOORD_1\": " + std::to_string(texcoords) + "}, \"material\": " + std::to_string(i) +
                          "}";
        }
        materialList += (materialList.empty() ? "" : ", ") + materials[i];
    }
    const std::string body = extra +
                             "\"images\": [{\"uri\": \"a.png\"}, {\"uri\": \"b.png\"}, {\"uri\": \"c.png\"}], " +
                             "\"textures\": [{\"source\": 0}, {\"source\": 1}, {\"source\": 2}], \"materials\": [" +
                             materialList + "], \"meshes\": [{\"primitives\": [" + primitives +
                             "]}], \"nodes\": [{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}], \"scene\": 0";
    const TempFile file("character.vrm", writer.glb(body));
    return loadScene(file.path());
}

const Material& materialNamed(const Scene& scene, const std::string& name) {
    for (const Mesh& mesh : scene.meshes) {
        if (mesh.material.name == name) return mesh.material;
    }
    ADD_FAILURE() << "no mesh with material '" << name << "'";
    static const Material none;
    return none;
}

std::size_t warningsMentioning(const Scene& scene, const std::string& text) {
    std::size_t count = 0;
    for (const Warning& warning : scene.report.warnings) count += warning.message.find(text) != std::string::npos;
    return count;
}

/** A VRM 0.x root extension whose materialProperties are `entries`. */
std::string vrm0(const std::string& entries) {
    return "\"extensionsUsed\": [\"VRM\"], \"extensions\": {\"VRM\": {\"materialProperties\": [" + entries + "]}}, ";
}

void expectVec3Near(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-5f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(VrmMaterials, SrgbToLinearFollowsTheSrgbCurve) {
    EXPECT_FLOAT_EQ(detail::srgbToLinear(0.0f), 0.0f);
    EXPECT_FLOAT_EQ(detail::srgbToLinear(1.0f), 1.0f);
    EXPECT_NEAR(detail::srgbToLinear(0.5f), 0.2140411f, 1e-6f);
    EXPECT_NEAR(detail::srgbToLinear(0.04045f), 0.04045f / 12.92f, 1e-7f) << "the linear segment's end";
    EXPECT_NEAR(detail::srgbToLinear(0.2f), 0.0331048f, 1e-6f);
}

TEST(VrmMaterials, Vrm10ReadsEveryParameter) {
    const Scene scene = loadVrm({R"({"name": "Skin", "extensions": {"VRMC_materials_mtoon": {
        "specVersion": "1.0",
        "shadeColorFactor": [0.25, 0.5, 0.75],
        "shadeMultiplyTexture": {"index": 1, "texCoord": 1},
        "shadingShiftFactor": -0.2,
        "shadingToonyFactor": 0.7,
        "parametricRimColorFactor": [0.1, 0.2, 0.3],
        "parametricRimFresnelPowerFactor": 3.5,
        "parametricRimLiftFactor": 0.15,
        "rimLightingMixFactor": 0.4,
        "matcapFactor": [0.5, 0.6, 0.7],
        "outlineWidthMode": "worldCoordinates",
        "outlineWidthFactor": 0.002,
        "outlineWidthMultiplyTexture": {"index": 2},
        "outlineColorFactor": [0.9, 0.8, 0.7],
        "outlineLightingMixFactor": 0.6,
        "shadingShiftTexture": {"index": 0, "scale": -0.5},
        "matcapTexture": {"index": 1},
        "rimMultiplyTexture": {"index": 2, "texCoord": 1},
        "uvAnimationMaskTexture": {"index": 2},
        "uvAnimationScrollXSpeedFactor": 0.25,
        "uvAnimationScrollYSpeedFactor": -0.5,
        "uvAnimationRotationSpeedFactor": 1.5}},
        "normalTexture": {"index": 0, "scale": 0.75}})"},
                                "\"extensionsUsed\": [\"VRMC_vrm\", \"VRMC_materials_mtoon\"], ");
    const Material& material = materialNamed(scene, "Skin");
    ASSERT_TRUE(material.mtoon.has_value());
    const MToonMaterial& mtoon = *material.mtoon;
    EXPECT_EQ(mtoon.specVersion, "1.0");
    EXPECT_EQ(mtoon.shadeColorFactor, glm::vec3(0.25f, 0.5f, 0.75f));
    EXPECT_EQ(mtoon.shadeMultiplyTexture.image, 1);
    EXPECT_EQ(mtoon.shadeMultiplyTexture.texCoord, 1);
    EXPECT_FLOAT_EQ(mtoon.shadingShiftFactor, -0.2f);
    EXPECT_FLOAT_EQ(mtoon.shadingToonyFactor, 0.7f);
    EXPECT_EQ(mtoon.parametricRimColorFactor, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_FLOAT_EQ(mtoon.parametricRimFresnelPowerFactor, 3.5f);
    EXPECT_FLOAT_EQ(mtoon.parametricRimLiftFactor, 0.15f);
    EXPECT_FLOAT_EQ(mtoon.rimLightingMixFactor, 0.4f);
    EXPECT_EQ(mtoon.matcapFactor, glm::vec3(0.5f, 0.6f, 0.7f));
    EXPECT_EQ(mtoon.outlineWidthMode, OutlineWidthMode::WorldCoordinates);
    EXPECT_FLOAT_EQ(mtoon.outlineWidthFactor, 0.002f);
    EXPECT_EQ(mtoon.outlineWidthMultiplyTexture.image, 2);
    EXPECT_EQ(mtoon.outlineWidthMultiplyTexture.texCoord, 0);
    EXPECT_EQ(mtoon.outlineColorFactor, glm::vec3(0.9f, 0.8f, 0.7f));
    EXPECT_FLOAT_EQ(mtoon.outlineLightingMixFactor, 0.6f);
    EXPECT_EQ(mtoon.shadingShiftTexture.image, 0);
    EXPECT_FLOAT_EQ(mtoon.shadingShiftTextureScale, -0.5f);
    EXPECT_EQ(mtoon.matcapTexture.image, 1);
    EXPECT_EQ(mtoon.rimMultiplyTexture.image, 2);
    EXPECT_EQ(mtoon.rimMultiplyTexture.texCoord, 1);
    EXPECT_EQ(mtoon.uvAnimationMaskTexture.image, 2);
    EXPECT_FLOAT_EQ(mtoon.uvAnimationScrollXSpeedFactor, 0.25f);
    EXPECT_FLOAT_EQ(mtoon.uvAnimationScrollYSpeedFactor, -0.5f);
    EXPECT_FLOAT_EQ(mtoon.uvAnimationRotationSpeedFactor, 1.5f);
    // glTF's own normal map, which MToon uses.
    EXPECT_EQ(material.normalTexture.image, 0);
    EXPECT_FLOAT_EQ(material.normalScale, 0.75f);
    EXPECT_TRUE(scene.report.warnings.empty()) << scene.report.warnings.front();
}

TEST(VrmMaterials, Vrm10ShadingShiftTextureScaleDefaultsToOne) {
    const Scene scene = loadVrm({R"({"name": "Shifted", "normalTexture": {"index": 1},
        "extensions": {"VRMC_materials_mtoon": {"specVersion": "1.0", "shadingShiftTexture": {"index": 2}}}})",
                                 R"({"name": "Plain", "normalTexture": {"index": 1}})"});
    const Material& shifted = materialNamed(scene, "Shifted");
    EXPECT_EQ(shifted.mtoon->shadingShiftTexture.image, 2);
    EXPECT_EQ(shifted.mtoon->shadingShiftTextureScale, 1.0f);
    EXPECT_EQ(shifted.normalTexture.image, 1);
    EXPECT_EQ(shifted.normalScale, 1.0f);
    EXPECT_FALSE(materialNamed(scene, "Plain").normalTexture.present()) << "only MToon draws normal maps";
}

TEST(VrmMaterials, Vrm0EmissionIsTheSrgbDecodedPropertyOverTheGltfFactor) {
    // _EmissionColor is a gamma-space Unity colour like the others: sRGB 0.5 is linear 0.214, taken over the glTF
    // emissiveFactor (which UniVRM 0.106/0.107 wrote unconverted, drawing code 188 where 128 was meant); _EmissionMap
    // is placed by _MainTex. An entry without them keeps the glTF material's.
    const Scene scene =
        loadVrm({R"({"name": "Glow", "emissiveFactor": [0.5, 0.5, 0.5]})",
                 R"({"name": "Kept", "emissiveFactor": [0.25, 0.5, 1], "emissiveTexture": {"index": 2}})"},
                vrm0(R"({"name": "Glow", "shader": "VRM/MToon",
        "vectorProperties": {"_EmissionColor": [0.5, 0.5, 0.5, 1], "_MainTex": [0.5, 0, 2, 1]},
        "textureProperties": {"_EmissionMap": 0}},
        {"name": "Kept", "shader": "VRM/MToon"})"));
    const Material& glow = materialNamed(scene, "Glow");
    const float half = 0.2140411f;
    expectVec3Near(glow.emissiveFactor, {half, half, half});
    EXPECT_EQ(glow.emissiveTexture.image, 0);
    glm::mat3 mainTex(1.0f);
    mainTex[0][0] = 2.0f;
    mainTex[2][0] = 0.5f;
    EXPECT_EQ(glow.emissiveTexture.transform, mainTex);
    const Material& kept = materialNamed(scene, "Kept");
    EXPECT_EQ(kept.emissiveFactor, glm::vec3(0.25f, 0.5f, 1.0f));
    EXPECT_EQ(kept.emissiveTexture.image, 2);
    EXPECT_TRUE(scene.report.warnings.empty()) << scene.report.warnings.front();
}

TEST(VrmMaterials, Vrm0SphereRimAndBumpMapsAreRead) {
    // The sphere map is 1.0's matcap at factor 1, placed by the normal (not by _MainTex); the rim texture multiplies
    // the rim and the bump map is the normal map, both placed by _MainTex; an entry without a bump map keeps the glTF
    // material's normal map.
    const Scene scene = loadVrm({R"({"name": "Shiny"})", R"({"name": "Kept", "normalTexture": {"index": 0}})"},
                                vrm0(R"({"name": "Shiny", "shader": "VRM/MToon",
        "floatProperties": {"_BumpScale": 0.5},
        "vectorProperties": {"_MainTex": [0.5, 0, 2, 1]},
        "textureProperties": {"_SphereAdd": 1, "_RimTexture": 2, "_BumpMap": 1}},
        {"name": "Kept", "shader": "VRM/MToon"})"));
    const Material& shiny = materialNamed(scene, "Shiny");
    glm::mat3 mainTex(1.0f);
    mainTex[0][0] = 2.0f;
    mainTex[2][0] = 0.5f;
    EXPECT_EQ(shiny.mtoon->matcapTexture.image, 1);
    EXPECT_EQ(shiny.mtoon->matcapTexture.transform, glm::mat3(1.0f)) << "the normal places the sphere map";
    EXPECT_EQ(shiny.mtoon->matcapFactor, glm::vec3(1.0f));
    EXPECT_EQ(shiny.mtoon->rimMultiplyTexture.image, 2);
    EXPECT_EQ(shiny.mtoon->rimMultiplyTexture.transform, mainTex);
    EXPECT_EQ(shiny.normalTexture.image, 1);
    EXPECT_EQ(shiny.normalTexture.transform, mainTex);
    EXPECT_FLOAT_EQ(shiny.normalScale, 0.5f);
    const Material& kept = materialNamed(scene, "Kept");
    EXPECT_EQ(kept.normalTexture.image, 0);
    EXPECT_FLOAT_EQ(kept.normalScale, 1.0f);
    EXPECT_TRUE(scene.report.warnings.empty()) << scene.report.warnings.front();
}

TEST(VrmMaterials, Vrm10DefaultsAreTheSpecifications) {
    const Scene scene =
        loadVrm({R"({"name": "Plain", "extensions": {"VRMC_materials_mtoon": {"specVersion": "1.0"}}})"});
    const Material& material = materialNamed(scene, "Plain");
    ASSERT_TRUE(material.mtoon.has_value());
    const MToonMaterial& mtoon = *material.mtoon;
    EXPECT_EQ(mtoon.shadeColorFactor, glm::vec3(0.0f));
    EXPECT_FALSE(mtoon.shadeMultiplyTexture.present());
    EXPECT_EQ(mtoon.shadingShiftFactor, 0.0f);
    EXPECT_FLOAT_EQ(mtoon.shadingToonyFactor, 0.9f);
    EXPECT_EQ(mtoon.parametricRimColorFactor, glm::vec3(0.0f));
    EXPECT_EQ(mtoon.parametricRimFresnelPowerFactor, 5.0f);
    EXPECT_EQ(mtoon.parametricRimLiftFactor, 0.0f);
    EXPECT_EQ(mtoon.rimLightingMixFactor, 1.0f);
    EXPECT_EQ(mtoon.outlineWidthMode, OutlineWidthMode::None);
    EXPECT_EQ(mtoon.outlineWidthFactor, 0.0f);
    EXPECT_FALSE(mtoon.outlineWidthMultiplyTexture.present());
    EXPECT_EQ(mtoon.outlineColorFactor, glm::vec3(0.0f));
    EXPECT_EQ(mtoon.outlineLightingMixFactor, 1.0f);
    MToonMaterial defaults;
    defaults.specVersion = "1.0";
    EXPECT_EQ(mtoon, defaults);
}

TEST(VrmMaterials, Vrm10OutlineModes) {
    const Scene scene = loadVrm({
        R"({"name": "None", "extensions": {"VRMC_materials_mtoon": {"specVersion": "1.0", "outlineWidthMode": "none", "outlineWidthFactor": 0.01}}})",
        R"({"name": "World", "extensions": {"VRMC_materials_mtoon": {"specVersion": "1.0", "outlineWidthMode": "worldCoordinates", "outlineWidthFactor": 0.01}}})",
        R"({"name": "Screen", "extensions": {"VRMC_materials_mtoon": {"specVersion": "1.0", "outlineWidthMode": "screenCoordinates", "outlineWidthFactor": 0.01}}})",
    });
    EXPECT_EQ(materialNamed(scene, "None").mtoon->outlineWidthMode, OutlineWidthMode::None);
    EXPECT_EQ(materialNamed(scene, "World").mtoon->outlineWidthMode, OutlineWidthMode::WorldCoordinates);
    EXPECT_EQ(materialNamed(scene, "Screen").mtoon->outlineWidthMode, OutlineWidthMode::ScreenCoordinates);
    for (const char* name : {"None", "World", "Screen"}) {
        EXPECT_FLOAT_EQ(materialNamed(scene, name).mtoon->outlineWidthFactor, 0.01f) << name;
    }
}

TEST(VrmMaterials, AMaterialWithoutMToonHasNone) {
    const Scene scene = loadVrm(
        {R"({"name": "Glass", "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1]}})", R"({"name": "Logo"})"},
        vrm0(R"({"name": "Glass", "shader": "VRM_USE_GLTFSHADER"})"));
    EXPECT_FALSE(materialNamed(scene, "Glass").mtoon.has_value());
    EXPECT_EQ(materialNamed(scene, "Glass").baseColorFactor, glm::vec4(1, 0, 0, 1)) << "the glTF material as it is";
    EXPECT_FALSE(materialNamed(scene, "Logo").mtoon.has_value()) << "no materialProperties entry";
    EXPECT_TRUE(scene.report.warnings.empty()) << scene.report.warnings.front();
}

TEST(VrmMaterials, Vrm0ShadeToonyAndShiftMigrateAsUniVrm) {
    // UniVRM's MToon10Migrator: range [shift, lerp(1, shift, toony)]; toony' = (2 - width) / 2, shift' = -centre.
    struct Case {
        float toony0, shift0, toony, shift;
    };
    const std::vector<Case> cases = {
        {0.9f, 0.0f, 0.95f, -0.05f},    // the defaults: range [0, 0.1]
        {0.8f, -0.45f, 0.855f, 0.305f}, // range [-0.45, -0.16]
        {0.0f, 0.5f, 0.75f, -0.75f},    // range [0.5, 1]
        {1.0f, -0.3f, 1.0f, 0.3f},      // a hard edge at -0.3
        {1.5f, -2.0f, 1.0f, 1.0f},      // out of range: lerp's t and both results clamped
    };
    std::vector<std::string> materials;
    std::string entries;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const std::string name = std::string("M").append(std::to_string(i)); // "M" + ...: GCC 12's -Wrestrict slip
        materials.push_back("{\"name\": \"" + name + "\"}");
        entries +=
            std::string(entries.empty() ? "" : ", ") + "{\"name\": \"" + name +
            "\", \"shader\": \"VRM/MToon\", \"floatProperties\": {\"_ShadeToony\": " + std::to_string(cases[i].toony0) +
            ", \"_ShadeShift\": " + std::to_string(cases[i].shift0) + "}}";
    }
    const Scene scene = loadVrm(materials, vrm0(entries));
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const Material& material = materialNamed(scene, std::string("M").append(std::to_string(i)));
        ASSERT_TRUE(material.mtoon.has_value());
        EXPECT_NEAR(material.mtoon->shadingToonyFactor, cases[i].toony, 1e-6f) << i;
        EXPECT_NEAR(material.mtoon->shadingShiftFactor, cases[i].shift, 1e-6f) << i;
        EXPECT_EQ(material.mtoon->specVersion, "0.x");
    }
}

TEST(VrmMaterials, Vrm0MapsEveryProperty) {
    const Scene scene =
        loadVrm({R"({"name": "Face", "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.1, 0.1, 1]}})"},
                vrm0(R"({"name": "Face", "shader": "VRM/MToon",
        "floatProperties": {"_ShadeShift": 0, "_ShadeToony": 0.9, "_RimFresnelPower": 2.5, "_RimLift": 0.1,
            "_RimLightingMix": 0.3, "_OutlineWidth": 0.5, "_OutlineWidthMode": 1, "_OutlineColorMode": 1,
            "_OutlineLightingMix": 0.75, "_Cutoff": 0.3, "_BlendMode": 1, "_CullMode": 0},
        "vectorProperties": {"_Color": [0.5, 1, 0, 0.5], "_ShadeColor": [0.2, 0.5, 1, 1], "_RimColor": [1, 0.5, 0, 1],
            "_OutlineColor": [0, 0.2, 0.5, 1], "_MainTex": [0.25, 0.125, 2, 0.5]},
        "textureProperties": {"_MainTex": 0, "_ShadeTexture": 1, "_OutlineWidthTexture": 2}})"));
    const Material& material = materialNamed(scene, "Face");
    ASSERT_TRUE(material.mtoon.has_value());
    const MToonMaterial& mtoon = *material.mtoon;
    const float half = 0.2140411f;  // sRGB 0.5 in linear
    const float fifth = 0.0331048f; // sRGB 0.2
    // The surface: _Color in sRGB (alpha linear), _MainTex with its scale/offset in glTF's uv, alpha and culling.
    expectVec3Near(glm::vec3(material.baseColorFactor), {half, 1.0f, 0.0f});
    EXPECT_FLOAT_EQ(material.baseColorFactor.a, 0.5f);
    EXPECT_EQ(material.baseColorTexture.image, 0);
    // Unity v' = v * 0.5 + 0.125 with v = 1 - v_gltf: v_gltf' = v_gltf * 0.5 + (1 - 0.5 - 0.125) = ... + 0.375.
    glm::mat3 expected(1.0f);
    expected[0][0] = 2.0f;
    expected[1][1] = 0.5f;
    expected[2][0] = 0.25f;
    expected[2][1] = 0.375f;
    EXPECT_EQ(material.baseColorTexture.transform, expected);
    const glm::vec3 corner = material.baseColorTexture.transform * glm::vec3(0.0f, 1.0f, 1.0f);
    EXPECT_FLOAT_EQ(corner.y, 0.875f) << "glTF's bottom edge (Unity's v = 0) maps to 1 - offset";
    EXPECT_EQ(material.alphaMode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(material.alphaCutoff, 0.3f);
    EXPECT_TRUE(material.doubleSided);
    // MToon.
    expectVec3Near(mtoon.shadeColorFactor, {fifth, half, 1.0f});
    EXPECT_EQ(mtoon.shadeMultiplyTexture.image, 1);
    EXPECT_EQ(mtoon.shadeMultiplyTexture.transform, expected);
    EXPECT_NEAR(mtoon.shadingToonyFactor, 0.95f, 1e-6f);
    EXPECT_NEAR(mtoon.shadingShiftFactor, -0.05f, 1e-6f);
    expectVec3Near(mtoon.parametricRimColorFactor, {1.0f, half, 0.0f});
    EXPECT_FLOAT_EQ(mtoon.parametricRimFresnelPowerFactor, 2.5f);
    EXPECT_FLOAT_EQ(mtoon.parametricRimLiftFactor, 0.1f);
    EXPECT_FLOAT_EQ(mtoon.rimLightingMixFactor, 0.3f);
    EXPECT_EQ(mtoon.outlineWidthMode, OutlineWidthMode::WorldCoordinates);
    EXPECT_FLOAT_EQ(mtoon.outlineWidthFactor, 0.005f) << "0.5 cm in metres";
    EXPECT_EQ(mtoon.outlineWidthMultiplyTexture.image, 2);
    EXPECT_EQ(mtoon.outlineWidthMultiplyTexture.transform, expected);
    expectVec3Near(mtoon.outlineColorFactor, {0.0f, fifth, half});
    EXPECT_FLOAT_EQ(mtoon.outlineLightingMixFactor, 0.75f);
    EXPECT_TRUE(scene.report.warnings.empty()) << scene.report.warnings.front();
}

TEST(VrmMaterials, OutlandishOutlineWidthsAndUndrawnFeaturesAreSaid) {
    // A 0.x width of 1e30 "percent": drawn as written but said; a world width beyond the renderer's range: dropped and
    // said; 0.x's shading grade texture: read, not drawn, and said once per material.
    const auto entry = [](const std::string& name, const std::string& floats, const std::string& textures) {
        return "{\"name\": \"" + name + "\", \"shader\": \"VRM/MToon\", \"floatProperties\": {" + floats +
               "}, \"textureProperties\": {" + textures + "}}";
    };
    const Scene scene = loadVrm({R"({"name": "Wide"})", R"({"name": "Far"})", R"({"name": "Shiny"})"},
                                vrm0(entry("Wide", "\"_OutlineWidthMode\": 2, \"_OutlineWidth\": 1e30", "") + ", " +
                                     entry("Far", "\"_OutlineWidthMode\": 1, \"_OutlineWidth\": 1e38", "") + ", " +
                                     entry("Shiny", "\"_UvAnimScrollX\": 0.5", "\"_ShadingGradeTexture\": 1")));
    const std::string warnings = ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.report.warnings.size(), 3u) << warnings;
    EXPECT_NE(warnings.find("more than 5 %"), std::string::npos) << warnings;
    EXPECT_EQ(materialNamed(scene, "Wide").mtoon->outlineWidthMode, OutlineWidthMode::ScreenCoordinates);
    EXPECT_NE(warnings.find("more than the renderer can place; no outline"), std::string::npos) << warnings;
    EXPECT_EQ(materialNamed(scene, "Far").mtoon->outlineWidthMode, OutlineWidthMode::None);
    EXPECT_NE(warnings.find("MToon's _ShadingGradeTexture is not drawn"), std::string::npos) << warnings;
    // The UV animation is drawn: converted as three-vrm converts it, the vertical scroll negated.
    EXPECT_FLOAT_EQ(materialNamed(scene, "Shiny").mtoon->uvAnimationScrollXSpeedFactor, 0.5f);
}

TEST(VrmMaterials, Vrm0UvAnimationIsTheSameSpeedsWithTheVerticalScrollNegated) {
    const Scene scene = loadVrm({R"({"name": "Scroll"})"},
                                vrm0("{\"name\": \"Scroll\", \"shader\": \"VRM/MToon\", \"floatProperties\": "
                                     "{\"_UvAnimScrollX\": 0.25, \"_UvAnimScrollY\": 0.1, \"_UvAnimRotation\": 0.2}, "
                                     "\"textureProperties\": {\"_UvAnimMaskTexture\": 0}}"));
    const MToonMaterial& mtoon = *materialNamed(scene, "Scroll").mtoon;
    EXPECT_FLOAT_EQ(mtoon.uvAnimationScrollXSpeedFactor, 0.25f);
    EXPECT_FLOAT_EQ(mtoon.uvAnimationScrollYSpeedFactor, -0.1f) << "0.x's v points up the image, 1.0's down";
    EXPECT_FLOAT_EQ(mtoon.uvAnimationRotationSpeedFactor, 0.2f);
    EXPECT_TRUE(mtoon.uvAnimationMaskTexture.present());
    EXPECT_TRUE(scene.report.warnings.empty()) << scene.report.warnings.front();
}

TEST(VrmMaterials, Vrm0OutlineWidthModesAndColourModes) {
    const auto entry = [](const std::string& name, const std::string& floats) {
        return "{\"name\": \"" + name + "\", \"shader\": \"VRM/MToon\", \"floatProperties\": {" + floats + "}}";
    };
    const Scene scene = loadVrm(
        {R"({"name": "None"})", R"({"name": "Screen"})", R"({"name": "Fixed"})", R"({"name": "Defaults"})"},
        vrm0(entry("None", "\"_OutlineWidthMode\": 0, \"_OutlineWidth\": 3") + ", " +
             entry("Screen", "\"_OutlineWidthMode\": 2, \"_OutlineWidth\": 0.5, \"_OutlineColorMode\": 1") + ", " +
             entry("Fixed", "\"_OutlineWidthMode\": 1, \"_OutlineWidth\": 1, \"_OutlineColorMode\": 0, "
                            "\"_OutlineLightingMix\": 0.8") +
             ", " + entry("Defaults", "")));
    const MToonMaterial& none = *materialNamed(scene, "None").mtoon;
    EXPECT_EQ(none.outlineWidthMode, OutlineWidthMode::None);
    EXPECT_EQ(none.outlineWidthFactor, 0.0f);
    const MToonMaterial& screen = *materialNamed(scene, "Screen").mtoon;
    EXPECT_EQ(screen.outlineWidthMode, OutlineWidthMode::ScreenCoordinates);
    EXPECT_FLOAT_EQ(screen.outlineWidthFactor, 0.0025f) << "0.5 % of half the screen height";
    EXPECT_FLOAT_EQ(screen.outlineLightingMixFactor, 1.0f) << "mixed lighting, _OutlineLightingMix absent";
    const MToonMaterial& fixed = *materialNamed(scene, "Fixed").mtoon;
    EXPECT_FLOAT_EQ(fixed.outlineWidthFactor, 0.01f);
    EXPECT_EQ(fixed.outlineLightingMixFactor, 0.0f) << "a fixed colour takes no lighting";
    // An entry without properties: three-vrm's defaults, the glTF material's surface kept.
    const Material& defaultsMaterial = materialNamed(scene, "Defaults");
    const MToonMaterial& defaults = *defaultsMaterial.mtoon;
    expectVec3Near(defaults.shadeColorFactor,
                   {detail::srgbToLinear(0.97f), detail::srgbToLinear(0.81f), detail::srgbToLinear(0.86f)});
    EXPECT_NEAR(defaults.shadingToonyFactor, 0.95f, 1e-6f);
    EXPECT_EQ(defaults.parametricRimFresnelPowerFactor, 1.0f);
    EXPECT_EQ(defaults.rimLightingMixFactor, 0.0f);
    EXPECT_EQ(defaults.outlineWidthMode, OutlineWidthMode::None);
    EXPECT_EQ(defaults.outlineLightingMixFactor, 0.0f);
    EXPECT_EQ(defaultsMaterial.alphaMode, AlphaMode::Opaque);
    EXPECT_FALSE(defaultsMaterial.doubleSided);
    EXPECT_FALSE(defaultsMaterial.baseColorTexture.present());
}

TEST(VrmMaterials, Vrm0UnlitShadersMakeUnlitMaterials) {
    const Scene scene = loadVrm({R"({"name": "Cutout"})", R"({"name": "Clear"})"},
                                vrm0(R"({"name": "Cutout", "shader": "VRM/UnlitCutout",
                                         "floatProperties": {"_Cutoff": 0.25}, "textureProperties": {"_MainTex": 2}},
                                        {"name": "Clear", "shader": "VRM/UnlitTransparent"})"));
    const Material& cutout = materialNamed(scene, "Cutout");
    EXPECT_FALSE(cutout.mtoon.has_value());
    EXPECT_TRUE(cutout.unlit);
    EXPECT_EQ(cutout.alphaMode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(cutout.alphaCutoff, 0.25f);
    EXPECT_EQ(cutout.baseColorTexture.image, 2);
    const Material& clear = materialNamed(scene, "Clear");
    EXPECT_TRUE(clear.unlit);
    EXPECT_EQ(clear.alphaMode, AlphaMode::Blend);
}

TEST(VrmMaterials, Vrm10BadValuesWarnAndUseTheDefault) {
    // Lenient like the viewers: each bad property is named in a warning (once per material, though two primitives
    // use it) and read as its default; the file loads.
    const Scene scene = loadVrm({R"({"name": "Bad", "extensions": {"VRMC_materials_mtoon": {
        "specVersion": "0.9",
        "shadingToonyFactor": "hard",
        "shadingShiftFactor": 1e300,
        "shadeColorFactor": [1, "red", 0],
        "parametricRimColorFactor": [1, 1],
        "shadeMultiplyTexture": {"index": 99},
        "outlineWidthMultiplyTexture": {"index": 0, "texCoord": 2},
        "outlineWidthMode": "pixels",
        "outlineWidthFactor": -1}}})",
                                 R"({"name": "NotAnObject", "extensions": {"VRMC_materials_mtoon": [1, 2]}})"},
                                "", 2);
    const Material& bad = materialNamed(scene, "Bad");
    ASSERT_TRUE(bad.mtoon.has_value());
    MToonMaterial defaults;
    defaults.specVersion = "1.0";
    EXPECT_EQ(*bad.mtoon, defaults);
    for (const char* key : {"specVersion", "shadingToonyFactor must be a number, got a string",
                            "shadingShiftFactor is 1e+300", "shadeColorFactor[1]", "parametricRimColorFactor must be",
                            "shadeMultiplyTexture.index must be a texture index in [0, 3), got 99", "texCoord 2",
                            "outlineWidthMode must be", "outlineWidthFactor -1 is negative"}) {
        EXPECT_EQ(warningsMentioning(scene, key), 1u) << key;
    }
    EXPECT_EQ(warningsMentioning(scene, "material 0 'Bad': VRMC_materials_mtoon."), 9u);
    EXPECT_FALSE(materialNamed(scene, "NotAnObject").mtoon.has_value());
    // tinygltf keeps only object-valued extensions, so an array reads as no MToon at all.
}

TEST(VrmMaterials, Vrm0BadValuesWarnAndUseTheDefault) {
    const Scene scene = loadVrm({R"({"name": "Bad"})", R"({"name": "Odd"})", R"({"name": "Third"})"},
                                vrm0(R"({"name": "Bad", "shader": "VRM/MToon", "floatProperties": [1],
                         "vectorProperties": {"_ShadeColor": "pink", "_Color": [1, 1]},
                         "textureProperties": {"_ShadeTexture": -1, "_MainTex": 0.5}},
                        {"name": "Renamed", "shader": "VRM/MToon", "floatProperties": {"_ShadeToony": null,
                         "_OutlineWidthMode": 7, "_BlendMode": 9, "_CullMode": "back"}},
                        {"name": "Third", "shader": "Standard"})"));
    const Material& bad = materialNamed(scene, "Bad");
    ASSERT_TRUE(bad.mtoon.has_value());
    expectVec3Near(bad.mtoon->shadeColorFactor,
                   {detail::srgbToLinear(0.97f), detail::srgbToLinear(0.81f), detail::srgbToLinear(0.86f)});
    EXPECT_FALSE(bad.mtoon->shadeMultiplyTexture.present());
    EXPECT_FALSE(bad.baseColorTexture.present());
    EXPECT_EQ(bad.baseColorFactor, glm::vec4(1.0f)) << "the glTF material's (glTF's default white)";
    for (const char* text : {"floatProperties must be an object, got an array", "_ShadeColor must be an array",
                             "_Color must be an array of 3 to 4 numbers, got 2 elements",
                             "_ShadeTexture must be a texture index in [0, 3), got -1", "_MainTex must be a texture"}) {
        EXPECT_EQ(warningsMentioning(scene, text), 1u) << text;
    }
    const Material& odd = materialNamed(scene, "Odd");
    ASSERT_TRUE(odd.mtoon.has_value()) << "paired by index, though named otherwise";
    EXPECT_NEAR(odd.mtoon->shadingToonyFactor, 0.95f, 1e-6f) << "_ShadeToony null (tinygltf drops it): 0.9";
    EXPECT_EQ(odd.mtoon->outlineWidthMode, OutlineWidthMode::None);
    EXPECT_EQ(odd.alphaMode, AlphaMode::Opaque);
    for (const char* text : {"materialProperties[1] is named 'Renamed'", "_OutlineWidthMode 7 is not 0, 1 or 2",
                             "_BlendMode 9 is not 0 to 3", "_CullMode must be a number, got a string"}) {
        EXPECT_EQ(warningsMentioning(scene, text), 1u) << text;
    }
    EXPECT_FALSE(materialNamed(scene, "Third").mtoon.has_value());
    EXPECT_EQ(warningsMentioning(scene, "shader 'Standard' is not VRM/MToon"), 1u);
}

TEST(VrmMaterials, FilesRequiringTheVrmExtensionsLoad) {
    const Scene scene = loadVrm({R"({"name": "Skin", "extensions": {"VRMC_materials_mtoon": {"specVersion": "1.0"}}})"},
                                "\"extensionsUsed\": [\"VRMC_vrm\", \"VRMC_materials_mtoon\"], \"extensionsRequired\": "
                                "[\"VRMC_vrm\", \"VRMC_materials_mtoon\"], ");
    EXPECT_TRUE(materialNamed(scene, "Skin").mtoon.has_value());
    for (const char* extension : {"VRM", "VRMC_vrm", "VRMC_materials_mtoon"}) {
        EXPECT_NE(std::ranges::find(supportedGltfExtensions(), extension), supportedGltfExtensions().end())
            << extension;
    }
}

} // namespace
} // namespace inkgraph::vrm_materials_test
