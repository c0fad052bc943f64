#include "passes/ViewUniforms.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace inkgraph {

void setViewUniforms(const GlProgram& program, const FrameParams& frame) {
    const glm::mat4 viewFromModel = frame.viewFromModel();
    const glm::mat3 viewNormalFromModel = glm::inverseTranspose(glm::mat3(viewFromModel));
    const glm::mat4 clipFromView = frame.clipFromView();
    glUniformMatrix4fv(program.uniform("viewFromModel"), 1, GL_FALSE, glm::value_ptr(viewFromModel));
    glUniformMatrix3fv(program.uniform("viewNormalFromModel"), 1, GL_FALSE, glm::value_ptr(viewNormalFromModel));
    glUniformMatrix4fv(program.uniform("clipFromView"), 1, GL_FALSE, glm::value_ptr(clipFromView));
    // Model space is world space moved to worldOrigin: the view's rotation is the world's.
    const glm::mat3 worldFromView = glm::inverse(glm::mat3(viewFromModel));
    glUniformMatrix3fv(program.uniform("worldFromView"), 1, GL_FALSE, glm::value_ptr(worldFromView));
}

} // namespace inkgraph
