#include "passes/shade/ShadePass.h"

#include "passes/ViewUniforms.h"

#include "gl/GraphExecutor.h"
#include "gl/Readback.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace inkgraph {
namespace {

const char* modelName(ShadingModel model) { return traitsOf(model).name; }

const char* modelDefine(ShadingModel model) { return traitsOf(model).define; }

bool usesShadeMap(ShadingModel model) { return traitsOf(model).shadeMap; }

/** A shade map's sRGB texels (CV_8UC4, RGBA) as linear light (CV_32FC4), decoded once here instead of in every
 *  pixel: IEC 61966-2-1 in double, alpha as is. */
cv::Mat linearTexels(const cv::Mat& srgb) {
    double decoded[256];
    for (int code = 0; code < 256; ++code) {
        const double encoded = code / 255.0;
        decoded[code] = encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
    }
    cv::Mat linear(srgb.size(), CV_32FC4);
    for (int row = 0; row < srgb.rows; ++row)
        for (int column = 0; column < srgb.cols; ++column) {
            const cv::Vec4b texel = srgb.at<cv::Vec4b>(row, column);
            linear.at<cv::Vec4f>(row, column) = cv::Vec4f(float(decoded[texel[0]]), float(decoded[texel[1]]),
                                                          float(decoded[texel[2]]), float(texel[3] / 255.0));
        }
    return linear;
}

} // namespace

ShadePass::ShadePass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame,
                     ShadeSettings settings, std::optional<ShadeMap> shadeMap)
    : mName(std::move(name)), mShaders(shaders), mScene(scene), mFrame(frame), mSettings(std::move(settings)),
      mDepth(mName + " depth test") {
    const std::string model = modelName(mSettings.model);
    if (traitsOf(mSettings.model).define == nullptr)
        throw std::invalid_argument("ShadePass(): the shading model '" + model + "' has no shading pass");
    if (!std::isfinite(mSettings.shininess) || mSettings.shininess < 0.0)
        throw std::invalid_argument("ShadePass(): shininess must be finite and >= 0, got " +
                                    std::to_string(mSettings.shininess));
    if (!std::isfinite(mSettings.specularStrength) || mSettings.specularStrength < 0.0f)
        throw std::invalid_argument("ShadePass(): specular strength must be finite and >= 0, got " +
                                    std::to_string(mSettings.specularStrength));
    // The maps move into mMaps; the settings keep none (they would hold a second copy of every map).
    std::vector<std::optional<ShadeMap>> meshShadeMaps = std::move(mSettings.meshShadeMaps);
    mSettings.meshShadeMaps.clear();
    const std::size_t meshCount = mScene.meshCount();
    if (meshShadeMaps.size() > meshCount)
        throw std::invalid_argument("ShadePass(): " + std::to_string(meshShadeMaps.size()) +
                                    " per-mesh shade maps for a scene of " + std::to_string(meshCount) + " meshes");
    if (usesShadeMap(mSettings.model)) {
        if (!shadeMap) throw std::invalid_argument("ShadePass(): the '" + model + "' model needs a shade map");
        // Every map is checked, also one that equals another, so the message names the map the caller gave.
        const auto check = [&](const ShadeMap& map, const std::string& owner) {
            const cv::Mat& texels = map.texels;
            if (texels.empty() || texels.type() != CV_8UC4)
                throw std::invalid_argument("ShadePass(): shade map '" + map.source + "'" + owner +
                                            " must be a non-empty CV_8UC4 image (see shadeMapFromImage())");
            if (traitsOf(mSettings.model).oneDimensionalMap && !map.isOneDimensional())
                throw std::invalid_argument("ShadePass(): the 'cel' model needs a one-row shade map, '" + map.source +
                                            "'" + owner + " has " + std::to_string(texels.rows) + " rows");
        };
        check(*shadeMap, "");
        for (std::size_t i = 0; i < meshShadeMaps.size(); ++i)
            if (meshShadeMaps[i]) check(*meshShadeMaps[i], " (mesh " + std::to_string(i) + ")");

        mMaps.push_back({});
        mMaps[0].map = std::move(*shadeMap);
        mMeshMap.assign(meshCount, 0);
        for (std::size_t i = 0; i < meshShadeMaps.size(); ++i)
            if (meshShadeMaps[i]) mMeshMap[i] = slotOf(std::move(*meshShadeMaps[i]));
        for (std::size_t slot : mMeshMap) mMaps[slot].used = true;
    }
    if (mSettings.msaa != 1 && mSettings.msaa != 2 && mSettings.msaa != 4 && mSettings.msaa != 8)
        throw std::invalid_argument("ShadePass(): msaa must be 1, 2, 4 or 8 samples, got " +
                                    std::to_string(mSettings.msaa));
    if (!mSettings.materialOutlines.empty() && !traits().materialOutlines)
        throw std::invalid_argument("ShadePass(): the '" + model +
                                    "' model draws no material outlines, got the layer '" + mSettings.materialOutlines +
                                    "'");
    if (usesConstantView()) {
        const glm::dvec3& direction = mSettings.view.constantView;
        const double length = glm::length(direction);
        if (!std::isfinite(length) || std::abs(length - 1.0) > 1e-6)
            throw std::invalid_argument("ShadePass(): the constant view vector must be a unit vector");
    }
    if (traits().specularRowBands) {
        for (MapSlot& slot : mMaps) {
            slot.rowBands = specularRowBands(slot.map, mSettings.shininess);
            // Only maps some mesh draws with decide the program: an unused default must not change the picture.
            if (slot.used)
                mSpecularBorderCount = std::max(mSpecularBorderCount, slot.rowBands.maxHalfSquaredDistance.size());
        }
        // Padding: a border of -1 never holds (x >= 0), so a map with fewer borders keeps exactly its own rows.
        for (MapSlot& slot : mMaps) {
            slot.borderLimit.assign(mSpecularBorderCount, -1.0f);
            slot.bandRow.assign(mSpecularBorderCount + 1, 0);
            const SpecularRowBands& bands = slot.rowBands;
            for (std::size_t k = 0; k < bands.maxHalfSquaredDistance.size() && k < mSpecularBorderCount; ++k)
                slot.borderLimit[k] = float(bands.maxHalfSquaredDistance[k]);
            for (std::size_t k = 0; k < bands.firstRow.size() && k < mSpecularBorderCount + 1; ++k)
                slot.bandRow[k] = bands.firstRow[k];
        }
    }
    mSceneBaseColor = sceneBaseColor();
    mSceneBlocker = sceneBlocker();
}

