#include "scene/SceneDerivedData.h"

#include "scene/MeshLabels.h"
#include "scene/mesh/SmoothPatches.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace inkgraph {

namespace {

/** `item`'s value, made by `make` on the first call (whichever thread comes first; the others wait for it). A `make`
 *  that throws leaves the item to be made by the next call. */
template <typename Item, typename Make>
const auto& derivedOnce(Item& item, Make&& make) {
    std::call_once(item.once, [&] {
        item.value = make();
        item.done.store(true);
    });
    return *item.value;
}

} // namespace

SceneDerivedData::SceneDerivedData(const Scene& scene) : mScene(scene) {
    mPositionWelds.reserve(scene.meshes.size());
    for (std::size_t index = 0; index < scene.meshes.size(); ++index)
        mPositionWelds.push_back(std::make_unique<Derived<WeldMap>>());
}

void SceneDerivedData::requireMeshIndex(const char* function, std::size_t meshIndex) const {
    if (meshIndex >= mScene.meshes.size())
        throw std::out_of_range(std::string(function) + ": mesh " + std::to_string(meshIndex) +
                                " out of range (the scene has " + std::to_string(mScene.meshes.size()) + ")");
}

const WeldMap& SceneDerivedData::positionWeld(std::size_t meshIndex) {
    requireMeshIndex("SceneDerivedData::positionWeld()", meshIndex);
    // One scene-wide distance, the load's: relative to the whole model, so units do not matter.
    const double distance = derivedOnce(mWeldDistance, [&] {
        BoundingBox box;
        for (const Mesh& mesh : mScene.meshes) {
            const BoundingBox meshBox = computeBoundingBox(mesh.positions);
            if (meshBox.empty()) continue;
            box.add(meshBox.min);
            box.add(meshBox.max);
        }
        return mScene.report.weldTolerance * box.diagonal();
    });
    return derivedOnce(*mPositionWelds[meshIndex],
                       [&] { return weldMeshPositions(mScene.meshes[meshIndex], distance); });
}

bool SceneDerivedData::positionWeldComputed(std::size_t meshIndex) const {
    return meshIndex < mPositionWelds.size() && mPositionWelds[meshIndex]->done.load();
}

const std::vector<glm::vec3>* SceneDerivedData::hullNormals(std::size_t meshIndex) {
    requireMeshIndex("SceneDerivedData::hullNormals()", meshIndex);
    const auto& normals = derivedOnce(mHullNormals, [&] {
        std::vector<std::optional<std::vector<glm::vec3>>> perMesh(mScene.meshes.size());
        for (std::size_t index = 0; index < mScene.meshes.size(); ++index) {
            const Mesh& mesh = mScene.meshes[index];
            const WeldMap& weld = positionWeld(index);
            // Nothing welded (kept in order) and smooth normals of their own: computePositionWeldedNormals() would
            // compute exactly computeSmoothNormals(positions, triangles), which the mesh already holds.
            if (mesh.normalsAreSmooth && weld.kept.size() == mesh.positions.size()) continue;
            perMesh[index] = computePositionWeldedNormals(mesh.positions, mesh.triangles, weld);
        }
        return perMesh;
    });
    return normals[meshIndex] ? &*normals[meshIndex] : nullptr;
}

const std::vector<glm::uvec3>* SceneDerivedData::hullTriangles(std::size_t meshIndex) {
    requireMeshIndex("SceneDerivedData::hullTriangles()", meshIndex);
    const auto& triangles = derivedOnce(mHullTriangles, [&] {
        std::vector<std::optional<std::vector<glm::uvec3>>> perMesh(mScene.meshes.size());
        for (std::size_t index = 0; index < mScene.meshes.size(); ++index) {
            const Mesh& mesh = mScene.meshes[index];
            const WeldMap& weld = positionWeld(index);
            std::vector<glm::uvec3> welded(mesh.triangles.size());
            for (std::size_t t = 0; t < welded.size(); ++t)
                welded[t] = glm::uvec3(weld.outputOf[mesh.triangles[t].x], weld.outputOf[mesh.triangles[t].y],
                                       weld.outputOf[mesh.triangles[t].z]);
            const std::vector<std::uint32_t> twins = backToBackTwins(welded);
            if (twins.empty()) continue;
            std::vector<glm::uvec3> kept = mesh.triangles;
            removeTriangles(kept, twins);
            perMesh[index] = std::move(kept);
        }
        return perMesh;
    });
    return triangles[meshIndex] ? &*triangles[meshIndex] : nullptr;
}

