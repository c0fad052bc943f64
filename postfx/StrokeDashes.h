#pragma once
/** @file Dashed strokes (--hidden-dash, docs/lines.md "Hidden lines"): a layer's kept strokes cut into their dashes by
 *  arc length, as Freestyle's dashed line shader and a technical drawing's hidden lines are. The strokes themselves
 *  are cut, so the raster (keptSkeleton(), strokeLines()) and the --svg paths (strokePolylines()) draw the same dashes.
 *  A pure function over Strokes: no GL, no file I/O. */

#include "postfx/Strokes.h"

namespace inkgraph {

/** A dash pattern along a stroke, in data pixels: `onPixels` drawn, then `offPixels` left out, repeated. */
struct DashPattern {
    double onPixels = 6.0;
    double offPixels = 4.0;
    /** No gaps: the strokes are drawn whole. */
    bool solid() const { return offPixels == 0.0; }
};

/** Cuts each kept stroke of layer `layer` into its dashes and returns how many dashes the layer is drawn as (a stroke
 *  no longer than `onPixels`, left whole, counts as one); other layers' strokes and dropped strokes are left as they
 *  are. The pattern starts at a stroke's first point (a dash) and runs on along
 *  its arc length through every point: a point whose arc length s has (s mod (on + off)) < on is drawn, and each dash
 *  ends and begins exactly on the pattern's boundary, at a point placed there on the segment it cuts (its pixel
 *  (-1, -1), as a bridging point; width and strength interpolated). A closed stroke's pattern runs round it from its
 *  first point, and the last dash, when it reaches the seam, continues into the first one (so a closed stroke has no
 *  break at its seam that the pattern does not put there). A stroke no longer than `onPixels` stays whole. A dash is
 *  an open Stroke of the same layer and chain, kept, with its own length and strengths; the dashes of a stroke replace
 *  it in place, in order along it. A solid pattern changes nothing. Throws std::invalid_argument naming 'pattern'
 *  for an `onPixels` not above 0 or an `offPixels` below 0 (or either not finite). */
std::size_t dashStrokes(Strokes& strokes, int layer, const DashPattern& pattern);

} // namespace inkgraph
