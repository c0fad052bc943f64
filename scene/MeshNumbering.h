#pragma once
/** @file The order that numbers a scene's meshes, objects, materials and triangles (scene/MeshLabels.h,
 *  scene/ObjectIds.h, scene/MaterialIds.h): every mesh of the file, the ones the loader skipped as degenerate
 *  (Scene::skippedMeshes) in their places. A pose that collapses a mesh then leaves every other mesh's, object's,
 *  material's and triangle's id as in the rest pose, so the labels of a data set's frames agree. No GL. */

#include "scene/Scene.h"

#include <cstddef>
#include <optional>
#include <vector>

namespace inkgraph {

/** A scene's meshes by number: number n is the mesh whose meshId is n + 1. Keeps a reference to the scene. */
class MeshNumbering {
public:
    /** Throws std::invalid_argument naming the function when Scene::skippedMeshes is not in order (a SkippedMesh's
     *  `before` beyond the drawn meshes or below the one before it). */
    explicit MeshNumbering(const Scene& scene);

    /** How many meshes are numbered: the drawn ones and the skipped ones. */
    std::size_t size() const { return mDrawnIndex.size(); }
    /** Mesh number `number`: a drawn mesh, or a skipped one (no triangles). Throws std::out_of_range beyond size(). */
    const Mesh& mesh(std::size_t number) const;
    /** Its index in Scene::meshes; none for a skipped mesh. */
    std::optional<std::size_t> drawnIndex(std::size_t number) const { return mDrawnIndex.at(number); }
    /** The number of drawn mesh `drawnIndex` (an index into Scene::meshes). Throws std::out_of_range beyond them. */
    std::size_t numberOf(std::size_t drawnIndex) const { return mNumberOfDrawn.at(drawnIndex); }

private:
    const Scene& mScene;
    std::vector<std::optional<std::size_t>> mDrawnIndex; ///< per number
    std::vector<std::size_t> mSkippedIndex;              ///< per number: its index in skippedMeshes, if skipped
    std::vector<std::size_t> mNumberOfDrawn;             ///< per drawn mesh
};

} // namespace inkgraph
