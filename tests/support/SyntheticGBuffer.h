#pragma once
/** @file G-buffers of analytic surfaces, ray cast in double on the CPU, with the same conventions as the GL
 *  G-buffer pass (passes/gbuffer/GBufferPass.h), so the post stage is tested and benchmarked without a context.
 *  Pinhole camera at `eye` looking at `target` (OpenGL lookAt with `up`, vertical field of view `fovYDegrees`),
 *  rows top-down, one ray through each pixel centre, background all zero. */

#include <glm/glm.hpp>
#include <opencv2/core.hpp>

#include <optional>

namespace inkgraph::test {

/** A world-space ray with a unit direction. */
struct SyntheticRay {
    glm::dvec3 origin;
    glm::dvec3 direction;
};

struct SyntheticCamera {
    int width = 512;
    int height = 512;
    glm::dvec3 eye{0.0, 0.0, 4.0};
    glm::dvec3 target{0.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double fovYDegrees = 35.0;

    double focalPixels() const; ///< (height / 2) / tan(fovY / 2)
    glm::dmat4 view() const;    ///< glm::lookAt(eye, target, up): world -> view space

    /** The ray from the eye through an image point in pixels: x right, y down, origin at the image's top-left
     *  corner, so pixel (col, row) has its centre at (col + 0.5, row + 0.5). */
    SyntheticRay rayThrough(const glm::dvec2& imagePoint) const;
    /** A world point in front of the camera -> its image point, in the units of rayThrough(). */
    glm::dvec2 project(const glm::dvec3& worldPoint) const;
    /** Throws std::invalid_argument after "`function`: " unless the size is positive, fovYDegrees lies in (0, 180),
     *  eye != target and `up` is not along the view direction. */
    void check(const char* function) const;
};

/** The fields a post-stage kernel reads, all CV_32F, width x height. */
struct SyntheticGBuffer {
    cv::Mat normal; ///< CV_32FC4: unit view-space normal, a = 1 on the model
    cv::Mat nDotV;  ///< CV_32FC1: n . v with the unit view vector
    cv::Mat depth;  ///< CV_32FC1: linear view depth (distance along -z), 0 = background
    cv::Mat radial; ///< CV_32FC4: (n . (c - p), (J w).x, (J w).y, |w|^2) with v = c - p unnormalised and J the
                    ///< projection Jacobian in pixels, x right and y down: J w = -(n . v) J n
};

/** Sphere of `radius` at `center` (world). */
SyntheticGBuffer renderSphere(const SyntheticCamera& camera, const glm::dvec3& center, double radius);

/** Torus around the world z axis through `center`: ring radius `ringRadius` (R), tube radius `tubeRadius` (r);
 *  P(u,v) = center + ((R + r cos v) cos u, (R + r cos v) sin u, r sin v). */
SyntheticGBuffer renderTorus(const SyntheticCamera& camera, const glm::dvec3& center, double ringRadius,
                             double tubeRadius);

/** Distance along `ray` to its first hit with the torus of renderTorus(), if any: the first root of the exact
 *  quartic, isolated between the roots of its derivatives, so thin grazing hits are found (error ~1e-12). */
std::optional<double> intersectTorus(const SyntheticRay& ray, const glm::dvec3& center, double ringRadius,
                                     double tubeRadius);

/** Infinite plane through `point` with unit `normal` (seen from either side; the normal turns toward the eye). */
SyntheticGBuffer renderPlane(const SyntheticCamera& camera, const glm::dvec3& point, const glm::dvec3& normal);

} // namespace inkgraph::test
