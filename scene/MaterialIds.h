#pragma once
/** @file A small id per mesh that is equal exactly for meshes of the same material, for the G-buffer's material-id
 *  field (the material-boundary lines). No GL. */

#include "scene/Scene.h"

#include <cstdint>
#include <vector>

namespace inkgraph {

/** One id per mesh of `scene` by its number (scene/MeshNumbering.h: the skipped meshes too, so a pose that collapses
 *  one leaves the other ids as they are; MeshNumbering::numberOf() finds a drawn mesh's entry): meshes share an id
 * exactly when they have the same Mesh::materialName, the same baseColor (compared exactly) and the same shadeMapPath.
 * Meshes without a material name share an id when their base colour and shade map are equal, since they look the same;
 * a named material never shares with an unnamed one. Ids are dense from 0, in the order of each material's first mesh.
 */
std::vector<std::uint32_t> materialIds(const Scene& scene);

} // namespace inkgraph
