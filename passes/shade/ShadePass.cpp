#include "passes/shade/ShadePass.h"

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
    if (!std::isfinite(mSettings.ambient) || mSettings.ambient < 0.0f || mSettings.ambient > 1.0f)
        throw std::invalid_argument("ShadePass(): ambient must be within [0, 1], got " +
                                    std::to_string(mSettings.ambient));
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
    if (mSettings.model == ShadingModel::Comic && mSettings.view.constant) {
        const glm::dvec3& direction = mSettings.view.constantView;
        const double length = glm::length(direction);
        if (!std::isfinite(length) || std::abs(length - 1.0) > 1e-6)
            throw std::invalid_argument("ShadePass(): the constant view vector must be a unit vector");
    }
    if (mSettings.model == ShadingModel::Comic) {
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
    builder.write("color", {Format::RGBA8}, Need::Required, {"shading.png", Appearance::Color});
}

bool ShadePass::drawsOrientationSets() const {
    return mSettings.model == ShadingModel::Comic && mScene.cpuOrientation() != nullptr;
}

bool ShadePass::usesSpecularRowBands() const {
    // Maps of one band (no specular rows) have nothing to compare: the generic path reads their single row.
    return mSettings.model == ShadingModel::Comic && !drawsOrientationSets() && mSpecularBorderCount > 0 &&
           mSpecularBorderCount <= std::size_t(kMaxSpecularRowBands);
}

std::vector<std::string> ShadePass::defines() const {
    std::vector<std::string> result = {modelDefine(mSettings.model), "MATERIAL_EMISSIVE 1"};
    if (usesSpecularRowBands()) result.push_back("SPECULAR_ROW_BANDS " + std::to_string(mSpecularBorderCount));
    if (drawsOrientationSets()) {
        result.push_back("SHADE_COORDS 1");
        result.push_back("SHADE_COORD_LOCATION " + std::to_string(SceneOrientation::kShadeCoordLocation));
    } else if (mSettings.model == ShadingModel::Comic && mSettings.view.constant) {
        result.push_back("VIEW_CONSTANT 1");
    }
    return result;
}

void ShadePass::prepare(GlPassContext&) {
    if (!mProgram)
        mProgram = std::make_unique<GlProgram>(
            mShaders.build({mName,
                            "shade/shade.vert",
                            "shade/shade.frag",
                            defines(),
                            {"common/color.glsl", "common/lighting.glsl", "common/material.glsl"}}));
    for (MapSlot& slot : mMaps) {
        if (!slot.used || slot.texture) continue;
        // Nearest, clamped to the edge (every GlTexture is). uploadImage() turns the image bottom-up, so GL row 0 is
        // the map's bottom row, t = 0, and the shader indexes rows by t directly.
        const cv::Mat& texels = slot.map.texels;
        slot.texture = std::make_unique<GlTexture>(Format::RGBA8, texels.cols, texels.rows,
                                                   mName + " shade map '" + slot.map.source + "'");
        uploadImage(*slot.texture, texels);
    }
    mScene.meshes();
    if (drawsMToonOutlines() && !mOutlineProgram) {
        // The outline shells are the inflated hull (silhouette/hull.vert), each mesh's as wide as its material says.
        std::vector<std::string> outlineDefines = defines();
        outlineDefines.push_back("MTOON_OUTLINE 1");
        outlineDefines.push_back("HULL_MATERIAL_WIDTH 1");
        mOutlineProgram = std::make_unique<GlProgram>(
            mShaders.build({mName + " mtoon outline",
                            "silhouette/hull.vert",
                            "shade/shade.frag",
                            outlineDefines,
                            {"common/color.glsl", "common/lighting.glsl", "common/material.glsl"}}));
        mScene.hullArrays(); // the outline shells are the hulls, made outside the timed execute()
    }
}

bool ShadePass::drawsMToonOutlines() const {
    if (mSettings.model != ShadingModel::MToon) return false;
    for (std::size_t index = 0; index < mScene.meshCount(); ++index)
        if (mScene.materials().outlineOf(index).has_value()) return true;
    return false;
}

