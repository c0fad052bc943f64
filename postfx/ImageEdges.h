#pragma once
/** @file Image-space edges after Saito and Takahashi (1990): depth discontinuities and normal creases found in the
 *  float G-buffer. One-pixel skeletons, drawn later at a constant width. */

#include "postfx/LineSkeleton.h"

namespace inkgraph {

struct DepthEdgeSettings {
    float relativeJump = 0.05f; ///< |za - zb| > relativeJump x min(za, zb) (isDepthBreak)
};

/** `depth`: CV_32FC1 linear view depth, 0 = background. The nearer pixel of every 4-neighbour depth break is marked
 *  (the model's pixel against the background), the point at the midpoint of the pair. Throws std::invalid_argument
 *  naming the argument for a wrong or empty `depth`, or a negative or non-finite jump. */
LineSkeleton extractDepthEdges(const cv::Mat& depth, const DepthEdgeSettings& settings);

struct NormalEdgeSettings {
    float creaseAngleDegrees = 30.0f; ///< normals of neighbours further apart than this make a crease
    float depthJump = 0.05f;          ///< pairs across a depth break are not compared (that is a depth edge)
};

/** `normal`: CV_32FC4 unit view-space normal (alpha = coverage); `depth`: CV_32FC1, 0 = background; same size.
 *  For every 4-neighbour pair on one surface whose normals differ by more than the crease angle (measured as
 *  atan2(|n1 x n2|, n1 . n2), well conditioned at small angles), the left or upper pixel is marked and the point
 *  is the midpoint of the pair. Coverage is read from `depth` alone (alpha is not read). The pair test itself does
 *  not depend on the normals' length, but blocks of nearly equal normals are passed over by a range check that
 *  relies on them being unit. Throws std::invalid_argument naming the argument for wrong types or sizes, a crease
 *  angle outside [0, 180] degrees, or a negative or non-finite jump. */
LineSkeleton extractNormalEdges(const cv::Mat& normal, const cv::Mat& depth, const NormalEdgeSettings& settings);

} // namespace inkgraph
