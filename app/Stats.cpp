#include "app/Stats.h"

#include "render/ImageFiles.h"
#include "render/MemoryBudget.h"
#include "app/StillOutputs.h"
#include "passes/orientation/SceneOrientation.h"
#include "scene/ObjectIds.h"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cstdlib>

namespace inkgraph {

nlohmann::ordered_json viewRecord(const RenderOptions& options) {
    using Json = nlohmann::ordered_json;
    if (!options.view) return Json();
    const ViewSample& view = *options.view;
    // The shortest text that reads back as the same double, as JSON writes numbers.
    const auto exact = [](double value) {
        char text[32];
        const auto written = std::to_chars(text, text + sizeof text, value);
        return std::string(text, written.ptr);
    };
    Json record;
    record["index"] = view.index;
    record["count"] = options.viewSampling.count;
    record["seed"] = options.viewSampling.seed;
    record["azimuth"] = view.azimuthDegrees;
    record["elevation"] = view.elevationDegrees;
    record["distance_scale"] = view.distanceScale;
    record["light"] =
        view.towardLight ? Json::array({view.towardLight->x, view.towardLight->y, view.towardLight->z}) : Json();
    record["expression"] = view.expressions ? Json(expressionSetText(*view.expressions)) : Json();
    record["pose"] = view.pose ? Json(*view.pose) : Json();
    record["orbit"] =
        exact(view.azimuthDegrees) + "," + exact(view.elevationDegrees) + ",x" + exact(view.distanceScale);
    return record;
}

nlohmann::ordered_json statsDocument(const StatsContext& context, const StillRenderer& renderer,
                                     const PreparedStill& still, const StillResult& result) {
    using Json = nlohmann::ordered_json;
    const RenderOptions& options = context.options;
    const Scene& scene = still.scene();
    const Camera& camera = still.camera;
    Json culled = Json::array();
    for (const CulledPass& pass : still.plan.culled) culled.push_back({{"name", pass.name}, {"reason", pass.reason}});
    Json stats;
    stats["model"] = still.request.modelPath;
    stats["scene"] = {{"format", scene.report.format},
                      {"meshes", scene.meshes.size()},
                      {"objects", sceneObjects(scene).objects.size()},
                      {"triangles", scene.triangleCount()},
                      {"vertices", scene.vertexCount()},
                      {"triangles_read", scene.report.trianglesRead},
                      {"degenerate_dropped", scene.report.degenerateDropped},
                      {"repeated_dropped", scene.report.repeatedDropped},
                      {"back_to_back_dropped", scene.report.backToBackDropped},
                      {"back_to_back_one_sided", scene.report.backToBackOneSided},
                      {"vertices_before_weld", scene.report.verticesBeforeWeld},
                      {"weld_distance", scene.report.weldTolerance},
                      {"normals_computed", scene.report.normalsComputed}};
    still.gpuScene->materials().describe(stats["scene"]);
    stats["size"] = {options.width, options.height};
    stats["camera_source"] = camera.source;
    stats["clip"] = {{"near", camera.zNear},
                     {"far", camera.zFar},
                     {"far_over_near", camera.zFar / camera.zNear},
                     {"source", camera.clipSource},
                     {"depth", "reversed-z float32"}};
    if (context.batch)
        stats["batch"] = {{"position", context.batch->position + 1}, {"list_length", context.batch->listLength}};
    if (options.view) stats["view"] = viewRecord(options);
    if (const HeadlessContext* gl = renderer.context())
        stats["gl"] = {{"platform", gl->platform()},
                       {"renderer", gl->renderer()},
                       {"version", gl->version()},
                       {"vendor", gl->vendor()}};
    stats["load_ms"] = still.loadMilliseconds;
    stats["model_reused"] = still.request.reusesEarlierLoad;
    stats["context_ms"] = result.contextMilliseconds;
    stats["context_reused"] = result.contextReused;
    // Programs this still compiled, and those it took from an earlier still of the process.
    stats["programs_compiled"] = result.programsCompiled;
    stats["programs_reused"] = result.programsReused;
    stats["look"] = describeLook(still, options.stylePath);
    if (traitsOf(still.request.look.shading).faceOrientation)
        stats["face_orientation"] = still.gpuScene->orientation()->describe();
    // The scene data the passes imported (PassBuilder::import()), derived before any pass prepared.
    Json imports = Json::object();
    for (const auto& [name, milliseconds] : result.executor->importMilliseconds()) imports[name] = milliseconds;
    stats["imports_ms"] = imports;
    stats["passes"] = describeTimings(result.timings);
    stats["post_stage"] = still.graph.describePostStage(result.timings);
    // How the still went through the batch's pipeline (--readback, --jobs, --draw-threads: app/Render.h).
    stats["readback"] = result.readBackEarly ? "early" : "late";
    stats["jobs"] = options.jobs;
    stats["draw_threads"] = options.drawThreads;
    stats["culled"] = culled;
    stats["write_ms"] = 0.0; // finishedStatsText()
    // Whether this process loaded OpenImageIO (~0.2 s): only formats other than PNG need it (render/ImageFiles.h).
    stats["image_io_module"] = imageIoModuleState();
    stats["textures_created"] = result.texturesCreated;
    stats["textures_reused"] = result.texturesReused;
    stats["estimated_peak_mib"] = double(context.estimatedPeakBytes) / (1 << 20);
    stats["estimated_textures_mib"] = double(context.estimatedTextureBytes) / (1 << 20);
    stats["estimated_meshes_mib"] = double(context.estimatedMeshBytes) / (1 << 20);
    stats["estimated_derived_mib"] = double(context.estimatedDerivedBytes) / (1 << 20);
    stats["peak_rss_mib"] = 0.0;   // finishedStatsText()
    stats["huge_pages_mib"] = 0.0; // finishedStatsText()
    // What the process runs glibc's malloc with (app/main.cpp sets it for the command line), null where unset.
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    stats["glibc_tunables"] = tunables ? Json(tunables) : Json();
    stats["total_ms"] = 0.0;
    return stats;
}

std::string finishedStatsText(nlohmann::ordered_json stats, double writeMilliseconds, double totalMilliseconds) {
    stats["write_ms"] = writeMilliseconds;
    // Measured once the outputs are encoded: what the estimate bounds, to compare.
    stats["peak_rss_mib"] = double(peakResidentBytes()) / (1 << 20);
    stats["huge_pages_mib"] = double(hugePageResidentBytes()) / (1 << 20);
    stats["total_ms"] = totalMilliseconds;
    return jsonText(stats);
}

} // namespace inkgraph
