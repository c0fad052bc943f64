#pragma once
/** @file The camera of one still: where it comes from (flags, the file, or auto-framing) and its matrices.
 *  Conventions: right-handed world, OpenGL lookAt and perspective (the camera looks down -Z in view space). */

#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** A view around the target (--orbit): the eye on a sphere about it, angles from the model's front. */
struct Orbit {
    /** Degrees about the up vector from the front (the side auto-framing looks from). Positive moves the eye toward
     *  the front view's right: counter-clockwise seen from above, so with up +Y and the front +Z, 90 looks from +X. */
    double azimuthDegrees = 0.0;
    /** Degrees above the plane through the target perpendicular to up, within [-89.9, 89.9]: at +-90 up would be
     *  parallel to the view. */
    double elevationDegrees = 0.0;
    std::optional<double> distance; ///< world units from the target; unset: the auto-framing distance
    /** With `distance` unset: the eye at this multiple of the auto-framing distance (--orbit AZ,EL,xS; --views'
     *  distance jitter). Positive and finite. */
    double distanceScale = 1.0;
};

/** What the user asked for; every unset field falls back to the glTF camera, then to auto-framing. */
struct CameraRequest {
    std::optional<glm::dvec3> eye;    ///< world coordinates (--eye)
    std::optional<Orbit> orbit;       ///< --orbit; places the eye, so not together with `eye`
    std::optional<glm::dvec3> target; ///< world coordinates (--target)
    /** World up (--up). Unset: the glTF camera's up when that camera is used, else (0, 1, 0). Set, it also wins over
     *  the glTF camera's up, and auto-framing looks at the model from a side chosen relative to it. */
    std::optional<glm::dvec3> up;
    /** Vertical field of view. Unset: the glTF camera's when that camera places the view, else 35 (a view placed
     *  by --eye, --orbit or --frame does not take the file camera's lens). */
    std::optional<double> fovYDegrees;
    /** --frame: node names (Mesh::nodePath); the framing (the default target, the auto-framing and --orbit
     *  distance) fits only the meshes under these nodes, and the file camera does not place the view. The clip
     *  planes still fit the whole scene. Empty: every mesh. */
    std::vector<std::string> frameNodes;
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
    std::string source;                ///< "flags" (--eye), "orbit", "gltf" or "auto-framed"
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
    /** OpenCV's intrinsic matrix K, for pixel coordinates (u, v) with u right, v down and the centre of pixel (col,
     *  row), row 0 at the top, at (col, row) (the manifest's and OpenGL's convention puts it at (col + 0.5, row +
     *  0.5), hence the half pixel): fx = fy = focalPixels(), cx = width/2 - 0.5, cy = height/2 - 0.5, no skew.
     *  glm is column-major: K[column][row], so K[2] = (cx, cy, 1) and K[2][0] = cx. With openCvExtrinsics() [R|t],
     *  a world point X lands on (u, v) = (x/z, y/z) for (x, y, z) = K (R X + t), where z is the linear view depth
     *  gbuffer.depth holds; so X = R^T (depth K^-1 (u, v, 1) - t). */
    glm::dmat3 openCvIntrinsics() const;
    /** OpenCV's extrinsics [R|t]: world coordinates (origin + local) to OpenCV's camera frame, x right, y down, z
     *  forward, which is view space (viewMatrix()) with y and z negated. glm's 4 columns of 3: columns 0 to 2 are R
     *  (R[column][row]), column 3 is t. R is viewMatrix()'s rotation with its second and third rows negated; t =
     *  -R worldEye(), from the world eye in double rather than from worldViewMatrix(), so an origin of 1e7 costs t
     *  no more than double rounding (about 1e-9 there). */
    glm::dmat4x3 openCvExtrinsics() const;
};

