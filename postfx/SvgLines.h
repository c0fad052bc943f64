#pragma once
/** @file Traced line layers (LineTracing) as one standalone SVG 1.1 document, one Inkscape layer per line type. Pure
 *  functions: no GL, no file I/O (the caller writes the string).
 *
 *  Coordinates. SVG user units are output pixels, origin at the top-left corner of the image, x right, y down; the
 *  viewBox is "0 0 width height" and width/height are the output size, so one user unit is one pixel. A layer's
 *  polylines are in data pixels at `supersample` S x the output size with pixel centres at integers (LinePoint
 *  coordinates), and map to x_svg = (x + 0.5) / S, y_svg = (y + 0.5) / S: a data pixel's centre lands on the centre
 *  of the output area it covers (at S = 1, data pixel (col, row) at (col + 0.5, row + 0.5)). Coordinates are written
 *  rounded to 2 decimals (1/100 output pixel), without trailing zeros. */

#include "postfx/LineTracing.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** One line type's polylines and how they are stroked. */
struct SvgLineLayer {
    std::string type;                ///< e.g. "contour": the group id is "lines-<type>"; [A-Za-z0-9_.-]+, unique
    std::vector<Polyline> polylines; ///< in data pixels at `supersample` x the output size
    int supersample = 1;             ///< >= 1: how many data pixels make one output pixel along each axis
    double widthPixels = 2;          ///< stroke width in output pixels, finite and > 0
    std::array<double, 4> color{0, 0, 0, 1}; ///< display (sRGB-encoded) RGBA, each in [0, 1]: stroke and opacity
    /** Line weight, optional: empty, or one entry per polyline with each vertex's width in output pixels (finite,
     *  > 0). A weighted polyline is written as a filled outline (its two sides at half the width from each vertex,
     *  joined by round caps), since an SVG stroke has one width. */
    std::vector<std::vector<double>> widths;
    /** Optional: empty, or one opacity per polyline in (0, 1], a faded line's (strokeOpacities()), written as the
     *  path's own stroke-opacity (fill-opacity for a weighted one) under the layer's group opacity. */
    std::vector<double> opacities;
};

/** The document around the layers. */
struct SvgDocumentOptions {
    std::string title;                               ///< the <title>, XML-escaped (e.g. the model's file name)
    std::optional<std::array<double, 4>> background; ///< display RGBA in [0, 1]: a full-size rect below the lines
};

/** A standalone SVG 1.1 document (UTF-8) of `width` x `height` output pixels:
 *  - the XML declaration, then <svg> with the SVG and Inkscape namespaces, width, height and viewBox "0 0 W H";
 *  - <title>: `options.title` with & < > " ' escaped, control characters other than tab, newline and carriage
 *    return, and bytes that are not valid UTF-8, replaced by '?' (XML 1.0 cannot hold them);
 *  - with `options.background`: <rect id="background"> covering the image, fill #rrggbb and fill-opacity;
 *  - per layer, in the given order (later layers are drawn on top): <g id="lines-<type>"
 *    inkscape:groupmode="layer" inkscape:label="<type>" opacity="A" fill="none" stroke="#rrggbb" stroke-width="W"
 *    stroke-linecap="round" stroke-linejoin="round">, an empty group when it has no polylines. The colour's alpha A
 *    is the group's opacity, so the layer is drawn opaque and then laid on at A, as the picture composites it: where
 *    its paths overlap they do not darken each other;
 *  - per polyline one <path d="M x y L x y ..."/> with absolute commands (with `widths`, a filled outline:
 *    <path fill="#rrggbb" stroke="none" d="M left side A right side A Z"/>), with stroke-opacity="O" (fill-opacity
 *    for a filled outline) where `opacities` gives it an opacity O below 1, " Z" appended when closed
 * (and it has 2 points or more). A 1-point polyline is written as a zero-length segment "M x y L x y", which round caps
 * draw as a dot of the stroke width; a polyline with no points writes nothing. Colours: each channel c becomes
 * round(255 c) in the hex colour; opacity is written with 3 decimals at most. Throws std::invalid_argument naming the
 * argument for a 'width' or 'height' below 1, and in 'layers' for a 'type' that is empty, holds a character outside
 * [A-Za-z0-9_.-] or repeats an earlier one, a 'supersample' below 1, a non-finite or non-positive 'widthPixels', a
 * 'color' channel outside [0, 1] or non-finite, a non-finite coordinate in 'polylines', or 'opacities' not one per
 * polyline in (0, 1]; and for an
 * 'options.background' channel outside [0, 1]. */
std::string svgDocument(int width, int height, const std::vector<SvgLineLayer>& layers,
                        const SvgDocumentOptions& options = {});

} // namespace inkgraph
