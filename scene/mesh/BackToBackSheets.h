#pragma once
/** @file Sheets that lie back to back on corners of their own, each seen from its own side only. No GL. */

#include "scene/Scene.h"

#include <cstddef>
#include <vector>

namespace inkgraph {

/** A card printed on both sides, written as two sheets on the same corners wound opposite ways whose sides carry
 *  texture coordinates or colours of their own, or are meshes of two materials, is drawn at one depth twice by a
 *  two-sided material: from either side the sheet drawn first, or stripes of both, show (a red and blue card looked red
 *  from behind). finalizeMesh() drops a twin that adds nothing (same mesh, same attributes); these it cannot, since
 *  each side is its own picture. Here every triangle of the scene is placed by its corners welded within
 *  `weldDistance`; a triangle's back is covered when an opaque triangle on the same corners faces the other way, in its
 *  own mesh or another (a blended sheet lets the back behind it show, an alpha-masked one shows it through holes that
 *  need not be the back's own), however many sheets lie there and in whatever order. A mesh of a two-sided material
 *  whose every triangle's back is so covered is drawn from its front only (Mesh::backCulled; its material stays as the
 *  file gives it). A mesh covered only in part (a card inside a larger mesh, a cape doubled where it leaves the body)
 *  is left as it is: culling part of a mesh's triangles is not done. Takes meshes as finalizeMesh() leaves them, so a
 *  lone mesh without texture coordinates or colours, whose twins it matched on positions, is passed over. Returns how
 *  many triangles are now drawn from their front only. */
std::size_t cullBackToBackSheets(std::vector<Mesh>& meshes, double weldDistance);

} // namespace inkgraph