std::size_t ShadePass::slotOf(ShadeMap map) {
    const cv::Mat& texels = map.texels;
    for (std::size_t slot = 0; slot < mMaps.size(); ++slot) {
        const cv::Mat& other = mMaps[slot].map.texels;
        if (other.size() != texels.size() || other.type() != texels.type()) continue;
        // One texture per picture, whatever the file it came from: a map equal to the default draws with the default.
        bool equal = true;
        const std::size_t rowBytes = std::size_t(texels.cols) * texels.elemSize();
        for (int row = 0; row < texels.rows && equal; ++row)
            equal = other.ptr(row) == texels.ptr(row) || std::memcmp(other.ptr(row), texels.ptr(row), rowBytes) == 0;
        if (equal) return slot;
    }
    mMaps.push_back({});
    mMaps.back().map = std::move(map);
    return mMaps.size() - 1;
}

std::size_t ShadePass::distinctShadeMapCount() const {
    return std::size_t(std::count_if(mMaps.begin(), mMaps.end(), [](const MapSlot& slot) { return slot.used; }));
}

ShadePass::~ShadePass() = default;

void ShadePass::declare(PassBuilder& builder) const {
    const std::string& gbuffer = mSettings.deferred.gbuffer;
    const bool deferred = !gbuffer.empty() && forwardReason(builder.liveFieldsAnyway(gbuffer)).empty();
    if (deferred) {
        // The G-buffer's depth test skips the pixels off the model before they are shaded (executeDeferred()), so
        // its fields are read only where it covers the frame.
        for (const std::string& field : deferredFields())
            builder.read(gbuffer + "." + field, ReadExtent::CoveredPixels);
        builder.read(gbuffer + ".zBuffer");
    } else {
        builder.import(SceneImport::kMeshes); // forward draws the meshes
        // The multisampled target, colour (rgba8) and depth (float32), which the pass keeps between runs.
        if (mSettings.msaa > 1) builder.ownTarget(std::size_t(8) * std::size_t(mSettings.msaa));
        // Comic's CPU face orientation (Winnemöller & Bangay 2002): the front sets it draws.
        if (traits().orientationSets && mSettings.faceOrientation != FaceOrientationMethod::Standard)
            builder.import(SceneImport::kFaceOrientation);
        if (!mSettings.materialOutlines.empty())
            for (const char* field : {".color", ".depth"}) builder.read(mSettings.materialOutlines + field);
    }
    builder.write("color", {Format::RGBA8}, Need::Required,
                  {"shading.png", Appearance::Color, "the shading layer, sRGB, alpha = coverage"});
}

