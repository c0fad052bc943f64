#pragma once
/** @file Material boundaries: where the visible material (or object) changes, as Pencil+ and Blender Freestyle draw
 *  them. Pure cv::Mat: no GL. */

#include "postfx/LineSkeleton.h"

#include <opencv2/core.hpp>

namespace inkgraph {

/** `materialId`: CV_32FC1, the visible surface's material id + 1 as an exact whole number, 0 off the model (the
 *  G-buffer's materialId field). Every pair of 4-neighbours that both hold the model with different ids is a boundary:
 *  the left or upper pixel of the pair is marked and a point of full strength is put at the midpoint of the two
 *  centres, so the line runs exactly along the pixel edge between the two materials. Where the model meets the
 *  background nothing is drawn (that is the contour). Throws std::invalid_argument naming 'materialId' unless
 *  CV_32FC1 and non-empty. */
LineSkeleton extractMaterialBoundaries(const cv::Mat& materialId);

} // namespace inkgraph
