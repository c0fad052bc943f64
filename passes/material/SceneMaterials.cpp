#include "passes/material/SceneMaterials.h"

#include "scene/MessageText.h"
#include "scene/TextureImage.h"

#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace inkgraph {
namespace {

int alphaModeCode(AlphaMode mode) {
    switch (mode) {
    case AlphaMode::Opaque: return 0;
    case AlphaMode::Mask: return 1;
    case AlphaMode::Blend: return 2;
    }
    return 0;
}

/** Binds `reference`'s texture and sampler to `unit` and sets `<prefix>Textured`, `<prefix>Set` and
 *  `<prefix>Transform`; an absent or unusable texture leaves the unit as it is and the flag 0. Returns whether it
 *  bound one. */
bool bindTexture(SceneMaterials& materials, const GlProgram& program, const TextureRef& reference, GLuint unit,
                 const std::string& prefix, bool srgb = true) {
    const GLint textured = program.uniform((prefix + "Textured").c_str());
    const GLuint texture = materials.texture(reference, srgb);
    glUniform1i(textured, texture != 0 ? 1 : 0);
    if (texture == 0) return false;
    glBindTextureUnit(unit, texture);
    glBindSampler(unit, materials.sampler(reference.sampler));
    glUniform1i(program.uniform((prefix + "Set").c_str()), reference.texCoord == 1 ? 1 : 0);
    glUniformMatrix3fv(program.uniform((prefix + "Transform").c_str()), 1, GL_FALSE,
                       glm::value_ptr(reference.transform));
    return true;
}

int mipmapLevels(int width, int height) {
    int levels = 1;
    for (int side = std::max(width, height); side > 1; side /= 2) ++levels;
    return levels;
}

/** The driver's largest texture side (GL_MAX_TEXTURE_SIZE; at least 16384 on GL 4.5 hardware, as llvmpipe). */
int maxTextureSide() {
    GLint side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &side);
    return std::max(side, 1);
}

/** `decoded` shrunk (area-averaged) so that neither side exceeds `maxSide`, keeping its aspect ratio. */
DecodedImage downscaled(const DecodedImage& decoded, int maxSide) {
    const double scale = double(maxSide) / double(std::max(decoded.width, decoded.height));
    DecodedImage smaller;
    smaller.width = std::clamp(int(std::lround(decoded.width * scale)), 1, maxSide);
    smaller.height = std::clamp(int(std::lround(decoded.height * scale)), 1, maxSide);
    auto pixels = std::shared_ptr<unsigned char>(new unsigned char[std::size_t(smaller.width) * smaller.height * 4],
                                                 std::default_delete<unsigned char[]>());
    // OpenCV only reads the source; its constructor over external data takes a non-const pointer.
    const cv::Mat source(decoded.height, decoded.width, CV_8UC4, const_cast<unsigned char*>(decoded.rgba.get()));
    cv::Mat target(smaller.height, smaller.width, CV_8UC4, pixels.get());
    cv::resize(source, target, target.size(), 0, 0, cv::INTER_AREA);
    smaller.rgba = std::move(pixels);
    return smaller;
}

/** `decoded` as a GL texture with mipmaps: colour (`srgb`: base colour, emissive, shade) in sRGB storage, so the
 *  sampler decodes to linear before filtering, as glTF's colours need; data (MToon's outline width, a width map) as it
 *  is. */
GlHandle<TextureDeleter> uploaded(const DecodedImage& decoded, bool srgb, const std::string& label) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    GlHandle<TextureDeleter> handle(id);
    glTextureStorage2D(id, mipmapLevels(decoded.width, decoded.height), srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8,
                       decoded.width, decoded.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // Rows top first, as decoded: GL's t = 0 is then the image's top row, which is glTF's v = 0.
    glTextureSubImage2D(id, 0, 0, 0, decoded.width, decoded.height, GL_RGBA, GL_UNSIGNED_BYTE, decoded.rgba.get());
    glGenerateTextureMipmap(id);
    labelObject(GL_TEXTURE, id, label);
    return handle;
}

} // namespace

SceneMaterials::SceneMaterials(const Scene& scene, std::string modelPath)
    : mScene(scene), mModelPath(std::move(modelPath)) {}

SceneMaterials::~SceneMaterials() = default;