std::optional<glm::vec4> ShadePass::sceneBaseColor() const {
    const std::vector<Mesh>& meshes = mScene.scene().meshes;
    if (meshes.empty()) return std::nullopt;
    const glm::vec4 color = meshes.front().material.baseColorFactor;
    for (const Mesh& mesh : meshes) {
        const Material& material = mesh.material;
        // MToon materials ignore vertex colours (common/material.glsl); the others multiply them in.
        const bool vertexColors = !mesh.colors.empty() && !material.mtoon;
        if (material.textured() || vertexColors || material.baseColorFactor != color) return std::nullopt;
    }
    return color;
}

std::vector<std::string> ShadePass::deferredFields() const {
    std::vector<std::string> fields = {"normal"};
    if (!mSceneBaseColor) fields.push_back("baseColor");
    // A constant view vector (comic's V_c) is a uniform; an exact one (phong, comic) is the pixel's.
    if (traits().specular && !usesConstantView()) fields.push_back("view");
    return fields;
}

std::string ShadePass::sceneBlocker() const {
    const std::string model = modelName(mSettings.model);
    if (!traitsOf(mSettings.model).perPixel)
        return "'" + model + "' shades from more than the pixel's normal, view and base colour";
    if (mSettings.faceOrientation != FaceOrientationMethod::Standard)
        return "'" + model + "' draws the front sets of the CPU face orientation '" +
               faceOrientationMethodName(mSettings.faceOrientation) + "'";
    if (mSettings.msaa > 1)
        return "the shading is multisampled (--msaa " + std::to_string(mSettings.msaa) +
               ") and the G-buffer holds one sample per pixel";
    if (mSettings.deferred.supersample != 1)
        return "the G-buffer is supersampled (" + std::to_string(mSettings.deferred.supersample) + "x the frame)";
    if (mSettings.deferred.precision != GBufferPrecision::Float32) return "the G-buffer stores float16 normals";
    const Scene& scene = mScene.scene();
    for (const Mesh& mesh : scene.meshes) {
        const Material& material = mesh.material;
        const std::string name = "material '" + material.name + "' of mesh '" + mesh.name + "'";
        if (material.alphaMode == AlphaMode::Blend) return name + " blends";
        if (material.emissiveFactor != glm::vec3(0.0f)) return name + " is emissive";
        if (material.unlit) return name + " is unlit";
    }
    if (distinctShadeMapCount() > 1)
        return "the meshes use " + std::to_string(distinctShadeMapCount()) + " different shade maps";
    return {};
}

std::string ShadePass::forwardReason(const std::vector<std::string>& liveFields) const {
    if (mSettings.deferred.gbuffer.empty()) return "the graph offers no G-buffer to shade";
    // First the reason that holds most often: shading alone does not justify a G-buffer.
    if (liveFields.empty()) return "no line type reads the G-buffer";
    if (!mSceneBlocker.empty()) return mSceneBlocker;
    std::vector<std::string> fields = liveFields;
    for (const std::string& field : deferredFields())
        if (std::find(fields.begin(), fields.end(), field) == fields.end()) fields.push_back(field);
    if (GBufferPass::drawCount(fields) > GBufferPass::drawCount(liveFields))
        return "the G-buffer would draw the meshes a second time for " + std::to_string(fields.size()) + " fields";
    return {};
}

