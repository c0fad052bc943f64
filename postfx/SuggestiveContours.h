#pragma once
/** @file Suggestive contours in image space (DeCarlo et al. 2003): D_w(n.v) = 0 with D_w D_w(n.v) > 0, by central
 *  differences in float32, with v = c - p unnormalised so the zero set is exactly kappa_r = 0 (docs/lines.md). */

#include "postfx/LineSkeleton.h"

namespace inkgraph {

/** The finite-difference stencil of both derivatives along w. */
enum class DifferenceStencil {
    /** (f(x+1) - f(x-1)) / 2: second order, the fast banded SIMD scanner (the default). */
    Central3,
    /** (-f(x+2) + 8 f(x+1) - 8 f(x-1) + f(x-2)) / 12: fourth order, but it needs two pixels of one surface on every
     *  side and amplifies data noise ~1.4x more (the sum of |weights| is 1.5 vs 1); a plain full-image path, slower.
     *  Kept to measure the trade (bench/TradeoffSweep). */
    Central5,
};

/** The app's default smoothing (`--suggestive-smoothing`), sigma as a fraction of the bounding radius: on the scanned
 *  models (docs/lines.md) it leaves the shape's lines and drops the bumps'. */
constexpr double kSuggestiveSmoothingFraction = 0.005;

/** The least angle, in degrees, at which a suggestive contour may cross the image's w direction
 *  (SuggestiveSettings::minAngleToW, `--suggestive-min-angle`). */
constexpr float kSuggestiveMinAngleToWDegrees = 15.0f;

struct SuggestiveSettings {
    /** Pixels with sin(theta) = |w| / |v| below this are skipped: near-frontal, w has no direction there, and
     *  n.v is at a maximum so no suggestive contour can pass. Noise in n.v makes points there otherwise (a sphere
     *  at 2048^2 with 3e-5 relative noise: 264 points at 0, none from 0.05 up). */
    float minSinTheta = 0.1f;
    /** Feature size fs in the scene's length units (rtsc's): makes the strength dimensionless. */
    float featureSize = 1.0f;
    /** Keep a crossing only where its strength q = fs^2 D_w D_w(n.v) / (|w|^2 n.v) exceeds this. q equals rtsc's
     *  fs^2 tan(theta) D_w^ kappa_r at kappa_r = 0. 0 keeps every crossing with D_w D_w(n.v) > 0. The default is
     *  rtsc's sug_thresh, for fs = 0.05 x the bounding radius: on a torus it keeps 85% of the zero set of kappa_r
     *  (the weakest, fastest-sliding ends go) and removes most points made by noise in n.v. */
    float threshold = 0.01f;
    /** > 0: each point's strength is (q - threshold) / (q - threshold + fade), rtsc's fade, so a line grows in from
     *  nothing instead of popping in; 0: full strength. The default is rtsc's. */
    float fade = 0.03f;
    /** Degrees: a crossing is kept only where the line it lies on crosses the image's w direction at least at this
     *  angle (the gradient of D_w(n.v) at least this far from perpendicular to J w at both pixels of the pair).
     *  D_w D_w(n.v) is the gradient of D_w(n.v) dotted with J w, so where a line runs nearly along w it is a small
     *  difference of large terms, and the differences' error decides its sign: such lines come and go with the
     *  sub-pixel phase, so with the size and a small turn of the view (docs/strokes.md). 0: every crossing with
     *  D_w D_w(n.v) > 0 (the plain test of DeCarlo et al.). */
    float minAngleToW = kSuggestiveMinAngleToWDegrees;
    float depthJump = 0.05f; ///< no difference is taken across a relative depth jump larger than this
    DifferenceStencil stencil = DifferenceStencil::Central3;
    /** > 0: the radial field is smoothed first (smoothRadialField()) by a Gaussian of this standard deviation on the
     *  surface, in the depth buffer's length units (the model's), so the derivatives see the surface at that scale,
     *  not its facets and scan noise, alike at every resolution (the stencil's own blur counted in). 0: no
     *  smoothing. */
    float smoothing = 0.0f;
    /** With smoothing > 0: a crossing is dropped where its surface ends (a depth break, the background or the image's
     *  edge) within this many sigmas of the smoothing, in pixels at the marked pixel's depth, where the smoothing's
     *  window sees one side only. The band is the same patch of surface at every resolution, as the stencil's own
     *  margin is (two pixels at 1024 rows, the same share of the height above; extractSuggestiveContours()), but
     *  measured in sigmas, so it reaches as far as the smoothing does. 0 (the default): no band beyond the
     *  stencil's. At 2 the lines hold better across sizes and about as well or a little worse across a 1 degree turn
     *  (docs/strokes.md), so it is a choice, not the default. */
    float breakClearance = 0.0f;
    /** With smoothing > 0 and surface ids (extractSuggestiveContours()'s `surface`): a crossing is dropped within this
     *  many sigmas of the smoothing of where its smooth patch meets another patch (parts that overlap or are set into
     *  one another, a hard edge), in pixels at the marked pixel's depth. The smoothing and the differences stop
     *  there, so the window sees one side only, as at any end of a surface; unlike at an outline, where suggestive
     *  contours run on into the contours they meet, no line runs on into such a seam, so the band takes only pieces
     *  whose ends the sampling decides: a line along a top's hem over a skirt, drawn whole at 2048^2 and in hooks at
     *  1024^2 (docs/strokes.md). 0: no band beyond the stencil's. */
    float patchClearance = 2.0f;
    /** The camera's focal length in pixels of this image, (height / 2) / tan(fovY / 2): converts `smoothing` to
     *  pixels, smoothing x focalPixels / depth at each pixel. Read only when smoothing > 0; then > 0. */
    float focalPixels = 0.0f;
};

/** The radial field smoothed on the surface at the scale settings.smoothing (> 0; 0 returns a copy): per pixel a
 *  Gaussian of sigma = smoothing x focalPixels / depth pixels (the model-space scale seen at that pixel's depth),
 *  rounded to 1% steps, its variance then less the blur settings.stencil's difference adds (1/3 px^2 for Central3,
 *  whose (f(x+1) - f(x-1)) / 2 answers a wave of k radians a pixel with sin(k) / k = 1 - k^2 / 6 + ..., a Gaussian's
 *  of that variance; none for Central5) and at least 1/16 px^2, so D_w(n.v), whose zero set is the line, sees sigma
 *  on the surface at every resolution, not a share of a pixel more where the pixels are coarse (docs/strokes.md);
 *  applied along rows then columns, each 1-D pass a Gaussian-weighted least-squares line (local linear regression)
 *  over the pixel's run of one surface: it stops at depth breaks (settings.depthJump), changes of
 *  `surface` id (computeRadialDerivatives()) and the background, and a field linear along the run is kept exactly, so
 *  a one-sided window at a silhouette or occlusion boundary does not bend n.v there. The window reaches 3 sigma, at
 *  most kMaxSmoothingReach pixels. All four channels are smoothed; the background stays 0. Same argument checks as
 *  extractSuggestiveContours(). */
cv::Mat smoothRadialField(const cv::Mat& radial, const cv::Mat& depth, const SuggestiveSettings& settings,
                          const cv::Mat& surface = cv::Mat());

/** The widest reach of smoothRadialField()'s window in pixels, so an eye inside the model's feature scale cannot make
 *  a kernel as wide as the image. */
constexpr int kMaxSmoothingReach = 256;

/** Per-pixel derivatives along w, for tests and the kernel. */
struct RadialDerivatives {
    /** CV_32FC1: D_w(n.v), central differences (settings.stencil) of n.(c - p) dotted with the image-space J w; 0
     *  where a difference would leave the pixel's surface (depth break, background, image edge). */
    cv::Mat dw;
    cv::Mat dwdw; ///< CV_32FC1: D_w D_w(n.v), central differences of dw along J w; 0 where not valid
    /** CV_8UC1: 255 where dwdw is defined: dw is defined at every neighbour the stencil reads (so every difference
     *  lies on one surface), n.v > 0 and sin(theta) >= minSinTheta. */
    cv::Mat valid;
};

/** `radial`: CV_32FC4 per pixel (n.(c - p) unnormalised, (J w).x, (J w).y, |w|^2), where J is the projection's
 *  Jacobian in pixels (x right, y down) and w = v - (n.v) n with v = c - p; zero off the model.
 *  `depth`: CV_32FC1 linear view depth, 0 = background; same size.
 *  `surface`: empty, or CV_32FC1 of the same size holding a surface id per covered pixel (any value off the model):
 *  two pixels of different ids are not of one surface, as if a depth break lay between them. Where the normal field
 *  steps (a hard edge, two parts meeting) n.v is not differentiable, so a renderer gives each smooth patch its own id
 *  (passes/GpuScene.h surfacePatches()). The same argument of smoothRadialField() and extractSuggestiveContours().
 *  No difference is taken across a depth break, a change of surface id or the background; pixels with
 *  sin(theta) < minSinTheta or n.v <= 0 are invalid. With settings.smoothing > 0 the derivatives are those of
 *  smoothRadialField(). */
RadialDerivatives computeRadialDerivatives(const cv::Mat& radial, const cv::Mat& depth,
                                           const SuggestiveSettings& settings, const cv::Mat& surface = cv::Mat());

/** Zero crossings of D_w(n.v) between valid 4-neighbours (the pixel with the smaller |D_w(n.v)| marked, the point
 *  at the linear crossing, no half-pixel shift), kept where D_w D_w(n.v) > 0 and the strength passes the threshold,
 *  both interpolated to the crossing. The result does not depend on the resolution: J w scales with it and the
 *  differences per pixel inversely. Above 1024 rows a crossing keeps the second difference's reach at 1024 rows (2
 *  pixels, 4 for Central5) from where its surface ends as the same share of the height (4 pixels at 2048 rows), as
 *  the stencil alone does at 1024 rows. Rows are split into bands over cv::parallel_for_; the result does not depend on
 *  the thread count either. With settings.smoothing > 0 the field is smoothRadialField()'s to the bit, smoothed band
 *  by band as the rows are scanned, so it is never held whole. Throws std::invalid_argument naming the argument for
 *  wrong types, sizes or settings. */
LineSkeleton extractSuggestiveContours(const cv::Mat& radial, const cv::Mat& depth, const SuggestiveSettings& settings,
                                       const cv::Mat& surface = cv::Mat());

} // namespace inkgraph
