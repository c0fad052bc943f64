#pragma once
/** @file A Scene from a triangle mesh already in memory (trimesh, Open3D, numpy arrays), checked and cleaned up as
 *  loadScene() checks and cleans up a file. The arrays are read the way an OBJ file with the same lines is read, so
 *  the two give the same Scene and the same pictures (below). */

#include "scene/Scene.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace inkgraph {

/** One triangle mesh as caller-owned arrays of tightly packed rows, read only during sceneFromArrays(). Every array
 *  but `faces` has one row per vertex. */
struct MeshArrays {
    const float* vertices = nullptr; ///< x y z per vertex, in the model's units
    std::size_t vertexCount = 0;
    /** Three 0-based vertex indices per face (a triangle), counter-clockwise seen from the front (outward normals). */
    const std::uint32_t* faces = nullptr;
    std::size_t faceCount = 0;
    const float* normals = nullptr; ///< nx ny nz per vertex (normalised on reading; zero ones are computed), or null
    /** u v per vertex with v up from the image's bottom, as OBJ's `vt` (and OpenGL, trimesh, Open3D) write it; stored
     *  as (u, 1 - v) like `vt` (Mesh::texcoords keeps glTF's top-left origin). Or null. */
    const float* uvs = nullptr;
    /** Linear RGB or RGBA per vertex in [0, 1] (values outside are clamped, as OBJ's and PLY's vertex colours are),
     *  `colorChannels` values a row; or null. Mesh::colors keeps them; the mesh's base colour is then white (it
     *  multiplies the vertex colours), as for a coloured OBJ or PLY. */
    const float* colors = nullptr;
    int colorChannels = 0; ///< 3 (RGB, alpha 1) or 4 (RGBA) when `colors` is given
    /** The mesh's name (Mesh::name) and its one-node path (Mesh::nodePath, what --frame selects), as an OBJ's `o`
     *  line names its mesh; it also names the mesh in messages. Empty: "arrays", without a node path. */
    std::string name = "arrays";
    /** The function messages start with: the caller's own, when it is not sceneFromArrays() (the library's
     *  Scene::fromArrays()), so they name what its user called. */
    std::string caller = "sceneFromArrays()";
};

/** The Scene of one mesh given as arrays: the Scene that loadScene() gives for the OBJ file holding `o <name>`, a
 *  `v` line per vertex and an `f` line per triangle (`f a//a` with a `vn` line per vertex when normals are given,
 *  `f a/a/a` with `vt` lines when uvs are too), each value written exactly: `%.17g` of the float as a double, since
 *  the OBJ reader computes 1 - v and a far model's offsets in double from the text, where `%.9g`'s decimal is not
 *  the float's value. So the positions are placed as OBJ's (detail::storeNearModel(), then re-centred on the
 *  bounding-box centre, Scene::origin), welded within options.weldTolerance of the model's size, degenerate triangles
 *  dropped and counted, unused vertices dropped; without normals the smooth area-weighted ones are computed. With
 *  normals or uvs the vertices come in the order the triangles first use them, as OBJ's face corners give them.
 *  LoadReport::format is "arrays"; no input files.
 *
 *  Checked before anything is copied, with OBJ's limits: a null array with a non-zero count, no triangles, more
 *  vertices than 32-bit indices reach, counts whose arrays overflow memory, colorChannels other than 3 or 4, the
 *  memory bound (LoadOptions::memoryLimitBytes, charged like a file's vertices and triangles, detail::MeshBudget),
 *  indices out of range, any non-finite value in any array (a file's reader refuses non-finite coordinates; arrays
 *  have no reason to hold one, so unlike OBJ's `vt` and PLY's colours they are refused too); then the model's extent
 *  (kMinModelExtent, kMaxModelExtent). Throws SceneError whose message starts with `<caller>: '<name>': `
 *  and names the array, the vertex or face and the value, e.g.
 *  `sceneFromArrays(): 'arrays': face 3: vertex index 7 out of range (vertices has 4 rows)`; and
 *  std::invalid_argument for options that loadScene() refuses. The Scene owns its memory: the arrays may be freed on
 *  return. */
Scene sceneFromArrays(const MeshArrays& arrays, const LoadOptions& options = {});

} // namespace inkgraph
