#pragma once
/** @file A camera for GL tests, resolved as the app resolves one (near and far fitted to the bounding sphere). */

#include "scene/Camera.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

namespace inkgraph::test {

/** Looks from `eye` at `target` with a vertical field of view in degrees, for a `width` x `height` image. */
inline Camera lookingAt(const Scene& scene, const glm::dvec3& eye, const glm::dvec3& target, double fovYDegrees,
                        int width, int height) {
    CameraRequest request;
    request.eye = eye;
    request.target = target;
    request.fovYDegrees = fovYDegrees;
    request.width = width;
    request.height = height;
    return resolveCamera(request, scene);
}

} // namespace inkgraph::test
