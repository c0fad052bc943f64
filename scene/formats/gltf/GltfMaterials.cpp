/** @file A glTF material as the renderer sees it (GltfMaterials.h): factors (base colour, metallic, roughness,
 *  emissive) clamped into their ranges, or KHR_materials_pbrSpecularGlossiness's diffuse; textures with their image
 *  (EXT_texture_webp's first), coordinate set, sampler and KHR_texture_transform, the inkgraph shade-map extra, then a
 *  VRM character's MToon (VrmMaterials.h). */

#include "scene/formats/gltf/GltfMaterials.h"

#include "scene/formats/ShaderValues.h"
#include "scene/formats/gltf/GltfFiles.h"
#include "scene/formats/gltf/VrmMaterials.h"

#include <nlohmann/json.hpp>

#include <climits>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <optional>

namespace inkgraph::detail {

struct GltfMaterials::Reader {
    Reader(const std::string& path, const tinygltf::Model& model, std::vector<Warning>& warnings)
        : mPath(path), mModel(model), mWarnings(warnings), mMaterialShadeMaps(model.materials.size()),
          mMaterials(model.materials.size()) {}

    [[noreturn]] void fail(const std::string& problem) const { throwLoadError(mPath, problem); }

    /** "material 2 'Metal'", or "material 2" for an unnamed one. */
    std::string materialLabel(int materialIndex) const {
        const std::string& name = mModel.materials[std::size_t(materialIndex)].name;
        return "material " + std::to_string(materialIndex) + (name.empty() ? "" : " '" + excerptForMessage(name) + "'");
    }

    /** The shade map material `materialIndex` names in `"extras": {"inkgraph": {"shademap": PATH}}`, resolved against
     *  the file's folder; empty when it names none. Read once per material (its warnings too), when a primitive first
     *  uses it. The original JSON is parsed rather than tinygltf's Value, which drops nulls and empty objects and
     *  arrays, so `"shademap": null` would pass for "no map" instead of being reported. */
    const std::string& materialShadeMap(int materialIndex) {
        std::optional<std::string>& cached = mMaterialShadeMaps[std::size_t(materialIndex)];
        if (cached) {
            return *cached;
        }
        cached.emplace();
        const std::string& extrasJson = mModel.materials[std::size_t(materialIndex)].extras_json_string;
        if (extrasJson.empty()) {
            return *cached;
        }
        const nlohmann::json extras = nlohmann::json::parse(extrasJson, nullptr, false);
        // Other tools may keep anything in extras; only the "inkgraph" member is ours.
        if (!extras.is_object() || !extras.contains("inkgraph")) {
            return *cached;
        }
        const std::string label = materialLabel(materialIndex);
        const nlohmann::json& ours = extras["inkgraph"];
        if (!ours.is_object()) {
            fail(label + ": extras.inkgraph must be an object, got " + std::string(ours.type_name()));
        }
        for (const auto& [key, value] : ours.items()) {
            if (key == "shademap") {
                continue;
            }
            // A newer file or a typo ("shadeMap"): the render still works, so say so instead of refusing it.
            mWarnings.push_back(makeWarning(WarningKind::ExtrasKeyIgnored,
                                            label + ": extras.inkgraph key '" + excerptForMessage(key) +
                                                "' ignored (known: 'shademap')",
                                            "", label));
        }
        const auto shadeMap = ours.find("shademap");
        if (shadeMap == ours.end()) {
            return *cached;
        }
        if (!shadeMap->is_string() || shadeMap->get_ref<const std::string&>().empty()) {
            fail(label + ": extras.inkgraph.shademap must be a non-empty string (a PNG path), got " +
                 (shadeMap->is_string() ? std::string("an empty string") : std::string(shadeMap->type_name())));
        }
        *cached = shadeMapBesideModel(mPath, shadeMap->get_ref<const std::string&>());
        return *cached;
    }

    /** "texture 2 'skin'", or "texture 2" for an unnamed one. */
    std::string textureLabel(int textureIndex) const {
        const std::string& name = mModel.textures[std::size_t(textureIndex)].name;
        return "texture " + std::to_string(textureIndex) + (name.empty() ? "" : " '" + excerptForMessage(name) + "'");
    }

