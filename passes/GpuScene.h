#pragma once
/** @file The scene's meshes on the GPU and the data derived from them (hull normals, edge adjacency, curvature, the
 *  CPU face orientation). Passes declare what they take as imports (SceneImport, PassBuilder::import()); the
 *  renderer derives the imports of the passes that run once, before any prepares (importDerived()). Each getter also
 *  derives on its first call, so a pass run without an importer (the tests) gets the same data. What does not depend
 *  on the view is the scene's SceneDerivedData, which the stills of one scene share (the views of a model). */

#include "gl/GlObjects.h"
#include "passes/material/SceneMaterials.h"
#include "passes/orientation/OrientationSettings.h"
#include "scene/mesh/EdgeAdjacency.h"
#include "scene/mesh/MeshCurvature.h"
#include "scene/mesh/MeshIntersections.h"
#include "scene/mesh/MeshOps.h"
#include "scene/Scene.h"
#include "scene/SceneDerivedData.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

namespace inkgraph {

struct FrameParams;
class SceneOrientation;

/** The scene data passes import (PassBuilder::import()): declared by the passes that use it, derived once by
 *  GpuScene::importDerived() before any pass prepares when the renderer runs the plan. */
namespace SceneImport {
inline constexpr const char* kMeshes = "scene.meshes";                    ///< meshes(): the meshes uploaded
inline constexpr const char* kHulls = "scene.hulls";                      ///< hullArrays(): welded hull normals
inline constexpr const char* kEdgeAdjacency = "scene.edge-adjacency";     ///< edgeAdjacency() of every mesh
inline constexpr const char* kFaceOrientation = "scene.face-orientation"; ///< cpuOrientation()
/** meshCurvature(): declared by the object-space suggestive contours, derived by them at their smoothing. */
inline constexpr const char* kCurvature = "scene.curvature";
/** surfacePatches(): declared by the image-space suggestive contours, which differentiate within one patch only. */
inline constexpr const char* kSurfacePatches = "scene.surface-patches";
/** meshIntersections(): declared by the intersection line types (`intersection`, `hidden-intersection`). */
inline constexpr const char* kIntersections = "scene.intersections";

/** What deriving import `name` adds to the run's peak memory per triangle of the scene, for the still's memory estimate
 *  (render/MemoryBudget.h): the measured cost with room for the spread, a bound. docs/batch.md ("Memory") gives the
 *  measurements. The meshes cost nothing here: the estimate counts them and their GPU copies by vertex and triangle.
 * Throws std::logic_error naming an unknown import. */
std::size_t bytesPerTriangle(std::string_view name);
} // namespace SceneImport

class GpuScene {
public:
    struct DrawMesh {
        GlBuffer positions;
        GlBuffer normals;
        GlBuffer indices;
        GlVertexArray vertexArray;
        GLsizei indexCount;
        glm::vec4 baseColor;
        std::uint32_t materialId;                ///< scene/MaterialIds.h: equal exactly for meshes of the same material
        std::uint32_t objectIndex;               ///< scene/ObjectIds.h: the index of the mesh's object (node instance)
        std::uint32_t meshNumber;                ///< scene/MeshNumbering.h: its meshId - 1, the same in every pose
        MeshAttributeBuffers materialAttributes; ///< texture coordinates and colours, in vertexArray too
        const Material* material;                ///< the scene mesh's
        bool drawsBackFaces;                     ///< Mesh::drawsBackFaces(): face culling off
    };

    static constexpr GLuint kPositionLocation = 0;
    static constexpr GLuint kNormalLocation = 1;

    /** Keeps references; nothing is uploaded until meshes() is called. `derived`: what other stills of the same
     *  scene derived already (the views of one model), shared with them; a fresh one without. Throws
     *  std::invalid_argument when `derived` is another scene's. */
    GpuScene(const Scene& scene, glm::dvec3 worldOrigin, std::shared_ptr<SceneDerivedData> derived = nullptr);
    ~GpuScene();
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;

    /** Uploads on first call (positions relative to worldOrigin, in float), then returns the cached meshes. */
    const std::vector<DrawMesh>& meshes();
    bool isUploaded() const { return mUploaded; }

    /** The view-independent data derived from the scene's meshes (scene/SceneDerivedData.h), shared by every still of
     *  the scene; the getters below are its, the CPU data derived once for all of them. */
    SceneDerivedData& derived() { return *mDerived; }
    const std::shared_ptr<SceneDerivedData>& sharedDerived() const { return mDerived; }

