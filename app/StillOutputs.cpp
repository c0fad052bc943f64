#include "app/StillOutputs.h"

#include "app/Stats.h"

#include "render/BuildInfo.h"
#include "render/ImageFiles.h"

#include "postfx/Composite.h"
#include "postfx/ContactSheet.h"
#include "postfx/SvgLines.h"
#include "scene/MeshLabels.h"
#include "scene/MeshNumbering.h"
#include "scene/ObjectIds.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <set>

namespace inkgraph {
namespace {

using Json = nlohmann::ordered_json;

/** A glm matrix of any shape as JSON rows: glm is column-major, so matrix[col][row]. */
template <glm::length_t Columns, glm::length_t Rows>
Json matrixRows(const glm::mat<Columns, Rows, double>& matrix) {
    Json rows = Json::array();
    for (glm::length_t row = 0; row < Rows; ++row) {
        Json values = Json::array();
        for (glm::length_t col = 0; col < Columns; ++col) values.push_back(matrix[col][row]);
        rows.push_back(values);
    }
    return rows;
}

Json vectorJson(const glm::dvec3& value) { return Json::array({value.x, value.y, value.z}); }

/** How the contact sheet shows a buffer: as its writer declared it, else by its format. */
TileContent tileContentOf(const PlannedResource& resource) {
    switch (resource.presentation.appearance) {
    case Appearance::Color: return TileContent::Color;
    case Appearance::Lines: return TileContent::Lines;
    case Appearance::Mask: return TileContent::Mask;
    case Appearance::UnitVector: return TileContent::UnitVector;
    case Appearance::SignedScalar: return TileContent::SignedScalar;
    case Appearance::Depth: return TileContent::Depth;
    case Appearance::Data: return TileContent::Data;
    case Appearance::Auto: break;
    }
    if (isFloatFormat(resource.desc.format)) return TileContent::Data;
    // 8-bit one-channel buffers are line layers and skeletons: ink on paper.
    return resource.desc.format == Format::R8 ? TileContent::Lines : TileContent::Color;
}

/** Whether a computed resource can be shown as an image: a texture, or an object with a picture (a skeleton's mask);
 *  the other objects (the strokes, the scene's imports) are data with no picture. */
bool hasPicture(const PlannedResource& resource) {
    return resource.kind == ResourceKind::Texture || resource.object.hasPicture;
}

std::string lookSummary(const Look& look) {
    std::string lines;
    for (const std::string& type : look.lines) lines += (lines.empty() ? "" : ",") + type;
    return "shading " + std::string(traitsOf(look.shading).name) + ", lines " + (lines.empty() ? "none" : lines);
}

std::string modelFileName(const PreparedStill& still) {
    return std::filesystem::path(still.request.modelPath).filename().string();
}

/** --contact-sheet: every buffer the plan computed (the executor kept them all), in the plan's order, so the
 *  pipeline reads left to right, top to bottom. */
cv::Mat contactSheetOf(const PreparedStill& still, ResourceStore& store) {
    std::vector<ContactTile> tiles;
    for (const PlannedResource& resource : still.plan.resources) {
        if (!store.contains(resource.name) || !hasPicture(resource)) continue;
        const cv::Mat& image = store.image(resource.name);
        tiles.push_back(
            {resource.name, describeImage(image) + " by " + resource.writer, image, tileContentOf(resource)});
    }
    ContactSheetLayout layout;
    const CameraRequest& camera = still.request.camera;
    layout.title = "inkgraph: '" + modelFileName(still) + "' " + std::to_string(camera.width) + "x" +
                   std::to_string(camera.height) + ", " + lookSummary(still.request.look);
    return composeContactSheet(tiles, layout);
}

/** --svg: each line type's strokes as simplified polylines, the strokes its layer was drawn from
 *  (StillGraph::svgLayers()). */
std::string svgOf(const RenderOptions& options, const PreparedStill& still, ResourceStore& store) {
    SvgDocumentOptions document;
    document.title = "inkgraph: '" + modelFileName(still) + "', " + lookSummary(still.request.look);
    return svgDocument(options.width, options.height, still.graph.svgLayers(store, options.svgTolerance), document);
}

/** --strokes: every kept stroke with its points' 3-D points (passes/lines/StrokePoints.h), one line of JSON
 *  (docs/datasets.md, docs/schemas/strokes.schema.json). */
std::string strokesOf(const RenderOptions& options, const PreparedStill& still, StillResult& result) {
    return strokesJson(options.width, options.height, still.camera, still.scene(),
                       still.graph.strokeRecords(result.store(), still.camera, still.scene()));
}

/** The objects the G-buffer's objectId field numbers (scene/ObjectIds.h): id (the field's value), the node's name,
 *  its path and its meshes' names, for a reader of objectid.exr to tell which pixels belong to which node. */
Json describeObjects(const Scene& scene) {
    Json objects = Json::array();
    const SceneObjects found = sceneObjects(scene);
    const MeshNumbering numbering(scene);
    for (std::size_t index = 0; index < found.objects.size(); ++index) {
        const SceneObject& object = found.objects[index];
        Json meshes = Json::array();
        for (const std::size_t mesh : object.meshes) meshes.push_back(numbering.mesh(mesh).name);
        objects.push_back(
            {{"id", index + 1}, {"name", object.name}, {"node_path", object.nodePath}, {"meshes", meshes}});
    }
    return objects;
}

/** The meshes the G-buffer's meshId and triangleId fields number (scene/MeshLabels.h): each mesh's id (the meshId
 *  value), name, node path, object and material ids, and its triangles' range of triangleId values
 *  (first_triangle + 1 ... first_triangle + triangle_count), so a label can name the mesh, node and material. */
Json describeMeshes(const SceneLabels& labels) {
    Json meshes = Json::array();
    for (const MeshLabel& mesh : labels.meshes)
        meshes.push_back({{"id", mesh.id},
                          {"drawn", mesh.drawn},
                          {"name", mesh.name},
                          {"node_path", mesh.nodePath},
                          {"object_id", mesh.objectId},
                          {"material_id", mesh.materialId},
                          {"material", labels.materials.at(mesh.materialId - 1).name},
                          {"first_triangle", mesh.firstTriangle},
                          {"triangle_count", mesh.triangleCount}});
    return meshes;
}

/** The materials the materialId field numbers: id (the field's value) and name ("" for an unnamed material). */
Json describeMaterials(const SceneLabels& labels) {
    Json materials = Json::array();
    for (const MaterialLabel& material : labels.materials)
        materials.push_back({{"id", material.id}, {"name", material.name}});
    return materials;
}

/** --dump: every buffer the plan computed, then manifest.json. */
void stageDump(const RenderOptions& options, const PreparedStill& still, StillResult& result, OutputSet& outputs) {
    ResourceStore& store = result.store();
    Json files = Json::array();
    std::set<std::string> usedNames;
    // Which id fields are dumped: the manifest names what their values stand for.
    bool objectIds = false, materialIds = false, meshLabels = false;
    for (const PlannedResource& resource : still.plan.resources) {
        if (!store.contains(resource.name) || !hasPicture(resource)) continue;
        const std::string fileName = dumpFileName(resource);
        const ResourceName parts = ResourceName::split(resource.name);
        const std::string field = parts.pass == kGBufferPass ? parts.field : std::string();
        objectIds = objectIds || field == "objectId";
        materialIds = materialIds || field == "materialId";
        meshLabels = meshLabels || field == "meshId" || field == "triangleId" || field == "barycentric";
        if (!usedNames.insert(fileName).second)
            throw std::logic_error("stageDump(): two resources dump to '" + fileName + "'");
        // Image files hold straight alpha; the shading is premultiplied in memory (postfx/Composite.h).
        const bool colour = resource.presentation.appearance == Appearance::Color;
        outputs.stageDumpImage(fileName,
                               colour ? straightAlphaOf(store.image(resource.name)) : store.image(resource.name));
        // Written buffers are not needed again: freeing them keeps the dump's peak memory to one copy.
        if (resource.name != still.graph.finalResource) store.release(resource.name);
        files.push_back({{"file", fileName},
                         {"resource", resource.name},
                         {"pass", resource.writer},
                         {"format", std::string(formatName(resource.desc.format))},
                         {"requested", resource.requested}});
    }
    Json manifest;
    manifest["inkgraph"] = inkgraphVersion();
    manifest["model"] = still.request.modelPath;
    manifest["size"] = {options.width, options.height};
    manifest["conventions"] = "right-handed world; OpenGL lookAt/perspective; row 0 at the top; pixel centres at "
                              "(col+0.5, row+0.5); matrices as rows; 8-bit images sRGB, float images linear data";
    manifest["camera"] = describeCamera(still.camera);
    manifest["toward_light_world"] = vectorJson(still.frame.towardLightWorld);
    if (options.view) manifest["view"] = viewRecord(options);
    manifest["look"] = describeLook(still, options.stylePath);
    manifest["files"] = files;
    if (objectIds) manifest["objects"] = describeObjects(still.scene());
    if (meshLabels || materialIds) {
        // The meshes name their materials, so the materials come with them.
        const SceneLabels labels = sceneLabels(still.scene());
        if (meshLabels) manifest["meshes"] = describeMeshes(labels);
        manifest["materials"] = describeMaterials(labels);
    }
    manifest["passes"] = describeTimings(result.timings);
    outputs.stageDumpManifest(jsonText(manifest));
}

} // namespace

std::string jsonText(const Json& json) { return json.dump(2, ' ', false, Json::error_handler_t::replace) + "\n"; }

std::string dumpFileName(const PlannedResource& resource) {
    if (!resource.presentation.fileName.empty()) return resource.presentation.fileName;
    const ResourceName name = ResourceName::split(resource.name);
    return name.pass + "-" + name.field + (isFloatFormat(resource.desc.format) ? ".exr" : ".png");
}

Json describeCamera(const Camera& camera) {
    return {{"source", camera.source},
            {"eye", vectorJson(camera.worldEye())},
            {"target", vectorJson(camera.worldTarget())},
            {"up", vectorJson(camera.up)},
            {"fov_y_degrees", camera.fovYDegrees},
            {"near", camera.zNear},
            {"far", camera.zFar},
            {"clip", camera.clipSource},
            {"depth", "reversed-z float32: window depth n (f - d) / ((f - n) d) at view depth d, 1 at near, 0 at far; "
                      "projection_matrix is OpenGL's standard one"},
            {"focal_pixels", camera.focalPixels()},
            {"view_matrix", matrixRows(camera.worldViewMatrix())},
            {"projection_matrix", matrixRows(camera.projectionMatrix())},
            {"opencv",
             "intrinsics K and extrinsics [R|t] as OpenCV takes them: [R|t] maps world points to x right, y "
             "down, z forward (the view space with y and z negated), z being the linear view depth; pixel "
             "centres at (col, row), so K's centre is (width/2 - 0.5, height/2 - 0.5); a buffer S times the size "
             "(--supersample) has S fx, S fy and centre (S width/2 - 0.5, S height/2 - 0.5)"},
            {"intrinsics", matrixRows(camera.openCvIntrinsics())},
            {"extrinsics", matrixRows(camera.openCvExtrinsics())}};
}

std::string strokesJson(int width, int height, const Camera& camera, const Scene& scene,
                        const std::vector<StrokeRecord>& strokes) {
    Json meshes = Json::array();
    for (const MeshLabel& mesh : sceneLabels(scene).meshes) meshes.push_back({{"id", mesh.id}, {"name", mesh.name}});
    const auto dumped = [](const Json& json) { return json.dump(-1, ' ', false, Json::error_handler_t::replace); };
    const Json file = {
        {"format", "inkgraph-strokes"},     {"version", 1},     {"width", width},          {"height", height},
        {"camera", describeCamera(camera)}, {"meshes", meshes}, {"strokes", Json::array()}};
    // One line: a still's strokes run to millions of points, so they are written point by point into the text, each
    // as the whole document's dump would write it; a document of them all took six times the text's memory (a
    // 118 MB file peaked at 1.7 GB, twice the still's memory estimate).
    std::string text = dumped(file);
    const std::string emptyList = "[]}";
    text.resize(text.size() - emptyList.size());
    text += '[';
    for (std::size_t index = 0; index < strokes.size(); ++index) {
        const StrokeRecord& stroke = strokes[index];
        std::string head = dumped(
            {{"type", stroke.type}, {"visible", stroke.visible}, {"closed", stroke.closed}, {"points", Json::array()}});
        head.resize(head.size() - emptyList.size());
        text += (index == 0 ? "" : ",") + head + '[';
        for (std::size_t at = 0; at < stroke.points.size(); ++at) {
            const StrokePointRecord& point = stroke.points[at];
            Json entry = {{"x", point.x}, {"y", point.y}};
            entry["world"] = point.world ? vectorJson(*point.world) : Json(nullptr);
            entry["mesh"] = point.mesh > 0 ? Json(point.mesh) : Json(nullptr);
            entry["triangle"] = point.triangle >= 0 ? Json(point.triangle) : Json(nullptr);
            if (at > 0) text += ',';
            text += dumped(entry);
        }
        text += "]}";
    }
    text += "]}\n";
    return text;
}

Json describeLook(const PreparedStill& still, const std::string& stylePath) {
    const Look& look = still.request.look;
    const StillGraph& graph = still.graph;
    const ShadingModelTraits& shading = traitsOf(look.shading);
    Json json;
    if (!stylePath.empty()) json["style"] = stylePath;
    json["shading"] = shading.name;
    // auto is each material's model; on a scene without MToon it runs cel.
    if (graph.shadingModel != look.shading) json["shading_model"] = traitsOf(graph.shadingModel).name;
    if (const std::string mode = graph.shadingModeIn(still.plan); !mode.empty()) json["shading_mode"] = mode;
    if (const std::string reason = graph.shadingForwardReasonIn(still.plan); !reason.empty())
        json["shading_forward_because"] = reason;
    if (shading.define != nullptr) json["msaa"] = look.msaa;
    if (shading.specular) json["shininess"] = look.shininess;
    if (!graph.shadeMapSource.empty()) json["shademap"] = graph.shadeMapSource;
    if (!graph.meshShadeMapSources.empty()) {
        Json meshMaps = Json::array();
        for (const auto& [mesh, source] : graph.meshShadeMapSources)
            meshMaps.push_back({{"mesh", mesh}, {"shademap", source}});
        json["mesh_shademaps"] = meshMaps;
    }
    json["gbuffer_precision"] = look.gbufferPrecision == GBufferPrecision::Float16 ? "half" : "float";
    json["lines"] = graph.describeLines();
    return json;
}

Json describeTimings(const std::vector<PassTiming>& timings) {
    Json passTimes = Json::array();
    for (const PassTiming& timing : timings)
        passTimes.push_back(
            {{"name", timing.pass}, {"ms", timing.milliseconds}, {"prepare_ms", timing.prepareMilliseconds}});
    return passTimes;
}

bool outputsUseImageIoModule(const RenderOptions& options) {
    // A dump is taken to hold float buffers without looking at the plan (the preload starts before the model loads):
    // every plan has some (the G-buffer's depth), and dumpFileName() gives them .exr.
    return (!options.outputPath.empty() && usesImageIoModule(options.outputPath)) ||
           (!options.contactSheetPath.empty() && usesImageIoModule(options.contactSheetPath)) ||
           !options.dumpDirectory.empty();
}

void stageStillOutputs(const RenderOptions& options, const PreparedStill& still, StillResult& result,
                       OutputSet& outputs) {
    ResourceStore& store = result.store();
    if (!options.contactSheetPath.empty()) outputs.stageContactSheet(contactSheetOf(still, store));
    if (!options.svgPath.empty()) outputs.stageSvg(svgOf(options, still, store));
    if (!options.strokesPath.empty()) outputs.stageStrokes(strokesOf(options, still, result));
    if (!options.dumpDirectory.empty()) stageDump(options, still, result, outputs);
}

} // namespace inkgraph
