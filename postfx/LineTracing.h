#pragma once
/** @file Line skeletons to simplified polylines, for vector output (SvgLines). Pure functions over cv::Mat: no GL,
 *  no file I/O, inputs never mutated. Coordinates are those of LinePoint: data-buffer pixels, x right, y down, pixel
 *  (col, row) has its centre at (col, row).
 *
 *  Topology. On-pixels are joined by the 8-connected links that are not redundant: every 4-neighbour link, and a
 *  diagonal link only where neither of the two pixels sharing an edge with both is on (else the two 4-links through
 *  that pixel already join them). So a staircase is a plain chain, not a run of spurious junctions, and the links
 *  still connect exactly the 8-connected components. A pixel with 2 links lies inside a chain; one with 1 link is an
 *  end, one with 3 or more a junction. Each link lies on exactly one polyline:
 *  - chains are walked from every end and junction to the next end or junction, so a junction is the first or last
 *    vertex of each of its branches (a T gives 3 polylines, an X 4);
 *  - a chain that leaves a junction and comes back to it is one closed polyline starting at that junction;
 *  - what is left are loops with no end or junction: each is one closed polyline, starting at its first pixel in
 *    raster order (the first vertex is not repeated at the end);
 *  - a pixel with no link is a 1-point polyline, so nothing in the mask is lost.
 *  Thick regions (a solid 3 x 3 block) are covered too, but as many short polylines; thin them first (traceMask).
 */

#include "postfx/LineSkeleton.h"

#include <opencv2/core.hpp>

#include <vector>

