#include "passes/FrameParams.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

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

void FrameParams::boundScene(const Scene& scene) {
    // Each triangle's image is the convex hull of its corners' images as long as every corner lies in front of the eye
    // (w > 0); clipping keeps a part of it. A corner at or behind the eye has no image to bound: then the whole frame.
    const glm::mat4 clipFromModel = clipFromView() * viewFromModel();
    glm::dvec2 low(INFINITY);
    glm::dvec2 high(-INFINITY);
    for (const Mesh& mesh : scene.meshes) {
        for (const glm::vec3& p : mesh.positions) {
            const glm::vec4 clip = clipFromModel * glm::vec4(glm::vec3(glm::dvec3(p) - worldOrigin), 1.0f);
            if (!(clip.w > 0.0f) || !std::isfinite(clip.x) || !std::isfinite(clip.y)) {
                sceneLow = glm::dvec2(-1.0);
                sceneHigh = glm::dvec2(1.0);
                return;
            }
            const glm::dvec2 ndc = glm::dvec2(clip.x, clip.y) / double(clip.w);
            low = glm::min(low, ndc);
            high = glm::max(high, ndc);
        }
    }
    // Beyond +-1 is outside the frame either way; +-2 keeps the bounds finite and a scene wholly outside apart from
    // one that touches the border. No vertex: nothing covers the frame.
    const bool anyVertex = low.x <= high.x;
    sceneLow = anyVertex ? glm::clamp(low, -2.0, 2.0) : glm::dvec2(-2.0);
    sceneHigh = anyVertex ? glm::clamp(high, -2.0, 2.0) : glm::dvec2(-2.0);
}

PixelRect FrameParams::scenePixels(int width, int height) const {
    // Window coordinates: pixel (i, j) spans [i, i + 1) x [j, j + 1), its samples inside it.
    const glm::dvec2 size(width, height);
    const glm::dvec2 low = (sceneLow + 1.0) * 0.5 * size;
    const glm::dvec2 high = (sceneHigh + 1.0) * 0.5 * size;
    const int x0 = std::clamp(int(std::floor(low.x)) - 1, 0, width);
    const int y0 = std::clamp(int(std::floor(low.y)) - 1, 0, height);
    const int x1 = std::clamp(int(std::ceil(high.x)) + 1, 0, width);
    const int y1 = std::clamp(int(std::ceil(high.y)) + 1, 0, height);
    return {x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
}

} // namespace inkgraph
