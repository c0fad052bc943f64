#pragma once
/** @file Material and object boundaries: where the visible material or object changes, as Pencil+ and Blender
 *  Freestyle draw them. One kernel over an id field serves both line types. Pure cv::Mat: no GL. */

#include "postfx/LineSkeleton.h"

#include <opencv2/core.hpp>

#include <string>

namespace inkgraph {

/** `ids`: CV_32FC1, an id + 1 per pixel as an exact whole number, 0 off the model (the G-buffer's materialId or
 *  objectId field). Every pair of 4-neighbours that both hold the model with different ids is a boundary: the left or
 *  upper pixel of the pair is marked and a point of full strength is put at the midpoint of the two centres, so the
 *  line runs exactly along the pixel edge between the two ids. Where the model meets the background nothing is drawn
 *  (that is the contour). Throws std::invalid_argument quoting `fieldName` unless CV_32FC1 and non-empty. */
LineSkeleton extractIdBoundaries(const cv::Mat& ids, const std::string& fieldName);

/** extractIdBoundaries() of the G-buffer's materialId field: where the visible material changes. */
LineSkeleton extractMaterialBoundaries(const cv::Mat& materialId);

} // namespace inkgraph
