#pragma once
/** @file What a surface looks like, as the file says: glTF 2.0's metallic-roughness material reduced to what a toon
 *  renderer uses (base colour factor and texture, metallic and roughness, emissive, alpha, double-sidedness),
 *  KHR_materials_unlit, an OBJ material library's Kd/map_Kd/d, and a VRM character's MToon parameters. Plain data, no
 *  GL: the images stay encoded here and are decoded only when a pass that runs samples them (scene/TextureImage.h). */

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** glTF's sampler filters and wraps, with their glTF (= OpenGL) enum values. */
enum class TextureWrap : std::uint32_t { Repeat = 10497, ClampToEdge = 33071, MirroredRepeat = 33648 };
enum class TextureFilter : std::uint32_t {
    Nearest = 9728,
    Linear = 9729,
    NearestMipmapNearest = 9984,
    LinearMipmapNearest = 9985,
    NearestMipmapLinear = 9986,
    LinearMipmapLinear = 9987,
};

struct TextureSampler {
    TextureFilter magFilter = TextureFilter::Linear;
    TextureFilter minFilter = TextureFilter::LinearMipmapLinear; ///< glTF leaves it to the renderer; trilinear
    TextureWrap wrapS = TextureWrap::Repeat;
    TextureWrap wrapT = TextureWrap::Repeat;
    bool operator==(const TextureSampler&) const = default;
};

/** A material's use of one image: which image, which texture-coordinate set, how it is sampled, and the
 *  KHR_texture_transform (uv' = transform * (u, v, 1)). */
struct TextureRef {
    int image = -1;   ///< index into Scene::images; -1: no texture
    int texCoord = 0; ///< TEXCOORD_<n> of the mesh (0 or 1: Mesh::texcoords)
    TextureSampler sampler;
    /** KHR_texture_transform as a matrix: translation * rotation * scale, in glTF's order (column-major, GLM). */
    glm::mat3 transform{1.0f};

    bool present() const { return image >= 0; }
    bool operator==(const TextureRef&) const = default;
};

enum class AlphaMode { Opaque, Mask, Blend };

/** A VRM character's MToon material, in VRMC_materials_mtoon-1.0's terms (VRM 0.x's properties are converted to these
 *  by the reader, scene/formats/gltf/VrmMaterials.cpp). docs/mtoon.md sets them beside the specification's formulas. */
struct MToonMaterial {
    glm::vec3 shadeColorFactor{0.0f};         ///< linear; the colour of the shaded side
    TextureRef shadeMultiplyTexture;          ///< times shadeColorFactor
    float shadingShiftFactor = 0.0f;          ///< added to n.l before the band
    float shadingToonyFactor = 0.9f;          ///< 1: a hard band edge; 0: a smooth ramp
    glm::vec3 parametricRimColorFactor{0.0f}; ///< linear; added rim light (black: none)
    float parametricRimFresnelPowerFactor = 5.0f;
    float parametricRimLiftFactor = 0.0f;
    float rimLightingMixFactor = 1.0f; ///< how much the rim takes the surface's lighting (0: like emission)
    /** R channel (linear data) times `shadingShiftTextureScale`, added to the shading shift per pixel. */
    TextureRef shadingShiftTexture;
    float shadingShiftTextureScale = 1.0f; ///< shadingShiftTexture.scale
    glm::vec3 matcapFactor{1.0f};          ///< linear; times the matcap texture
    /** sRGB image sampled by the view-space normal (the specification's matcap uv), added to the rim; none: no matcap
     *  (the factor alone adds nothing). */
    TextureRef matcapTexture;
    TextureRef rimMultiplyTexture; ///< sRGB image; multiplies the rim (matcap + parametric rim)
    enum class OutlineWidthMode { None, WorldCoordinates, ScreenCoordinates };
    OutlineWidthMode outlineWidthMode = OutlineWidthMode::None;
    /** World: metres (model units); screen: a share of the screen height. */
    float outlineWidthFactor = 0.0f;
    TextureRef outlineWidthMultiplyTexture; ///< its green channel scales the width
    glm::vec3 outlineColorFactor{0.0f};     ///< linear
    float outlineLightingMixFactor = 1.0f;  ///< how much the outline takes the surface's lighting (0: flat colour)
    /** B channel (linear data) scales the UV animation's speeds per texel; none: 1. */
    TextureRef uvAnimationMaskTexture;
    float uvAnimationScrollXSpeedFactor = 0.0f;  ///< uv units per second, +u
    float uvAnimationScrollYSpeedFactor = 0.0f;  ///< uv units per second, +v (down the image)
    float uvAnimationRotationSpeedFactor = 0.0f; ///< radians per second about uv (0.5, 0.5)
    std::string specVersion;                     ///< "0.x" or "1.0": where the parameters came from

