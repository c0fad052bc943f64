#pragma once
/** @file Lines found on the mesh as 3-D segments (object space: suggestive-object, intersection), drawn as a one-pixel
 *  skeleton: each segment projected with the camera's own view and projection (in double: the G-buffer's matrices
 *  before rounding to float), clipped to the near and far planes as the rasteriser clips, and sampled along the image
 *  every <= 0.5 data pixels (the depth perspective-correct, the strength linear along the 3-D segment), so the
 *  skeleton has no gaps and the stroke's discs overlap.
 *
 *  A sample is visible when one of the four pixel centres around it holds the model (depth > 0) at a linear depth d
 *  with z <= d (1 + depthJump): a point on the surface it lies on passes (its own pixel is at most a pixel's depth
 *  slope away), a point behind a nearer surface fails, background pixels beside a silhouette do not vote, and
 *  visibility is decided to within a pixel of an occluder's outline, as for the mesh edges. So a line that passes
 *  behind an occluder where the eye grazes it (the intersection circle of two spheres, where it turns behind one: in
 *  the image it runs along that sphere's outline) is drawn a few pixels past where it is hidden. The hidden lines
 *  (`hidden-<type>`) keep the samples in the frame that fail the same test, so a line's visible and hidden parts
 *  share their samples' positions and split where the test turns. */

#include "postfx/LineSkeleton.h"
#include "scene/Camera.h"

#include <glm/glm.hpp>
#include <opencv2/core.hpp>

#include <cstddef>

namespace inkgraph {

/** Which samples SegmentProjector keeps. */
enum class SegmentVisibility {
    Visible, ///< those the visible surface does not hide
    Hidden,  ///< those in the frame it hides (the hidden-line types)
};

/** Projects segments into one skeleton at the size of `depth` (the G-buffer's linear depth, CV_32F, 0 off the model).
 *  `camera` and `depth` must outlive it. */
class SegmentProjector {
public:
    SegmentProjector(const Camera& camera, const cv::Mat& depth, double depthJump, SegmentVisibility keep);

    /** Samples segment `a`-`b` (the scene's local frame, like the positions); the strength runs linearly from
     *  `strengthA` to `strengthB` along the 3-D segment, clamped to 1, and samples of strength <= 0 are dropped.
     *  Each sample's 3-D point goes into the skeleton's `surface` with `mesh` and `triangle` (the mesh's own
     *  index; -1 when not known), for --strokes. */
    void add(const glm::dvec3& a, const glm::dvec3& b, double strengthA = 1.0, double strengthB = 1.0, int mesh = -1,
             long triangle = -1);

    /** The skeleton so far, moved out. */
    LineSkeleton take() { return std::move(mSkeleton); }

private:
    bool isVisible(double x, double y, double pointDepth) const;

    glm::dmat4 mView;
    glm::dmat4 mProjection;
    const cv::Mat& mDepth;
    double mTolerance;
    SegmentVisibility mKeep;
    LineSkeleton mSkeleton;
};

} // namespace inkgraph
