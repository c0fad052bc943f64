#include "passes/LineMaskTarget.h"

#include <glm/gtc/type_ptr.hpp>

namespace inkgraph {

bool beginLineMask(GlPassContext& gl, GlFramebuffer& framebuffer, PassDepthBuffer& depth, GpuScene& scene,
                   const glm::dvec3& eye) {
    const int width = gl.widthOf("lines");
    const int height = gl.heightOf("lines");
    framebuffer.attachColor(0, gl.outputTexture("lines"));
    framebuffer.attachDepth(depth.sized(width, height));
    framebuffer.finish({0});
    framebuffer.bind();
    glViewport(0, 0, width, height);
    clearColorAndDepth(1);
    if (scene.containsPoint(eye)) {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        return false;
    }
    return true;
}

void drawModelDepth(const GlProgram& program, GpuScene& scene, const glm::mat4& viewFromModel,
                    const glm::mat4& clipFromView) {
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    program.use();
    glUniformMatrix4fv(program.uniform("viewFromModel"), 1, GL_FALSE, glm::value_ptr(viewFromModel));
    glUniformMatrix4fv(program.uniform("clipFromView"), 1, GL_FALSE, glm::value_ptr(clipFromView));
    const bool transparency = scene.hasTransparency();
    const std::vector<GpuScene::DrawMesh>& meshes = scene.meshes();
    for (std::size_t index = 0; index < meshes.size(); ++index) {
        if (transparency) scene.bindMaterial(program, index, MaterialUse::Coverage);
        meshes[index].vertexArray.bind();
        glDrawElements(GL_TRIANGLES, meshes[index].indexCount, GL_UNSIGNED_INT, nullptr);
    }
}

std::vector<std::string> materialAlphaDefines(const GpuScene& scene) {
    if (!scene.hasTransparency()) return {};
    return {"MATERIAL_ALPHA 1", "MATERIAL_SOLID_ONLY 1"};
}

} // namespace inkgraph
