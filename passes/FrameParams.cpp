#include "passes/FrameParams.h"

#include <glm/gtc/matrix_transform.hpp>

namespace inkgraph {

glm::mat4 FrameParams::viewFromModel() const {
    return glm::mat4(camera.viewMatrix() * glm::translate(glm::dmat4(1.0), worldOrigin));
}

glm::mat4 FrameParams::clipFromView() const {
    // glm::perspective's x, y and w rows with a reversed-Z depth row: z_clip = n (f + z) / (f - n) for view z < 0, so
    // z_clip / w is 1 at z = -n and 0 at z = -f (gl/GlObjects.h). Computed in double; the float entries are n / (f - n)
    // and n f / (f - n), both well inside float's range for any ratio the camera allows.
    glm::dmat4 projection = camera.projectionMatrix();
    const double n = camera.zNear;
    const double f = camera.zFar;
    projection[2][2] = n / (f - n);
    projection[3][2] = n * f / (f - n);
    return glm::mat4(projection);
}

glm::vec3 FrameParams::towardLightView() const {
    const glm::dvec3 view = glm::dmat3(camera.viewMatrix()) * towardLightWorld;
    return glm::vec3(glm::normalize(view));
}

} // namespace inkgraph
