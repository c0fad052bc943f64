#pragma once
/** @file The camera of one still: where it comes from (flags, the file, or auto-framing) and its matrices.
 *  Conventions: right-handed world, OpenGL lookAt and perspective (the camera looks down -Z in view space). */

#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <optional>
#include <string>

namespace inkgraph {

/** What the user asked for; every unset field falls back to the glTF camera, then to auto-framing. */
struct CameraRequest {
    std::optional<glm::dvec3> eye;    ///< world coordinates (--eye)
    std::optional<glm::dvec3> target; ///< world coordinates (--target)
    /** World up (--up). Unset: the glTF camera's up when that camera is used, else (0, 1, 0). Set, it also wins over
     *  the glTF camera's up, and auto-framing looks at the model from a side chosen relative to it. */
    std::optional<glm::dvec3> up;
    std::optional<double> fovYDegrees; ///< vertical field of view; default 35
    /** --camera auto: the file's camera is not used at all (its placement, up and field of view); the view is
     *  auto-framed unless --eye places it. */
    bool ignoreFileCamera = false;
    /** Near and far clip distances (--clip); unset, both are fitted to the bounding sphere. */
    std::optional<double> zNear;
    std::optional<double> zFar;
    int width = 1024;
    int height = 1024;
};

/** A resolved camera in the scene's local frame (Scene::origin), the frame of the mesh positions: `eye`, `target` and
 *  viewMatrix() are what the renderer uses with the stored positions. For anything reported to the user (the
 *  manifest), use the world* functions, which add `origin` back. */
struct Camera {
    glm::dvec3 eye{0.0, 0.0, 1.0}; ///< local: world eye = origin + eye
    glm::dvec3 target{0.0};        ///< local: world target = origin + target
    /** The scene origin the camera was resolved for (Scene::origin): world = origin + local. */
    glm::dvec3 origin{0.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double fovYDegrees = 35.0;
    double zNear = 0.01;
    double zFar = 100.0;
    int width = 1024;
    int height = 1024;
    std::string source;                ///< "flags", "gltf" or "auto-framed"
    std::string clipSource = "fitted"; ///< "fitted" (to the bounding sphere) or "flags" (--clip)

    double aspect() const { return double(width) / double(height); }
    glm::dmat4 viewMatrix() const; ///< glm::lookAt(eye, target, up): local (scene-frame) points to view space
    glm::dvec3 worldEye() const { return origin + eye; }
    glm::dvec3 worldTarget() const { return origin + target; }
    /** viewMatrix() * translate(-origin): world points to view space, for reports. Its translation is as large as
     *  the world coordinates, so do not render with it in float. */
    glm::dmat4 worldViewMatrix() const;
    glm::dmat4 projectionMatrix() const; ///< glm::perspective(fovY, aspect, zNear, zFar)
    /** Focal length in pixels along y: (height/2) / tan(fovY/2). */
    double focalPixels() const;
};

/** Resolves a camera in the scene's local frame. The request's eye and target are world coordinates; scene.origin is
 *  subtracted (in double) and kept in Camera::origin. Precedence per field: the request, then the scene's glTF
 *  camera, then auto-framing, which looks at the bounding-sphere centre at the distance where the sphere fits the
 *  smaller field of view with a 5% margin, from the direction normalize(h + 0.25 u): u is the unit up, h the unit
 *  horizontal toward world +Z (or toward world -Y when |Z . u| > 0.9, so Z-up models are seen from the front), i.e.
 *  from the front and slightly above; for the default up (0, 1, 0) that is normalize(0, 0.25, 1). Near and far are
 *  fitted to the bounding sphere: far = distance to the centre + radius (x1.01); near = max(distance - radius, far
 *  x 1e-4) (x0.99), so the sphere is never clipped when the eye is outside it; a requested zNear and zFar replace both
 *  (finite, 0 < near < far, else std::invalid_argument naming --clip). Throws std::invalid_argument, with a message
 *  that names the flags involved (--eye, --target, --up, --fov, --size), for eye == target, a zero up or one
 *  parallel to the view direction, fov outside (0, 180), non-finite vectors, or a non-positive size. */
Camera resolveCamera(const CameraRequest& request, const Scene& scene);

} // namespace inkgraph
