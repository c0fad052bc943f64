#pragma once
/** @file The measures of how clean a render's lines are (issue 19), for bench/LineCleanliness.cpp: how much of the
 *  model the ink covers, how many SVG paths are specks, and how stable each line type's skeleton is across
 *  resolution and across small turns of the camera (issues 19 and 39). Pure functions over cv::Mat and STL: no GL,
 *  no file I/O, inputs never mutated. Point coordinates are those of postfx/LineMetrics.h: x right, y down, pixel
 *  (col, row) has its centre at (col, row).
 *
 *  Agreement of two point sets A and B at a tolerance k (the F1 of postfx/LineMetrics.h, made symmetric because
 *  neither set is the truth): precision = share of A's points within k of a point of B, recall = share of B's points
 *  within k of a point of A, F1 = 2PR / (P + R), 0 when P + R = 0. Empty cases as in LineMetrics.h: both empty gives
 *  P = R = F1 = 1; A empty alone gives P = 1, R = 0, F1 = 0; B empty alone gives P = 0, R = 1, F1 = 0. */

#include <opencv2/core.hpp>

#include <cstddef>
#include <vector>

namespace inkgraph::bench {

/** Ink against the model's pixels. Shares are of modelPixels (0 when there are none). */
struct InkShare {
    std::size_t modelPixels = 0;     ///< coverage > 0
    std::size_t inkInsideModel = 0;  ///< ink pixels on the model
    std::size_t inkOutsideModel = 0; ///< ink pixels off it (outlines drawn outside the silhouette)
    double insideShare = 0.0;        ///< inkInsideModel / modelPixels
    double outsideShare = 0.0;       ///< inkOutsideModel / modelPixels
};

/** Ink is where the largest value over `lineLayers` is >= `inkThreshold`; the model is where `coverage` > 0.
 *  All CV_8UC1 of one size (no layers: no ink). Throws std::invalid_argument naming the argument for a wrong type,
 *  an empty image or a size that differs from coverage's, or an 'inkThreshold' outside 1..255. */
InkShare measureInkShare(const cv::Mat& coverage, const std::vector<cv::Mat>& lineLayers, int inkThreshold = 128);

/** A path's length: the sum of its segments' lengths, plus the closing segment when `closed`. One point, or
 *  several at one place, is 0. Throws std::invalid_argument naming 'points' when it is empty. */
double pathLength(const std::vector<cv::Point2d>& points, bool closed);

/** Statistics of path lengths. */
struct PathLengthSummary {
    std::size_t pathCount = 0;      ///< paths measured
    std::size_t shortPathCount = 0; ///< paths strictly shorter than the threshold
    double shortShare = 0.0;        ///< shortPathCount / pathCount, 0 with no paths
    double medianLength = 0.0;      ///< the middle length (mean of the two middle ones for an even count), 0 if none
};

/** Summarises `lengths` with `shortBelow` as the threshold of a short path. Throws std::invalid_argument naming
 *  'lengths' for a negative or non-finite length, 'shortBelow' unless finite and > 0. */
PathLengthSummary summarisePathLengths(const std::vector<double>& lengths, double shortBelow = 3.0);

/** The one-pixel skeleton of a line layer: pixels >= `inkThreshold` (the ink), thinned by thinLines()
 *  (postfx/LineMetrics.h), as points at the pixel centres in row-major order. Throws std::invalid_argument naming
 *  'lineLayer' unless a non-empty CV_8UC1, 'inkThreshold' outside 1..255. */
std::vector<cv::Point2d> skeletonPoints(const cv::Mat& lineLayer, int inkThreshold = 128);

/** Points of an image `factor` times the size mapped into the smaller image's pixels: (p + 0.5) / factor - 0.5 on
 *  each axis, so pixel centres stay at integers at both sizes. Throws std::invalid_argument naming 'factor' unless
 *  finite and > 0. */
std::vector<cv::Point2d> toSmallerImage(const std::vector<cv::Point2d>& points, double factor);

/** The points of `points` whose distance to the nearest point of `reference` is <= `tolerance` (exact Euclidean; a
 *  grid only prunes the comparisons). Throws std::invalid_argument naming 'tolerance' unless finite and >= 0, or the
 *  set holding a non-finite coordinate. */
std::size_t countWithin(const std::vector<cv::Point2d>& points, const std::vector<cv::Point2d>& reference,
                        double tolerance);

/** Agreement of two point sets (see the file comment). */
struct PointSetAgreement {
    std::size_t firstCount = 0;   ///< points of A
    std::size_t firstWithin = 0;  ///< A's points within the tolerance of B
    std::size_t secondCount = 0;  ///< points of B
    std::size_t secondWithin = 0; ///< B's points within the tolerance of A
    double precision = 0.0;       ///< firstWithin / firstCount
    double recall = 0.0;          ///< secondWithin / secondCount
    double f1 = 0.0;              ///< 2PR / (P + R)
};

/** Precision, recall and F1 from counts, with the empty cases of the file comment. Throws std::invalid_argument when
 *  a within count exceeds its count. */
PointSetAgreement agreementFromCounts(std::size_t firstCount, std::size_t firstWithin, std::size_t secondCount,
                                      std::size_t secondWithin);

/** countWithin() both ways, then agreementFromCounts(). */
PointSetAgreement comparePointSets(const std::vector<cv::Point2d>& first, const std::vector<cv::Point2d>& second,
                                   double tolerance);

/** One view's skeleton at two sizes, compared at the smaller size's pixel grid: `larger` (points of the image `factor`
 *  times the size) mapped by toSmallerImage(), then comparePointSets(smaller, mapped, tolerance), so `tolerance` is in
 *  the smaller image's pixels and precision is the share of the smaller image's points. Throws as toSmallerImage()
 *  and countWithin() do. */
PointSetAgreement compareAcrossSizes(const std::vector<cv::Point2d>& smaller, const std::vector<cv::Point2d>& larger,
                                     double factor, double tolerance);

/** The smallest F1 of `agreements` (the worst of several comparisons). Throws std::invalid_argument naming
 *  'agreements' when it is empty. */
double smallestF1(const std::vector<PointSetAgreement>& agreements);

/** A camera as the dump's manifest.json gives it: OpenGL view and projection matrices (rows as written) and the
 *  image size. NDC x = (col + 0.5) / width * 2 - 1, NDC y = 1 - (row + 0.5) / height * 2 (row 0 at the top). */
struct PinholeView {
    cv::Matx44d view = cv::Matx44d::eye();
    cv::Matx44d projection = cv::Matx44d::eye();
    cv::Size size;
};

/** Where reprojected points went. */
struct Reprojection {
    std::vector<cv::Point2d> points; ///< landed in the target frame and visible there, in its pixels
    std::size_t withoutDepth = 0;    ///< no model pixel within the search radius in the source depth
    std::size_t outsideFrame = 0;    ///< behind the target camera or outside its image
    std::size_t hiddenInTarget = 0;  ///< the target's surface there is at another depth (occluded, or off-model)
};

/** Moves image points of one view into another through the source's depth. `sourceDepth`, `targetDepth`: CV_32FC1
 *  linear view depth (distance along -z in view space, 0 off the model; gbuffer.depth), of the views' sizes.
 *  A point's depth is the smallest positive source depth within `searchRadius` pixels (Chebyshev) of its rounded
 *  pixel, so a line drawn just off the silhouette (an outline, a contour's outer pixel) takes the surface it outlines
 *  and, at an occluding edge, the nearer surface. It is unprojected with the source camera, projected with the
 *  target's and kept when it lands inside the target image (pixel centres from -0.5 to size - 0.5) and the smallest
 *  positive target depth within `searchRadius` of its rounded pixel is within `relativeDepthTolerance` x that depth
 *  of its own view depth there. Throws std::invalid_argument naming the argument for a depth of the wrong type or
 *  size, a singular matrix, 'relativeDepthTolerance' not finite and > 0, 'searchRadius' < 0. */
Reprojection reprojectPoints(const std::vector<cv::Point2d>& points, const cv::Mat& sourceDepth,
                             const PinholeView& source, const cv::Mat& targetDepth, const PinholeView& target,
                             double relativeDepthTolerance = 0.03, int searchRadius = 2);

/** Two views' skeletons compared through reprojection both ways. */
struct ViewAgreement {
    PointSetAgreement agreement; ///< first = the first view's points in the second, second = the converse
    Reprojection firstInSecond;  ///< the first view's points reprojected into the second
    Reprojection secondInFirst;  ///< the second view's points reprojected into the first
};

/** `first` (skeleton points of the view `firstView` with depth `firstDepth`) reprojected into the second view and
 *  `second` into the first (reprojectPoints() with `relativeDepthTolerance` and `searchRadius`); precision = share of
 *  the first's reprojected points within `tolerance` of `second`, recall = share of the second's reprojected points
 *  within `tolerance` of `first` (agreementFromCounts()). Points left out by the reprojection count in neither share.
 *  Throws as reprojectPoints() and countWithin() do. */
ViewAgreement compareAcrossViews(const std::vector<cv::Point2d>& first, const cv::Mat& firstDepth,
                                 const PinholeView& firstView, const std::vector<cv::Point2d>& second,
                                 const cv::Mat& secondDepth, const PinholeView& secondView, double tolerance,
                                 double relativeDepthTolerance = 0.03, int searchRadius = 2);

/** Where two point sets of one frame of `size` disagree, for looking at (inkgraph_line_cleanliness --disagreement):
 *  CV_8UC4, RGBA, opaque white paper; each point of `second` at its nearest pixel, grey (150, 150, 150) where `first`
 *  has a point within `tolerance` and blue (0, 0, 255) where not; then each point of `first`, black where `second` has
 *  one within `tolerance` and red (255, 0, 0) where not. Points outside the frame are not drawn. Throws as
 *  countWithin() does, and std::invalid_argument naming 'size' when it is empty. */
cv::Mat disagreementPicture(cv::Size size, const std::vector<cv::Point2d>& first,
                            const std::vector<cv::Point2d>& second, double tolerance);

} // namespace inkgraph::bench