/** Resolves a camera in the scene's local frame. The request's eye and target are world coordinates; scene.origin is
 *  subtracted (in double) and kept in Camera::origin. Precedence per field: the request, then the scene's glTF
 *  camera, then auto-framing, which looks at the framed bounding-sphere centre (the whole scene's, or with
 *  frameNodes that of the meshes under them) at the distance where that sphere fits the smaller field of view with a
 *  5% margin, from the direction normalize(h + 0.25 u): u is the unit up, h the unit horizontal toward the model's
 *  front (Scene::front, else world +Z; world -Y when that is within |. u| > 0.9 of up, so Z-up models are seen from
 *  the front as in Blender), i.e. from the front and slightly above; for the default up (0, 1, 0) that is
 *  normalize(0, 0.25, 1), an orbit of azimuth 0 and elevation atan(0.25) = 14.04 degrees. An orbit puts the eye at
 *  target + distance x (cos e (cos a h + sin a (u x h)) + sin e u), its distance else the auto-framing distance times
 *  its distanceScale. A view placed by the request (eye, orbit or
 *  frameNodes) does not use the file camera at all, its field of view included. Near and far are fitted to the whole
 *  bounding sphere: far = distance to the centre + radius (x1.01); near = max(depth of the sphere's front along the
 *  view axis, far x 1e-4) (x0.99), so the sphere is never clipped when the eye is outside it; a requested zNear and
 *  zFar replace both (finite, 0 < near < far, else std::invalid_argument naming --clip). Throws
 *  std::invalid_argument, with a message that names the flags involved (--eye, --orbit, --frame, --target, --up,
 *  --fov, --size), for eye == target, an eye with an orbit, an orbit elevation outside [-89.9, 89.9] or a
 *  non-positive distance, a zero up or one within 0.05 degrees of the view direction, fov outside (0, 180),
 *  non-finite values, or a non-positive size; SceneError for a frame name that no mesh lies under and no joint or
 *  bone has (naming up to 10 of the scene's node names, bones and joints: the model lacks it), or whose meshes and
 *  joints have no vertices. */
Camera resolveCamera(const CameraRequest& request, const Scene& scene);

/** Where a still samples its model, for modelOutsideView(). */
struct PictureSampling {
    int supersample = 1; ///< --supersample: the data buffers' pixels per output pixel, each way
    int msaaSamples = 1; ///< --msaa: the shading's samples per pixel
    /** Lines drawn from the mesh itself (outline, silhouette, mesh edges, MToon's outline shells) show a model under a
     *  pixel wide as a line of its length, whatever samples its surface covers. */
    bool linesDrawTheMesh = false;
};

/** A warning when `camera` shows none of `scene`'s model, which would render blank paper: every vertex lies behind the
 *  eye, beyond one side of the view (left, right, above or below), nearer than the near plane or beyond the far one;
 *  or what lies beyond the near plane (the vertices there and the corners the plane cuts from the triangles) holds no
 *  place the picture samples (an eye far away, a sliver under a pixel wide between two columns of pixels, an eye at
 *  the model's edge looking away with what lies before it beside the picture, or a wide view whose eye has the rest
 *  of the scene behind it). The places are the centres of the pixels, `supersample` times as many each way with
 *  --supersample; with --msaa (`msaaSamples` over 1), every point of a grid of 1/16 pixel, where GL's sample
 *  positions lie, so no picture that shows a sample is warned about. With `linesDrawTheMesh` only a model under a
 *  pixel both ways is judged (a sliver's lines draw it, and bands beside the picture may reach into it).
 *  It names where the view comes from (the glTF camera by its name, --eye, --orbit, auto-framing; --clip for the
 *  planes it set). Empty when some of the model may show. A model beside a corner of the view, outside the view but
 *  on the inner side of each of its planes, is caught only where its projected box misses every sample. A
 *  model-outside-view warning without a file: the camera does not know it. */
std::optional<Warning> modelOutsideView(const Camera& camera, const Scene& scene, const PictureSampling& sampling = {});

} // namespace inkgraph