    bool operator==(const MToonMaterial&) const = default;
};

struct Material {
    std::string name; ///< the file's material name, for messages and --stats; empty without one
    glm::vec4 baseColorFactor{0.8f, 0.8f, 0.8f, 1.0f}; ///< linear RGBA; a model without materials is light grey
    TextureRef baseColorTexture;                       ///< sRGB image, times baseColorFactor
    /** The factor drawn when baseColorTexture cannot be used (missing, undecodable, no texture coordinates), where
     *  the file's own colour differs from the factor the texture is drawn with: an OBJ map_Kd replaces a `Kd 0 0 0`
     *  or an absent Kd, and without the map the Kd as written is drawn. Unset: baseColorFactor. */
    std::optional<glm::vec4> baseColorFactorWithoutTexture;
    /** glTF's pbrMetallicRoughness, which `--shading mtoon` draws a material without MToon with (docs/mtoon.md). The
     *  glTF reader writes the file's values (glTF's defaults: metallic 1, roughness 1); a material that does not come
     *  from a glTF material (OBJ, STL, PLY, a glTF primitive without one, arrays) keeps these: a rough dielectric,
     *  since metallic 1 with no environment light would draw it black. */
    float metallicFactor = 0.0f;
    float roughnessFactor = 1.0f;
    TextureRef metallicRoughnessTexture; ///< linear data: B times metallicFactor, G times roughnessFactor
    glm::vec3 emissiveFactor{0.0f};      ///< linear, added after lighting
    TextureRef emissiveTexture;          ///< sRGB image, times emissiveFactor
    /** glTF's tangent-space normal map (linear data, xyz = 2 rgb - 1); drawn by MToon materials only. */
    TextureRef normalTexture;
    float normalScale = 1.0f; ///< normalTexture.scale: multiplies the map's x and y
    /** KHR_materials_unlit: the base colour as is. False for a material with MToon, whose unlit flag is the VRM
     *  exporters' fallback for viewers without MToon (the glTF reader clears it). */
    bool unlit = false;
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f; ///< Mask: a fragment whose alpha is below this is cut out
    /** true: both sides drawn, a back face lit with the flipped normal (meshes without a glTF material: OBJ, STL);
     *  false: back faces culled, as a glTF material says by default. */
    bool doubleSided = true;
    std::optional<MToonMaterial> mtoon;
    /** The shade map this material asks for (glTF material extras {"inkgraph": {"shademap": "..."}}), a path resolved
     *  against the glTF file's folder and lexically normalised; empty: the run's map. Read by the app, not here. */
    std::string shadeMapPath;

    bool textured() const { return baseColorTexture.present(); }
    bool operator==(const Material&) const = default;
};

/** The least base colour alpha a blended material shows at: under half a level of 8-bit colour (1/510), drawing it over
 *  anything changes no pixel of the picture. */
inline constexpr float kLeastVisibleAlpha = 1.0f / 510.0f;

/** Why `material` draws nothing at all, or "" when it may draw: MASK with a base colour alpha under its cutoff (the
 *  texture's and the vertices' alphas only multiply it down, so every fragment is cut out), BLEND with one under
 *  kLeastVisibleAlpha. For the material-invisible warning, which a model drawn as blank paper would lack otherwise. */
std::string whyMaterialDrawsNothing(const Material& material);

/** Every texture `material` may sample, present or not: the one list of a material's TextureRef fields, for what counts
 *  them (the memory estimate, scene/TextureImage.h); a new texture field is added here. */
inline std::vector<const TextureRef*> textureRefsOf(const Material& material) {
    std::vector<const TextureRef*> refs = {&material.baseColorTexture, &material.metallicRoughnessTexture,
                                           &material.emissiveTexture, &material.normalTexture};
    if (material.mtoon) {
        const MToonMaterial& mtoon = *material.mtoon;
        refs.insert(refs.end(),
                    {&mtoon.shadeMultiplyTexture, &mtoon.shadingShiftTexture, &mtoon.matcapTexture,
                     &mtoon.rimMultiplyTexture, &mtoon.outlineWidthMultiplyTexture, &mtoon.uvAnimationMaskTexture});
    }
    return refs;
}

/** One image a material refers to, still encoded (PNG, JPEG, ...): its bytes when the file embeds it, else the path
 *  of the file it lives in (read when decoded). Shared, because scenes are copied and images are large. */
struct SceneImage {
    std::string name;                                          ///< the image's name or URI, for messages
    std::string path;                                          ///< the external file; empty when embedded
    std::string mimeType;                                      ///< as the file says, may be empty
    std::shared_ptr<const std::vector<unsigned char>> encoded; ///< embedded bytes; null for an external file
};

} // namespace inkgraph