ShadeMode ShadePass::modeIn(const Plan& plan) const {
    const PlannedPass* planned = plan.findPass(mName);
    const std::string normal = mSettings.deferred.gbuffer + ".normal";
    const bool deferred = planned != nullptr && !mSettings.deferred.gbuffer.empty() &&
                          std::find(planned->reads.begin(), planned->reads.end(), normal) != planned->reads.end();
    return deferred ? ShadeMode::Deferred : ShadeMode::Forward;
}

std::string ShadePass::forwardReasonIn(const Plan& plan) const {
    if (modeIn(plan) == ShadeMode::Deferred) return {};
    std::vector<std::string> liveFields;
    if (const PlannedPass* gbuffer = plan.findPass(mSettings.deferred.gbuffer))
        for (const std::string& resource : gbuffer->liveWrites)
            liveFields.push_back(ResourceName::split(resource).field);
    const std::string reason = forwardReason(liveFields);
    // The G-buffer may run for requested buffers alone, which do not decide how the still is drawn.
    return reason.empty() ? "no line type reads the G-buffer (it runs for the requested buffers only)" : reason;
}

bool ShadePass::drawsOrientationSets() const { return traits().orientationSets && mScene.cpuOrientation() != nullptr; }

bool ShadePass::usesSpecularRowBands() const {
    // Maps of one band (no specular rows) have nothing to compare: the generic path reads their single row.
    return traits().specularRowBands && !drawsOrientationSets() && mSpecularBorderCount > 0 &&
           mSpecularBorderCount <= std::size_t(kMaxSpecularRowBands);
}

std::vector<std::string> ShadePass::defines() const {
    std::vector<std::string> result = {modelDefine(mSettings.model)};
    if (mMode == ShadeMode::Deferred) {
        result.push_back("SHADE_DEFERRED 1");
        result.push_back("GBUFFER_NORMAL_UNIT " + std::to_string(kNormalUnit));
        const std::vector<std::string> fields = deferredFields();
        if (std::find(fields.begin(), fields.end(), "baseColor") != fields.end())
            result.push_back("GBUFFER_BASECOLOR_UNIT " + std::to_string(kBaseColorUnit));
        if (std::find(fields.begin(), fields.end(), "view") != fields.end())
            result.push_back("GBUFFER_VIEW_UNIT " + std::to_string(kViewUnit));
    } else {
        result.push_back("MATERIAL_EMISSIVE 1");
    }
    if (usesSpecularRowBands()) result.push_back("SPECULAR_ROW_BANDS " + std::to_string(mSpecularBorderCount));
    if (drawsOrientationSets()) {
        result.push_back("SHADE_COORDS 1");
        result.push_back("SHADE_COORD_LOCATION " + std::to_string(SceneOrientation::kShadeCoordLocation));
    } else if (usesConstantView()) {
        result.push_back("VIEW_CONSTANT 1");
    }
    return result;
}

