#pragma once
/** @file The shade maps a scene's meshes name themselves (Mesh::shadeMapPath, from glTF material extras), read for
 *  the shading pass (ShadeSettings::meshShadeMaps). */

#include "passes/shade/ShadeMap.h"
#include "passes/shade/ShadingModel.h"
#include "scene/Scene.h"

#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** One entry per mesh of `scene`, in its order: the map the mesh's shadeMapPath names, or empty where it names none
 *  (the mesh uses the run's map). Each distinct path is read once with readShadeMapFile() (one row required for
 *  cel), and the meshes naming it share its pixels. Only cel and comic use maps: for any other `shading` nothing is
 *  read, every entry is empty, and when some meshes name maps `warnings` (may be null) gets "N meshes name shade
 *  maps, which only --shading cel and comic use" ("1 mesh names a shade map, ..." for one; shade-map-unused, about
 *  no file: the still names the model). Throws InputFileError
 *  naming the first mesh (in scene order) that names an unusable file, its glTF material and the file, e.g.
 *  "mesh 'Teapot' (glTF material 'Metal') shade map: 'x.png': file not found" (exit code 3). */
std::vector<std::optional<ShadeMap>> readSceneShadeMaps(const Scene& scene, ShadingModel shading,
                                                        std::vector<Warning>* warnings);

} // namespace inkgraph