GLuint SceneMaterials::texture(const TextureRef& reference, bool srgb) {
    if (!reference.present()) return 0;
    if (std::size_t(reference.image) >= mScene.images.size())
        throw SceneError("SceneMaterials::texture(): '" + mModelPath + "': image " + std::to_string(reference.image) +
                         " out of range (the model has " + std::to_string(mScene.images.size()) + ")");
    const std::pair<int, bool> key(reference.image, srgb);
    if (auto found = mTextures.find(key); found != mTextures.end()) return found->second.id();
    if (mUnusableImages.contains(reference.image)) return 0;
    const SceneImage& image = mScene.images[std::size_t(reference.image)];
    const std::size_t left = mTextureByteLimit > mTextureBytes ? mTextureByteLimit - mTextureBytes : 0;
    DecodedImage decoded;
    try {
        decoded = decodeSceneImage(image, std::size_t(reference.image), mModelPath, left);
    } catch (const ImageUnusableError& error) {
        // As an OBJ's missing map is: the materials are drawn without the image rather than failing the still (a
        // model with one broken texture still gives its lines and shading), and the warning says so; --strict
        // makes it an error for pipelines that want one.
        mUnusableImages.insert(reference.image);
        const bool missing = error.reason() == ImageUnusableError::Reason::Missing;
        const std::string name = image.name.empty() ? "" : " '" + detail::excerptForMessage(image.name) + "'";
        mWarnings.push_back(makeWarning(missing ? WarningKind::TextureMissing : WarningKind::TextureUndecodable,
                                        "image " + std::to_string(reference.image) + name + ": " + error.problem() +
                                            "; the materials that use it are drawn without it",
                                        image.path.empty() ? mModelPath : image.path,
                                        "image " + std::to_string(reference.image) + name));
        mDescribedUnusable.push_back({reference.image, image.name, missing});
        return 0;
    }
    // A texture the driver cannot hold (a 17000 x 1 strip) is shrunk to fit rather than failing the still: a toon
    // render needs no more texels than that, and the warning and --stats say so.
    if (const int maxSide = maxTextureSide(); decoded.width > maxSide || decoded.height > maxSide) {
        const DecodedImage smaller = downscaled(decoded, maxSide);
        const std::string name = image.name.empty() ? "" : " '" + image.name + "'";
        const std::string warning = "image " + std::to_string(reference.image) + name + " is " +
                                    std::to_string(decoded.width) + "x" + std::to_string(decoded.height) +
                                    " pixels, more than the driver's largest texture (" + std::to_string(maxSide) +
                                    " a side): downscaled to " + std::to_string(smaller.width) + "x" +
                                    std::to_string(smaller.height);
        // Colour and data uses of one image are two textures; the image is named once.
        if (std::ranges::find(mWarnings, warning, &Warning::message) == mWarnings.end())
            mWarnings.push_back(makeWarning(WarningKind::TextureDownscaled, warning,
                                            image.path.empty() ? mModelPath : image.path,
                                            "image " + std::to_string(reference.image) + name));
        mDownscaled.push_back(
            {reference.image, image.name, decoded.width, decoded.height, smaller.width, smaller.height});
        decoded = smaller;
    }
    GlHandle<TextureDeleter> handle = uploaded(decoded, srgb, "image " + std::to_string(reference.image));
    mTextureBytes += decodedImageBytes(decoded.width, decoded.height);
    return mTextures.emplace(key, std::move(handle)).first->second.id();
}

