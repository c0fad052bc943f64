#pragma once
/** @file The scene's objects and a small id per mesh naming its object, for the G-buffer's objectId field (the
 *  object-boundary lines) and the --dump manifest. An object is a node instance: every mesh (primitive) one glTF node
 *  holds is one object, and two nodes instancing one mesh are two objects; a format without nodes (STL, PLY) is one
 *  object. No GL. */

#include "scene/Scene.h"

#include <cstdint>
#include <string>
#include <vector>

namespace inkgraph {

/** One object: the meshes of one node instance. */
struct SceneObject {
    /** The node's name; for an unnamed node, or a format without nodes, the name of its first mesh (the glTF mesh's
     *  name or "mesh N", the file stem). */
    std::string name;
    std::vector<std::string> nodePath; ///< as Mesh::nodePath (empty for a format without nodes)
    /** Its meshes' numbers (scene/MeshNumbering.h: meshId - 1; skipped meshes too), ascending. */
    std::vector<std::size_t> meshes;
};

struct SceneObjects {
    /** Per mesh number (scene/MeshNumbering.h), the index of its object in `objects`. */
    std::vector<std::uint32_t> ofMesh;
    std::vector<SceneObject> objects; ///< in the order of each object's first mesh; object id = index + 1
};

/** The objects of `scene`: meshes are one object exactly when their Mesh::nodePath and Mesh::nodeInstance are equal.
 *  Indices are dense from 0, in the order of each object's first mesh by number (the meshes the loader skipped
 *  included, so a pose that collapses one leaves the others' ids as they are), so they are deterministic for a
 *  file. */
SceneObjects sceneObjects(const Scene& scene);

} // namespace inkgraph