void ShadePass::drawMToonOutlines(const glm::mat4& viewFromModel, const glm::mat3& viewNormalFromModel,
                                  const glm::mat4& clipFromView, int width, int height) {
    GlProgram& program = *mOutlineProgram;
    program.use();
    glUniformMatrix4fv(program.uniform("viewFromModel"), 1, GL_FALSE, glm::value_ptr(viewFromModel));
    glUniformMatrix3fv(program.uniform("viewNormalFromModel"), 1, GL_FALSE, glm::value_ptr(viewNormalFromModel));
    glUniformMatrix4fv(program.uniform("clipFromView"), 1, GL_FALSE, glm::value_ptr(clipFromView));
    glUniform2f(program.uniform("viewportSize"), float(width), float(height));
    glUniform3fv(program.uniform("towardLightView"), 1, glm::value_ptr(mFrame.towardLightView()));
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    // Only the shell's back faces: where it sticks out beyond the surface, the outline.
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    for (std::size_t index = 0; index < mScene.meshCount(); ++index) {
        if (!mScene.materials().outlineOf(index)) continue;
        mScene.bindMaterial(program, index, MaterialUse::Colour);
        mScene.hullArrays()[index].bind();
        glDrawElements(GL_TRIANGLES, mScene.meshes()[index].indexCount, GL_UNSIGNED_INT, nullptr);
    }
    glCullFace(GL_BACK);
    glDisable(GL_CULL_FACE);
}

void ShadePass::execute(GlPassContext& gl) {
    const int width = gl.widthOf("color");
    const int height = gl.heightOf("color");
    GlFramebuffer framebuffer(mName);
    framebuffer.attachColor(0, gl.outputTexture("color"));
    framebuffer.attachDepth(mDepth.sized(width, height));
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
    const glm::mat3 viewNormalFromModel = glm::inverseTranspose(glm::mat3(viewFromModel));
    const glm::mat4 clipFromView = mFrame.clipFromView();
    GlProgram& program = *mProgram;
    program.use();
    glUniformMatrix4fv(program.uniform("viewFromModel"), 1, GL_FALSE, glm::value_ptr(viewFromModel));
    glUniformMatrix3fv(program.uniform("viewNormalFromModel"), 1, GL_FALSE, glm::value_ptr(viewNormalFromModel));
    glUniformMatrix4fv(program.uniform("clipFromView"), 1, GL_FALSE, glm::value_ptr(clipFromView));
    glUniform3fv(program.uniform("towardLightView"), 1, glm::value_ptr(mFrame.towardLightView()));
    glUniform1f(program.uniform("ambient"), mSettings.ambient);
    glUniform1f(program.uniform("shininess"), float(mSettings.shininess));
    glUniform1f(program.uniform("specularStrength"), mSettings.specularStrength);
    if (mSettings.model == ShadingModel::Comic && mSettings.view.constant) {
        // V_c is eye -> centre in world space; the shader wants surface -> eye in view space (rotation only).
        const glm::dvec3 towardEye = glm::dmat3(mFrame.camera.viewMatrix()) * -mSettings.view.constantView;
        glUniform3fv(program.uniform("constantTowardEye"), 1, glm::value_ptr(glm::vec3(glm::normalize(towardEye))));
    }
    const bool rowBands = usesSpecularRowBands();
    const GLint borderLimitLocation = rowBands ? program.uniform("specularBorderLimit") : -1;
    const GLint bandRowLocation = rowBands ? program.uniform("specularBandRow") : -1;

    std::optional<std::size_t> boundSlot;
    bool blending = false;
    bool outlinesDrawn = false;
    for (const std::size_t i : mScene.drawOrder(viewFromModel)) {
        if (!mMaps.empty() && boundSlot != mMeshMap[i]) {
            // Each mesh's own map; consecutive meshes that share one keep it bound.
            const MapSlot& slot = mMaps[mMeshMap[i]];
            glBindTextureUnit(0, slot.texture->id());
            if (rowBands) {
                // The band borders in x = |r - v|^2 / 2 (ShadeMap.h): the shader finds the row without a log or exp.
                glUniform1fv(borderLimitLocation, GLsizei(slot.borderLimit.size()), slot.borderLimit.data());
                glUniform1iv(bandRowLocation, GLsizei(slot.bandRow.size()), slot.bandRow.data());
            }
            boundSlot = mMeshMap[i];
        }
        if (meshes[i].material->alphaMode == AlphaMode::Blend && !blending) {
            // MToon's outlines belong to the opaque world: drawn before the blended surfaces, which go over them.
            if (mOutlineProgram) {
                drawMToonOutlines(viewFromModel, viewNormalFromModel, clipFromView, width, height);
                program.use();
                if (!mMaps.empty() && boundSlot) glBindTextureUnit(0, mMaps[*boundSlot].texture->id());
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
        setFaceCulling(*meshes[i].material);
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
    if (mOutlineProgram && !outlinesDrawn)
        drawMToonOutlines(viewFromModel, viewNormalFromModel, clipFromView, width, height);
    glBindVertexArray(0);
    if (!mMaps.empty()) glBindTextureUnit(0, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_DEPTH_TEST);
}

} // namespace inkgraph