void SceneMaterials::bindWidthMap(const GlProgram& program, std::size_t meshIndex, const WidthMap& map) {
    const Mesh& mesh = mScene.meshes.at(meshIndex);
    int source = 0;
    if (map.source == WidthMap::Source::VertexColor) source = mesh.colors.empty() ? 0 : 1;
    if (map.source == WidthMap::Source::Texture) source = mesh.texcoords[0].empty() ? 0 : 2;
    if (map.enabled() && source == 0 && mWidthMapUnreadMeshes.insert(meshIndex).second) {
        // Warned, not refused: in a batch of characters, one without vertex colours still gets its lines (at the
        // widths the flags say), and --strict makes it an error for whoever wants one.
        const std::string lacks = map.source == WidthMap::Source::VertexColor ? "vertex colours (COLOR_0)"
                                                                              : "texture coordinates (TEXCOORD_0)";
        mWarnings.push_back(makeWarning(WarningKind::WidthMapUnread,
                                        "mesh '" + detail::excerptForMessage(mesh.name) + "' has no " + lacks +
                                            " for --outline-width-map " + map.text() +
                                            ": its outline widths are left unscaled",
                                        mModelPath, "mesh '" + detail::excerptForMessage(mesh.name) + "'"));
    }
    glUniform1i(program.uniform("outlineWidthMapSource"), source);
    glUniform1i(program.uniform("outlineWidthMapChannel"), map.channel);
    if (map.source != WidthMap::Source::Texture) return;
    // Resolved even when this mesh has no texture coordinates, so a misspelt file is refused whatever the model.
    if (mWidthMapTexture == 0 || mWidthMapName != map.texture) {
        mWidthMapFileTexture = {};
        mWidthMapTexture = 0;
        const std::string what = "SceneMaterials::bindWidthMap(): --outline-width-map: '" + map.texture + "'";
        std::error_code error;
        if (std::filesystem::exists(map.texture, error)) {
            // A file: decoded as data (its stored values / 255, as MToon's width texture), charged to the limit.
            const std::size_t left = mTextureByteLimit > mTextureBytes ? mTextureByteLimit - mTextureBytes : 0;
            DecodedImage decoded;
            try {
                decoded = decodeSceneImage(SceneImage{map.texture, map.texture, {}, nullptr}, 0, mModelPath, left);
            } catch (const ImageUnusableError& unusable) {
                throw SceneError(what + ": " + unusable.problem());
            }
            const int maxSide = maxTextureSide();
            if (decoded.width > maxSide || decoded.height > maxSide) decoded = downscaled(decoded, maxSide);
            mWidthMapFileTexture = uploaded(decoded, false, "--outline-width-map " + map.texture);
            mTextureBytes += decodedImageBytes(decoded.width, decoded.height);
            mWidthMapTexture = mWidthMapFileTexture.id();
        } else {
            std::string names;
            for (std::size_t image = 0; image < mScene.images.size() && mWidthMapTexture == 0; ++image) {
                if (mScene.images[image].name == map.texture) {
                    TextureRef reference;
                    reference.image = int(image);
                    mWidthMapTexture = texture(reference, /*srgb=*/false);
                    if (mWidthMapTexture == 0) // missing or undecodable: texture() has warned; a refusal here
                        throw SceneError(what + ": the model's image of that name cannot be decoded");
                }
                if (!mScene.images[image].name.empty())
                    names += (names.empty() ? "'" : ", '") + detail::excerptForMessage(mScene.images[image].name) + "'";
            }
            if (mWidthMapTexture == 0)
                throw SceneError(what + " is neither a file nor the name of an image of '" + mModelPath +
                                 "' (its named images: " + (names.empty() ? "none" : names) + ")");
        }
        mWidthMapName = map.texture;
    }
    if (source != 2) return;
    glBindTextureUnit(kWidthMapTextureUnit, mWidthMapTexture);
    // Clamped to the edge: a map laid over [0, 1] must not blend its two ends (its left edge with its right).
    TextureSampler clamped;
    clamped.wrapS = clamped.wrapT = TextureWrap::ClampToEdge;
    glBindSampler(kWidthMapTextureUnit, sampler(clamped));
}

