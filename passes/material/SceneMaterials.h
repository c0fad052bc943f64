#pragma once
/** @file The materials of the scene on the GPU: their images decoded (scene/TextureImage.h) and uploaded the first
 *  time a draw samples them, their samplers, and one call that binds a mesh's material for a program that includes
 *  shaders/common/material.glsl. Every pass that draws the surface binds through here, so base colour, vertex
 *  colours, alpha cut-outs, metallic-roughness and MToon parameters mean the same in each. */

#include "gl/GlObjects.h"
#include "passes/WidthMap.h"
#include "scene/Scene.h"

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <map>
#include <set>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** Texture units the material snippet samples (the shade map keeps unit 0). */
inline constexpr GLuint kBaseColorTextureUnit = 1;
inline constexpr GLuint kEmissiveTextureUnit = 2;
inline constexpr GLuint kShadeMultiplyTextureUnit = 3;
inline constexpr GLuint kOutlineWidthTextureUnit = 4;
inline constexpr GLuint kMatcapTextureUnit = 7;
inline constexpr GLuint kRimMultiplyTextureUnit = 8;
inline constexpr GLuint kShadingShiftTextureUnit = 9;
inline constexpr GLuint kNormalTextureUnit = 10;
inline constexpr GLuint kUvAnimationMaskTextureUnit = 11;
inline constexpr GLuint kMetallicRoughnessTextureUnit = 13; ///< shaders/common/pbr.glsl
inline constexpr GLuint kWidthMapTextureUnit = 14;          ///< shaders/common/width_map.glsl

/** Vertex attribute locations of the material snippet (positions and normals are 0 and 1). */
inline constexpr GLuint kTexcoord0Location = 2;
inline constexpr GLuint kTexcoord1Location = 3;
inline constexpr GLuint kVertexColorLocation = 4;

/** In the passes that build the G-buffer and the line masks, a blended (BLEND) surface counts as solid where its alpha
 *  reaches this: a character's hair or clothes marked BLEND with opaque texels get their lines, while glass and veils
 *  let the lines of what lies behind show through. */
inline constexpr float kBlendSolidAlpha = 0.9f;

/** What a draw needs of a material: its colour (shading, the G-buffer's baseColor), or only where the surface is (the
 *  G-buffer's other fields, the line masks), for which an opaque material's texture is never decoded. */
enum class MaterialUse { Colour, Coverage };

/** `material`'s MToon material when it asks for an outline (a width mode other than none and a width above 0), else
 *  empty. No GL: the still graph asks it of the scene before anything is drawn. */
std::optional<MToonMaterial> outlineOf(const Material& material);

class SceneMaterials {
public:
    /** Keeps a reference to `scene`; nothing is decoded until a texture is bound. `modelPath` names the model in
     *  messages. */
    SceneMaterials(const Scene& scene, std::string modelPath);
    ~SceneMaterials();
    SceneMaterials(const SceneMaterials&) = delete;
    SceneMaterials& operator=(const SceneMaterials&) = delete;

    /** The most bytes the decoded textures may take together (decodedImageBytes() each, mipmaps included); a texture
     *  that would go beyond it is refused with a SceneError that names the image and --memory-limit. */
    void setTextureMemoryLimit(std::size_t bytes) { mTextureByteLimit = bytes; }
    std::size_t textureBytes() const { return mTextureBytes; }
    /** The render's time in seconds (FrameParams::time), which bind() hands every program as `frameTime`: the clock
     *  of MToon's UV animation (shaders/common/material.glsl), the same in every pass that draws the surface. */
    void setTime(double seconds) { mTime = seconds; }
    std::size_t texturesDecoded() const { return mTextures.size(); }

    /** Sets the material uniforms of `program` (in use) for mesh `meshIndex` and binds the textures `use` needs,
     *  decoding and uploading them on first use; sets the constant attribute values a mesh without texture
     *  coordinates or colours reads. */
    void bind(const GlProgram& program, std::size_t meshIndex, MaterialUse use);

    /** For --stats: each distinct material (name, meshes, base colour factor, texture, alpha, sides, unlit,
     *  metallic-roughness, emissive, MToon) and the images (count, decoded, bytes, and those downscaled to the
     *  driver's largest texture). */
    void describe(nlohmann::ordered_json& out) const;

    /** Mesh `meshIndex`'s MToon material when it asks for an outline (a width mode other than none and a width
     *  above 0), else empty. */
    std::optional<MToonMaterial> outlineOf(std::size_t meshIndex) const;

