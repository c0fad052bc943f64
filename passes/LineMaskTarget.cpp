#include "passes/LineMaskTarget.h"

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

} // namespace inkgraph
