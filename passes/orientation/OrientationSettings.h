#pragma once
/** @file The settings of the CPU face orientation, in a header of their own: GpuScene stores them without including
 *  SceneOrientation.h (which includes GpuScene.h). */

#include "scene/mesh/FaceOrientation.h"

namespace inkgraph {

struct OrientationSettings {
    FaceOrientationMethod method = FaceOrientationMethod::Standard;
    ViewVectorMode viewVector = ViewVectorMode::Exact;
    int frontRule = 3;
    double shininess = 32.0;
};

/** Throws std::invalid_argument, the message starting with `function`, for a front rule outside 1..3 or a negative
 *  (or NaN) shininess. */
void checkOrientationSettings(const char* function, const OrientationSettings& settings);

} // namespace inkgraph
