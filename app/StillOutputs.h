#pragma once
/** @file What one still writes besides its stats: the final picture, --contact-sheet, --svg, and --dump with its
 *  manifest, each staged into the run's OutputSet (app/OutputFiles.h), which puts them all in place or none. */

#include "app/OutputFiles.h"
#include "render/StillRenderer.h"

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace inkgraph {

/** The file name --dump gives a planned resource: the one its writer declared ("normal.exr", "shading.png",
 *  "lines-<type>.png"), else "<pass>-<field>.exr" for float formats and ".png" for 8-bit ones. */
std::string dumpFileName(const PlannedResource& resource);
/** What --dump's manifest.json holds, for README's --dump table (app/GeneratedDocs.h); stageDump() writes it. */
inline constexpr const char* kDumpManifestMeaning =
    "the inkgraph version, model, size, conventions, camera (source, eye, target, up, fov, near, far and whether "
    "--clip set them, the reversed-Z depth convention, focal length in pixels, view and OpenGL projection matrices "
    "as rows, OpenCV's intrinsics K and extrinsics [R|t] as rows), the light, the look, each file's resource, writing "
    "pass and format, milliseconds per pass, with objectid.exr the objects (id, node name, node path, mesh "
    "names), with meshid.exr, triangleid.exr or barycentric.exr the meshes (id, name, node path, object and material "
    "ids, material name, first triangle and triangle count), and with those or materialid.exr the materials (id, "
    "name)";

/** The camera for --stats and manifest.json: its source, world eye and target, matrices and depth convention. */
nlohmann::ordered_json describeCamera(const Camera& camera);
/** The look for --stats and manifest.json: style file, shading and its map, precision, and each drawn line type. */
nlohmann::ordered_json describeLook(const PreparedStill& still, const std::string& stylePath);
/** The passes' timings for --stats and manifest.json. */
nlohmann::ordered_json describeTimings(const std::vector<PassTiming>& timings);

/** Whether the images `options` asks for need the OpenImageIO module (render/ImageIoModule.h), so that a run loads it
 *  only then: -o or --contact-sheet in a format other than PNG, or --dump (its float buffers are EXR files). */
bool outputsUseImageIoModule(const RenderOptions& options);

/** Stages the outputs `options` asks for but the final picture and --stats (--contact-sheet, --svg, --dump) from a
 *  still that executed; app/Render.cpp encodes the picture, off the critical path. */
void stageStillOutputs(const RenderOptions& options, const PreparedStill& still, StillResult& result,
                       OutputSet& outputs);

/** JSON text; a path that is not valid UTF-8 gets U+FFFD in place of the bad bytes rather than failing the run. */
std::string jsonText(const nlohmann::ordered_json& json);
/** --strokes' file (docs/datasets.md, "Strokes with their 3-D points"): one line of JSON, the camera as the dump
 *  manifest's (describeCamera()), the scene's meshes by id, and `strokes`. */
std::string strokesJson(int width, int height, const Camera& camera, const Scene& scene,
                        const std::vector<StrokeRecord>& strokes);

} // namespace inkgraph
