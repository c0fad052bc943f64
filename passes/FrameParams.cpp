#include "passes/FrameParams.h"

#include <glm/gtc/matrix_transform.hpp>

namespace inkgraph {

glm::mat4 FrameParams::viewFromModel() const {
    return glm::mat4(camera.viewMatrix() * glm::translate(glm::dmat4(1.0), worldOrigin));
}

glm::mat4 FrameParams::clipFromView() const { return glm::mat4(camera.projectionMatrix()); }

glm::vec3 FrameParams::towardLightView() const {
    const glm::dvec3 view = glm::dmat3(camera.viewMatrix()) * towardLightWorld;
    return glm::vec3(glm::normalize(view));
}

} // namespace inkgraph
