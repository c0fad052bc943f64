#include "passes/outline/OutlinePass.h"

#include "gl/GraphExecutor.h"
#include "passes/LineMaskTarget.h"

#include <nlohmann/json.hpp>

#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <stdexcept>

namespace inkgraph {

OutlinePass::OutlinePass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame,
                         float widthPixels)
    : mName(std::move(name)), mShaders(shaders), mScene(scene), mFrame(frame), mWidthPixels(widthPixels),
      mDepth(mName + " model depth") {
    if (!std::isfinite(mWidthPixels) || mWidthPixels < 0.0f)
        throw std::invalid_argument("OutlinePass(): pass '" + mName + "': 'widthPixels' must be finite and >= 0, got " +
                                    std::to_string(mWidthPixels));
}

void OutlinePass::declare(PassBuilder& builder) const {
    builder.write("lines", {Format::R8}, Need::Required, {"band-" + mName + ".png", Appearance::Lines});
}

void OutlinePass::describe(nlohmann::ordered_json& report) const { report["skipped_eye_inside"] = skippedEyeInside(); }

void OutlinePass::prepare(GlPassContext&) {
    if (!mDepthProgram)
        mDepthProgram = std::make_unique<GlProgram>(mShaders.build({mName + " model depth",
                                                                    "outline/outline.vert",
                                                                    "common/line_mask.frag",
                                                                    materialAlphaDefines(mScene),
                                                                    {"common/material.glsl"}}));
    if (!mLineProgram)
        mLineProgram = std::make_unique<GlProgram>(mShaders.build({mName + " back edges",
                                                                   "outline/outline.vert",
                                                                   "common/line_mask.frag",
                                                                   materialAlphaDefines(mScene),
                                                                   {"common/material.glsl"},
                                                                   "outline/outline.geom"}));
    mScene.meshes();
    if (SceneOrientation* orientation = mScene.cpuOrientation())
        orientation->sets(); // marks and uploads outside the timed execute()
}

void OutlinePass::execute(GlPassContext& gl) {
    GlFramebuffer framebuffer(mName);
    mSkippedEyeInside = !beginLineMask(gl, framebuffer, mDepth, mScene, mFrame.camera.eye);
    if (mSkippedEyeInside) return;
    const int width = gl.widthOf("lines");
    const int height = gl.heightOf("lines");

    const glm::mat4 viewFromModel = mFrame.viewFromModel();
    const glm::mat4 clipFromView = mFrame.clipFromView();
    const std::vector<GpuScene::DrawMesh>& meshes = mScene.meshes();
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE); // the depth draw takes every face; the line draw culls in its geometry shader

    // 1. The model's depth: every face (open meshes show their insides through holes), no colour.
    glDepthFunc(kDepthNearer);
    drawModelDepth(*mDepthProgram, mScene, viewFromModel, clipFromView);

    // 2. Back-face edges as quads 2 x widthPixels wide. Nearer or equal: a silhouette edge lies exactly on the model's
    // depth.
    glDepthFunc(kDepthNearerOrEqual);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_FALSE);
    mLineProgram->use();
    glUniformMatrix4fv(mLineProgram->uniform("viewFromModel"), 1, GL_FALSE, glm::value_ptr(viewFromModel));
    glUniformMatrix4fv(mLineProgram->uniform("clipFromView"), 1, GL_FALSE, glm::value_ptr(clipFromView));
    glUniform2f(mLineProgram->uniform("viewportSize"), float(width), float(height));
    glUniform1f(mLineProgram->uniform("halfWidthPixels"), mWidthPixels);
    // With a CPU method its back sets decide what is submitted (Winnemoller & Bangay 2002's saving); they hold every
    // true back face, and the geometry shader's facing test drops the front-facing "intermediate" ones, so the outline
    // is the same.
    // A cut-out's edges are cut with it (the corners carry the surface's texture coordinates to line_mask.frag).
    const bool transparency = mScene.hasTransparency();
    if (SceneOrientation* orientation = mScene.cpuOrientation()) {
        const std::vector<SceneOrientation::MeshSets>& sets = orientation->sets();
        for (std::size_t index = 0; index < sets.size(); ++index) {
            if (transparency) mScene.bindMaterial(*mLineProgram, index, MaterialUse::Coverage);
            sets[index].backArray.bind();
            glDrawElements(GL_TRIANGLES, sets[index].backIndexCount, GL_UNSIGNED_INT, nullptr);
        }
    } else {
        for (std::size_t index = 0; index < meshes.size(); ++index) {
            if (transparency) mScene.bindMaterial(*mLineProgram, index, MaterialUse::Coverage);
            meshes[index].vertexArray.bind();
            glDrawElements(GL_TRIANGLES, meshes[index].indexCount, GL_UNSIGNED_INT, nullptr);
        }
    }

    glDepthMask(GL_TRUE);
    glDepthFunc(kDepthNearer);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

} // namespace inkgraph
