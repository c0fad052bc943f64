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
    std::vector<std::uint32_t> turnedTriangles; ///< the triangles whose last two corners swapped, ascending
};

/** Turns the closed surfaces of a mesh that are wound inside out outward. Each connected surface (the triangles
 *  joined through shared vertices, those within `weldDistance` counting as one) is judged alone: when the volume its
 *  triangles enclose is negative (clockwise seen from outside) and it is closed, each of its triangles' last two
 *  corners swap; given normals (`normals`, empty or one per position) of the turned surfaces' vertices that then point
 *  against their faces (the area-weighted sum of n . face normal over their corners is negative) are negated too.
 *  Closed here means at most 1% of the surface's edges on a rim or shared by more than two faces
 *  (buildEdgeAdjacency()) and at most 1% of its shared edges run the same way by both their faces: a scan with a few
 *  small holes counts; an open surface (a floor, a dish, a cloth), whose inside is a matter of the view, does not and
 *  is left as it is, and so is a surface whose volume is within 1e-9 of its cubed bounding-box diagonal (a closed sheet
 *  of two coincident sides). Only a mesh whose triangles enclose a negative volume in all is looked at surface by
 *  surface, so the common case costs one pass over the triangles. */
OutwardTurn orientMeshOutward(std::span<const glm::vec3> positions, std::vector<glm::uvec3>& triangles,
                              std::vector<glm::vec3>& normals, double weldDistance);

/** Turns the faces of a connected surface that are wound against their neighbours (a patch of a scan merged from
 *  several range images, an exporter's flipped faces), so each surface is wound one way and the G-buffer's front
 *  faces, the hull and the outline see one side as the outside. Faces are neighbours across manifold edges (two faces,
 *  vertices within `weldDistance` counting as one: buildEdgeAdjacency()); two that run their shared edge the same
 *  way disagree. Of the two ways to wind each surface, the one the given normals (`normals`, one per position, or
 *  empty) agree with is kept, without normals the one most of its area is wound already, so a few faces turn, not the
 *  rest. A non-orientable surface (a Möbius band) keeps the way found first along each face's first neighbour.
 *  Returns the triangles whose last two corners it swapped, ascending; none on a mesh wound one way throughout. */
std::vector<std::uint32_t> turnMixedWinding(std::span<const glm::vec3> positions, std::vector<glm::uvec3>& triangles,
                                            std::span<const glm::vec3> normals, double weldDistance);

/** Turns round given normals that point against their faces' winding nearly everywhere: a caller's normals made with
 *  the other convention (clockwise cross products, normals of the inside), or a mesh whose faces were turned without
 *  its normals. A vertex's normal points against its faces when the sum over its corners of n . (b - a) x (c - a) is
 *  negative; when the corners whose own n . (b - a) x (c - a) is negative hold more than 90% of the mesh's corner
 *  area, the normals of those vertices are negated. The G-buffer turns a back face's normal toward the eye by its
 *  winding, so a normal against the winding is inward seen from either side: lighting and every n . v line read it
 *  reversed. Normals that disagree on less of the mesh (a foliage card's normals bent round the tree) are left as
 *  given. Returns how many normals were negated. */
std::size_t turnNormalsAlongWinding(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                    std::vector<glm::vec3>& normals);

} // namespace inkgraph