    /** A sampler enum as the file writes it, or `fallback` (with a warning) for a value glTF does not define;
     *  tinygltf leaves an absent one at -1. */
    template <typename Enum>
    Enum samplerValue(int value, std::initializer_list<Enum> allowed, Enum fallback, const std::string& what) {
        if (value == -1) return fallback;
        for (Enum candidate : allowed)
            if (std::uint32_t(candidate) == std::uint32_t(value)) return candidate;
        mWarnings.push_back(
            makeWarning(WarningKind::MaterialValueInvalid,
                        what + " " + std::to_string(value) + " is not a glTF value; the default is used", "",
                        what.substr(0, what.rfind(' '))));
        return fallback;
    }

    TextureSampler readSampler(int samplerIndex) {
        TextureSampler result;
        if (samplerIndex == -1) return result; // glTF: repeat, filters up to the renderer
        if (samplerIndex < 0 || std::size_t(samplerIndex) >= mModel.samplers.size()) {
            fail("sampler index " + std::to_string(samplerIndex) + " out of range (file has " +
                 std::to_string(mModel.samplers.size()) + " samplers)");
        }
        const tinygltf::Sampler& sampler = mModel.samplers[std::size_t(samplerIndex)];
        const std::string label = "sampler " + std::to_string(samplerIndex);
        using F = TextureFilter;
        using W = TextureWrap;
        result.magFilter =
            samplerValue(sampler.magFilter, {F::Nearest, F::Linear}, result.magFilter, label + " magFilter");
        result.minFilter = samplerValue(sampler.minFilter,
                                        {F::Nearest, F::Linear, F::NearestMipmapNearest, F::LinearMipmapNearest,
                                         F::NearestMipmapLinear, F::LinearMipmapLinear},
                                        result.minFilter, label + " minFilter");
        const std::initializer_list<W> wraps = {W::Repeat, W::ClampToEdge, W::MirroredRepeat};
        result.wrapS = samplerValue(sampler.wrapS, wraps, result.wrapS, label + " wrapS");
        result.wrapT = samplerValue(sampler.wrapT, wraps, result.wrapT, label + " wrapT");
        return result;
    }

    /** A number of an extension object, or `fallback` when absent; a present non-number or non-finite one fails. */
    double extensionNumber(const tinygltf::Value& object, const char* key, double fallback,
                           const std::string& label) const {
        if (!object.Has(key)) return fallback;
        const tinygltf::Value& value = object.Get(key);
        const double number = value.IsNumber() ? value.GetNumberAsDouble() : std::nan("");
        if (!std::isfinite(number)) fail(label + ": '" + key + "' must be a finite number");
        return number;
    }

    /** An [x, y] array of an extension object, or `fallback` when absent. */
    glm::dvec2 extensionPair(const tinygltf::Value& object, const char* key, glm::dvec2 fallback,
                             const std::string& label) const {
        if (!object.Has(key)) return fallback;
        const tinygltf::Value& value = object.Get(key);
        if (!value.IsArray() || value.ArrayLen() != 2) fail(label + ": '" + key + "' must be an array of 2 numbers");
        glm::dvec2 pair;
        for (int i = 0; i < 2; ++i) {
            const tinygltf::Value& item = value.Get(i);
            pair[i] = item.IsNumber() ? item.GetNumberAsDouble() : std::nan("");
            if (!std::isfinite(pair[i])) fail(label + ": '" + key + "' must be an array of 2 finite numbers");
        }
        return pair;
    }

    /** "[x, y]", for messages. */
    static std::string formatPair(const glm::dvec2& pair) {
        // Appended rather than "[" + ...: GCC 12 warns falsely (-Wrestrict, bug 105329) on that inlined here.
        std::string text = "[";
        text.append(formatNumber(pair.x)).append(", ").append(formatNumber(pair.y)).append("]");
        return text;
    }

