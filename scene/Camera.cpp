#include "scene/Camera.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace inkgraph {

namespace {

constexpr double kDefaultFovYDegrees = 35.0;
const glm::dvec3 kDefaultUp(0.0, 1.0, 0.0);
/** Auto-framing looks from the model's front, raised by this much of the up vector so tops of models read as tops. */
constexpr double kAutoFrameLift = 0.25;
/** When world +Z lies this close to up (|Z . u| above it), the front is world -Y instead (Z-up CAD and STL models). */
constexpr double kMaxFrontAlongUp = 0.9;
constexpr double kFramingMargin = 1.05;
/** Near never drops below far x this, which bounds depth-buffer precision loss when the eye is close or inside. */
constexpr double kMinNearOverFar = 1e-4;

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

[[noreturn]] void invalid(const std::string& problem) { throw std::invalid_argument("resolveCamera(): " + problem); }

/** "x,y,z", the syntax of the vector flags. */
std::string formatVector(const glm::dvec3& v) {
    std::ostringstream text;
    text << v.x << ',' << v.y << ',' << v.z;
    return text.str();
}

std::string formatNumber(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

/** Distance at which a sphere of `radius` fits the narrower of the vertical and horizontal fields of view. */
double framingDistance(double radius, double fovYRadians, double aspect) {
    const double fovXRadians = 2.0 * std::atan(std::tan(fovYRadians / 2.0) * aspect);
    return kFramingMargin * radius / std::sin(std::min(fovYRadians, fovXRadians) / 2.0);
}

/** Unit direction from the target toward the auto-framed eye: the front (world +Z, or world -Y when +Z is nearly
 *  along up) made perpendicular to up, then lifted by kAutoFrameLift x up. `up` must be non-zero and finite. For up
 *  (0, 1, 0) every step is exact, giving exactly normalize(0, 0.25, 1). */
glm::dvec3 autoFrameDirection(const glm::dvec3& up, const std::optional<glm::dvec3>& modelFront) {
    const glm::dvec3 u = glm::normalize(up);
    glm::dvec3 front = modelFront.value_or(glm::dvec3(0.0, 0.0, 1.0));
    if (std::abs(glm::dot(front, u)) > kMaxFrontAlongUp) {
        front = glm::dvec3(0.0, -1.0, 0.0); // |Y . u| < sqrt(1 - 0.9^2) here, so the projection below is not short
    }
    const glm::dvec3 horizontal = glm::normalize(front - glm::dot(front, u) * u);
    return glm::normalize(horizontal + kAutoFrameLift * u);
}

} // namespace

glm::dmat4 Camera::viewMatrix() const { return glm::lookAt(eye, target, up); }

glm::dmat4 Camera::worldViewMatrix() const { return viewMatrix() * glm::translate(glm::dmat4(1.0), -origin); }

glm::dmat4 Camera::projectionMatrix() const {
    return glm::perspective(glm::radians(fovYDegrees), aspect(), zNear, zFar);
}

double Camera::focalPixels() const { return (double(height) / 2.0) / std::tan(glm::radians(fovYDegrees) / 2.0); }

Camera resolveCamera(const CameraRequest& request, const Scene& scene) {
    if (request.width <= 0 || request.height <= 0) {
        invalid("the image size " + std::to_string(request.width) + "x" + std::to_string(request.height) +
                " (--size) must be positive");
    }
    const auto requireFinite = [](const std::optional<glm::dvec3>& vector, const char* flag) {
        if (vector && !isFinite(*vector)) {
            invalid(std::string(flag) + " " + formatVector(*vector) + " must be finite");
        }
    };
    requireFinite(request.eye, "--eye");
    requireFinite(request.target, "--target");
    requireFinite(request.up, "--up");

    Camera camera;
    camera.width = request.width;
    camera.height = request.height;
    camera.origin = scene.origin;
    // The user speaks world coordinates; the scene and the renderer work relative to the scene origin. Messages show
    // world values (what the user typed), so `world` converts back.
    const std::optional<glm::dvec3> requestEye =
        request.eye ? std::optional<glm::dvec3>(*request.eye - scene.origin) : std::nullopt;
    const std::optional<glm::dvec3> requestTarget =
        request.target ? std::optional<glm::dvec3>(*request.target - scene.origin) : std::nullopt;
    const auto world = [&](const glm::dvec3& local) { return formatVector(scene.origin + local); };

    // The file's field of view is a property of its lens and applies whoever places the camera; its placement
    // (eye, orientation) is one unit that an explicit eye replaces entirely.
    const SceneCamera* sceneCamera = scene.camera && !request.ignoreFileCamera ? &*scene.camera : nullptr;
    camera.fovYDegrees = request.fovYDegrees ? *request.fovYDegrees
                         : sceneCamera       ? sceneCamera->fovYDegrees
                                             : kDefaultFovYDegrees;
    const SceneCamera* fileCamera = !request.eye ? sceneCamera : nullptr;
    if (!std::isfinite(camera.fovYDegrees) || camera.fovYDegrees <= 0.0 || camera.fovYDegrees >= 180.0) {
        const std::string fov = formatNumber(camera.fovYDegrees);
        invalid(request.fovYDegrees
                    ? "the vertical field of view (--fov " + fov + ") is outside (0, 180) degrees"
                    : "the glTF camera's vertical field of view " + fov + " degrees is outside (0, 180); set --fov");
    }

    // Unset, up follows the glTF camera when that camera places the view; an explicit --up always wins.
    camera.up = request.up ? *request.up : fileCamera ? fileCamera->up : kDefaultUp;
    const std::string upText = request.up ? "--up " + formatVector(camera.up)
                               : fileCamera
                                   ? "the glTF camera's up " + formatVector(camera.up) + "; override it with --up"
                                   : "the default " + formatVector(camera.up) + " without --up";
    if (!(glm::length(camera.up) > 0.0)) {
        invalid("the up vector (" + upText + ") is zero");
    }

    const BoundingSphere sphere = computeBoundingSphere(scene);
    const std::string centreText = "the model's bounding-sphere centre (" + world(sphere.center) + ")";
    // A point-sized scene still needs a usable framing distance.
    const double radius = sphere.radius > 0.0 ? sphere.radius : 1.0;

    // Each branch also says, for the error messages below, where its eye, target and view direction come from.
    std::string eyeText;
    std::string targetText;
    std::string viewText;
    if (requestEye) {
        camera.eye = *requestEye;
        camera.target = requestTarget ? *requestTarget : sphere.center;
        camera.source = "flags";
        eyeText = "the eye (--eye " + formatVector(*request.eye) + ")";
        targetText = request.target ? "the target (--target " + formatVector(*request.target) + ") coincide"
                                    : "the target coincide; without --target the target is " + centreText;
        viewText = "from --eye to " + (request.target ? std::string("--target") : centreText);
    } else if (fileCamera) {
        camera.eye = fileCamera->eye;
        if (requestTarget) {
            camera.target = *requestTarget;
        } else {
            // Only the direction matters to lookAt; aim at the depth of the model so the target is meaningful.
            const double depth = glm::length(sphere.center - fileCamera->eye);
            camera.target = fileCamera->eye + fileCamera->forward * (depth > 0.0 ? depth : 1.0);
        }
        camera.source = "gltf";
        eyeText = "the glTF camera's eye (" + world(camera.eye) + "; override it with --eye)";
        targetText = request.target ? "the target (--target " + formatVector(*request.target) + ") coincide"
                                    : "its target coincide";
        viewText = request.target ? "from the glTF camera's eye to --target"
                                  : "the glTF camera's forward " + formatVector(fileCamera->forward);
    } else {
        camera.target = requestTarget ? *requestTarget : sphere.center;
        camera.eye = camera.target + autoFrameDirection(camera.up, scene.front) *
                                         framingDistance(radius, glm::radians(camera.fovYDegrees), camera.aspect());
        camera.source = "auto-framed";
        eyeText = "the auto-framed eye (" + world(camera.eye) + ")";
        targetText = (request.target ? "the target (--target " + formatVector(*request.target) + ")"
                                     : "the target, " + centreText + ",") +
                     " coincide: the model is too small for its distance from the origin; set --eye";
        viewText = "the auto-framing direction";
    }

    const glm::dvec3 view = camera.target - camera.eye;
    const double viewLength = glm::length(view);
    if (!(viewLength > 1e-12 * std::max(1.0, glm::length(camera.eye)))) {
        invalid(eyeText + " and " + targetText);
    }
    if (glm::length(glm::cross(view / viewLength, glm::normalize(camera.up))) < 1e-6) {
        invalid("the up vector (" + upText + ") is parallel to the view direction (" + viewText + ")");
    }

    // Fit the clip planes to the bounding sphere so nothing is clipped and depth precision is spent on the model. The
    // planes are perpendicular to the view axis, so the sphere's nearest depth is its centre's depth along that axis
    // less the radius: with the model off the axis (--target elsewhere) the centre's distance would put the near
    // plane behind the front of the sphere and clip a cap off it.
    const double distance = glm::length(camera.eye - sphere.center);
    const double centreDepth = glm::dot(sphere.center - camera.eye, view / viewLength);
    camera.zFar = (distance + sphere.radius) * 1.01;
    if (!(camera.zFar > 0.0)) {
        camera.zFar = 1.0; // the eye sits on a point-sized scene
    }
    const double minNear = camera.zFar * kMinNearOverFar;
    const double nearestDepth = centreDepth - sphere.radius;
    camera.zNear = distance < sphere.radius || !(nearestDepth > 0.0) ? minNear : std::max(nearestDepth, minNear) * 0.99;
    if (request.zNear || request.zFar) {
        if (!request.zNear || !request.zFar) {
            invalid("--clip needs both the near and the far distance");
        }
        const double n = *request.zNear;
        const double f = *request.zFar;
        if (!std::isfinite(n) || !std::isfinite(f) || !(n > 0.0) || !(n < f)) {
            invalid("--clip " + formatNumber(n) + "," + formatNumber(f) + " must be finite with 0 < near < far");
        }
        camera.zNear = n;
        camera.zFar = f;
        camera.clipSource = "flags";
    }
    return camera;
}

} // namespace inkgraph