    /** SceneDerivedData::positionWeld(): what the hull normals, the edge adjacency and the curvature are built on.
     *  Throws std::out_of_range for a bad index. */
    const WeldMap& positionWeld(std::size_t meshIndex) { return mDerived->positionWeld(meshIndex); }
    bool positionWeldComputed(std::size_t meshIndex) const { return mDerived->positionWeldComputed(meshIndex); }

    /** The inflated hull's normals of mesh `meshIndex` on the GPU (SceneDerivedData::hullNormals(), or the mesh's own
     *  normal buffer from meshes() where those are the same). Uploaded for every mesh the first time any is asked for
     *  (only a pass that runs asks). Throws std::out_of_range for a bad index. */
    const GlBuffer& hullNormals(std::size_t meshIndex);
    bool hullNormalsComputed() const { return !mHullNormals.empty(); }
    /** One vertex array per mesh for drawing its inflated hull (the silhouette, MToon's outline shell): its
     *  positions, hullNormals() at the normal location, its material attributes and its indices, or
     *  SceneDerivedData::hullTriangles()' where a double-faced card's second sheet is left out (draw
     *  hullIndexCount() of them). Made on the first call. */
    const std::vector<GlVertexArray>& hullArrays();
    /** How many indices hullArrays()[meshIndex] draws. */
    GLsizei hullIndexCount(std::size_t meshIndex);

    /** SceneDerivedData::edgeAdjacency(): welded edges, their kinds, face normals and planes, in the scene's frame. */
    const EdgeAdjacency& edgeAdjacency(std::size_t meshIndex) { return mDerived->edgeAdjacency(meshIndex); }
    bool edgeAdjacencyComputed() const { return mDerived->edgeAdjacencyComputed(); }

    /** SceneDerivedData::meshCurvature(): per-vertex curvature smoothed over `smoothing` model units, derived for
     *  every mesh the first time any is asked for at that smoothing (only a pass that runs asks: the object-space
     *  suggestive contours). */
    const MeshCurvature& meshCurvature(std::size_t meshIndex, double smoothing = 0.0) {
        return mDerived->meshCurvature(meshIndex, smoothing);
    }
    bool meshCurvatureComputed() const { return mDerived->meshCurvatureComputed(); }
    bool meshCurvatureComputed(double smoothing) const { return mDerived->meshCurvatureComputed(smoothing); }

    /** SceneDerivedData::meshIntersections(): where the scene's surfaces cross (the intersection line types). */
    const MeshIntersections& meshIntersections() { return mDerived->meshIntersections(); }
    bool meshIntersectionsComputed() const { return mDerived->meshIntersectionsComputed(); }

    /** SceneDerivedData::surfacePatches(): the smooth patch of each triangle id (the image-space suggestive
     *  contours). */
    using SurfacePatches = SceneDerivedData::SurfacePatches;
    const SurfacePatches& surfacePatches() { return mDerived->surfacePatches(); }
    bool surfacePatchesComputed() const { return mDerived->surfacePatchesComputed(); }
    /** SceneDerivedData::surfacesMeet(): whether surfacePatches() can tell surfaces apart that the depth cannot. */
    bool surfacesMeet() { return mDerived->surfacesMeet(); }

    /** What the G-buffer's triangle id and barycentric draws make of gl_PrimitiveID (a mesh's drawn triangle): the
     *  triangle id (scene/MeshLabels.h TriangleNumbering, which counts the triangles the loader dropped too) and
     *  whether its corners are swapped from the file's (Mesh::cornersSwapped). */
    struct TriangleIdMap {
        /** A mesh whose drawn triangles are the file's, in order, none with swapped corners. */
        static constexpr std::uint32_t kAsDrawn = 0xffffffffu;
        static constexpr std::uint32_t kCornersSwapped = 0x80000000u; ///< the flag bit of a fileTriangles entry
        std::vector<std::uint32_t> firstTriangle;                     ///< per mesh the global index of its first
        /** Per mesh where its entries start in `fileTriangles`, or kAsDrawn where it needs none. */
        std::vector<std::uint32_t> fileTrianglesAt;
        /** Per drawn triangle of those meshes its index among the file's (Mesh::fileTriangleOf()), with
         *  kCornersSwapped set where Mesh::cornersSwapped is; a single 0 when no mesh needs any. */
        GlBuffer fileTriangles;
    };
    /** Made on the first call (only a G-buffer draw of triangle ids or barycentrics asks). Throws
     *  std::invalid_argument for a mesh of 2^31 triangles or more, whose indices the flag bit would take. */
    const TriangleIdMap& triangleIdMap();

