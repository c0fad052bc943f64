#pragma once
/** @file Contours in image space: where n.v changes sign on the model, and where the model ends (against the
 *  background or in front of a farther surface). A one-pixel skeleton, drawn later at a constant width. */

#include "postfx/LineSkeleton.h"

namespace inkgraph {

struct ContourSettings {
    float depthJump = 0.05f; ///< relative depth jump that separates two surfaces (isDepthBreak)
};

/** `nDotV`: CV_32FC1, n.v of the visible surface (unit or unnormalised v: only the sign and the ratio of
 *  neighbours matter); `depth`: CV_32FC1 linear view depth, 0 = background; same size.
 *  Skeleton, over every 4-neighbour pair (p, q):
 *  - both on one surface (no depth break) with n.v of opposite sign (0 counts as positive): the one with the smaller
 *    |n.v| is marked, the point at the linear zero crossing between the two centres;
 *  - a depth break (including model against background): the nearer pixel is marked, the point at the midpoint.
 *  Background pixels are never marked (a NaN depth counts as background), and no NaN point is produced.
 *  Throws std::invalid_argument naming the argument for wrong types or sizes, or a negative or non-finite jump. */
LineSkeleton extractContours(const cv::Mat& nDotV, const cv::Mat& depth, const ContourSettings& settings);

/** The depth-break part alone, appended to `skeleton` (shared with extractDepthEdges()): `depth` as above; an empty
 *  `skeleton.mask` is allocated, otherwise it must be CV_8UC1 of the size of `depth` and keeps what it has.
 *  Throws std::invalid_argument naming the argument for wrong types or sizes, or a negative or non-finite jump. */
void appendDepthBreaks(const cv::Mat& depth, float relativeJump, LineSkeleton& skeleton);

} // namespace inkgraph
