#include "scene/Camera.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace inkgraph {

namespace {

constexpr double kDefaultFovYDegrees = 35.0;
/** Auto-framing looks from +Z, raised a little so tops of models read as tops. */
const glm::dvec3 kAutoFrameDirection = glm::normalize(glm::dvec3(0.0, 0.25, 1.0));
constexpr double kFramingMargin = 1.05;
/** Near never drops below far x this, which bounds depth-buffer precision loss when the eye is close or inside. */
constexpr double kMinNearOverFar = 1e-4;

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

[[noreturn]] void invalid(const std::string& problem) { throw std::invalid_argument("resolveCamera(): " + problem); }

/** Distance at which a sphere of `radius` fits the narrower of the vertical and horizontal fields of view. */
double framingDistance(double radius, double fovYRadians, double aspect) {
    const double fovXRadians = 2.0 * std::atan(std::tan(fovYRadians / 2.0) * aspect);
    return kFramingMargin * radius / std::sin(std::min(fovYRadians, fovXRadians) / 2.0);
}

} // namespace

glm::dmat4 Camera::viewMatrix() const { return glm::lookAt(eye, target, up); }

glm::dmat4 Camera::projectionMatrix() const {
    return glm::perspective(glm::radians(fovYDegrees), aspect(), zNear, zFar);
}

double Camera::focalPixels() const { return (double(height) / 2.0) / std::tan(glm::radians(fovYDegrees) / 2.0); }

Camera resolveCamera(const CameraRequest& request, const Scene& scene) {
    if (request.width <= 0 || request.height <= 0) {
        invalid("image size " + std::to_string(request.width) + "x" + std::to_string(request.height) +
                " must be positive");
    }
    if ((request.eye && !isFinite(*request.eye)) || (request.target && !isFinite(*request.target)) ||
        !isFinite(request.up)) {
        invalid("eye, target and up must be finite");
    }

    Camera camera;
    camera.width = request.width;
    camera.height = request.height;

    // The file's field of view is a property of its lens and applies whoever places the camera; its placement
    // (eye, orientation) is one unit that an explicit eye replaces entirely.
    camera.fovYDegrees = request.fovYDegrees ? *request.fovYDegrees
                         : scene.camera      ? scene.camera->fovYDegrees
                                             : kDefaultFovYDegrees;
    const SceneCamera* fileCamera = !request.eye && scene.camera ? &*scene.camera : nullptr;
    if (!std::isfinite(camera.fovYDegrees) || camera.fovYDegrees <= 0.0 || camera.fovYDegrees >= 180.0) {
        invalid("vertical field of view " + std::to_string(camera.fovYDegrees) + " degrees is outside (0, 180)");
    }

    const BoundingSphere sphere = computeBoundingSphere(scene);
    // A point-sized scene still needs a usable framing distance.
    const double radius = sphere.radius > 0.0 ? sphere.radius : 1.0;
    const glm::dvec3 autoFrameOffset =
        kAutoFrameDirection * framingDistance(radius, glm::radians(camera.fovYDegrees), camera.aspect());

    if (request.eye) {
        camera.eye = *request.eye;
        camera.target = request.target ? *request.target : sphere.center;
        camera.up = request.up;
        camera.source = "flags";
    } else if (fileCamera) {
        camera.eye = fileCamera->eye;
        if (request.target) {
            camera.target = *request.target;
        } else {
            // Only the direction matters to lookAt; aim at the depth of the model so the target is meaningful.
            const double depth = glm::length(sphere.center - fileCamera->eye);
            camera.target = fileCamera->eye + fileCamera->forward * (depth > 0.0 ? depth : 1.0);
        }
        camera.up = fileCamera->up;
        camera.source = "gltf";
    } else {
        camera.target = request.target ? *request.target : sphere.center;
        camera.eye = camera.target + autoFrameOffset;
        camera.up = request.up;
        camera.source = "auto-framed";
    }

    const glm::dvec3 view = camera.target - camera.eye;
    const double viewLength = glm::length(view);
    if (!(viewLength > 1e-12 * std::max(1.0, glm::length(camera.eye)))) {
        invalid("eye and target coincide");
    }
    const double upLength = glm::length(camera.up);
    if (!(upLength > 0.0) || glm::length(glm::cross(view / viewLength, camera.up / upLength)) < 1e-6) {
        invalid("up vector is zero or parallel to the view direction");
    }

    // Fit the clip planes to the bounding sphere so nothing is clipped and depth precision is spent on the model.
    const double distance = glm::length(camera.eye - sphere.center);
    camera.zFar = (distance + sphere.radius) * 1.01;
    if (!(camera.zFar > 0.0)) {
        camera.zFar = 1.0; // the eye sits on a point-sized scene
    }
    const double minNear = camera.zFar * kMinNearOverFar;
    camera.zNear = distance < sphere.radius ? minNear : std::max(distance - sphere.radius, minNear) * 0.99;
    return camera;
}

} // namespace inkgraph
