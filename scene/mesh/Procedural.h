#pragma once
/** @file Analytic meshes for tests and benchmarks, built to any size. */

#include "scene/Scene.h"

namespace inkgraph {

/** A UV sphere with exact unit normals (position - centre) / radius, `segments` around and `rings` from pole to pole.
 *  Triangle count: 2 x segments x (rings - 1). */
Mesh makeUvSphere(glm::vec3 center, float radius, int segments, int rings);

/** A torus around the z axis: P(u,v) = ((R + r cos v) cos u, (R + r cos v) sin u, r sin v), with exact normals.
 *  Triangle count: 2 x majorSegments x minorSegments. */
Mesh makeTorus(float majorRadius, float minorRadius, int majorSegments, int minorSegments);

/** An axis-aligned cube of half-size `halfSize` with hard edges, as a file with per-face normals gives it: 24
 *  vertices (each face its own 4, carrying the face normal), 12 triangles counter-clockwise from outside, each face
 *  split along the diagonal from its first corner to its third. */
Mesh makeCube(glm::vec3 center, float halfSize);

/** Wraps one mesh as a scene (no camera, no light), with a report as if it were loaded. */
Scene makeScene(Mesh mesh);

} // namespace inkgraph
