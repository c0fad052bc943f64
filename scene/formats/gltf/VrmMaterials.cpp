/** @file VRM MToon materials: VRMC_materials_mtoon-1.0 read as it is, VRM 0.x's materialProperties migrated to it.
 *  Every conversion names its source; docs/mtoon.md has the table. Lenient like the viewers: a bad value is a warning
 *  and its default, never a refused file. */

#include "scene/formats/gltf/VrmMaterials.h"

#include "scene/formats/FormatReaders.h"
#include "scene/formats/ShaderValues.h"
#include "scene/formats/gltf/VrmExpressions.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace inkgraph::detail {

float srgbToLinear(float encoded) {
    // IEC 61966-2-1; Unity's Color.linear, which UniVRM's migration (MigrationMToon) converts VRM 0.x colours with.
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

namespace {

/** VRM 0.x's shader names (UniVRM's VRM/MToon and its unlit family, glTF's own shading). */
constexpr const char* kMToonShader = "VRM/MToon";
constexpr const char* kGltfShader = "VRM_USE_GLTFSHADER";

/** Every finite float: for properties that are no shader value (enums, a texture coordinate set). */
constexpr ShaderRange kAnyFloat{-double(std::numeric_limits<float>::max()), double(std::numeric_limits<float>::max())};

/** Reads one material's properties, reporting each bad one as "<material>: <where>.<key> ...; using <default>". */
class PropertyReader {
public:
    PropertyReader(const tinygltf::Model& model, std::string label, const VrmTextureResolver& resolveTexture,
                   std::vector<Warning>& warnings)
        : mModel(model), mLabel(std::move(label)), mResolveTexture(resolveTexture), mWarnings(warnings) {}

    void warn(const std::string& problem) { warn(WarningKind::VrmPropertyInvalid, problem); }
    void warn(WarningKind kind, const std::string& problem) {
        mWarnings.push_back(makeWarning(kind, mLabel + ": " + problem, "", mLabel));
    }

    /** The object `object[key]`, or null when absent; another type is reported and read as absent. */
    const tinygltf::Value* object(const tinygltf::Value& object, const std::string& key, const std::string& where) {
        if (!object.IsObject() || !object.Has(key)) return nullptr;
        const tinygltf::Value& member = object.Get(key);
        if (!member.IsObject()) {
            warn(where + "." + key + " must be an object, got " + jsonTypeName(member) + "; ignored");
            return nullptr;
        }
        return &member;
    }

    /** A finite number, as float: absent, wrong type or out of float's range is `fallback` (the last two reported);
     *  outside `range` (what the shaders make sense of: ShaderValues.h), the nearest end of it (reported). */
    float number(const tinygltf::Value* object, const std::string& key, float fallback, const std::string& where,
                 ShaderRange range = kAnyFloat) {
        if (object == nullptr || !object->IsObject() || !object->Has(key)) return fallback;
        const tinygltf::Value& member = object->Get(key);
        if (!member.IsNumber()) {
            warn(where + "." + excerptForMessage(key) + " must be a number, got " + jsonTypeName(member) + "; using " +
                 formatNumber(fallback));
            return fallback;
        }
        const double value = member.GetNumberAsDouble();
        if (!std::isfinite(value) || std::abs(value) > double(std::numeric_limits<float>::max())) {
            warn(where + "." + excerptForMessage(key) + " is " + formatNumber(value) + ", not a finite float; using " +
                 formatNumber(fallback));
            return fallback;
        }
        return inRange(value, range, where + "." + excerptForMessage(key));
    }

    /** `value` through shaderValue(), its warning reported as this material's. */
    float inRange(double value, ShaderRange range, const std::string& what) {
        std::vector<Warning> problems;
        const float used = shaderValue(value, range, what, problems);
        for (const Warning& problem : problems) warn(WarningKind::ValueOutOfRange, problem.message);
        return used;
    }

    /** A colour of `minCount` to `maxCount` components (numbers()), each clamped to [0, 1] (reported), the range of
     *  VRM's colours: 0.x's gamma-encoded ones would otherwise overflow their conversion to linear light. */
    std::optional<std::vector<double>> colour(const tinygltf::Value* object, const std::string& key,
                                              std::size_t minCount, std::size_t maxCount, const std::string& where) {
        std::optional<std::vector<double>> values = numbers(object, key, minCount, maxCount, where);
        for (std::size_t i = 0; values && i < values->size(); ++i) {
            (*values)[i] =
                inRange((*values)[i], kUnitRange, where + "." + excerptForMessage(key) + "[" + std::to_string(i) + "]");
        }
        return values;
    }

    /** `count` numbers finite in float (3 for a VRM 1.0 colour, 4 for a VRM 0.x vector), as the file writes them;
     *  missing or bad: none. */
    std::optional<std::vector<double>> numbers(const tinygltf::Value* object, const std::string& key,
                                               std::size_t minCount, std::size_t maxCount, const std::string& where) {
        if (object == nullptr || !object->IsObject() || !object->Has(key)) return std::nullopt;
        const tinygltf::Value& member = object->Get(key);
        const std::string expected = minCount == maxCount
                                         ? std::to_string(minCount)
                                         : std::to_string(minCount) + " to " + std::to_string(maxCount);
        if (!member.IsArray() || member.ArrayLen() < minCount || member.ArrayLen() > maxCount) {
            warn(where + "." + excerptForMessage(key) + " must be an array of " + expected + " numbers, got " +
                 (member.IsArray() ? std::to_string(member.ArrayLen()) + " elements"
                                   : std::string(jsonTypeName(member))) +
                 "; using the default");
            return std::nullopt;
        }
        std::vector<double> values;
        for (std::size_t i = 0; i < member.ArrayLen(); ++i) {
            const tinygltf::Value& element = member.Get(int(i));
            const double value = element.IsNumber() ? element.GetNumberAsDouble() : std::nan("");
            if (!std::isfinite(value) || std::abs(value) > double(std::numeric_limits<float>::max())) {
                warn(where + "." + excerptForMessage(key) + "[" + std::to_string(i) +
                     "] must be a finite number, got " +
                     (element.IsNumber() ? formatNumber(value) : std::string(jsonTypeName(element))) +
                     "; using the default");
                return std::nullopt;
            }
            values.push_back(value);
        }
        return values;
    }

    glm::vec3 color3(const tinygltf::Value* object, const std::string& key, glm::vec3 fallback,
                     const std::string& where) {
        const auto values = colour(object, key, 3, 3, where);
        return values ? glm::vec3(glm::dvec3((*values)[0], (*values)[1], (*values)[2])) : fallback;
    }

    /** A glTF `textures` index as a file gives it: a whole number in range, or none (reported). */
    std::optional<int> textureIndex(const tinygltf::Value& value, const std::string& where) {
        const double index = value.IsNumber() ? value.GetNumberAsDouble() : std::nan("");
        if (!value.IsNumber() || !(index >= 0.0) || index != std::floor(index) ||
            index >= double(mModel.textures.size())) {
            warn(where + " must be a texture index in [0, " + std::to_string(mModel.textures.size()) + "), got " +
                 (value.IsNumber() ? formatNumber(index) : std::string(jsonTypeName(value))) + "; no texture");
            return std::nullopt;
        }
        return int(index);
    }

    /** A VRM 1.0 textureInfo {"index", "texCoord", "extensions"}; absent or bad: no texture. */
    TextureRef textureInfo(const tinygltf::Value& extension, const std::string& key, const std::string& where) {
        const tinygltf::Value* info = object(extension, key, where);
        if (info == nullptr) return {};
        const std::string infoWhere = where + "." + key;
        if (!info->Has("index")) {
            warn(infoWhere + " has no index; no texture");
            return {};
        }
        const std::optional<int> index = textureIndex(info->Get("index"), infoWhere + ".index");
        if (!index) return {};
        // Mesh::texcoords holds TEXCOORD_0 and TEXCOORD_1.
        const float texCoord = number(info, "texCoord", 0.0f, infoWhere);
        if (texCoord != 0.0f && texCoord != 1.0f) {
            warn(WarningKind::TextureCoordinateSetUnsupported,
                 infoWhere + ".texCoord " + formatNumber(texCoord) + " is not 0 or 1 (the sets read); no texture");
            return {};
        }
        const tinygltf::Value* extensions =
            info->Has("extensions") && info->Get("extensions").IsObject() ? &info->Get("extensions") : nullptr;
        return mResolveTexture(*index, int(texCoord), extensions);
    }

    /** A VRM 0.x textureProperties entry: a bare texture index, TEXCOORD_0. */
    TextureRef textureProperty(const tinygltf::Value* properties, const std::string& key, const std::string& where) {
        if (properties == nullptr || !properties->Has(key)) return {};
        const std::optional<int> index = textureIndex(properties->Get(key), where + "." + key);
        return index ? mResolveTexture(*index, 0, nullptr) : TextureRef{};
    }

private:
    const tinygltf::Model& mModel;
    std::string mLabel;
    const VrmTextureResolver& mResolveTexture;
    std::vector<Warning>& mWarnings;
};

/** One warning naming the MToon features a material uses that inkgraph does not draw (docs/mtoon.md "Not supported"),
 *  so a still that differs from a VRM viewer says why; nothing when it uses none. */
void warnUndrawn(const std::vector<std::string>& features, PropertyReader& read) {
    if (features.empty()) return;
    std::string list;
    for (std::size_t i = 0; i < features.size(); ++i)
        list += (i == 0 ? "" : i + 1 == features.size() ? " and " : ", ") + features[i];
    read.warn(WarningKind::MToonFeatureNotDrawn, "MToon's " + list + (features.size() == 1 ? " is" : " are") +
                                                     " not drawn by inkgraph (docs/mtoon.md, \"Not supported\")");
}

/** Outline widths a file may well hold by mistake (a 0.x width of 1e30 "cm"): a screen width above 5 % of the picture's
 *  height buries a character in its outline, so it is drawn as written but said; a world width too large for the
 *  renderer's float positions would draw nothing, so it is dropped with a warning. */
void checkOutlineWidth(MToonMaterial& mtoon, PropertyReader& read) {
    using Mode = MToonMaterial::OutlineWidthMode;
    if (mtoon.outlineWidthMode == Mode::ScreenCoordinates && mtoon.outlineWidthFactor > 0.05f) {
        read.warn(WarningKind::MToonOutlineWidth,
                  "MToon outline width " + formatNumber(mtoon.outlineWidthFactor) +
                      " of the screen height is more than 5 %: the outline may cover most of the picture");
    } else if (mtoon.outlineWidthMode == Mode::WorldCoordinates &&
               !(double(mtoon.outlineWidthFactor) <= kMaxModelExtent)) {
        read.warn(WarningKind::MToonOutlineWidth, "MToon outline width " + formatNumber(mtoon.outlineWidthFactor) +
                                                      " model units is more than the renderer can place; no outline");
        mtoon.outlineWidthMode = Mode::None;
        mtoon.outlineWidthFactor = 0.0f;
    }
}

MToonMaterial readMToon10(const tinygltf::Value& extension, PropertyReader& read) {
    const std::string where = "VRMC_materials_mtoon";
    const tinygltf::Value* fields = &extension;
    MToonMaterial mtoon; // its initialisers are the specification's defaults
    mtoon.specVersion = "1.0";
    if (extension.Has("specVersion")) {
        const tinygltf::Value& version = extension.Get("specVersion");
        if (!version.IsString() || version.Get<std::string>() != "1.0") {
            read.warn(where + ".specVersion is " +
                      (version.IsString() ? "'" + excerptForMessage(version.Get<std::string>()) + "'"
                                          : std::string(jsonTypeName(version))) +
                      ", not '1.0'; read as 1.0");
        }
    }
    mtoon.shadeColorFactor = read.color3(fields, "shadeColorFactor", mtoon.shadeColorFactor, where);
    mtoon.shadeMultiplyTexture = read.textureInfo(extension, "shadeMultiplyTexture", where);
    mtoon.shadingShiftFactor = read.number(fields, "shadingShiftFactor", mtoon.shadingShiftFactor, where, kSignedRange);
    mtoon.shadingToonyFactor = read.number(fields, "shadingToonyFactor", mtoon.shadingToonyFactor, where, kUnitRange);
    mtoon.parametricRimColorFactor =
        read.color3(fields, "parametricRimColorFactor", mtoon.parametricRimColorFactor, where);
    mtoon.parametricRimFresnelPowerFactor = read.number(
        fields, "parametricRimFresnelPowerFactor", mtoon.parametricRimFresnelPowerFactor, where, kNonNegativeRange);
    mtoon.parametricRimLiftFactor =
        read.number(fields, "parametricRimLiftFactor", mtoon.parametricRimLiftFactor, where, kSignedRange);
    mtoon.rimLightingMixFactor =
        read.number(fields, "rimLightingMixFactor", mtoon.rimLightingMixFactor, where, kUnitRange);
    if (const tinygltf::Value* shift = read.object(extension, "shadingShiftTexture", where)) {
        mtoon.shadingShiftTexture = read.textureInfo(extension, "shadingShiftTexture", where);
        mtoon.shadingShiftTextureScale =
            read.number(shift, "scale", mtoon.shadingShiftTextureScale, where + ".shadingShiftTexture", kSignedRange);
    }
    mtoon.matcapFactor = read.color3(fields, "matcapFactor", mtoon.matcapFactor, where);
    mtoon.matcapTexture = read.textureInfo(extension, "matcapTexture", where);
    mtoon.rimMultiplyTexture = read.textureInfo(extension, "rimMultiplyTexture", where);
    if (extension.Has("outlineWidthMode")) {
        const tinygltf::Value& mode = extension.Get("outlineWidthMode");
        const std::string name = mode.IsString() ? mode.Get<std::string>() : std::string();
        if (name == "none") {
            mtoon.outlineWidthMode = MToonMaterial::OutlineWidthMode::None;
        } else if (name == "worldCoordinates") {
            mtoon.outlineWidthMode = MToonMaterial::OutlineWidthMode::WorldCoordinates;
        } else if (name == "screenCoordinates") {
            mtoon.outlineWidthMode = MToonMaterial::OutlineWidthMode::ScreenCoordinates;
        } else {
            read.warn(where + ".outlineWidthMode must be 'none', 'worldCoordinates' or 'screenCoordinates', got " +
                      (mode.IsString() ? "'" + excerptForMessage(name) + "'" : std::string(jsonTypeName(mode))) +
                      "; no outline");
        }
    }
    mtoon.outlineWidthFactor = read.number(fields, "outlineWidthFactor", mtoon.outlineWidthFactor, where);
    if (mtoon.outlineWidthFactor < 0.0f) {
        read.warn(where + ".outlineWidthFactor " + formatNumber(mtoon.outlineWidthFactor) + " is negative; using 0");
        mtoon.outlineWidthFactor = 0.0f;
    }
    mtoon.outlineWidthMultiplyTexture = read.textureInfo(extension, "outlineWidthMultiplyTexture", where);
    mtoon.outlineColorFactor = read.color3(fields, "outlineColorFactor", mtoon.outlineColorFactor, where);
    mtoon.outlineLightingMixFactor =
        read.number(fields, "outlineLightingMixFactor", mtoon.outlineLightingMixFactor, where, kUnitRange);
    checkOutlineWidth(mtoon, read);
    mtoon.uvAnimationMaskTexture = read.textureInfo(extension, "uvAnimationMaskTexture", where);
    mtoon.uvAnimationScrollXSpeedFactor =
        read.number(fields, "uvAnimationScrollXSpeedFactor", mtoon.uvAnimationScrollXSpeedFactor, where, kSignedRange);
    mtoon.uvAnimationScrollYSpeedFactor =
        read.number(fields, "uvAnimationScrollYSpeedFactor", mtoon.uvAnimationScrollYSpeedFactor, where, kSignedRange);
    mtoon.uvAnimationRotationSpeedFactor = read.number(fields, "uvAnimationRotationSpeedFactor",
                                                       mtoon.uvAnimationRotationSpeedFactor, where, kSignedRange);
    return mtoon;
}

/** _MainTex's Unity scale/offset [offsetX, offsetY, scaleX, scaleY] (UniVRM's MigrationMToon reads offsetScale[0..1]
 *  as the offset, [2..3] as the scale) as a glTF uv transform. Unity's v runs up from the image's bottom, glTF's down
 *  from its top (v_gltf = 1 - v_unity), so v_gltf' = 1 - ((1 - v_gltf) * sy + oy) = v_gltf * sy + (1 - sy - oy): the
 *  offset three-vrm's VRMMaterialsV0CompatPlugin (_portTextureTransform) writes into KHR_texture_transform. In double:
 *  an offset of 1e38 is a whole number of repeats, which shaderTextureTransform() reduces away, but 1 - sy - oy in
 *  float would lose the fraction of a smaller one. A scale float cannot resolve (shaderTextureTransform()) is dropped
 *  with a warning, once for the material. */
std::optional<glm::dmat3> mainTexTransform(const std::vector<double>& offsetScale, PropertyReader& read) {
    glm::dmat3 transform(1.0);
    transform[0][0] = offsetScale[2];
    transform[1][1] = offsetScale[3];
    transform[2][0] = offsetScale[0];
    transform[2][1] = 1.0 - offsetScale[3] - offsetScale[1];
    // Only the scale is judged here: the offset is reduced by each texture's own wrap (withTransform()).
    glm::dmat3 scaleOnly = transform;
    scaleOnly[2] = glm::dvec3(0.0, 0.0, 1.0);
    std::string problem;
    if (!shaderTextureTransform(scaleOnly, TextureSampler{}, problem)) {
        read.warn(WarningKind::TextureTransformDropped,
                  "vectorProperties._MainTex: " + problem + "; the textures are drawn without it");
        return std::nullopt;
    }
    return transform;
}

/** `texture` placed by _MainTex's `transform` as well (after its own KHR_texture_transform); an offset that its wrap
 *  cannot reduce into float's reach leaves it without (a warning naming `key`). */
TextureRef withTransform(TextureRef texture, const std::optional<glm::dmat3>& transform, const std::string& key,
                         PropertyReader& read) {
    if (!texture.present() || !transform) return texture;
    std::string problem;
    const std::optional<glm::mat3> composed =
        shaderTextureTransform(*transform * glm::dmat3(texture.transform), texture.sampler, problem);
    if (composed) {
        texture.transform = *composed;
    } else {
        read.warn(WarningKind::TextureTransformDropped, "vectorProperties._MainTex on textureProperties." + key + ": " +
                                                            problem + "; the texture is drawn without it");
    }
    return texture;
}

/** VRM 0.x stores Unity colours in gamma space (UniVRM MigrationMToon: ToFloat3(ColorSpace.sRGB, ColorSpace.Linear);
 *  three-vrm: gammaEOTF); 1.0 factors are linear. Alpha is linear in both. */
glm::vec3 linearFromV0(const std::vector<double>& encoded) {
    return {srgbToLinear(float(encoded[0])), srgbToLinear(float(encoded[1])), srgbToLinear(float(encoded[2]))};
}

/** The alpha mode, cutoff, double-sidedness, base colour factor and texture a VRM 0.x entry gives (shared by MToon
 *  and the unlit shaders); each only when the entry has it, so the glTF material's stays otherwise. */
void applyV0Surface(const tinygltf::Value* floats, const tinygltf::Value* vectors, const tinygltf::Value* textures,
                    const std::optional<glm::dmat3>& transform, Material& material, PropertyReader& read) {
    if (const auto color = read.colour(vectors, "_Color", 3, 4, "vectorProperties")) {
        material.baseColorFactor = glm::vec4(linearFromV0(*color), color->size() == 4 ? float((*color)[3]) : 1.0f);
    }
    const TextureRef mainTexture = read.textureProperty(textures, "_MainTex", "textureProperties");
    if (mainTexture.present()) material.baseColorTexture = withTransform(mainTexture, transform, "_MainTex", read);
    if (floats != nullptr && floats->Has("_CullMode")) {
        // MToon 0.x's CullMode { Off, Front, Back }; glTF cannot cull front faces, so Front is double-sided as in
        // UniVRM's migration (MigrationMToon).
        const float cullMode = read.number(floats, "_CullMode", 2.0f, "floatProperties");
        if (cullMode == 0.0f || cullMode == 1.0f) {
            material.doubleSided = true;
        } else if (cullMode == 2.0f) {
            material.doubleSided = false;
        } else {
            read.warn("floatProperties._CullMode " + formatNumber(cullMode) +
                      " is not 0 (off), 1 (front) or 2 (back); the glTF material's doubleSided is kept");
        }
    }
}

MToonMaterial readMToon0(const tinygltf::Value& entry, Material& material, PropertyReader& read) {
    const tinygltf::Value* floats = read.object(entry, "floatProperties", "materialProperties");
    const tinygltf::Value* vectors = read.object(entry, "vectorProperties", "materialProperties");
    const tinygltf::Value* textures = read.object(entry, "textureProperties", "materialProperties");
    const std::string f = "floatProperties";
    const std::string v = "vectorProperties";
    const std::string t = "textureProperties";

    std::optional<glm::dmat3> transform;
    if (const auto offsetScale = read.numbers(vectors, "_MainTex", 4, 4, v))
        transform = mainTexTransform(*offsetScale, read);
    applyV0Surface(floats, vectors, textures, transform, material, read);

    if (floats != nullptr && floats->Has("_BlendMode")) {
        // MToon 0.x's RenderMode { Opaque, Cutout, Transparent, TransparentWithZWrite } (UniVRM MigrationMToon).
        const float blendMode = read.number(floats, "_BlendMode", 0.0f, f);
        if (blendMode == 0.0f) {
            material.alphaMode = AlphaMode::Opaque;
        } else if (blendMode == 1.0f) {
            material.alphaMode = AlphaMode::Mask;
        } else if (blendMode == 2.0f || blendMode == 3.0f) {
            material.alphaMode = AlphaMode::Blend;
        } else {
            read.warn(f + "._BlendMode " + formatNumber(blendMode) +
                      " is not 0 to 3; the glTF material's alphaMode is kept");
        }
    }
    if (material.alphaMode == AlphaMode::Mask && floats != nullptr && floats->Has("_Cutoff")) {
        material.alphaCutoff = read.number(floats, "_Cutoff", material.alphaCutoff, f, kUnitRange);
    }

    MToonMaterial mtoon;
    mtoon.specVersion = "0.x";
    // Defaults where the entry leaves a property out: three-vrm's VRMMaterialsV0CompatPlugin (UniVRM's exporter
    // writes them all).
    if (const auto shade = read.colour(vectors, "_ShadeColor", 3, 4, v)) {
        mtoon.shadeColorFactor = linearFromV0(*shade);
    } else {
        mtoon.shadeColorFactor = linearFromV0({0.97f, 0.81f, 0.86f}); // the floats Unity's default holds
    }
    mtoon.shadeMultiplyTexture =
        withTransform(read.textureProperty(textures, "_ShadeTexture", t), transform, "_ShadeTexture", read);

    // UniVRM's MToon10Migrator: 0.x shades over [shift, lerp(1, shift, toony)] (lerp's t clamped to [0, 1] as Unity's
    // Mathf.Lerp does); 1.0's toony is that range's margin, its shift the range's centre negated.
    const float shift0 = read.number(floats, "_ShadeShift", 0.0f, f);
    const float toony0 = read.number(floats, "_ShadeToony", 0.9f, f);
    const float rangeMin = shift0;
    const float rangeMax = 1.0f + (shift0 - 1.0f) * std::clamp(toony0, 0.0f, 1.0f);
    mtoon.shadingToonyFactor = std::clamp((2.0f - (rangeMax - rangeMin)) * 0.5f, 0.0f, 1.0f);
    mtoon.shadingShiftFactor = std::clamp(-(rangeMax + rangeMin) * 0.5f, -1.0f, 1.0f);

    if (const auto rim = read.colour(vectors, "_RimColor", 3, 4, v))
        mtoon.parametricRimColorFactor = linearFromV0(*rim);
    mtoon.parametricRimFresnelPowerFactor = read.number(floats, "_RimFresnelPower", 1.0f, f, kNonNegativeRange);
    mtoon.parametricRimLiftFactor = read.number(floats, "_RimLift", 0.0f, f, kSignedRange);
    mtoon.rimLightingMixFactor = read.number(floats, "_RimLightingMix", 0.0f, f, kUnitRange);

    // OutlineWidthMode { None, WorldCoordinates, ScreenCoordinates }; UniVRM reads anything above 2 as None.
    const float widthMode = read.number(floats, "_OutlineWidthMode", 0.0f, f);
    const float width = std::max(read.number(floats, "_OutlineWidth", 0.0f, f), 0.0f);
    if (widthMode == 1.0f) {
        mtoon.outlineWidthMode = MToonMaterial::OutlineWidthMode::WorldCoordinates;
        mtoon.outlineWidthFactor = width * 0.01f; // centimetres to metres (UniVRM, three-vrm)
    } else if (widthMode == 2.0f) {
        // The 0.x shader moves a vertex 0.01 * width * w in clip space, i.e. width percent of half the screen height
        // (NDC spans 2); 1.0's factor is a share of the whole height, so 0.005 keeps the drawn width. UniVRM's
        // MigrationMToon uses 0.01, doubling it under its 1.0 shader; three-vrm also uses 0.01 but draws 1.0's
        // factor as a share of half the height, so its 0.x widths agree with these (docs/mtoon.md).
        mtoon.outlineWidthMode = MToonMaterial::OutlineWidthMode::ScreenCoordinates;
        mtoon.outlineWidthFactor = width * 0.005f;
    } else if (widthMode != 0.0f) {
        read.warn(f + "._OutlineWidthMode " + formatNumber(widthMode) + " is not 0, 1 or 2; no outline");
    }
    mtoon.outlineWidthMultiplyTexture = withTransform(read.textureProperty(textures, "_OutlineWidthTexture", t),
                                                      transform, "_OutlineWidthTexture", read);
    if (const auto outline = read.colour(vectors, "_OutlineColor", 3, 4, v)) {
        mtoon.outlineColorFactor = linearFromV0(*outline);
    }
    // OutlineColorMode { FixedColor, MixedLighting }: a fixed colour takes no lighting (UniVRM, three-vrm).
    const float colorMode = read.number(floats, "_OutlineColorMode", 0.0f, f);
    mtoon.outlineLightingMixFactor =
        colorMode == 1.0f ? read.number(floats, "_OutlineLightingMix", 1.0f, f, kUnitRange) : 0.0f;
    checkOutlineWidth(mtoon, read);

    // The additive sphere map is 1.0's matcap at factor 1, sampled by the normal, so without _MainTex's placement;
    // the rim texture multiplies the rim as 1.0's does (UniVRM MigrationMToon, three-vrm).
    mtoon.matcapTexture = read.textureProperty(textures, "_SphereAdd", t);
    mtoon.rimMultiplyTexture =
        withTransform(read.textureProperty(textures, "_RimTexture", t), transform, "_RimTexture", read);
    if (const TextureRef bump = read.textureProperty(textures, "_BumpMap", t); bump.present()) {
        material.normalTexture = withTransform(bump, transform, "_BumpMap", read);
        material.normalScale = read.number(floats, "_BumpScale", 1.0f, f, kSignedRange);
    }
    // Emission as the other 0.x colours: a Unity colour in gamma space (UniVRM, three-vrm). UniVRM 0.106 and 0.107
    // wrote the glTF emissiveFactor without converting it, so the property is taken over the glTF material's.
    if (const auto emission = read.colour(vectors, "_EmissionColor", 3, 4, v))
        material.emissiveFactor = linearFromV0(*emission);
    if (const TextureRef map = read.textureProperty(textures, "_EmissionMap", t); map.present())
        material.emissiveTexture = withTransform(map, transform, "_EmissionMap", read);
    // UV animation as three-vrm's VRMMaterialsV0CompatPlugin migrates it: the same speeds, but the vertical scroll
    // negated (0.x scrolls Unity's v, which points up the image; 1.0's v points down it), the mask placed by _MainTex
    // like the other textures (1.0 reads its B channel).
    mtoon.uvAnimationMaskTexture =
        withTransform(read.textureProperty(textures, "_UvAnimMaskTexture", t), transform, "_UvAnimMaskTexture", read);
    mtoon.uvAnimationScrollXSpeedFactor = read.number(floats, "_UvAnimScrollX", 0.0f, f, kSignedRange);
    mtoon.uvAnimationScrollYSpeedFactor = -read.number(floats, "_UvAnimScrollY", 0.0f, f, kSignedRange);
    mtoon.uvAnimationRotationSpeedFactor = read.number(floats, "_UvAnimRotation", 0.0f, f, kSignedRange);
    std::vector<std::string> undrawn;
    if (textures != nullptr && textures->IsObject() && textures->Has("_ShadingGradeTexture"))
        undrawn.push_back("_ShadingGradeTexture");
    warnUndrawn(undrawn, read);
    return mtoon;
}

/** VRM/UnlitTexture, VRM/UnlitCutout, VRM/UnlitTransparent, VRM/UnlitTransparentZWrite: the alpha mode is in the
 *  shader's name (three-vrm's _parseV0UnlitProperties). */
void readUnlit0(const tinygltf::Value& entry, const std::string& shader, Material& material, PropertyReader& read) {
    const tinygltf::Value* floats = read.object(entry, "floatProperties", "materialProperties");
    const tinygltf::Value* vectors = read.object(entry, "vectorProperties", "materialProperties");
    const tinygltf::Value* textures = read.object(entry, "textureProperties", "materialProperties");
    std::optional<glm::dmat3> transform;
    if (const auto offsetScale = read.numbers(vectors, "_MainTex", 4, 4, "vectorProperties")) {
        transform = mainTexTransform(*offsetScale, read);
    }
    applyV0Surface(floats, vectors, textures, transform, material, read);
    material.unlit = true;
    if (shader == "VRM/UnlitCutout") {
        material.alphaMode = AlphaMode::Mask;
        material.alphaCutoff = read.number(floats, "_Cutoff", 0.5f, "floatProperties", kUnitRange);
    } else if (shader == "VRM/UnlitTransparent" || shader == "VRM/UnlitTransparentZWrite") {
        material.alphaMode = AlphaMode::Blend;
    } else {
        material.alphaMode = AlphaMode::Opaque;
    }
}

} // namespace

std::optional<MToonMaterial> readVrmMaterial(const tinygltf::Model& model, int materialIndex, Material& material,
                                             const VrmTextureResolver& resolveTexture, std::vector<Warning>& warnings) {
    const tinygltf::Material& gltfMaterial = model.materials[std::size_t(materialIndex)];
    PropertyReader read(model,
                        "material " + std::to_string(materialIndex) +
                            (gltfMaterial.name.empty() ? "" : " '" + excerptForMessage(gltfMaterial.name) + "'"),
                        resolveTexture, warnings);

    // VRM 1.0 (and any glTF that uses the extension) first: a converted 0.x file may keep its old root extension.
    if (const auto found = gltfMaterial.extensions.find("VRMC_materials_mtoon");
        found != gltfMaterial.extensions.end()) {
        if (!found->second.IsObject()) {
            read.warn(std::string("VRMC_materials_mtoon must be an object, got ") + jsonTypeName(found->second) +
                      "; ignored");
            return std::nullopt;
        }
        return readMToon10(found->second, read);
    }

    const auto vrm = model.extensions.find("VRM");
    if (vrm == model.extensions.end() || !vrm->second.IsObject() || !vrm->second.Has("materialProperties")) {
        return std::nullopt;
    }
    const tinygltf::Value& properties = vrm->second.Get("materialProperties");
    if (!properties.IsArray()) {
        read.warn(std::string("VRM.materialProperties must be an array, got ") + jsonTypeName(properties) +
                  "; its MToon is ignored");
        return std::nullopt;
    }
    // UniVRM (MigrationMToon, its 0.x importer) and three-vrm pair materialProperties[i] with materials[i].
    if (std::size_t(materialIndex) >= properties.ArrayLen()) return std::nullopt;
    const tinygltf::Value& entry = properties.Get(materialIndex);
    const std::string where = "VRM.materialProperties[" + std::to_string(materialIndex) + "]";
    if (!entry.IsObject()) {
        read.warn(where + " must be an object, got " + jsonTypeName(entry) + "; ignored");
        return std::nullopt;
    }
    if (entry.Has("name") && entry.Get("name").IsString() &&
        entry.Get("name").Get<std::string>() != gltfMaterial.name) {
        read.warn(where + " is named '" + excerptForMessage(entry.Get("name").Get<std::string>()) +
                  "'; paired by index all the same, as UniVRM and three-vrm pair them");
    }
    const tinygltf::Value& shaderValue = entry.Has("shader") ? entry.Get("shader") : tinygltf::Value();
    const std::string shader = shaderValue.IsString() ? shaderValue.Get<std::string>() : std::string();
    if (shader == kMToonShader) return readMToon0(entry, material, read);
    if (shader.rfind("VRM/Unlit", 0) == 0) {
        readUnlit0(entry, shader, material, read);
        return std::nullopt;
    }
    if (shader != kGltfShader) {
        read.warn(
            where + ".shader " +
            (shaderValue.IsString() ? "'" + excerptForMessage(shader) + "'" : std::string(jsonTypeName(shaderValue))) +
            " is not VRM/MToon, VRM/Unlit* or VRM_USE_GLTFSHADER; the glTF material is used");
    }
    return std::nullopt;
}

} // namespace inkgraph::detail