namespace inkgraph {

/** A traced line: consecutive points joined by straight segments, in data-buffer pixels (LinePoint coordinates).
 *  `closed` joins the last point back to the first, which is not repeated. One point alone is a dot. */
struct Polyline {
    std::vector<cv::Point2f> points;
    bool closed = false;
};

/** A skeleton's chain of pixels before simplification, as traceSkeleton() finds it (see the file comment). */
struct PixelChain {
    std::vector<cv::Point2d> positions; ///< each pixel's position: the mean of its sub-pixel points, else its centre
    std::vector<cv::Point> pixels;      ///< the pixels (col, row), in order
    /** Runs back to its first pixel, which is not repeated: a loop from a junction (its first pixel is that
     *  junction) or a loop with no end or junction. */
    bool closed = false;
    bool anchored = true; ///< the first pixel is an end or a junction (false only for a loop with neither)
};

/** How traceSkeleton() and traceMask() turn pixels into polylines. */
struct TraceSettings {
    /** Ramer-Douglas-Peucker tolerance in data pixels, >= 0 and finite: every traced pixel position stays within it
     *  of its simplified polyline. 0 drops only vertices exactly on the line between their neighbours. Chains of pixel
     *  centres (traceMask(), or no sub-pixel points) stray up to ~0.5 px from the line they raster, and RDP's chord
     *  from one end pixel to the other up to ~0.5 px more, so at 0.5 a shallow slanted line keeps many of its steps;
     *  about 1 px simplifies those cleanly (a 6-px line and circle: 257 vertices at 0.5, 34 at 1). */
    double tolerancePixels = 0.5;
    /** traceMask() only: a pixel is on where mask >= maskThreshold (128 for anti-aliased 8-bit line masks). */
    uchar maskThreshold = 128;
};

/** A one-pixel-wide, 8-connected skeleton of a thick mask, e.g. the outline or silhouette GL line layers (bands a
 *  few pixels wide). `mask`: CV_8UC1, non-empty; a pixel is set where mask >= `threshold`, outside the image is
 *  unset. Returns CV_8UC1 of the same size, 255 on the skeleton, 0 elsewhere.
 *  Method: sequential thinning by simple points in four directional sub-passes (north, south, east, west borders)
 *  per round until nothing changes. A sub-pass takes the border pixels of its side as they were at its start, then
 *  removes each that is still simple (its removal changes neither the 8-connected shapes nor the 4-connected
 *  background: Yokoi's 8-connectivity number is 1) and has at least 2 set neighbours (ends are kept, so lines do not
 *  shorten from their ends once thin). So, unlike Zhang-Suen, no shape ever vanishes (a 2 x 2 block leaves 2 pixels)
 *  and no pixel stays that could be removed: no staircase corners remain. Peeling from alternate sides keeps the
 *  skeleton in the middle of a band, within a pixel (a straight band of odd width: exactly its centre row or column;
 *  of even width: half a pixel to one side); band ends shorten by about half the width, and a bump on a border can
 * leave a short spur, as with every thinning. Cost O(set pixels x half the band width) after one O(W x H) scan. Throws
 * std::invalid_argument naming 'mask' unless it is a non-empty CV_8UC1. */
cv::Mat thinToSkeleton(const cv::Mat& mask, uchar threshold = 128);

/** The polylines of a skeleton, simplified. `skeleton.mask`: CV_8UC1, non-empty, non-zero = on (kernels write 255)
 *  gives the topology (see the file comment). `skeleton.points` may place pixels to sub-pixel precision: a traced
 *  pixel lies at the mean position of the points that round to it (pixel (col, row) takes x in [col - 0.5,
 *  col + 0.5) and y in [row - 0.5, row + 0.5)), else at its centre; points that round outside the image or onto an
 *  off pixel are ignored, and strengths are not used. Each polyline is then simplified by Ramer-Douglas-Peucker
 *  with `settings.tolerancePixels`; a closed loop is split at its first vertex and the vertex farthest from it, and
 *  a loop's raster-order start is dropped too when the loop still holds within tolerance without it (a junction
 *  where a loop meets its branches is always kept). Nothing else is dropped: ends, junctions, short spurs and
 *  isolated pixels all stay. Order: chains from ends and junctions in raster order of their start pixel, then
 *  loops, then isolated pixels in raster order.
 *  Cost O(W x H) for one scan of the mask, then O(on pixels + points log points) for tracing; RDP is
 *  O(n log n) per polyline of n pixels on lines met in practice (O(n^2) only on contrived zigzags).
 *  Throws std::invalid_argument naming the argument for a wrong or empty 'skeleton.mask', a non-finite position
 *  in 'skeleton.points', or a negative or non-finite 'settings.tolerancePixels'. */
std::vector<Polyline> traceSkeleton(const LineSkeleton& skeleton, const TraceSettings& settings = {});

/** The chains traceSkeleton() simplifies, in its order: from ends and junctions (an end or junction is the first
 *  and last pixel of each of its chains), then loops, then isolated pixels (one pixel each). Every link of the
 *  skeleton lies on exactly one chain. Throws std::invalid_argument as traceSkeleton() does, naming
 *  tracePixelChains(). */
std::vector<PixelChain> tracePixelChains(const LineSkeleton& skeleton);

/** traceSkeleton() of thinToSkeleton(mask, settings.maskThreshold), with no sub-pixel points: for masks drawn
 *  elsewhere (the GL line layers), one-pixel or thick. Polyline vertices lie on skeleton pixel centres before
 *  simplification. Throws std::invalid_argument as those two do, naming the function traceMask(). */
std::vector<Polyline> traceMask(const cv::Mat& mask, const TraceSettings& settings = {});

/** Ramer-Douglas-Peucker on one polyline, as traceSkeleton() applies it: keeps the end points of an open polyline
 *  and every vertex needed so that each input point lies within `tolerancePixels` of the result. A closed polyline
 *  is split at its first vertex and the vertex farthest from it; `keepFirstOfClosed` false also lets the first
 *  vertex go when the loop holds without it (at least 3 vertices stay). 1- and 2-point polylines are returned as
 *  they are. Throws std::invalid_argument naming 'tolerancePixels' if negative or non-finite, or 'polyline' for a
 *  non-finite coordinate. */
Polyline simplifyPolyline(const Polyline& polyline, double tolerancePixels, bool keepFirstOfClosed = true);

} // namespace inkgraph