    /** The image `texture` shows: EXT_texture_webp's source when it names one (the core `source` is then
     *  the fallback of viewers without WebP), else the core source; -1 when it has neither. */
    int textureSource(const tinygltf::Texture& texture, const std::string& where) const {
        const auto webp = texture.extensions.find("EXT_texture_webp");
        if (webp == texture.extensions.end() || !webp->second.IsObject() || !webp->second.Has("source"))
            return texture.source;
        const double source = extensionNumber(webp->second, "source", 0.0, where + " EXT_texture_webp");
        if (source < 0.0 || source != std::floor(source) || source >= double(mModel.images.size()))
            fail(where + " EXT_texture_webp: image index " + formatNumber(source) + " out of range (file has " +
                 std::to_string(mModel.images.size()) + " images)");
        return int(source);
    }

    /** A material's textureInfo as a TextureRef: the image its texture shows (textureSource()), the coordinate set and
     *  sampler, and the KHR_texture_transform matrix. A texture without an image the renderer decodes (only an
     *  extension's, e.g. KHR_texture_basisu's KTX2) or on a third coordinate set leaves the material untextured, with a
     *  warning. */
    TextureRef readTextureRef(const tinygltf::TextureInfo& info, const std::string& label) {
        TextureRef ref;
        if (info.index == -1) return ref;
        if (info.index < 0 || std::size_t(info.index) >= mModel.textures.size()) {
            fail(label + ": texture index " + std::to_string(info.index) + " out of range (file has " +
                 std::to_string(mModel.textures.size()) + " textures)");
        }
        const tinygltf::Texture& texture = mModel.textures[std::size_t(info.index)];
        const std::string textureName = textureLabel(info.index);
        const int source = textureSource(texture, label + ": " + textureName);
        if (source == -1) {
            std::string extensions;
            std::size_t named = 0;
            for (const auto& [name, value] : texture.extensions)
                if (++named <= kMaxNamedExtensions)
                    extensions += (extensions.empty() ? " (it has only '" : "', '") + excerptForMessage(name);
            mWarnings.push_back(makeWarning(WarningKind::TextureWithoutCoreImage,
                                            label + ": " + textureName + " has no PNG, JPEG or WebP source" +
                                                (extensions.empty() ? "" : extensions + "')") + "; drawn untextured",
                                            "", textureName));
            return ref;
        }
        if (source < 0 || std::size_t(source) >= mModel.images.size()) {
            fail(label + ": " + textureName + ": image index " + std::to_string(source) + " out of range (file has " +
                 std::to_string(mModel.images.size()) + " images)");
        }
        double texCoord = info.texCoord;
        std::optional<glm::dmat3> transform;
        std::string transformText;
        const auto extension = info.extensions.find("KHR_texture_transform");
        if (extension != info.extensions.end() && extension->second.IsObject()) {
            const tinygltf::Value& object = extension->second;
            const std::string where = label + " KHR_texture_transform";
            const glm::dvec2 offset = extensionPair(object, "offset", glm::dvec2(0.0), where);
            const double rotation = extensionNumber(object, "rotation", 0.0, where);
            const glm::dvec2 scale = extensionPair(object, "scale", glm::dvec2(1.0), where);
            texCoord = extensionNumber(object, "texCoord", texCoord, where);
            // uv' = T * R * S * (u, v, 1), the extension's order. R is not the matrix its GLSL listing writes (a
            // counter-clockwise turn with v up) but its transpose: counter-clockwise in glTF's UV space, where v points
            // down, as the extension's own example (offset [0, 1], a quarter turn, scale [0.5, 0.5] samples the
            // image's lower left quadrant), Khronos's TextureTransformTest sample, three.js and Babylon.js read it
            // (KhronosGroup/glTF issue 1563).
            const glm::dmat3 translation(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, offset.x, offset.y, 1.0);
            const double c = std::cos(rotation);
            const double s = std::sin(rotation);
            const glm::dmat3 rotationMatrix(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
            const glm::dmat3 scaleMatrix(scale.x, 0.0, 0.0, 0.0, scale.y, 0.0, 0.0, 0.0, 1.0);
            transform = translation * rotationMatrix * scaleMatrix;
            transformText = where + " (offset " + formatPair(offset) + ", rotation " + formatNumber(rotation) +
                            ", scale " + formatPair(scale) + ")";
        }
        if (texCoord != 0.0 && texCoord != 1.0) {
            mWarnings.push_back(makeWarning(WarningKind::TextureCoordinateSetUnsupported,
                                            label + ": texture coordinate set " + formatNumber(texCoord) +
                                                " is not read (only TEXCOORD_0 and TEXCOORD_1); drawn untextured",
                                            "", textureName));
            return ref;
        }
        ref.image = source;
        ref.texCoord = int(texCoord);
        ref.sampler = readSampler(texture.sampler);
        if (transform) {
            // The transform says where the image lies: one the shaders' float cannot follow is refused, not guessed.
            std::string problem;
            const std::optional<glm::mat3> forShaders = shaderTextureTransform(*transform, ref.sampler, problem);
            if (!forShaders) fail(transformText + ": " + problem);
            ref.transform = *forShaders;
        }
        return ref;
    }

    /** `object[key]`, a textureInfo inside an extension, as tinygltf's TextureInfo, so readTextureRef() reads it (its
     *  coordinate set, sampler and KHR_texture_transform) as it reads a core one; absent: no texture (index -1). */
    tinygltf::TextureInfo extensionTextureInfo(const tinygltf::Value& object, const char* key,
                                               const std::string& label) const {
        tinygltf::TextureInfo info;
        if (!object.Has(key)) return info;
        const std::string where = label + " " + key;
        const tinygltf::Value& value = object.Get(key);
        if (!value.IsObject()) fail(where + " must be an object (a textureInfo)");
        if (!value.Has("index")) fail(where + " has no 'index'");
        const auto wholeNumber = [&](const char* member, double fallback) {
            const double number = extensionNumber(value, member, fallback, where);
            if (number < 0.0 || number != std::floor(number) || number > double(INT_MAX))
                fail(where + ": '" + member + "' " + formatNumber(number) + " is not a whole number >= 0");
            return int(number);
        };
        info.index = wholeNumber("index", 0.0);
        info.texCoord = wholeNumber("texCoord", 0.0);
        if (value.Has("extensions") && value.Get("extensions").IsObject()) {
            const tinygltf::Value& extensions = value.Get("extensions");
            for (const std::string& name : extensions.Keys()) info.extensions[name] = extensions.Get(name);
        }
        return info;
    }

    /** KHR_materials_pbrSpecularGlossiness, when the material has it, instead of its metallic-roughness (which the
     *  extension keeps only as the fallback of viewers without it): diffuseFactor and diffuseTexture are the base
     *  colour and alpha. The specular colour and its texture are not drawn (no shading model takes a specular colour);
     *  glossinessFactor becomes roughness 1 - glossiness on a non-metal, so --shading mtoon's metallic-roughness
     *  fallback draws a diffuse surface rather than glTF's default metal. Returns false when the material does not have
     *  it. */
    bool readSpecularGlossiness(const tinygltf::Material& source, const std::string& label, Material& result) {
        const auto extension = source.extensions.find("KHR_materials_pbrSpecularGlossiness");
        if (extension == source.extensions.end()) return false;
        const std::string where = label + " KHR_materials_pbrSpecularGlossiness";
        const tinygltf::Value& object = extension->second;
        if (!object.IsObject()) fail(where + " must be an object");
        if (object.Has("diffuseFactor")) {
            const tinygltf::Value& factor = object.Get("diffuseFactor");
            if (!factor.IsArray() || factor.ArrayLen() != 4)
                fail(where + ": 'diffuseFactor' must be an array of 4 numbers");
            for (int i = 0; i < 4; ++i) {
                const tinygltf::Value& item = factor.Get(i);
                const double value = item.IsNumber() ? item.GetNumberAsDouble() : std::nan("");
                if (!std::isfinite(value)) fail(where + ": 'diffuseFactor' must be an array of 4 finite numbers");
                result.baseColorFactor[i] = shaderValue(
                    value, kUnitRange, where + " diffuseFactor[" + std::to_string(i) + "]", mWarnings, label);
            }
        } else {
            result.baseColorFactor = glm::vec4(1.0f); // the extension's default
        }
        result.baseColorTexture =
            readTextureRef(extensionTextureInfo(object, "diffuseTexture", where), where + " diffuseTexture");
        const double glossiness = extensionNumber(object, "glossinessFactor", 1.0, where);
        result.metallicFactor = 0.0f;
        result.roughnessFactor =
            1.0f - shaderValue(glossiness, kUnitRange, where + " glossinessFactor", mWarnings, label);
        return true;
    }

    /** A VRM character's MToon (scene/formats/gltf/VrmMaterials.h), which may also adjust `material`. Its textures go
     * through readTextureRef(), so their samplers and KHR_texture_transform are read as the glTF material's are. Called
     * once per material, by material(), so its warnings are reported once. */
    std::optional<MToonMaterial> vrmMaterial(int materialIndex, Material& material) {
        const std::string label = materialLabel(materialIndex) + " MToon texture";
        const VrmTextureResolver resolveTexture = [&](int texture, int texCoord,
                                                      const tinygltf::Value* textureInfoExtensions) {
            tinygltf::TextureInfo info;
            info.index = texture;
            info.texCoord = texCoord;
            if (textureInfoExtensions && textureInfoExtensions->IsObject()) {
                for (const std::string& key : textureInfoExtensions->Keys())
                    info.extensions[key] = textureInfoExtensions->Get(key);
            }
            return readTextureRef(info, label);
        };
        std::vector<Warning> warnings;
        std::optional<MToonMaterial> mtoon = readVrmMaterial(mModel, materialIndex, material, resolveTexture, warnings);
        mWarnings.insert(mWarnings.end(), warnings.begin(), warnings.end());
        return mtoon;
    }

    /** Material `materialIndex` as the renderer sees it, read once (its warnings too) when a primitive first uses
     *  it: the glTF material, then a VRM character's MToon (vrmMaterial()). */
    const Material& material(int materialIndex) {
        std::optional<Material>& cached = mMaterials[std::size_t(materialIndex)];
        if (cached) return *cached;
        const tinygltf::Material& source = mModel.materials[std::size_t(materialIndex)];
        const std::string label = materialLabel(materialIndex);
        Material result;
        result.name = source.name;
        if (!readSpecularGlossiness(source, label, result)) {
            // Factors beyond glTF's ranges are clamped with a warning, as viewers draw them (ShaderValues.h).
            const std::vector<double>& factor = source.pbrMetallicRoughness.baseColorFactor;
            for (std::size_t i = 0; i < 4 && factor.size() == 4; ++i) {
                result.baseColorFactor[int(i)] = shaderValue(
                    factor[i], kUnitRange, label + " baseColorFactor[" + std::to_string(i) + "]", mWarnings, label);
            }
            result.baseColorTexture =
                readTextureRef(source.pbrMetallicRoughness.baseColorTexture, label + " baseColorTexture");
            // tinygltf fills in glTF's defaults (1, 1) for absent factors, so a glTF material is metallic unless it
            // says not.
            result.metallicFactor = shaderValue(source.pbrMetallicRoughness.metallicFactor, kUnitRange,
                                                label + " metallicFactor", mWarnings, label);
            result.roughnessFactor = shaderValue(source.pbrMetallicRoughness.roughnessFactor, kUnitRange,
                                                 label + " roughnessFactor", mWarnings, label);
            result.metallicRoughnessTexture = readTextureRef(source.pbrMetallicRoughness.metallicRoughnessTexture,
                                                             label + " metallicRoughnessTexture");
        }
        for (std::size_t i = 0; i < 3 && source.emissiveFactor.size() == 3; ++i) {
            result.emissiveFactor[int(i)] =
                shaderValue(source.emissiveFactor[i], kUnitRange, label + " emissiveFactor[" + std::to_string(i) + "]",
                            mWarnings, label);
        }
        const auto strength = source.extensions.find("KHR_materials_emissive_strength");
        if (strength != source.extensions.end() && strength->second.IsObject()) {
            const std::string where = label + " KHR_materials_emissive_strength";
            const double multiplier = extensionNumber(strength->second, "emissiveStrength", 1.0, where);
            if (multiplier < 0.0) fail(label + ": emissiveStrength " + formatNumber(multiplier) + " is negative");
            result.emissiveFactor *=
                shaderValue(multiplier, kNonNegativeRange, where + " emissiveStrength", mWarnings, label);
        }
        result.emissiveTexture = readTextureRef(source.emissiveTexture, label + " emissiveTexture");
        result.unlit = source.extensions.count("KHR_materials_unlit") > 0;
        if (source.alphaMode == "MASK") {
            result.alphaMode = AlphaMode::Mask;
        } else if (source.alphaMode == "BLEND") {
            result.alphaMode = AlphaMode::Blend;
        } else if (source.alphaMode != "OPAQUE") {
            mWarnings.push_back(makeWarning(WarningKind::MaterialValueInvalid,
                                            label + ": alphaMode '" + excerptForMessage(source.alphaMode) +
                                                "' is not OPAQUE, MASK or BLEND; drawn opaque",
                                            "", label));
        }
        if (std::isfinite(source.alphaCutoff) && source.alphaCutoff >= 0.0) {
            // Above 1 every fragment would be cut out: blank paper.
            result.alphaCutoff = shaderValue(source.alphaCutoff, kUnitRange, label + " alphaCutoff", mWarnings, label);
        } else {
            mWarnings.push_back(makeWarning(WarningKind::MaterialValueInvalid,
                                            label + ": alphaCutoff " + formatNumber(source.alphaCutoff) +
                                                " is not a number >= 0; 0.5 is used",
                                            "", label));
        }
        result.doubleSided = source.doubleSided;
        result.shadeMapPath = materialShadeMap(materialIndex);
        result.mtoon = vrmMaterial(materialIndex, result);
        // VRM exporters (UniVRM, VRoid, the Blender add-on) write KHR_materials_unlit beside MToon as the fallback of
        // viewers without MToon: not a request for unlit shading, so every look lights such a material.
        if (result.mtoon) result.unlit = false;
        // Only MToon draws normal maps (docs/mtoon.md); a VRM 0.x material's _BumpMap, read above, comes first.
        if (result.mtoon && !result.normalTexture.present() && source.normalTexture.index != -1) {
            tinygltf::TextureInfo normalInfo;
            normalInfo.index = source.normalTexture.index;
            normalInfo.texCoord = source.normalTexture.texCoord;
            normalInfo.extensions = source.normalTexture.extensions;
            result.normalTexture = readTextureRef(normalInfo, label + " normalTexture");
            result.normalScale =
                shaderValue(source.normalTexture.scale, kSignedRange, label + " normalTexture.scale", mWarnings, label);
        }
        // Said, not changed, as an MTL's d 0 is: a model of such materials alone was blank paper without a word.
        if (const std::string why = whyMaterialDrawsNothing(result); !why.empty())
            mWarnings.push_back(makeWarning(WarningKind::MaterialInvisible,
                                            label + ": " + why + ": its faces are not drawn", "", label));
        cached = std::move(result);
        return *cached;
    }

    const std::string& mPath;
    const tinygltf::Model& mModel;
    std::vector<Warning>& mWarnings;
    std::vector<std::optional<std::string>> mMaterialShadeMaps; ///< per material, once read: its shade map or ""
    std::vector<std::optional<Material>> mMaterials;            ///< per material, once read
};

GltfMaterials::GltfMaterials(const std::string& path, const tinygltf::Model& model, std::vector<Warning>& warnings)
    : mReader(std::make_unique<Reader>(path, model, warnings)) {}

GltfMaterials::~GltfMaterials() = default;

const Material& GltfMaterials::material(int materialIndex) { return mReader->material(materialIndex); }

} // namespace inkgraph::detail