void SceneMaterials::describe(nlohmann::ordered_json& out) const {
    using Json = nlohmann::ordered_json;
    auto imageName = [&](const TextureRef& reference) -> Json {
        if (!reference.present()) return nullptr;
        if (std::size_t(reference.image) >= mScene.images.size()) return reference.image;
        return mScene.images[std::size_t(reference.image)].name;
    };
    static const char* const kAlphaModes[] = {"opaque", "mask", "blend"};
    std::vector<const Material*> seen;
    std::vector<int> meshCounts;
    for (const Mesh& mesh : mScene.meshes) {
        auto found = std::find_if(seen.begin(), seen.end(), [&](const Material* m) { return *m == mesh.material; });
        if (found == seen.end()) {
            seen.push_back(&mesh.material);
            meshCounts.push_back(1);
        } else {
            ++meshCounts[std::size_t(found - seen.begin())];
        }
    }
    Json materials = Json::array();
    for (std::size_t index = 0; index < seen.size(); ++index) {
        const Material& material = *seen[index];
        const glm::vec4& factor = material.baseColorFactor;
        Json entry = {{"name", material.name},
                      {"meshes", meshCounts[index]},
                      {"base_color_factor", {factor.r, factor.g, factor.b, factor.a}},
                      {"base_color_texture", imageName(material.baseColorTexture)},
                      {"alpha_mode", kAlphaModes[alphaModeCode(material.alphaMode)]},
                      {"double_sided", material.doubleSided},
                      {"unlit", material.unlit},
                      {"metallic_factor", material.metallicFactor},
                      {"roughness_factor", material.roughnessFactor},
                      {"metallic_roughness_texture", imageName(material.metallicRoughnessTexture)}};
        if (material.alphaMode == AlphaMode::Mask) entry["alpha_cutoff"] = material.alphaCutoff;
        // As drawn: an emissive image that cannot be used takes the emission with it (bind()).
        const bool emissionDropped =
            material.emissiveTexture.present() && mUnusableImages.contains(material.emissiveTexture.image);
        if (material.emissiveFactor != glm::vec3(0.0f) && !emissionDropped)
            entry["emissive_factor"] = {material.emissiveFactor.r, material.emissiveFactor.g,
                                        material.emissiveFactor.b};
        if (material.emissiveTexture.present()) entry["emissive_texture"] = imageName(material.emissiveTexture);
        if (material.mtoon) {
            const MToonMaterial& mtoon = *material.mtoon;
            static const char* const kOutlineModes[] = {"none", "worldCoordinates", "screenCoordinates"};
            entry["mtoon"] = {
                {"spec_version", mtoon.specVersion},
                {"shade_color_factor", {mtoon.shadeColorFactor.r, mtoon.shadeColorFactor.g, mtoon.shadeColorFactor.b}},
                {"shading_shift", mtoon.shadingShiftFactor},
                {"shading_toony", mtoon.shadingToonyFactor},
                {"outline_width_mode", kOutlineModes[int(mtoon.outlineWidthMode)]},
                {"outline_width", mtoon.outlineWidthFactor}};
        }
        materials.push_back(std::move(entry));
    }
    out["materials"] = std::move(materials);
    Json downscaled = Json::array();
    for (const DownscaledImage& image : mDownscaled)
        downscaled.push_back({{"image", image.image},
                              {"name", image.name},
                              {"decoded", {image.decodedWidth, image.decodedHeight}},
                              {"uploaded", {image.uploadedWidth, image.uploadedHeight}}});
    Json unusable = Json::array();
    for (const UnusableImage& image : mDescribedUnusable)
        unusable.push_back(
            {{"image", image.image}, {"name", image.name}, {"reason", image.missing ? "missing" : "undecodable"}});
    // Those the load found missing (an OBJ's maps) have no image index: nothing refers to them.
    for (const SceneImage& image : mScene.report.missingImages)
        unusable.push_back({{"image", nullptr}, {"name", image.name}, {"reason", "missing"}});
    out["images"] = {{"count", mScene.images.size()},
                     {"decoded", mTextures.size()},
                     {"decoded_bytes", mTextureBytes},
                     {"downscaled", std::move(downscaled)},
                     {"unusable", std::move(unusable)},
                     {"byte_limit", mTextureByteLimit == std::size_t(-1) ? Json(nullptr) : Json(mTextureByteLimit)}};
}

std::optional<MToonMaterial> outlineOf(const Material& material) {
    const std::optional<MToonMaterial>& mtoon = material.mtoon;
    if (!mtoon || mtoon->outlineWidthMode == MToonMaterial::OutlineWidthMode::None ||
        !(mtoon->outlineWidthFactor > 0.0f))
        return std::nullopt;
    return mtoon;
}

std::optional<MToonMaterial> SceneMaterials::outlineOf(std::size_t meshIndex) const {
    return inkgraph::outlineOf(mScene.meshes.at(meshIndex).material);
}

GLuint SceneMaterials::sampler(const TextureSampler& settings) {
    for (const auto& [known, handle] : mSamplers)
        if (known == settings) return handle.id();
    GLuint id = 0;
    glCreateSamplers(1, &id);
    GlHandle<SamplerDeleter> handle(id);
    glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, GLint(settings.magFilter));
    glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, GLint(settings.minFilter));
    glSamplerParameteri(id, GL_TEXTURE_WRAP_S, GLint(settings.wrapS));
    glSamplerParameteri(id, GL_TEXTURE_WRAP_T, GLint(settings.wrapT));
    mSamplers.emplace_back(settings, std::move(handle));
    return id;
}

