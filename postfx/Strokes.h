#pragma once
/** @file Line skeletons of every type chained into strokes, the unit an artist draws: pixels chained through
 *  junctions where a line runs on, ends joined across small gaps and from one type into another where they
 *  continue (as Blender Freestyle chains its edges), then a length rule and hysteresis on strength decide which
 *  strokes are drawn. The raster layers (drawStrokeLayer) and the vector paths (strokePolylines) are both made
 *  from the result, so they match. Pure functions over cv::Mat: no GL, no file I/O.
 *
 *  Coordinates are LinePoint's, in data pixels (x right, y down, pixel centres at integers) of the common data
 *  resolution; a layer found at a lower resolution (GL bands at the output size while the G-buffer is
 *  supersampled) gives its `scale`, and its positions are mapped as (p + 0.5) x scale - 0.5.
 *
 *  Method.
 *  1. Each layer's skeleton is traced into chains of pixels between ends and junctions (tracePixelChains). A pixel's
 *     strength is the largest of its points'.
 *  2. Every chain end gets an outward direction, from the end to the vertex `directionPixels` back along the chain.
 *     Two ends of any layers within `joinRadiusPixels` of each other are a candidate continuation when the line
 *     turns by at most `joinAngleDegrees` from one into the other (and into the gap between them, when they are
 *     apart); a lone pixel has no direction and continues whatever comes within reach, after every true
 *     continuation. Candidates are taken greedily, the straightest and nearest first, each end at most once: at a
 *     junction the two branches that run on most straight become one stroke and the others end there, as Freestyle's
 *     chaining by natural continuation does.
 *  3. Joined chains make a path (a chain of strokes, `StrokeChain`), open or closed. A path is cut into one stroke
 *     per run of one layer; a gap inside one layer is bridged by points every half pixel, so the stroke closes it.
 *     A run shorter than `absorbPixels` between runs of other layers joins its longer neighbour (a pixel or two of
 *     crease where a contour runs on is drawn as contour), so no path is a speck.
 *  4. A chain is kept when it is long enough for each of its strokes' layers (`minLengthPixels`, measured along the
 *     whole chain, so a short piece that continues a long line of another type stays) and seeded: some point
 *     reaches its layer's `seedStrength` (hysteresis, as Canny's: a weak line is drawn only where it continues a
 *     strong one). */

#include "postfx/LineSkeleton.h"
#include "postfx/LineTracing.h"

#include <opencv2/core.hpp>

#include <cstddef>
#include <vector>