const EdgeAdjacency& SceneDerivedData::edgeAdjacency(std::size_t meshIndex) {
    requireMeshIndex("SceneDerivedData::edgeAdjacency()", meshIndex);
    return derivedOnce(mEdgeAdjacency, [&] {
        std::vector<EdgeAdjacency> adjacency;
        adjacency.reserve(mScene.meshes.size());
        for (std::size_t index = 0; index < mScene.meshes.size(); ++index) {
            const Mesh& mesh = mScene.meshes[index];
            adjacency.push_back(buildEdgeAdjacency(mesh.positions, mesh.triangles, positionWeld(index)));
        }
        return adjacency;
    })[meshIndex];
}

const MeshCurvature& SceneDerivedData::meshCurvature(std::size_t meshIndex, double smoothing) {
    requireMeshIndex("SceneDerivedData::meshCurvature()", meshIndex);
    Derived<std::vector<MeshCurvature>>* entry = nullptr;
    {
        const std::lock_guard<std::mutex> lock(mCurvatureMutex);
        auto& slot = mCurvature[smoothing];
        if (!slot) slot = std::make_unique<Derived<std::vector<MeshCurvature>>>();
        entry = slot.get(); // entries are never removed: the pointer stays valid without the lock
    }
    return derivedOnce(*entry, [&] {
        // Every mesh's cost first, in all: a refusal must not come after minutes of work on the meshes before, nor
        // many meshes each within the limit add up to hours.
        std::vector<MeshToSmooth> meshes;
        for (std::size_t index = 0; index < mScene.meshes.size(); ++index)
            meshes.push_back({mScene.meshes[index].positions, mScene.meshes[index].triangles, &positionWeld(index)});
        requireAffordableSmoothing(meshes, smoothing);
        std::vector<MeshCurvature> curvature;
        curvature.reserve(mScene.meshes.size());
        for (std::size_t index = 0; index < mScene.meshes.size(); ++index) {
            const Mesh& mesh = mScene.meshes[index];
            curvature.push_back(computeMeshCurvature(mesh.positions, mesh.triangles, positionWeld(index), smoothing));
        }
        return curvature;
    })[meshIndex];
}

bool SceneDerivedData::meshCurvatureComputed(double smoothing) const {
    const std::lock_guard<std::mutex> lock(mCurvatureMutex);
    const auto found = mCurvature.find(smoothing);
    return found != mCurvature.end() && found->second->done.load();
}

bool SceneDerivedData::meshCurvatureComputed() const {
    const std::lock_guard<std::mutex> lock(mCurvatureMutex);
    for (const auto& [smoothing, entry] : mCurvature)
        if (entry->done.load()) return true;
    return false;
}

const MeshIntersections& SceneDerivedData::meshIntersections() {
    return derivedOnce(mIntersections, [&] {
        std::vector<const WeldMap*> welds;
        welds.reserve(mScene.meshes.size());
        for (std::size_t index = 0; index < mScene.meshes.size(); ++index) welds.push_back(&positionWeld(index));
        return findMeshIntersections(mScene.meshes, welds);
    });
}

const SceneDerivedData::SurfacePatches& SceneDerivedData::surfacePatches() {
    return derivedOnce(mSurfacePatches, [&] {
        SurfacePatches patches;
        const TriangleNumbering numbering(mScene);
        // Id 0 is off the model; a dropped triangle's id appears nowhere.
        patches.patchOfTriangle.assign(numbering.total() + 1, 0.0f);
        for (std::size_t index = 0; index < mScene.meshes.size(); ++index) {
            const Mesh& mesh = mScene.meshes[index];
            const SmoothPatches meshPatches =
                smoothPatches(mesh.normals, mesh.triangles, positionWeld(index), edgeAdjacency(index));
            patches.seamEdges += meshPatches.seamEdges;
            for (std::size_t triangle = 0; triangle < meshPatches.patchOf.size(); ++triangle)
                patches.patchOfTriangle[numbering.global(index, triangle) + 1] =
                    float(numbering.global(index, meshPatches.patchOf[triangle]) + 1);
        }
        return patches;
    });
}

bool SceneDerivedData::surfacesMeet() {
    return derivedOnce(mSurfacesMeet, [&] {
        bool meet = mScene.meshes.size() > 1;
        for (std::size_t index = 0; !meet && index < mScene.meshes.size(); ++index)
            meet = !isOneSmoothPatch(mScene.meshes[index].normals, mScene.meshes[index].triangles, positionWeld(index));
        return meet;
    });
}

} // namespace inkgraph