    std::size_t meshCount() const { return mScene.meshes.size(); }
    /** The scene the meshes were uploaded from (their CPU triangles, in the same vertex order as meshes()). */
    const Scene& scene() const { return mScene; }

    /** The materials' textures and uniforms (passes/material/SceneMaterials.h); textures are decoded the first time a
     *  draw binds them. */
    SceneMaterials& materials() { return mMaterials; }
    /** Binds mesh `meshIndex`'s material for `program` (in use): SceneMaterials::bind(). */
    void bindMaterial(const GlProgram& program, std::size_t meshIndex, MaterialUse use) {
        mMaterials.bind(program, meshIndex, use);
    }
    /** Whether any mesh's material cuts out (MASK) or blends (BLEND): passes that draw depth then sample alpha. */
    bool hasTransparency() const;
    /** The order meshes are drawn in where blending matters: opaque and masked meshes in scene order, then blended ones
     *  back to front (by their bounding-box centres' depth along the view axis of `viewFromModel`). */
    std::vector<std::size_t> drawOrder(const glm::mat4& viewFromModel);

    /** The face orientation the passes draw with: stores `frame` (by reference: it must outlive this scene, and the
     *  camera and light are read when the orientation is computed) and `settings`, creating nothing; drops an
     *  orientation made for earlier settings. Throws std::invalid_argument for a front rule outside 1..3 or a negative
     *  shininess (SceneOrientation's checks, made here so they come before any GL work). */
    void setOrientation(const FrameParams& frame, OrientationSettings settings);
    /** The CPU face orientation (Winnemoller & Bangay 2002's marking: front and back sets) the passes draw with,
     *  made on the first call; nullptr when setOrientation() was never called or its method is Standard (the GPU
     *  culls). */
    SceneOrientation* cpuOrientation();
    /** The orientation for any method, Standard included (whose report() counts the exact front share for --stats),
     *  made on the first call; nullptr when setOrientation() was never called. */
    SceneOrientation* orientation();

    /** Whether `worldPoint` lies inside any mesh (MeshOps isPointInsideMesh, ray parity on the CPU). The answer for
     *  the last point asked is kept, so the line passes of one frame share one computation. */
    bool containsPoint(glm::dvec3 worldPoint);
    /** Whether `worldPoint` lies inside any mesh's hull inflated by `objectWidth` model units along the hull normals
     *  (`weldedNormals`, as hullArrays() draws it) or the mesh's own: the silhouette's object-space hull, which from
     *  inside draws nothing, as the model does. Not kept: only that hull asks. */
    bool inflatedHullContainsPoint(glm::dvec3 worldPoint, float objectWidth, bool weldedNormals);

    glm::dvec3 worldOrigin() const { return mWorldOrigin; }

    /** Derives the import `name` (SceneImport): the executor's importer (ExecuteOptions::importData). Throws
     *  std::logic_error for a name it does not know. */
    void importDerived(const std::string& name);

private:
    const Scene& mScene;
    glm::dvec3 mWorldOrigin;
    std::shared_ptr<SceneDerivedData> mDerived;
    SceneMaterials mMaterials;
    std::vector<DrawMesh> mMeshes;
    bool mUploaded = false;
    std::vector<const GlBuffer*> mHullNormals;            ///< one per mesh once computed (its own or mesh normals)
    std::vector<GlBuffer> mOwnHullNormals;                ///< the hull normals that are not a mesh's own
    std::vector<GlVertexArray> mHullArrays;               ///< one per mesh once made, else empty
    std::vector<GLsizei> mHullIndexCounts;                ///< one per mesh with mHullArrays
    std::vector<GlBuffer> mOwnHullIndices;                ///< the hull index buffers that are not a mesh's own
    std::optional<TriangleIdMap> mTriangleIdMap;          ///< made by the first triangleIdMap()
    std::vector<std::optional<glm::dvec3>> mBlendCentres; ///< per blended mesh, once drawOrder() needed it
    std::optional<glm::dvec3> mContainmentPoint;          ///< the last point containsPoint() was asked about
    bool mContainsPoint = false;
    const FrameParams* mOrientationFrame = nullptr; ///< set by setOrientation()
    OrientationSettings mOrientationSettings;
    std::unique_ptr<SceneOrientation> mOrientation; ///< made by the first orientation() or cpuOrientation()
};

} // namespace inkgraph