void SceneMaterials::bind(const GlProgram& program, std::size_t meshIndex, MaterialUse use) {
    const Material& material = mScene.meshes.at(meshIndex).material;
    const bool colour = use == MaterialUse::Colour;
    // MToon ignores vertex colours (its specification), alpha included, in every pass alike.
    glUniform1i(program.uniform("materialUsesVertexColor"), material.mtoon ? 0 : 1);
    glUniform4fv(program.uniform("materialBaseColorFactor"), 1, glm::value_ptr(material.baseColorFactor));
    glUniform3fv(program.uniform("materialEmissiveFactor"), 1, glm::value_ptr(material.emissiveFactor));
    glUniform1i(program.uniform("materialUnlit"), material.unlit ? 1 : 0);
    glUniform1i(program.uniform("materialAlphaMode"), alphaModeCode(material.alphaMode));
    glUniform1f(program.uniform("materialAlphaCutoff"), material.alphaCutoff);
    glUniform1f(program.uniform("materialBlendSolidAlpha"), kBlendSolidAlpha);
    // Only programs that sample a texture look its uniforms up, and a draw for coverage samples only a material that
    // cuts out or blends: a pass that never reads colour never decodes an opaque material's texture.
    if (program.uniform("materialBaseColorTextured") >= 0) {
        if (colour || material.alphaMode != AlphaMode::Opaque) {
            if (!bindTexture(*this, program, material.baseColorTexture, kBaseColorTextureUnit, "materialBaseColor") &&
                material.baseColorFactorWithoutTexture) // an image that cannot be used: the file's own colour
                glUniform4fv(program.uniform("materialBaseColorFactor"), 1,
                             glm::value_ptr(*material.baseColorFactorWithoutTexture));
        } else {
            glUniform1i(program.uniform("materialBaseColorTextured"), 0);
        }
    }
    if (colour && program.uniform("materialEmissiveTextured") >= 0 &&
        !bindTexture(*this, program, material.emissiveTexture, kEmissiveTextureUnit, "materialEmissive") &&
        material.emissiveTexture.present()) {
        // An emissive image that cannot be used (missing, undecodable) takes the emission with it: the factor is the
        // image's multiplier, often 1 1 1, and alone it drew the material white.
        const glm::vec3 none(0.0f);
        glUniform3fv(program.uniform("materialEmissiveFactor"), 1, glm::value_ptr(none));
    }
    // glTF's metallic-roughness, which only shading draws (common/pbr.glsl): its texture is data, not colour, and an
    // MToon or unlit material never reads it, so it is not decoded for one.
    glUniform1f(program.uniform("materialMetallicFactor"), material.metallicFactor);
    glUniform1f(program.uniform("materialRoughnessFactor"), material.roughnessFactor);
    if (program.uniform("materialMetallicRoughnessTextured") >= 0) {
        if (colour && !material.mtoon && !material.unlit)
            bindTexture(*this, program, material.metallicRoughnessTexture, kMetallicRoughnessTextureUnit,
                        "materialMetallicRoughness", /*srgb=*/false);
        else
            glUniform1i(program.uniform("materialMetallicRoughnessTextured"), 0);
    }
    const MToonMaterial mtoon = material.mtoon.value_or(MToonMaterial{});
    glUniform1i(program.uniform("mtoonPresent"), material.mtoon ? 1 : 0);
    glUniform3fv(program.uniform("mtoonShadeColorFactor"), 1, glm::value_ptr(mtoon.shadeColorFactor));
    glUniform1f(program.uniform("mtoonShadingShiftFactor"), mtoon.shadingShiftFactor);
    glUniform1f(program.uniform("mtoonShadingToonyFactor"), mtoon.shadingToonyFactor);
    glUniform3fv(program.uniform("mtoonRimColorFactor"), 1, glm::value_ptr(mtoon.parametricRimColorFactor));
    glUniform1f(program.uniform("mtoonRimFresnelPowerFactor"), mtoon.parametricRimFresnelPowerFactor);
    glUniform1f(program.uniform("mtoonRimLiftFactor"), mtoon.parametricRimLiftFactor);
    glUniform1f(program.uniform("mtoonRimLightingMixFactor"), mtoon.rimLightingMixFactor);
    if (colour && program.uniform("mtoonShadeMultiplyTextured") >= 0)
        bindTexture(*this, program, mtoon.shadeMultiplyTexture, kShadeMultiplyTextureUnit, "mtoonShadeMultiply");
    glUniform1f(program.uniform("mtoonShadingShiftTextureScale"), mtoon.shadingShiftTextureScale);
    glUniform3fv(program.uniform("mtoonMatcapFactor"), 1, glm::value_ptr(mtoon.matcapFactor));
    if (colour && program.uniform("mtoonShadingShiftTextured") >= 0)
        bindTexture(*this, program, mtoon.shadingShiftTexture, kShadingShiftTextureUnit, "mtoonShadingShift",
                    /*srgb=*/false);
    if (colour && program.uniform("mtoonMatcapTextured") >= 0)
        bindTexture(*this, program, mtoon.matcapTexture, kMatcapTextureUnit, "mtoonMatcap");
    if (colour && program.uniform("mtoonRimMultiplyTextured") >= 0)
        bindTexture(*this, program, mtoon.rimMultiplyTexture, kRimMultiplyTextureUnit, "mtoonRimMultiply");
    // Only MToon draws normal maps (docs/mtoon.md).
    glUniform1f(program.uniform("materialNormalScale"), material.normalScale);
    if (colour && program.uniform("materialNormalTextured") >= 0)
        bindTexture(*this, program, material.mtoon ? material.normalTexture : TextureRef{}, kNormalTextureUnit,
                    "materialNormal", /*srgb=*/false);
    // UV animation moves every texture a pass samples, so it is set for every use; the mask is decoded only when the
    // material animates.
    const glm::vec3 uvAnimationSpeed(mtoon.uvAnimationScrollXSpeedFactor, mtoon.uvAnimationScrollYSpeedFactor,
                                     mtoon.uvAnimationRotationSpeedFactor);
    glUniform3fv(program.uniform("materialUvAnimationSpeed"), 1, glm::value_ptr(uvAnimationSpeed));
    glUniform1f(program.uniform("frameTime"), float(mTime));
    if (program.uniform("materialUvAnimationMaskTextured") >= 0)
        bindTexture(*this, program, uvAnimationSpeed != glm::vec3(0.0f) ? mtoon.uvAnimationMaskTexture : TextureRef{},
                    kUvAnimationMaskTextureUnit, "materialUvAnimationMask", /*srgb=*/false);
    if (program.uniform("mtoonOutlineMode") >= 0) {
        const int mode = mtoon.outlineWidthMode == MToonMaterial::OutlineWidthMode::WorldCoordinates    ? 1
                         : mtoon.outlineWidthMode == MToonMaterial::OutlineWidthMode::ScreenCoordinates ? 2
                                                                                                        : 0;
        glUniform1i(program.uniform("mtoonOutlineMode"), material.mtoon ? mode : 0);
        glUniform1f(program.uniform("mtoonOutlineWidthFactor"), mtoon.outlineWidthFactor);
        glUniform3fv(program.uniform("mtoonOutlineColorFactor"), 1, glm::value_ptr(mtoon.outlineColorFactor));
        glUniform1f(program.uniform("mtoonOutlineLightingMixFactor"), mtoon.outlineLightingMixFactor);
        bindTexture(*this, program, mtoon.outlineWidthMultiplyTexture, kOutlineWidthTextureUnit,
                    "mtoonOutlineWidthMultiply", /*srgb=*/false);
    }
    // What a mesh without the attribute reads: GL's current value of a disabled attribute array.
    glVertexAttrib2f(kTexcoord0Location, 0.0f, 0.0f);
    glVertexAttrib2f(kTexcoord1Location, 0.0f, 0.0f);
    glVertexAttrib4f(kVertexColorLocation, 1.0f, 1.0f, 1.0f, 1.0f);
}

