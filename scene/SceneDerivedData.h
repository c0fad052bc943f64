#pragma once
/** @file What the passes derive from a scene's meshes whatever the view: position welds, hull normals, edge adjacency,
 *  curvature, intersections, smooth patches. Each is derived the first time something asks for it (only a pass that
 *  runs asks) and kept as long as this object. The stills that draw one loaded scene share one (a batch's views of a
 *  model, app/RecentModel.h; a library Scene rendered again), so a later view derives nothing: on a 1.3-million-
 *  triangle mesh the object-space suggestive contours' curvature alone takes most of a minute. Safe to use from several
 *  threads at once (a still's post stage reads it on a worker while the next still's passes ask on the drawing thread):
 *  each item is derived once, by whoever asks first, the others waiting for that item only. */

#include "scene/Scene.h"
#include "scene/mesh/EdgeAdjacency.h"
#include "scene/mesh/MeshCurvature.h"
#include "scene/mesh/MeshIntersections.h"
#include "scene/mesh/MeshOps.h"

#include <glm/glm.hpp>

#include <atomic>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

namespace inkgraph {

class SceneDerivedData {
public:
    /** The smooth surfaces of the scene as the G-buffer's triangleId numbers triangles (scene/MeshLabels.h
     *  TriangleNumbering, + 1): entry t of `patchOfTriangle` is the patch of triangle id t, named by the triangleId of
     *  its first triangle (scene/mesh/SmoothPatches.h: joined across edges where the normals are continuous; meshes
     *  never join one another), 0 at t = 0 (off the model) and at the ids of triangles the loader dropped; floats,
     *  exact below 2^24 triangles as triangleId is. */
    struct SurfacePatches {
        std::vector<float> patchOfTriangle;
        std::size_t seamEdges = 0; ///< edges where a mesh's normals step (SmoothPatches::seamEdges), over all meshes
    };

    /** Keeps a reference to `scene`, which must outlive this object and not change. */
    explicit SceneDerivedData(const Scene& scene);
    SceneDerivedData(const SceneDerivedData&) = delete;
    SceneDerivedData& operator=(const SceneDerivedData&) = delete;

    const Scene& scene() const { return mScene; }

    /** The position weld of mesh `meshIndex` (MeshOps weldMeshPositions(), distance the loader's default relative
     *  tolerance x the scene's bounding-box diagonal): what the hull normals, the edge adjacency and the curvature are
     *  built on. Throws std::out_of_range for a bad index. */
    const WeldMap& positionWeld(std::size_t meshIndex);
    bool positionWeldComputed(std::size_t meshIndex) const;

    /** Unit normals for the inflated hull of mesh `meshIndex`, one per vertex: smooth normals shared by every vertex
     *  at the same position (MeshOps computePositionWeldedNormals() on positionWeld()), so split normals at hard edges
     *  do not tear the hull open. Null where the mesh's own normals are exactly these (its weld merges nothing and its
     *  normals are the smooth ones, Mesh::normalsAreSmooth). Derived for every mesh at once. */
    const std::vector<glm::vec3>* hullNormals(std::size_t meshIndex);

    /** The triangles of mesh `meshIndex`'s inflated hull: its own without the later of each back-to-back pair on
     *  positionWeld() (MeshOps backToBackTwins(): a double-faced card of a one-sided material, whose second sheet's
     *  hull would lie on the first's and draw lines across it). Null where there is no such pair, the mesh's own
     *  triangles serving. Derived for every mesh at once. */
    const std::vector<glm::uvec3>* hullTriangles(std::size_t meshIndex);

    /** Edge adjacency of mesh `meshIndex` (scene/mesh/EdgeAdjacency.h), keyed on positionWeld(), so split normals do
     *  not turn creases into borders. Derived for every mesh at once. */
    const EdgeAdjacency& edgeAdjacency(std::size_t meshIndex);
    bool edgeAdjacencyComputed() const { return mEdgeAdjacency.done.load(); }

    /** Per-vertex curvature of mesh `meshIndex` (scene/mesh/MeshCurvature.h) on positionWeld(), smoothed over
     *  `smoothing` model units (computeMeshCurvature()). Derived for every mesh at once, per smoothing asked. */
    const MeshCurvature& meshCurvature(std::size_t meshIndex, double smoothing);
    /** Whether the curvature for this smoothing, or for any, is derived. */
    bool meshCurvatureComputed(double smoothing) const;
    bool meshCurvatureComputed() const;

    /** Where the scene's surfaces cross (scene/mesh/MeshIntersections.h), on positionWeld() of every mesh. */
    const MeshIntersections& meshIntersections();
    bool meshIntersectionsComputed() const { return mIntersections.done.load(); }

    /** The scene's smooth patches, on positionWeld() and edgeAdjacency(). */
    const SurfacePatches& surfacePatches();
    bool surfacePatchesComputed() const { return mSurfacePatches.done.load(); }

    /** Whether surfacePatches() can tell surfaces apart that the depth cannot: the scene has several meshes, or a mesh
     *  that is not one smooth patch (isOneSmoothPatch(), on positionWeld()). False for one mesh smooth and connected
     *  everywhere, answered without any adjacency. */
    bool surfacesMeet();

    /** Throws std::out_of_range starting with `function` unless the scene has mesh `meshIndex`. */
    void requireMeshIndex(const char* function, std::size_t meshIndex) const;

private:
    /** One item derived once: `once` guards `value`, and `done` says so without waiting. */
    template <typename T>
    struct Derived {
        std::once_flag once;
        std::optional<T> value;
        std::atomic<bool> done{false};
    };

    const Scene& mScene;
    Derived<double> mWeldDistance;
    std::vector<std::unique_ptr<Derived<WeldMap>>> mPositionWelds; ///< one per mesh
    /** Per mesh: the hull normals, or none where the mesh's own serve. */
    Derived<std::vector<std::optional<std::vector<glm::vec3>>>> mHullNormals;
    /** Per mesh: the hull's triangles, or none where the mesh's own serve. */
    Derived<std::vector<std::optional<std::vector<glm::uvec3>>>> mHullTriangles;
    Derived<std::vector<EdgeAdjacency>> mEdgeAdjacency;
    mutable std::mutex mCurvatureMutex; ///< guards the map, not its entries
    std::map<double, std::unique_ptr<Derived<std::vector<MeshCurvature>>>> mCurvature;
    Derived<MeshIntersections> mIntersections;
    Derived<SurfacePatches> mSurfacePatches;
    Derived<bool> mSurfacesMeet;
};

} // namespace inkgraph