    /** What the textures decoded so far had to warn about: each image wider or taller than the driver's
     *  GL_MAX_TEXTURE_SIZE, which was downscaled to fit (a toon render needs no more texels than that): a
     *  texture-downscaled warning about the image's file (the model's for an embedded image) and the image; each image
     *  whose file is missing (texture-missing) or whose bytes cannot be decoded (texture-undecodable), which the
     *  materials that name it are drawn without. */
    const std::vector<Warning>& warnings() const { return mWarnings; }

    /** The material's GL texture for `reference`, decoded and uploaded on the first call with mipmaps, or 0 when
     *  `reference` names no image or an image that cannot be used (missing or undecodable: warned once, as every file
     *  of an OBJ's material library that is missing). An image larger than the driver takes is downscaled to fit,
     *  with a warning. The memory limit's refusal is a SceneError. Colour
     * (`srgb`: base colour, emissive, shade) is stored sRGB8_ALPHA8, so sampling decodes it to linear; data (the
     * outline width, metallic-roughness) RGBA8 as is. */
    GLuint texture(const TextureRef& reference, bool srgb = true);
    /** Sets shaders/common/width_map.glsl's uniforms of `program` (in use) for mesh `meshIndex` and `map`
     *  (--outline-width-map), binding its texture, decoded and uploaded on the first call of the run (the passes that
     *  draw a width-scaled band call this; nothing is decoded otherwise). The texture is the file at map.texture when
     *  one is there, else the model's image of that name. A mesh that lacks what the map reads (COLOR_0 for
     *  `color:`, TEXCOORD_0 for `texture:`) is drawn unscaled, with a width-map-unread warning (once per mesh).
     *  Throws SceneError naming --outline-width-map and the file when the file cannot be read or decoded, or when
     *  neither a file nor a model image has that name; the memory limit's refusal as texture()'s. */
    void bindWidthMap(const GlProgram& program, std::size_t meshIndex, const WidthMap& map);

    /** A sampler object with the reference's filters and wraps. */
    GLuint sampler(const TextureSampler& settings);

private:
    /** An image shrunk to the driver's largest texture (Scene::images index, name, decoded and uploaded sizes). */
    struct DownscaledImage {
        int image = 0;
        std::string name;
        int decodedWidth = 0, decodedHeight = 0, uploadedWidth = 0, uploadedHeight = 0;
    };
    /** An image the materials are drawn without: missing, else undecodable. */
    struct UnusableImage {
        int image = 0;
        std::string name;
        bool missing = false;
    };

    const Scene& mScene;
    std::string mModelPath;
    std::size_t mTextureByteLimit = std::size_t(-1);
    std::size_t mTextureBytes = 0;
    double mTime = 0.0;
    std::vector<Warning> mWarnings;
    std::vector<DownscaledImage> mDownscaled;                           ///< for --stats
    std::map<std::pair<int, bool>, GlHandle<TextureDeleter>> mTextures; ///< by Scene::images index and sRGB-ness
    std::set<int> mUnusableImages;                                      ///< Scene::images indices warned about
    std::vector<UnusableImage> mDescribedUnusable;                      ///< for --stats
    std::vector<std::pair<TextureSampler, GlHandle<SamplerDeleter>>> mSamplers;
    /** bindWidthMap()'s texture: the name it was made for, and the GL texture (a file's, owned here) or the model
     *  image's id from mTextures. */
    std::string mWidthMapName;
    GlHandle<TextureDeleter> mWidthMapFileTexture;
    GLuint mWidthMapTexture = 0;
    std::set<std::size_t> mWidthMapUnreadMeshes; ///< warned about already
};

/** Back-face culling as the mesh is drawn (GpuScene::DrawMesh::drawsBackFaces): on (GL_BACK, counter-clockwise
 *  fronts) for a single-sided glTF material or a sheet whose back another covers, off for a double-sided one (its back
 *  faces are lit with the flipped normal by the shaders). */
void setFaceCulling(bool drawsBackFaces);

/** A mesh's texture coordinates and colours on the GPU (those it has), at the snippet's attribute locations. */
struct MeshAttributeBuffers {
    struct Attribute {
        GLuint location;
        int components; ///< 2 (texture coordinates) or 4 (colour)
        GlBuffer buffer;
    };
    std::vector<Attribute> attributes;

    /** Adds every attribute to `vertexArray` (another array over the same vertices: the hull, the CPU face sets). */
    void attachTo(GlVertexArray& vertexArray) const;
};
MeshAttributeBuffers uploadMaterialAttributes(const Mesh& mesh, const std::string& label);

} // namespace inkgraph
