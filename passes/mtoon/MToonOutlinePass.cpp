#include "passes/mtoon/MToonOutlinePass.h"

#include "passes/ViewUniforms.h"

#include "gl/GraphExecutor.h"
#include "scene/mesh/MeshOps.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include <stdexcept>

namespace inkgraph {

MToonOutlinePass::MToonOutlinePass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame,
                                   int samples, WidthMap widthMap)
    : mName(std::move(name)), mShaders(shaders), mScene(scene), mFrame(frame), mSamples(samples),
      mWidthMap(std::move(widthMap)) {
    if (samples != 1 && samples != 2 && samples != 4 && samples != 8)
        throw std::invalid_argument("MToonOutlinePass(): samples must be 1, 2, 4 or 8, got " + std::to_string(samples));
}

bool MToonOutlinePass::drawsAnyOutline(const Scene& scene) {
    for (const Mesh& mesh : scene.meshes)
        if (outlineOf(mesh.material)) return true;
    return false;
}

void MToonOutlinePass::declare(PassBuilder& builder) const {
    builder.import(SceneImport::kMeshes);
    builder.import(SceneImport::kHulls); // the shells are the hulls
    builder.write("color", {Format::RGBA8, 1, mSamples}, Need::Required,
                  {mName + ".png", Appearance::Color,
                   "MToon's outline shells alone (--shading mtoon, materials that ask for an outline), sRGB"});
    builder.write("depth", {Format::Depth32F, 1, mSamples}, Need::Required,
                  {mName + "-depth.exr", Appearance::Data,
                   "the outline shells' depth, which the shade pass lays them in by (reversed-Z window depth)"});
}

void MToonOutlinePass::describe(nlohmann::ordered_json& report) const {
    report["shells"] = mShellsDrawn;
    report["triangles"] = mTrianglesDrawn;
    report["shells_skipped_eye_inside"] = mShellsSkippedEyeInside;
    if (mWidthMap.enabled()) report["width_map"] = mWidthMap.text();
}

void MToonOutlinePass::prepare(GlPassContext&) {
    // The fragment stage lights the shell as the shade pass lights the surface (common/mtoon.glsl), with the
    // material's emissive (MATERIAL_EMISSIVE), as forward shading has it.
    if (!mProgram)
        mProgram = std::make_unique<GlProgram>(
            mShaders.build({mName,
                            "mtoon/outline.vert",
                            "mtoon/outline.frag",
                            {"MATERIAL_EMISSIVE 1"},
                            {"common/color.glsl", "common/hull.glsl", "common/material.glsl", "common/lighting.glsl",
                             "common/mtoon.glsl", "common/width_map.glsl"}}));
    mScene.meshes();
    mScene.hullArrays(); // the shells are the hulls, made outside the timed execute()
}

void MToonOutlinePass::execute(GlPassContext& gl) {
    const int width = gl.widthOf("color");
    const int height = gl.heightOf("color");
    GlFramebuffer framebuffer(mName);
    framebuffer.attachColor(0, gl.outputTexture("color"));
    framebuffer.attachDepth(gl.outputTexture("depth"));
    framebuffer.finish({0});
    framebuffer.bind();
    glViewport(0, 0, width, height);
    clearColorAndDepth(1);

    GlProgram& program = *mProgram;
    program.use();
    setViewUniforms(program, mFrame);
    glUniform2f(program.uniform("viewportSize"), float(width), float(height));
    glUniform3fv(program.uniform("towardLightView"), 1, glm::value_ptr(mFrame.towardLightView()));
    glUniform3fv(program.uniform("ambientLight"), 1, glm::value_ptr(mFrame.ambientLight));
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(kDepthNearer);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    // Only the shells' back faces: where a shell sticks out beyond its surface, the outline.
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    mShellsDrawn = 0;
    mTrianglesDrawn = 0;
    mShellsSkippedEyeInside = 0;
    // The whole model's answer first, which the outline and silhouette passes share; only then each mesh's own.
    const glm::dvec3 eye = mFrame.camera.eye;
    const bool eyeInsideModel = mScene.containsPoint(eye);
    const std::vector<GpuScene::DrawMesh>& meshes = mScene.meshes();
    for (std::size_t index = 0; index < meshes.size(); ++index) {
        if (!mScene.materials().outlineOf(index)) continue;
        // From inside a mesh every back face of its shell faces the eye, so the shell would flood the picture in
        // its outline colour (the eye in a character's head): not drawn, as the outline and the silhouette are not.
        if (eyeInsideModel && isPointInsideMesh(mScene.scene().meshes[index], eye)) {
            ++mShellsSkippedEyeInside;
            continue;
        }
        mScene.bindMaterial(program, index, MaterialUse::Colour);
        mScene.materials().bindWidthMap(program, index, mWidthMap);
        mScene.hullArrays()[index].bind();
        glDrawElements(GL_TRIANGLES, mScene.hullIndexCount(index), GL_UNSIGNED_INT, nullptr);
        ++mShellsDrawn;
        mTrianglesDrawn += std::size_t(mScene.hullIndexCount(index)) / 3;
    }
    glCullFace(GL_BACK);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

} // namespace inkgraph
