#pragma once
/** @file What a reader of the G-buffer's id fields needs to name them (issue 37): per mesh, the values it has in the
 *  meshId, objectId, materialId and triangleId fields, and per material its name. The one place that numbers
 *  triangles over the scene: the triangleId field, the --dump manifest's `meshes`, the library's Scene::meshes() and
 *  the strokes file all count them this way. No GL. */

#include "scene/MeshNumbering.h"
#include "scene/Scene.h"
#include "scene/Warning.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** One mesh (primitive) of the scene, as the id fields see it. */
struct MeshLabel {
    std::uint32_t id = 0; ///< its number + 1 (scene/MeshNumbering.h): its value in the meshId field
    /** False for a mesh the loader skipped (Scene::skippedMeshes): its id and triangle ids appear nowhere. */
    bool drawn = true;
    std::string name;                  ///< Mesh::name
    std::vector<std::string> nodePath; ///< Mesh::nodePath (empty for a format without nodes)
    std::uint32_t objectId = 0;        ///< its object's value in the objectId field (scene/ObjectIds.h)
    std::uint32_t materialId = 0;      ///< its material's value in the materialId field (scene/MaterialIds.h)
    std::size_t firstTriangle = 0; ///< the global index of its first triangle: the file triangles of the meshes before
    /** Its triangles have the triangleId values firstTriangle + 1 ... + count: the file's, the ones the loader dropped
     *  included (Mesh::numberedTriangleCount(); those numbers appear nowhere). */
    std::size_t triangleCount = 0;
};

/** One material of the scene (meshes share one exactly when scene/MaterialIds.h says so). */
struct MaterialLabel {
    std::uint32_t id = 0; ///< its value in the materialId field
    std::string name;     ///< Material::name of its first mesh; empty for an unnamed material (STL, OBJ without MTL)
};

struct SceneLabels {
    std::vector<MeshLabel> meshes;        ///< by number, the skipped meshes too: meshes[i].id == i + 1
    std::vector<MaterialLabel> materials; ///< by id: materials[i].id == i + 1
};

/** The labels of `scene`'s meshes and materials. */
SceneLabels sceneLabels(const Scene& scene);

/** The scene's triangle numbering: the meshes by number (scene/MeshNumbering.h, the skipped ones too), each mesh's
 *  triangles as its file gives them (Mesh::fileTriangles), so the numbers of the triangles the loader dropped go
 *  unused and every other triangle keeps the number the file gives it, in every pose. Keeps a reference to the
 *  scene. */
class TriangleNumbering {
public:
    explicit TriangleNumbering(const Scene& scene);

    /** The global index of the first file triangle of drawn mesh `meshIndex` (an index into Scene::meshes): the file
     *  triangles of the meshes numbered before it. */
    std::size_t firstOfMesh(std::size_t meshIndex) const { return mFirst.at(mMeshes.numberOf(meshIndex)); }
    /** Likewise of the mesh numbered `number`, drawn or skipped. */
    std::size_t firstOfNumber(std::size_t number) const { return mFirst.at(number); }
    /** The numbers all meshes take: the file triangles of the scene. */
    std::size_t total() const { return mFirst.back(); }
    /** The global index of loaded triangle `triangle` (an index into Mesh::triangles) of mesh `meshIndex`: the
     *  triangleId field holds this + 1. Throws
     *  std::out_of_range for a mesh or triangle that is not there. */
    std::size_t global(std::size_t meshIndex, std::size_t triangle) const;

    /** A global index as the mesh holding it and its loaded triangle there. */
    struct Loaded {
        std::size_t mesh = 0; ///< an index into Scene::meshes
        std::size_t triangle = 0;
    };
    /** The loaded triangle a global index names; none beyond the scene's numbers or for one the loader dropped (a
     *  skipped mesh's too). */
    std::optional<Loaded> loaded(std::size_t global) const;
    /** The number of the mesh whose triangles hold a global index (a dropped triangle's too, or a skipped mesh's);
     *  none beyond the scene's numbers. */
    std::optional<std::size_t> meshNumberOf(std::size_t global) const;

private:
    const Scene& mScene;
    MeshNumbering mMeshes;
    std::vector<std::size_t> mFirst; ///< per mesh number its first global index, then the total
};

/** The most triangles whose ids the G-buffer's triangleId field (float32: the render graph has no integer format)
 *  holds exactly: every integer up to 2^24 is a float32. */
inline constexpr std::size_t kExactTriangleIds = std::size_t(1) << 24;

/** The triangle-id-inexact warning for a scene whose triangle ids run to `idCount` (TriangleNumbering::total())
 *  when some exceed kExactTriangleIds (they round to a neighbour's), else none. A warning rather than a refusal: the
 *  ids of the first 2^24 triangles are still right, and --strict makes it an error. */
std::optional<Warning> triangleIdWarning(std::size_t idCount);

} // namespace inkgraph
