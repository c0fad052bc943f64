#include "passes/silhouette/SilhouettePass.h"

#include "gl/GraphExecutor.h"
#include "passes/LineMaskTarget.h"

#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <stdexcept>

namespace inkgraph {
namespace {

void requireWidth(const std::string& pass, const char* what, float value) {
    if (!std::isfinite(value) || value < 0.0f)
        throw std::invalid_argument("SilhouettePass(): pass '" + pass + "': '" + what +
                                    "' must be finite and >= 0, got " + std::to_string(value));
}

} // namespace

SilhouettePass::SilhouettePass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame,
                               HullSettings settings)
    : mName(std::move(name)), mShaders(shaders), mScene(scene), mFrame(frame), mSettings(settings),
      mDepth(mName + " model depth") {
    requireWidth(mName, "widthPixels", mSettings.widthPixels);
    if (mSettings.objectWidth) requireWidth(mName, "objectWidth", *mSettings.objectWidth);
}

void SilhouettePass::declare(PassBuilder& builder) const {
    builder.import(SceneImport::kMeshes);
    if (mSettings.weldNormals) builder.import(SceneImport::kHulls);
    const std::string& depth = mSettings.modelDepth;
    if (!depth.empty() && builder.runsAnyway(ResourceName::split(depth).pass)) builder.read(depth);
    builder.write("lines", {Format::R8}, Need::Required,
                  {"band-" + mName + ".png", Appearance::Lines,
                   "the band GL drew for " + mName + ", at the output size, before the stroke stage thins it"});
}

void SilhouettePass::describe(nlohmann::ordered_json& report) const {
    report["skipped_eye_inside"] = skippedEyeInside();
    report["model_depth"] = mModelDepthResource.empty() ? "drawn by the pass" : mModelDepthResource;
    if (mSettings.widthMap.enabled()) report["width_map"] = mSettings.widthMap.text();
}

void SilhouettePass::prepare(GlPassContext& gl) {
    mModelDepthResource = !mSettings.modelDepth.empty() && gl.reads(mSettings.modelDepth) ? mSettings.modelDepth : "";
    if (!mDepthProgram && mModelDepthResource.empty())
        mDepthProgram = std::make_unique<GlProgram>(
            mShaders.build({mName + " model depth",
                            "silhouette/hull.vert",
                            "common/line_mask.frag",
                            materialAlphaDefines(mScene),
                            {"common/hull.glsl", "common/material.glsl", "common/width_map.glsl"}}));
    if (!mHullProgram) {
        std::vector<std::string> defines = materialAlphaDefines(mScene);
        defines.push_back(mSettings.objectWidth ? "HULL_OBJECT_WIDTH 1" : "HULL_SCREEN_WIDTH 1");
        mHullProgram = std::make_unique<GlProgram>(
            mShaders.build({mName + " hull",
                            "silhouette/hull.vert",
                            "common/line_mask.frag",
                            defines,
                            {"common/hull.glsl", "common/material.glsl", "common/width_map.glsl"}}));
    }
    mScene.meshes();
    if (mSettings.weldNormals) mScene.hullArrays(); // made in prepare(), outside the timed execute()
}

void SilhouettePass::execute(GlPassContext& gl) {
    GlFramebuffer framebuffer(mName);
    const bool drawsModelDepth = mModelDepthResource.empty();
    mSkippedEyeInside = drawsModelDepth ? !beginLineMask(gl, framebuffer, mDepth, mScene, mFrame.camera.eye)
                                        : !beginLineMask(gl, framebuffer, gl.inputTexture(mModelDepthResource), mScene,
                                                         mFrame.camera.eye);
    // A hull offset in model units can hold the eye where the model does not (a width of 10 units 5 units away): from
    // inside it, it draws nothing either, and that is said the same way. A width map only narrows it.
    if (!mSkippedEyeInside && mSettings.objectWidth && !mSettings.widthMap.enabled() &&
        mScene.inflatedHullContainsPoint(mFrame.camera.eye, *mSettings.objectWidth, mSettings.weldNormals)) {
        mSkippedEyeInside = true;
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    if (mSkippedEyeInside) return;
    const int width = gl.widthOf("lines");
    const int height = gl.heightOf("lines");

    const glm::mat4 viewFromModel = mFrame.viewFromModel();
    const glm::mat3 viewNormalFromModel = glm::inverseTranspose(glm::mat3(viewFromModel));
    const glm::mat4 clipFromView = mFrame.clipFromView();
    const std::vector<GpuScene::DrawMesh>& meshes = mScene.meshes();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(kDepthNearer);
    glDisable(GL_BLEND);

    // 1. The model's depth: every face (open meshes show their insides through holes), no colour; or the one the
    // G-buffer drew.
    if (drawsModelDepth) {
        glDisable(GL_CULL_FACE);
        drawModelDepth(*mDepthProgram, mScene, viewFromModel, clipFromView);
    }

    // 2. The hull's back faces where they are nearer than the model by more than a pixel of their own depth slope
    // (gl/GlObjects.h): where the hull meets the model's own depth, or lies as good as on a surface seen at a grazing
    // angle, the model wins. Without the offset such a hull face and the surface take turns pixel by pixel, dotted
    // slivers a pixel wide that appear at one size and not at another (docs/strokes.md, "Silhouettes: the hull where it
    // lies on a grazing surface").
    // The depth stays the model's, so hulls of different meshes never hide each other.
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_FALSE);
    mHullProgram->use();
    glUniformMatrix4fv(mHullProgram->uniform("viewFromModel"), 1, GL_FALSE, glm::value_ptr(viewFromModel));
    glUniformMatrix3fv(mHullProgram->uniform("viewNormalFromModel"), 1, GL_FALSE, glm::value_ptr(viewNormalFromModel));
    glUniformMatrix4fv(mHullProgram->uniform("clipFromView"), 1, GL_FALSE, glm::value_ptr(clipFromView));
    glUniform2f(mHullProgram->uniform("viewportSize"), float(width), float(height));
    glUniform1f(mHullProgram->uniform("widthPixels"), bandWidthPixels(mSettings.widthPixels, height));
    glUniform1f(mHullProgram->uniform("objectWidth"), mSettings.objectWidth.value_or(0.0f));
    const bool transparency = mScene.hasTransparency();
    {
        const OnePixelFartherFill farther;
        for (std::size_t index = 0; index < meshes.size(); ++index) {
            // A cut-out's hull is cut where the surface is (its vertices carry the surface's texture coordinates).
            if (transparency) mScene.bindMaterial(*mHullProgram, index, MaterialUse::Coverage);
            mScene.materials().bindWidthMap(*mHullProgram, index, mSettings.widthMap);
            (mSettings.weldNormals ? mScene.hullArrays()[index] : meshes[index].vertexArray).bind();
            glDrawElements(GL_TRIANGLES,
                           mSettings.weldNormals ? mScene.hullIndexCount(index) : meshes[index].indexCount,
                           GL_UNSIGNED_INT, nullptr);
        }
    }
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

} // namespace inkgraph