void ShadePass::prepare(GlPassContext& gl) {
    // The plan says which: deferred reads the G-buffer's normal (declare()).
    mMode = !mSettings.deferred.gbuffer.empty() && gl.reads(mSettings.deferred.gbuffer + ".normal")
                ? ShadeMode::Deferred
                : ShadeMode::Forward;
    if (mProgram && mProgramMode != mMode) mProgram.reset();
    mProgramMode = mMode;
    if (!mProgram && mMode == ShadeMode::Deferred)
        mProgram = std::make_unique<GlProgram>(
            mShaders.build({mName,
                            "shade/deferred.vert",
                            "shade/shade.frag",
                            defines(),
                            {"common/fullscreen.glsl", "common/color.glsl", "common/lighting.glsl"}}));
    if (!mProgram)
        mProgram = std::make_unique<GlProgram>(
            mShaders.build({mName,
                            "shade/shade.vert",
                            "shade/shade.frag",
                            defines(),
                            {"common/color.glsl", "common/lighting.glsl", "common/material.glsl", "common/mtoon.glsl",
                             "common/pbr.glsl"}}));
    for (MapSlot& slot : mMaps) {
        if (!slot.used || slot.texture) continue;
        // Nearest, clamped to the edge (every GlTexture is). uploadImage() turns the image bottom-up, so GL row 0 is
        // the map's bottom row, t = 0, and the shader indexes rows by t directly. Linear texels, so the shader decodes
        // nothing per pixel, in float16: its 11 significant bits keep every 8-bit sRGB code apart (the closest two,
        // 0 and 1, are 3.0e-4 apart in linear light), at half float32's memory (a 4096^2 map: 128 MiB, not 256).
        const cv::Mat& texels = slot.map.texels;
        slot.texture = std::make_unique<GlTexture>(Format::RGBA16F, texels.cols, texels.rows,
                                                   mName + " shade map '" + slot.map.source + "'");
        uploadImage(*slot.texture, linearTexels(texels));
    }
    if (mMode == ShadeMode::Deferred) return; // the G-buffer has drawn the meshes
    mScene.meshes();
    if (mSettings.materialOutlines.empty() || mOutlineProgram) return;
    // The layer is laid in sample by sample, so it must have the samples of the target it goes into.
    const std::string layerColor = mSettings.materialOutlines + ".color";
    for (const std::string& layer : {layerColor, mSettings.materialOutlines + ".depth"})
        if (gl.samplesOf(layer) != mSettings.msaa)
            throw std::logic_error("ShadePass::prepare(): '" + layer + "' has " + std::to_string(gl.samplesOf(layer)) +
                                   " samples per pixel, the shading " + std::to_string(mSettings.msaa));
    std::vector<std::string> outlineDefines = {"OUTLINE_COLOR_UNIT " + std::to_string(kOutlineColorUnit),
                                               "OUTLINE_DEPTH_UNIT " + std::to_string(kOutlineDepthUnit)};
    if (mSettings.msaa > 1) outlineDefines.push_back("OUTLINE_MULTISAMPLED 1");
    mOutlineProgram = std::make_unique<GlProgram>(mShaders.build({mName + " material outlines",
                                                                  "shade/deferred.vert",
                                                                  "shade/outlines.frag",
                                                                  outlineDefines,
                                                                  {"common/fullscreen.glsl"}}));
}

const GlTexture& ShadePass::multisampledColor(int width, int height) {
    if (!mMultisampledColor || mMultisampledColor->width() != width || mMultisampledColor->height() != height ||
        mMultisampledColor->samples() != mSettings.msaa) {
        mMultisampledColor.reset(); // the old one goes first, so two never exist at once
        mMultisampledColor =
            std::make_unique<GlTexture>(Format::RGBA8, width, height, mName + " multisampled", mSettings.msaa);
    }
    return *mMultisampledColor;
}

void ShadePass::layMaterialOutlines(GlPassContext& gl) {
    GlProgram& program = *mOutlineProgram;
    program.use();
    glBindTextureUnit(kOutlineColorUnit, gl.inputTexture(mSettings.materialOutlines + ".color").id());
    glBindTextureUnit(kOutlineDepthUnit, gl.inputTexture(mSettings.materialOutlines + ".depth").id());
    for (const GLuint unit : {kOutlineColorUnit, kOutlineDepthUnit}) glBindSampler(unit, 0); // texelFetch only
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDepthMask(GL_TRUE);
    // Core profile draws nothing without a vertex array, even when the vertices come from gl_VertexID.
    GlVertexArray empty(mName + " material outlines");
    empty.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindTextureUnit(kOutlineColorUnit, 0);
    glBindTextureUnit(kOutlineDepthUnit, 0);
}

