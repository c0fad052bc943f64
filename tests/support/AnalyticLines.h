#pragma once
/** @file Analytic ground-truth lines for the shapes of SyntheticGBuffer.h (docs/accuracy.md), in double, for
 *  scoring line methods with postfx/LineMetrics.h. Every result is in LinePoint coordinates (pixels, x right, y down,
 *  pixel centres at integers: SyntheticCamera::project() - 0.5), holds only visible parts, and is cut where it
 *  leaves the image [-0.5, width - 0.5] x [-0.5, height - 0.5]. No GL. */

#include "postfx/LineMetrics.h"
#include "tests/support/SyntheticGBuffer.h"

#include <glm/glm.hpp>

#include <vector>

namespace inkgraph::test {

/** The torus of renderTorus() and its differential geometry (docs/accuracy.md), in its own frame (centre at the
 *  origin, axis z): P(u,v) = ((R + r cos v) cos u, (R + r cos v) sin u, r sin v), outward normal
 *  n = (cos v cos u, cos v sin u, sin v). Curvature signs follow trimesh2 (a sphere has +1/radius). */
struct TorusGeometry {
    double ring = 1.0; ///< R
    double tube = 0.4; ///< r, 0 < r < R

    glm::dvec3 point(double u, double v) const;
    glm::dvec3 normal(double u, double v) const;
    glm::dvec3 tangentU(double u) const;           ///< unit e_u
    glm::dvec3 tangentV(double u, double v) const; ///< unit e_v
    double curvatureU(double v) const;             ///< kappa_u = cos v / (R + r cos v)
    double curvatureV() const;                     ///< kappa_v = 1 / r
    /** (u, v) of a point on (or near) the torus, u and v in (-pi, pi]. */
    glm::dvec2 parameters(const glm::dvec3& p) const;
    /** |w|^2 kappa_r = kappa_u (w.e_u)^2 + kappa_v (w.e_v)^2 with w = v - (n.v) n and v = eye - P(u,v): what
     *  D_w(n.v) equals (docs/lines.md); smooth where kappa_r alone is not (w -> 0). `eye` in the torus frame. */
    double wSquaredRadialCurvature(const glm::dvec3& eye, double u, double v) const;
    /** kappa_r = II(w^, w^) for the view from `eye` (torus frame); NaN where w = 0. */
    double radialCurvature(const glm::dvec3& eye, double u, double v) const;
    /** D_w^ kappa_r: central difference (step `step` in length units) of kappa_r, each point with its own view
     *  vector, along w^ on the surface. */
    double radialCurvatureDerivative(const glm::dvec3& eye, double u, double v, double step = 1e-5) const;
};

/** The silhouette of a sphere: the tangency circle (centre c (1 - R^2 / d^2) from the eye, radius
 *  R sqrt(d^2 - R^2) / d, in the plane normal to c = center - eye, d = |c|), `samples` points, projected; one
 *  closed polyline when it lies wholly in the image. Throws std::invalid_argument naming the argument for a
 *  non-positive radius, an eye inside the sphere, a circle not wholly in front of the camera, or samples < 3. */
std::vector<LinePolyline> sphereSilhouette(const SyntheticCamera& camera, const glm::dvec3& center, double radius,
                                           int samples = 4096);

/** The visible contours (n.(E - P) = 0) of the torus of renderTorus(): per u of `uSamples`, the closed form
 *  v = atan2(B, A) +- acos(r / sqrt(A^2 + B^2)) with A = E_x cos u + E_y sin u - R, B = E_z (E the eye in the torus
 *  frame); a point is kept when intersectTorus() finds nothing on its eye ray more than 1e-6 (relative) before it
 *  (the ray grazes the torus at a contour, so "no earlier hit" is robust where "the first hit is this point" is
 *  not). Each branch is a polyline, split where it stops existing (sqrt(A^2 + B^2) < r), becomes hidden, jumps
 *  (|dv| > 0.2 between neighbouring u) or leaves the image; closed when nothing splits it.
 *  Throws std::invalid_argument naming the argument unless 0 < tubeRadius < ringRadius and uSamples >= 8. */
std::vector<LinePolyline> torusContours(const SyntheticCamera& camera, const glm::dvec3& center, double ringRadius,
                                        double tubeRadius, int uSamples = 8192);

/** A curve on the torus, for checking the ground truth itself: each vertex's surface parameters and its image. */
struct TorusCurve {
    std::vector<glm::dvec2> parameters; ///< (u, v) of each vertex, in radians (not wrapped)
    LinePolyline image;                 ///< the same vertices, in the same order, in LinePoint coordinates
};

/** torusContours() with each vertex's (u, v). */
std::vector<TorusCurve> torusContourCurves(const SyntheticCamera& camera, const glm::dvec3& center, double ringRadius,
                                           double tubeRadius, int uSamples = 8192);

/** The rule a suggestive-contour point must pass, in the units of SuggestiveSettings. */
struct AnalyticSuggestiveSettings {
    double featureSize = 1.0; ///< fs, scene length units
    /** Keep where q = fs^2 tan(theta) D_w^ kappa_r > threshold (SuggestiveSettings::threshold); 0 keeps every point
     *  with D_w^ kappa_r > 0. */
    double threshold = 0.0;
    double minSinTheta = 0.1; ///< drop near-frontal points, sin(theta) = |w| / |v| below this
};

/** The visible suggestive contours of the torus of renderTorus() (DeCarlo et al. Def. I, v = eye - P per point):
 *  the zero set of |w|^2 kappa_r (the sign of kappa_r sin^2 theta) traced by marching squares over a periodic
 *  (u, v) grid of uSamples x vSamples, every vertex on a grid edge refined by bisection to double precision; a vertex
 *  is kept where n.v > 0, sin(theta) >= minSinTheta, D_w^ kappa_r > 0 (central difference, h = 1e-5), q passes the
 *  threshold, nothing hides it (as torusContours) and it lies in the image; polylines split at dropped vertices.
 *  Throws std::invalid_argument naming the argument for a bad torus, sample counts < 8, a non-positive
 *  featureSize, a negative or non-finite threshold, or minSinTheta outside [0, 1). */
std::vector<LinePolyline> torusSuggestiveContours(const SyntheticCamera& camera, const glm::dvec3& center,
                                                  double ringRadius, double tubeRadius,
                                                  const AnalyticSuggestiveSettings& settings, int uSamples = 4096,
                                                  int vSamples = 1024);

/** torusSuggestiveContours() with each vertex's (u, v). */
std::vector<TorusCurve> torusSuggestiveContourCurves(const SyntheticCamera& camera, const glm::dvec3& center,
                                                     double ringRadius, double tubeRadius,
                                                     const AnalyticSuggestiveSettings& settings, int uSamples = 4096,
                                                     int vSamples = 1024);

/** A sphere seen from a camera, for the contour's analytic tests (a circle or an ellipse in the image). */
struct SphereCase {
    glm::dvec3 eye;
    glm::dvec3 target;
    glm::dvec3 center;
    double radius;
};
/** The spheres the contour kernels are scored on, CPU and GPU alike. */
inline const SphereCase kSphereCases[] = {
    {{0.0, 0.0, 4.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, 1.0},    // on axis, d = 4 R
    {{0.3, -0.2, 5.0}, {0.0, 0.0, 0.0}, {0.9, -0.6, -0.4}, 0.6}, // off axis: an ellipse
};

} // namespace inkgraph::test
