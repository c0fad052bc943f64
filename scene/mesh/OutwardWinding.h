#pragma once
/** @file Closed meshes wound inside out, turned outward at load. The inflated hull (the silhouette pass) pushes each
 *  vertex out along its normal and draws the hull's back faces, and Lander's outline draws the model's back faces: both
 *  take a triangle's counter-clockwise side as the outside. A closed mesh whose faces are wound clockwise seen from
 *  outside (some OBJ, STL and PLY exporters, a scan flipped by its software) then loses its silhouette entirely: the
 *  hull shrinks inside the model and only its inner side is drawn, hidden. No GL. */

#include <glm/glm.hpp>

#include <span>
#include <vector>

namespace inkgraph {

/** What orientMeshOutward() changed. */
struct OutwardTurn {
    bool windingReversed = false; ///< every triangle's winding reversed: the mesh was closed and inside out
    bool normalsFlipped = false;  ///< the given normals pointed inward as well and were turned round
};

/** Turns a closed mesh that is wound inside out outward: when the signed volume its triangles enclose is negative
 *  (clockwise seen from outside) and the mesh is closed, each triangle's last two corners swap; given normals
 *  (`normals`, empty or one per position) that then point against the faces they belong to (the area-weighted sum
 *  of n . face normal over all corners is negative) are negated too. Closed here means, with vertices within
 *  `weldDistance` as one (buildEdgeAdjacency()), at most 1% of the edges on a rim or shared by more than two faces
 *  and at most 1% of the shared edges run the same way by both their faces: a scan with a few small holes counts,
 *  an open surface (a plane, a dish, a cloth), whose inside is a matter of the view, does not, and is left as it
 *  is. A volume within 1e-9 of the cubed bounding-box diagonal (a closed sheet of two coincident sides) decides
 *  nothing either. */
OutwardTurn orientMeshOutward(std::span<const glm::vec3> positions, std::vector<glm::uvec3>& triangles,
                              std::vector<glm::vec3>& normals, double weldDistance);

} // namespace inkgraph
