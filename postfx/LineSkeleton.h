#pragma once
/** @file A line type's one-pixel skeleton, and its drawing at a width constant in output pixels, anti-aliased.
 *  Pure functions over cv::Mat: no GL. Coordinates: x right, y down, pixel (col, row) has its centre at (col, row). */

#include <opencv2/core.hpp>

#include <cstddef>
#include <vector>

namespace inkgraph {

/** One sample of a line: where it passes, to sub-pixel precision, and how strongly it is drawn. */
struct LinePoint {
    cv::Point2f position;  ///< in data-buffer pixels (x right, y down, pixel centres at integers)
    float strength = 1.0f; ///< alpha in (0, 1]: 1 for a full line, less for a faded one
    float width = 1.0f;    ///< the stroke's width here as a share of the layer's width, in (0, 1] (line weight)
};

/** Where a line sample lies on the mesh, for lines found on the mesh itself (object space): --strokes gives each
 *  stroke point its own 3-D point (passes/lines/StrokePoints.h). */
struct SurfacePoint {
    cv::Point3d position; ///< the scene's local frame (Scene::origin), like the mesh positions
    int mesh = -1;        ///< index into Scene::meshes, or -1 when not known
    long triangle = -1;   ///< the mesh's own triangle index, or -1 when not known
};

/** What a line kernel finds, at the resolution of the buffers it read (the data resolution). */
struct LineSkeleton {
    cv::Mat mask;                  ///< CV_8UC1, the data size: 255 on each pixel a line passes through, else 0
    std::vector<LinePoint> points; ///< the line's sub-pixel samples; a mask pixel has one or more
    /** One per point, where the kernel found the line on the mesh (object-space types); else empty. */
    std::vector<SurfacePoint> surface;
};

/** Room for a closed line around a quarter of a frame of `size` without reallocating: what a kernel reserves for a
 *  skeleton's points; longer skeletons grow as usual. */
inline std::size_t expectedSkeletonPoints(cv::Size size) {
    return 4 * static_cast<std::size_t>(size.width + size.height);
}

/** A skeleton from a one-pixel mask drawn elsewhere (e.g. GL lines): every non-zero pixel becomes a point at its
 *  centre with strength mask/255. Throws std::invalid_argument naming 'mask' unless CV_8UC1. */
LineSkeleton skeletonFromMask(const cv::Mat& mask);

/** The line layer for the composite: CV_8UC1 of size mask.size() / supersample (which must divide it), 255 = full
 *  line. Each point is a disc of diameter widthPixels x supersample at the data resolution, with coverage
 *  clamp(radius + 0.5 - distance, 0, 1) x strength, combined by maximum, so the line is anti-aliased and
 *  `widthPixels` wide in output pixels at any resolution; then area-downsampled (INTER_AREA) by `supersample`.
 *  The points are what is drawn; the mask gives the data size. Points may lie off the image (what reaches it is
 *  drawn). Where stamping every disc would cost more than a few passes over the image (wide lines, dense points),
 *  each pixel instead takes only the disc of its nearest point, found by an exact distance transform between the
 *  points' pixels (the strongest point of a pixel standing for it). For lines of one strength that is the same
 *  picture up to the rim, which may follow a point ~0.7 px farther where two are almost equally near; where a faded
 *  point lies nearer than a stronger one, the faded one is drawn there. A point's `width` scales its disc's diameter
 *  (line weight: tapered ends, thinner far away); when any point has width < 1 every disc is stamped.
 *  Throws std::invalid_argument naming the argument for a non-finite or non-positive width, supersample < 1 or not
 *  dividing the size, a wrong or empty mask, or a point with a non-finite position or a strength or width outside
 *  (0, 1]. */
cv::Mat strokeLines(const LineSkeleton& skeleton, float widthPixels, int supersample);

/** True when two neighbouring linear depths (> 0; 0 = background) do not belong to one surface: exactly one is
 *  background, or both are surface and |za - zb| > relativeJump x min(za, zb). Judged relative to depth, so the
 *  answer does not change with the scene's units or distance. */
inline bool isDepthBreak(float za, float zb, float relativeJump) {
    const bool aCovered = za > 0.0f;
    const bool bCovered = zb > 0.0f;
    if (aCovered != bCovered) return true;
    if (!aCovered) return false;
    const float nearer = za < zb ? za : zb;
    const float jump = za > zb ? za - zb : zb - za;
    return jump > relativeJump * nearer;
}

} // namespace inkgraph
