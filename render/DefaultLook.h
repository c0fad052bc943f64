#pragma once
/** @file The look a still has when nobody chooses one: the command line's default and the library's Look(). */

#include "passes/Look.h"

#include <string>
#include <vector>

namespace inkgraph {

/** The line types drawn when neither --lines nor a style file names any: the silhouette (the inflated hull, bold around
 *  the figure) and the contour (n.v zero crossings and the model's ends, one pixel), which also edges a flat card seen
 *  face-on, where the hull has no width. */
inline const std::vector<std::string> kDefaultLines = {"silhouette", "contour"};

/** A Look with kDefaultLines, so no model is white on white: a white or untextured model's lit band is the paper's
 *  colour, and its lines still set it apart. */
inline Look defaultLook() {
    Look look;
    look.lines = kDefaultLines;
    return look;
}

} // namespace inkgraph