void ShadePass::setShadingUniforms(const GlProgram& program) const {
    glUniform3fv(program.uniform("towardLightView"), 1, glm::value_ptr(mFrame.towardLightView()));
    glUniform3fv(program.uniform("ambientLight"), 1, glm::value_ptr(mFrame.ambientLight));
    glUniform1f(program.uniform("shininess"), float(mSettings.shininess));
    glUniform1f(program.uniform("specularStrength"), mSettings.specularStrength);
    if (usesConstantView()) {
        // V_c is eye -> centre in world space; the shader wants surface -> eye in view space (rotation only).
        const glm::dvec3 towardEye = glm::dmat3(mFrame.camera.viewMatrix()) * -mSettings.view.constantView;
        glUniform3fv(program.uniform("constantTowardEye"), 1, glm::value_ptr(glm::vec3(glm::normalize(towardEye))));
    }
}

void ShadePass::bindShadeMap(const GlProgram& program, const MapSlot& slot) const {
    glBindTextureUnit(0, slot.texture->id());
    if (usesSpecularRowBands()) {
        // The band borders in x = |r - v|^2 / 2 (ShadeMap.h): the shader finds the row without a log or exp.
        glUniform1fv(program.uniform("specularBorderLimit"), GLsizei(slot.borderLimit.size()), slot.borderLimit.data());
        glUniform1iv(program.uniform("specularBandRow"), GLsizei(slot.bandRow.size()), slot.bandRow.data());
    }
}

void ShadePass::execute(GlPassContext& gl) {
    if (mMode == ShadeMode::Deferred)
        executeDeferred(gl);
    else
        executeForward(gl);
}

