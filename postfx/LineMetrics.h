#pragma once
/** @file How accurately a line method finds its lines: predicted points or masks scored against ground truth
 *  (the distance-tolerant measure of the BSDS boundary benchmark, Martin, Fowlkes & Malik 2004; docs/references.md).
 *  Pure functions over cv::Mat and STL: no GL, no file I/O, inputs never mutated.
 *  Coordinates are those of LinePoint: x right, y down, pixel (col, row) has its centre at (col, row).
 *
 *  Definitions, for a tolerance k in pixels:
 *  - precision P = share of the predicted points whose distance to the truth is <= k;
 *  - recall R = share of the truth's arc length whose distance to the nearest predicted point is <= k;
 *  - F1 = 2PR / (P + R), 0 when P + R = 0.
 *  Empty cases, so negative controls score:
 *  - no truth and no prediction: P = R = F1 = 1, every distance 0;
 *  - prediction but no truth: P = 0, R = 1 (nothing to find), F1 = 0, every predicted point spurious, the
 *    predicted-to-truth distances, hausdorff and chamferMean +infinity, truth-to-predicted 0;
 *  - truth but no prediction: P = 1 (nothing wrong was drawn), R = 0, F1 = 0, truth-to-predicted distances,
 *    hausdorff and chamferMean +infinity, predicted-to-truth 0.
 *  Statistics over an empty set are 0. */

#include "postfx/LineSkeleton.h"

#include <opencv2/core.hpp>

#include <cstddef>
#include <vector>

namespace inkgraph {

/** A ground-truth line: consecutive points joined by straight segments, in LinePoint coordinates (pixels, centres
 *  at integers); `closed` joins the last point back to the first. One point alone is a line of length 0. */
struct LinePolyline {
    std::vector<cv::Point2d> points;
    bool closed = false;
};

/** The score of one prediction against one truth at one tolerance. Distances in pixels. */
struct LineAccuracy {
    double tolerancePixels = 0.0;             ///< k
    std::size_t predictedCount = 0;           ///< predicted points (scoreLineMasks: skeleton pixels)
    std::size_t predictedWithinTolerance = 0; ///< predicted points within k of the truth
    std::size_t spuriousCount = 0;            ///< predicted points farther than k: predictedCount - within
    double truthLength = 0.0;                 ///< arc length of the truth (scoreLineMasks: truth skeleton pixels)
    double truthLengthWithinTolerance = 0.0;  ///< the part of truthLength within k of a predicted point
    std::size_t truthSampleCount = 0;         ///< truth samples measured (<= 0.25 px apart; masks: pixels)
    double precision = 0.0;                   ///< P, in [0, 1]
    double recall = 0.0;                      ///< R, in [0, 1], by arc length
    double f1 = 0.0;                          ///< 2PR / (P + R)
    double predictedToTruthMean = 0.0;        ///< mean distance of a predicted point to the truth
    double predictedToTruthP95 = 0.0;         ///< its 95th percentile
    double predictedToTruthMax = 0.0;         ///< its largest value
    double truthToPredictedMean = 0.0; ///< mean over the truth's length of the distance to the nearest prediction
    double truthToPredictedP95 = 0.0;  ///< its 95th percentile, by length
    double truthToPredictedMax = 0.0;  ///< its largest value (polyline vertices included)
    double hausdorff = 0.0;            ///< max(predictedToTruthMax, truthToPredictedMax)
    double chamferMean = 0.0;          ///< (predictedToTruthMean + truthToPredictedMean) / 2
};

/** Sub-pixel points against sub-pixel truth. `predicted`: points in LinePoint coordinates (each counts once,
 *  whatever its strength; duplicates count twice). `truth`: polylines in the same coordinates. Distances are exact:
 *  a predicted point's to the nearest truth segment, and each truth sample's (the truth resampled at <= 0.25 px,
 *  every vertex included) to the nearest predicted point; a uniform grid only prunes which are compared.
 *  Throws std::invalid_argument naming the argument for a negative or non-finite 'tolerancePixels' or a non-finite
 *  coordinate in 'predicted' or 'truth'. */
LineAccuracy scoreLinePoints(const std::vector<cv::Point2d>& predicted, const std::vector<LinePolyline>& truth,
                             double tolerancePixels);

/** Two line rasters, e.g. a method against a supersampled reference, or band boundaries. `predicted`, `truth`:
 *  CV_8UC1 of one size, non-zero = line. Both are thinned to one-pixel skeletons first (thinLines()), so a thick line
 *  counts once along its length; then each skeleton pixel's distance to the other skeleton comes from
 *  cv::distanceTransform (DIST_L2, DIST_MASK_PRECISE: exact Euclidean between pixel centres). Truth "length" and
 *  recall are counted in truth skeleton pixels. Throws std::invalid_argument naming the argument for a wrong type,
 *  an empty mask, different sizes, or a negative or non-finite 'tolerancePixels'. */
LineAccuracy scoreLineMasks(const cv::Mat& predicted, const cv::Mat& truth, double tolerancePixels);

/** Zhang-Suen thinning (1984): peels the boundary of every 8-connected shape in two alternating sub-passes until
 *  nothing changes, leaving an 8-connected skeleton one pixel wide along the shape's middle. `mask`: CV_8UC1,
 *  non-zero = set; outside the image counts as unset. Returns CV_8UC1 of the same size, 255 on the skeleton. As with
 *  every Zhang-Suen thinning, a 2 x 2 block vanishes and line ends may shorten by about half the width.
 *  Throws std::invalid_argument naming 'mask' unless it is a non-empty CV_8UC1. */
cv::Mat thinLines(const cv::Mat& mask);

/** A skeleton's point positions in output pixels, for a kernel run at `supersample` S x the output size:
 *  output = (p + 0.5) / S - 0.5 on each axis (pixel centres at integers at both resolutions). Strengths are dropped.
 *  Throws std::invalid_argument naming 'supersample' unless >= 1. */
std::vector<cv::Point2d> outputPixelPositions(const LineSkeleton& skeleton, int supersample = 1);

} // namespace inkgraph
