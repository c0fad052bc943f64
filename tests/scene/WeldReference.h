#pragma once
/** @file The weld as it was written before issue 20 (a hash grid, vertices in input order, 8 cells looked up as each
 *  vertex comes): the reference weldVertices(), which now makes its lookups ahead and prefetches them, must match map
 *  for map. Test code only. */

#include "scene/mesh/MeshOps.h"

#include <cstdint>
#include <span>

namespace inkgraph::test {

/** weldVertices()'s contract, computed by the original hash-grid code. */
WeldMap referenceWeldVertices(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals, double distance,
                              std::span<const std::uint32_t> attributeClasses = {});

} // namespace inkgraph::test