void ShadePass::executeDeferred(GlPassContext& gl) {
    const int width = gl.widthOf("color");
    const int height = gl.heightOf("color");
    GlFramebuffer framebuffer(mName);
    framebuffer.attachColor(0, gl.outputTexture("color"));
    // The G-buffer's own z-buffer, read only: the full-screen triangle lies at the far plane (window depth 0, reversed
    // Z), so the early depth test passes exactly the pixels a surface covers (depth > 0) and the rest keep the clear,
    // the transparent black the shader would write there. On llvmpipe that halves the pass: most of a frame is paper.
    framebuffer.attachDepth(gl.inputTexture(mSettings.deferred.gbuffer + ".zBuffer"));
    framebuffer.finish({0});
    framebuffer.bind();
    glViewport(0, 0, width, height);
    const GLfloat transparent[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(framebuffer.id(), GL_COLOR, 0, transparent);
    // Only inside the scene's bounds can the depth test pass: llvmpipe then skips the tiles outside them instead of
    // testing every pixel of the frame (the bounds are about half of it for an auto-framed model).
    const PixelRect scene = mFrame.scenePixels(width, height);
    glEnable(GL_SCISSOR_TEST);
    glScissor(scene.x, scene.y, scene.width, scene.height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    GlProgram& program = *mProgram;
    program.use();
    setShadingUniforms(program);
    // forwardReason() allows deferred with one distinct map: the one every mesh uses.
    for (const MapSlot& slot : mMaps)
        if (slot.used) bindShadeMap(program, slot);
    const std::vector<std::string> fields = deferredFields();
    const GLuint units[] = {kNormalUnit, kBaseColorUnit, kViewUnit};
    const char* names[] = {"normal", "baseColor", "view"};
    for (std::size_t i = 0; i < 3; ++i)
        if (std::find(fields.begin(), fields.end(), names[i]) != fields.end())
            glBindTextureUnit(units[i], gl.inputTexture(mSettings.deferred.gbuffer + "." + names[i]).id());
    if (const std::optional<glm::vec4> base = mSceneBaseColor)
        glUniform3fv(program.uniform("sceneBaseColor"), 1, glm::value_ptr(glm::vec3(*base)));
    // Core profile draws nothing without a vertex array, even when the vertices come from gl_VertexID.
    GlVertexArray empty(mName + " fullscreen");
    empty.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_SCISSOR_TEST);
    glBindVertexArray(0);
    for (const GLuint unit : {GLuint(0), kNormalUnit, kBaseColorUnit, kViewUnit}) glBindTextureUnit(unit, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void ShadePass::executeForward(GlPassContext& gl) {
    const int width = gl.widthOf("color");
    const int height = gl.heightOf("color");
    // With msaa the surfaces are drawn into a multisampled target of the pass's own, resolved into the output at the
    // end. shade.frag asks for no per-sample shading, so GL may shade a pixel once per triangle (a pixel inside a
    // surface keeps the colour it has without msaa), while each sample keeps its own coverage and depth.
    const bool multisampled = mSettings.msaa > 1;
    GlTexture& output = gl.outputTexture("color");
    GlFramebuffer framebuffer(mName);
    framebuffer.attachColor(0, multisampled ? multisampledColor(width, height) : output);
    framebuffer.attachDepth(mDepth.sized(width, height, mSettings.msaa));
    framebuffer.finish({0});

    // CPU face orientation (comic only): marked, lit and uploaded on the first call, so it counts as this pass's
    // work, like the GPU's own culling would.
    const std::vector<GpuScene::DrawMesh>& meshes = mScene.meshes();
    const std::vector<SceneOrientation::MeshSets>* sets = nullptr;
    if (drawsOrientationSets()) {
        sets = &mScene.cpuOrientation()->sets();
        if (sets->size() != meshes.size())
            throw std::logic_error("ShadePass::execute(): the scene orientation has " + std::to_string(sets->size()) +
                                   " mesh sets for " + std::to_string(meshes.size()) + " meshes");
    }

    framebuffer.bind();
    glViewport(0, 0, width, height);
    clearColorAndDepth(1);

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(kDepthNearer);
    glDisable(GL_BLEND);

    const glm::mat4 viewFromModel = mFrame.viewFromModel();
    GlProgram& program = *mProgram;
    program.use();
    setViewUniforms(program, mFrame);
    setShadingUniforms(program);

    std::optional<std::size_t> boundSlot;
    bool blending = false;
    bool outlinesDrawn = false;
    for (const std::size_t i : mScene.drawOrder(viewFromModel)) {
        if (!mMaps.empty() && boundSlot != mMeshMap[i]) {
            // Each mesh's own map; consecutive meshes that share one keep it bound.
            bindShadeMap(program, mMaps[mMeshMap[i]]);
            boundSlot = mMeshMap[i];
        }
        if (meshes[i].material->alphaMode == AlphaMode::Blend && !blending) {
            // The material outlines belong to the opaque world: laid in before the blended surfaces, which go over
            // them.
            if (mOutlineProgram) {
                layMaterialOutlines(gl);
                program.use();
            }
            outlinesDrawn = true;
            // drawOrder() puts blended meshes last, back to front: each goes over what is behind it, writing no
            // depth. The target holds premultiplied colour (postfx/Composite.h), so over nothing a surface leaves
            // colour x alpha and its alpha.
            glEnable(GL_BLEND);
            glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
            glDepthMask(GL_FALSE);
            blending = true;
        }
        mScene.bindMaterial(program, i, MaterialUse::Colour);
        setFaceCulling(meshes[i].drawsBackFaces);
        if (sets) {
            const SceneOrientation::MeshSets& set = (*sets)[i];
            set.frontArray.bind();
            glDrawElements(GL_TRIANGLES, set.frontIndexCount, GL_UNSIGNED_INT, nullptr);
        } else {
            meshes[i].vertexArray.bind();
            glDrawElements(GL_TRIANGLES, meshes[i].indexCount, GL_UNSIGNED_INT, nullptr);
        }
    }
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    if (mOutlineProgram && !outlinesDrawn) layMaterialOutlines(gl);
    glBindVertexArray(0);
    if (!mMaps.empty()) glBindTextureUnit(0, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_DEPTH_TEST);
    if (multisampled) {
        // The resolve averages each pixel's samples. They hold premultiplied colour with alpha (blending keeps
        // them so, and the background's samples are transparent black), so an edge pixel is its covered share of
        // the surface over nothing, which the composite lays over the paper as it lays any partly covered pixel.
        GlFramebuffer resolved(mName + " resolved");
        resolved.attachColor(0, output);
        resolved.finish({0});
        glNamedFramebufferReadBuffer(framebuffer.id(), GL_COLOR_ATTACHMENT0);
        glBlitNamedFramebuffer(framebuffer.id(), resolved.id(), 0, 0, width, height, 0, 0, width, height,
                               GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
}

} // namespace inkgraph