namespace inkgraph {

/** One line type's skeleton and the rules its strokes obey. */
struct StrokeLayer {
    const LineSkeleton* skeleton = nullptr; ///< not null; its mask's size times `scale` is the data size
    int scale = 1;                          ///< data pixels per pixel of this skeleton (>= 1)
    double minLengthPixels = 0.0;           ///< data pixels: a chain shorter than this is not drawn
    float seedStrength = 0.0f;              ///< a chain needs a point of this layer this strong; 0: every point seeds
    /** Data pixels each end of this layer adds to the join radius: a layer sampled coarser than the data has its end
     *  samples further inside its lines (strokeJoinAllowancePixels()). */
    double joinAllowancePixels = 0.0;
};

/** How ends are joined; lengths in data pixels. */
struct StrokeSettings {
    double joinRadiusPixels = 2.0;  ///< ends this close may continue one another (the gap is bridged)
    double joinAngleDegrees = 50.0; ///< the largest turn where a line runs on through a junction or a gap
    double directionPixels = 4.0;   ///< how far back from an end its direction is taken
    /** A run of one type shorter than this between runs of others joins its longer neighbour's type. */
    double absorbPixels = 4.0;
};

/** A run of one layer along a chain. */
struct Stroke {
    int layer = 0;                 ///< index into the layers given
    std::vector<LinePoint> points; ///< in order along the stroke, at the data resolution; a closed one not repeated
    std::vector<cv::Point> pixels; ///< each point's pixel in its layer's skeleton; (-1, -1) for a bridging point
    bool closed = false;
    double lengthPixels = 0.0; ///< along its points (and round a closed one), data pixels
    float meanStrength = 0.0f; ///< over its points
    float peakStrength = 0.0f;
    std::size_t chain = 0; ///< index into Strokes::chains
    bool kept = false;     ///< its chain is kept
};

/** Strokes joined end to end. */
struct StrokeChain {
    double lengthPixels = 0.0; ///< the whole chain, bridges included
    bool closed = false;
    bool longEnough = false; ///< for every layer it holds
    bool seeded = false;
    bool kept() const { return longEnough && seeded; }
};

struct Strokes {
    std::vector<Stroke> strokes;
    std::vector<StrokeChain> chains;
    std::size_t junctionJoins = 0;     ///< continuations through a shared pixel
    std::size_t gapJoins = 0;          ///< continuations across a gap (bridged within a layer)
    std::size_t crossTypeJoins = 0;    ///< continuations from one layer into another
    std::size_t absorbedFragments = 0; ///< short runs drawn as their neighbour's type
    std::size_t overlapsMerged = 0;    ///< strokes not drawn since an earlier type's stroke draws the same line
    /** Counts for --stats: kept strokes, and what the length rule and the hysteresis removed. */
    std::size_t keptStrokes() const;
    std::size_t droppedShort() const;
    std::size_t droppedWeak() const;
};

/** The height in pixels at and below which the length rule and the join radius are the plain span rules
 *  (strokeSpanBiasPixels()). */
inline constexpr double kLengthReferenceRows = 1024.0;

/** What one pixel of sampling is worth at `heightPixels` rows against a picture kLengthReferenceRows high, in pixels of
 *  `heightPixels`. Spans are measured between samples, one a pixel: the line a chain draws covers a pixel more than
 *  its first sample to its last, and the gap between two ends a pixel less than between their samples. In pixels of a
 *  1024-row picture that pixel is one at 1024 rows and half of one at 2048, so a rule counted in a share of the height
 *  judged the same line half a pixel (of 1024) longer, and the same gap half a pixel wider, at 2048 (issue 39). Above
 *  kLengthReferenceRows this is height / 1024 - 1, the difference a rule takes back; at and below it 0, so a small
 *  picture keeps its rules as they were. Throws std::invalid_argument naming 'heightPixels' unless it is finite and
 *  > 0. */
double strokeSpanBiasPixels(double heightPixels);
/** The same for a line sampled once every `samplePixels` pixels of a picture `heightPixels` high (a skeleton found on
 *  a field coarser than the picture, StrokeLayer::scale): height / 1024 - samplePixels, at least 0. A line sampled at
 *  1024 rows and drawn at 2048 has its samples two pixels apart and needs no bias. Throws std::invalid_argument naming
 *  the argument unless both are finite and > 0. */
double strokeSpanBiasPixels(double heightPixels, double samplePixels);

/** The span a chain needs (StrokeLayer::minLengthPixels) for a rule of `share` x the height, in pixels of a picture
 *  `heightPixels` high: share x height + strokeSpanBiasPixels(height), so one line on the picture passes or fails at
 *  every size alike. 0 for a share of 0, which keeps every chain. Throws std::invalid_argument naming the argument
 *  unless `share` is finite and >= 0 and `heightPixels` finite and > 0. */
double strokeLengthLimitPixels(double share, double heightPixels);
/** The same for a layer sampled once every `samplePixels` pixels (strokeSpanBiasPixels(height, samplePixels)). */
double strokeLengthLimitPixels(double share, double heightPixels, double samplePixels);
/** What each end of a layer sampled once every `samplePixels` pixels of a picture `heightPixels` high adds to the join
 *  radius of strokeSettingsFor(), which counts ends sampled once a pixel: half the difference of the two biases
 *  (strokeSpanBiasPixels()), since each end's sample lies half a sample step inside its line. 0 for samplePixels 1. */
double strokeJoinAllowancePixels(double heightPixels, double samplePixels);

/** How far ends may be apart and still continue one another, in output pixels of a 1024-row picture; scaled with the
 *  height (never under 2 pixels, a diagonal step and a half). */
inline constexpr double kJoinRadiusAt1024 = 2.0;

/** How ends are joined in a picture `outputRows` high whose lines are found `supersample` times larger (the data
 *  resolution), in data pixels: the join radius kJoinRadiusAt1024 scaled with the height, less
 *  strokeSpanBiasPixels() of the data height, so a gap of a given width on the picture is bridged at every size alike
 *  (at 2048 rows, 3 pixels between two ends' samples, a gap of 2 pixels, as 2 between samples at 1024 are a gap of 1);
 *  an end's direction and the fragments absorbed are counted over twice the scaled radius, lengths along a line that
 *  the sampling does not bias. Throws std::invalid_argument naming the argument unless `outputRows` is finite and > 0
 *  and `supersample` >= 1. */
StrokeSettings strokeSettingsFor(double outputRows, int supersample);

/** Chains every layer's skeleton into strokes and decides which are drawn (see the file comment). Throws
 *  std::invalid_argument naming the argument for a null or empty skeleton, a `scale` below 1, layers whose sizes
 *  times their scales differ, a negative or non-finite length, a seed strength outside [0, 1], or settings that are
 *  negative, non-finite or (the angle) above 180. */
Strokes chainStrokes(const std::vector<StrokeLayer>& layers, const StrokeSettings& settings = {});

/** Per layer, how many strokes were decided near a rule's limit, where the decision may flip between two sizes or two
 *  views of one model (issue 39): strokes whose chain's length lies within `share` x the layer's minLengthPixels of
 *  it, and, where the layer seeds (seedStrength > 0) and no stroke of the chain is of a layer that always seeds,
 *  strokes whose chain's strongest peak relative to its layer's seedStrength lies within `share` of 1. Counted over
 *  kept and dropped strokes alike. Throws std::invalid_argument naming 'share' unless it is finite and in [0, 1), and
 *  naming 'layers' when a stroke's layer is not in it. */
struct StrokesNearLimits {
    std::vector<std::size_t> length; ///< per layer
    std::vector<std::size_t> seed;   ///< per layer
};
StrokesNearLimits strokesNearLimits(const Strokes& strokes, const std::vector<StrokeLayer>& layers, double share);

/** One line drawn once: a kept stroke of a later layer with at least half its points within `halfWidths[later] +
 *  the widest earlier half width` (data pixels) of a kept stroke of an earlier layer (the contour along the outline's
 *  band, a crease along a contour) is that line drawn again, and is not drawn. Decided per stroke, so no scattered
 *  pieces are left where two lines part. Layers in `layers`' order: earlier ones win (the composite's order,
 *  docs/lines.md). Throws std::invalid_argument naming 'halfWidths' unless it holds one width per layer. */
void mergeOverlaps(Strokes& strokes, const std::vector<StrokeLayer>& layers, const std::vector<double>& halfWidths);

/** A kept stroke's points with `width` set: its line weight, a share of the layer's width in (0, 1]. */
using StrokeWeight = std::vector<float>;

/** What scales a stroke's width (docs/lines.md, "Line weight"). Each factor is in (0, 1]; they multiply. */
struct LineWeightSettings {
    /** Thinner far away: the width falls linearly from 1 at `nearDepth` to `farWidth` at `farDepth` (linear view
     *  depths; clamped outside). 1 turns it off. */
    double farWidth = 1.0;
    double nearDepth = 0.0, farDepth = 0.0;
    /** Thinner where weaker: width x (1 - strengthShare + strengthShare x strength); 0 turns it off. */
    double strengthShare = 0.0;
    /** Tapered ends: an open stroke's width grows from `taperStart` at each end to 1 over `taperPixels` (data pixels)
     *  or half the stroke, whichever is shorter. 0 pixels turns it off. */
    double taperPixels = 0.0;
    double taperStart = 0.25;
    bool any() const { return farWidth != 1.0 || strengthShare != 0.0 || taperPixels != 0.0; }
};

/** Scales every point's `width` in the kept strokes by `weight` (a point's own width, 1 unless a band of varying
 *  width set it, times the weight's share; at least 0.02); `depth` (CV_32FC1 at the data size, linear view
 *  depth, 0 = background, may be empty when weight.farWidth is 1) gives each point's depth (off the model: the
 *  nearest surface within 3 pixels, else the far depth). Throws std::invalid_argument naming 'depth' when it is
 *  needed and is not CV_32FC1 or not `dataSize`. */
void weighStrokes(Strokes& strokes, const LineWeightSettings& weight, const cv::Mat& depth, cv::Size dataSize);

/** What strokeLines() draws of layer `layer`: at the data size, the layer's own sub-pixel points on the pixels of its
 *  kept strokes (each with the width share of its pixel's stroke point) and the points bridging their gaps, and a
 *  mask of those pixels. With every stroke kept and no weight this is the layer's skeleton as it was found. A layer
 *  found at a lower resolution is drawn from its traced positions, filled in to a data pixel apart (a line traced
 *  every two data pixels and stamped with discs of a data pixel's radius would be beaded, half ink between two
 *  points). `layers` as given to chainStrokes(). */
LineSkeleton keptSkeleton(const Strokes& strokes, const std::vector<StrokeLayer>& layers, int layer);

/** Layer `layer`'s kept strokes as polylines (Ramer-Douglas-Peucker with `tolerancePixels`, data pixels), in stroke
 *  order, with each vertex's width share in `widths` (one vector per polyline, when not null). With `widths`, the
 *  polylines also keep the points where a side of the line (half the width, at `widthPixels` data pixels per share)
 *  would leave its straight interpolation between kept neighbours by more than `tolerancePixels` or an eighth of
 *  `widthPixels`, the smaller: a straight tapered stroke keeps its middle. */
std::vector<Polyline> strokePolylines(const Strokes& strokes, int layer, double tolerancePixels,
                                      std::vector<std::vector<float>>* widths = nullptr, double widthPixels = 1.0);

/** The opacity of each of layer `layer`'s kept strokes, in strokePolylines()' order: the mean strength of its points
 *  that carry one of their own (a faded line's, e.g. suggestive contours' --suggestive-fade; 1 for a full line),
 *  leaving out the token strength of pixels that bridge a gap. */
std::vector<float> strokeOpacities(const Strokes& strokes, int layer);

} // namespace inkgraph
