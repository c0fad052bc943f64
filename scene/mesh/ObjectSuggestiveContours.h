#pragma once
/** @file Suggestive contours in object space (DeCarlo et al. 2003 with rtsc's per-view test, docs/lines.md):
 *  per view, the zero set of the radial curvature on the mesh, kept where the surface faces the eye and the
 *  strength passes the threshold. No GL; all in double. The mesh's curvature (MeshCurvature.h) is computed once and
 *  reused for every view.
 *
 *  The strength is the image-space kernel's (postfx/SuggestiveContours.h), so `--suggestive-threshold` and
 *  `--suggestive-fade` mean the same for both line types: q = fs^2 tan(theta) D_w^ kappa_r, kept where q > T,
 *  drawn with alpha (q - T) / (q - T + F). */

#include "scene/mesh/MeshCurvature.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace inkgraph {

/** The app's default curvature smoothing (`--suggestive-object-smoothing`, computeMeshCurvature()'s smoothing), sigma
 *  as a fraction of the bounding radius. */
constexpr double kSuggestiveObjectSmoothingFraction = 0.01;

struct ObjectSuggestiveSettings {
    /** Feature size fs in the mesh's length units (rtsc's): makes the strength dimensionless. The app uses
     *  0.05 x the bounding radius, as for the image-space lines. */
    double featureSize = 1.0;
    double threshold = 0.01; ///< keep where q > threshold (rtsc's sug_thresh); >= 0
    /** > 0: strength (q - threshold) / (q - threshold + fade), rtsc's fade; 0: full strength. >= 0. */
    double fade = 0.03;
};

/** The per-view quantities of every welded vertex (rtsc's compute_perview), with u = v^.e1, v = v^.e2 for the unit
 *  vector v^ from the vertex to the eye, so u^2 + v^2 = sin^2(theta). */
struct SuggestiveViewField {
    /** kr = kappa1 u^2 + kappa2 v^2 = kappa_r sin^2(theta): the radial curvature without the division, so it is
     *  finite and zero where the view is frontal. Its zero set is the suggestive contour generator's candidate set. */
    std::vector<double> radialCurvature;
    /** fs^2 (sin(theta) C(w^, w^, w^) - 2 cos(theta) tau_r^2), tau_r = (kappa2 - kappa1) u v / sin^2(theta), so
     *  numerator / denominator = q = fs^2 (tan(theta) C(w^, w^, w^) - 2 tau_r^2) = fs^2 tan(theta) D_w^ kappa_r.
     *  Where sin^2(theta) < 1e-20 (v^ along the normal: w^ has no direction, rtsc's 1/(u^2 + v^2) is Inf or NaN) it
     *  is 0, the limit of the C term; the tau term has no limit there, and 0 is the bounded choice (q = 0 <= T). */
    std::vector<double> numerator;
    std::vector<double> denominator; ///< cos(theta) = n . v^: positive where the vertex faces the eye
};

/** One piece of suggestive contour on one face, between two points on its edges (or where it was cut). */
struct SuggestiveSegment {
    std::array<glm::dvec3, 2> ends;  ///< in the mesh's space
    std::array<double, 2> strengths; ///< alpha at each end, in [0, 1]: 0 where the piece was cut at the threshold
    std::uint32_t face;              ///< index into MeshCurvature::triangles
};

/** The per-view field for the eye at `eye` (the mesh's space). Throws std::invalid_argument naming 'eye' when it is
 *  not finite and 'featureSize' unless it is positive and finite. Every value is finite. */
SuggestiveViewField computeSuggestiveViewField(const MeshCurvature& curvature, const glm::dvec3& eye,
                                               double featureSize);

/** The suggestive contours seen from `eye`: on each face where kr changes sign, the segment between the linear zero
 *  crossings on its two edges (rtsc's linear mode, kr < 0 against kr >= 0, so a face of exact zeros, a plane, has
 *  none), with the numerator and denominator interpolated linearly along it and the segment cut where
 *  numerator - T x denominator or the denominator crosses zero, keeping the parts where both are positive: the
 *  strength passes the threshold and the surface faces the eye (n . v > 0). A vertex exactly at the eye has
 *  v^ = 0, so kr = 0 and no line. Throws std::invalid_argument naming the setting or 'eye' for a non-finite value,
 *  a non-positive feature size, or a negative threshold or fade. */
std::vector<SuggestiveSegment> extractObjectSuggestiveContours(const MeshCurvature& curvature, const glm::dvec3& eye,
                                                               const ObjectSuggestiveSettings& settings);

} // namespace inkgraph