void setFaceCulling(bool drawsBackFaces) {
    if (drawsBackFaces) {
        glDisable(GL_CULL_FACE);
        return;
    }
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
}

MeshAttributeBuffers uploadMaterialAttributes(const Mesh& mesh, const std::string& label) {
    MeshAttributeBuffers uploaded;
    for (int set = 0; set < 2; ++set) {
        const std::vector<glm::vec2>& texcoords = mesh.texcoords[set];
        if (texcoords.empty()) continue;
        uploaded.attributes.push_back({set == 0 ? kTexcoord0Location : kTexcoord1Location, 2,
                                       GlBuffer(texcoords.data(), texcoords.size() * sizeof(glm::vec2),
                                                label + " texcoords " + std::to_string(set))});
    }
    if (!mesh.colors.empty())
        uploaded.attributes.push_back(
            {kVertexColorLocation, 4,
             GlBuffer(mesh.colors.data(), mesh.colors.size() * sizeof(glm::vec4), label + " colours")});
    return uploaded;
}

void MeshAttributeBuffers::attachTo(GlVertexArray& vertexArray) const {
    for (const Attribute& attribute : attributes) {
        if (attribute.components == 2)
            vertexArray.setVec2Attribute(attribute.location, attribute.buffer);
        else
            vertexArray.setVec4Attribute(attribute.location, attribute.buffer);
    }
}

} // namespace inkgraph
