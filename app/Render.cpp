#include "app/Render.h"

#include "app/ImageFiles.h"
#include "app/MemoryBudget.h"
#include "app/OutputFiles.h"
#include "app/SceneShadeMaps.h"
#include "app/StillGraph.h"
#include "app/StyleFile.h"
#include "app/TemporaryFiles.h"
#include "gl/GraphExecutor.h"
#include "gl/HeadlessContext.h"
#include "gl/ShaderLibrary.h"
#include "gl/TexturePool.h"
#include "graph/GraphCompiler.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/edges/MeshEdgesPass.h"
#include "passes/lines/LineLayerPass.h"
#include "passes/outline/OutlinePass.h"
#include "passes/shade/ShadeMap.h"
#include "passes/silhouette/SilhouettePass.h"
#include "postfx/ContactSheet.h"
#include "postfx/LineTracing.h"
#include "postfx/SvgLines.h"
#include "scene/Camera.h"
#include "scene/Scene.h"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <set>

#include <unistd.h>

namespace inkgraph {
namespace {

using Json = nlohmann::ordered_json;

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

Json matrixRows(const glm::dmat4& matrix) {
    Json rows = Json::array();
    for (int row = 0; row < 4; ++row) {
        Json values = Json::array();
        for (int col = 0; col < 4; ++col) values.push_back(matrix[col][row]); // glm is column-major
        rows.push_back(values);
    }
    return rows;
}

Json vectorJson(const glm::dvec3& value) { return Json::array({value.x, value.y, value.z}); }

/** JSON text; a path that is not valid UTF-8 gets U+FFFD in place of the bad bytes rather than failing the run. */
std::string jsonText(const Json& json) { return json.dump(2, ' ', false, Json::error_handler_t::replace) + "\n"; }

/** Default key light: from the upper left, behind the camera, fixed in view space so every auto-framed still is lit
 *  the same way. */
glm::dvec3 defaultLight(const Camera& camera) {
    const glm::dvec3 towardLightView = glm::normalize(glm::dvec3(-0.4, 0.5, 0.77));
    return glm::normalize(glm::transpose(glm::dmat3(camera.viewMatrix())) * towardLightView);
}

/** The whole run's peak for the plan, as an upper bound (app/MemoryBudget.h): the process, the scene, every GL target
 *  as llvmpipe stores it, and the post stage's read-backs, working images and encoders at their largest moment.
 *  Without the scene (not loaded yet) its meshes add nothing. */
std::size_t estimatePlanBytes(const Plan& plan, const RenderOptions& options, const Scene* scene) {
    return estimateRunMemory(plan, options, scene ? sceneSizeOf(*scene) : SceneSize{}).total();
}

/** --dump and --contact-sheet show every buffer the plan computed, so the executor keeps them all. */
bool keepsEveryBuffer(const RenderOptions& options) {
    return !options.dumpDirectory.empty() || !options.contactSheetPath.empty();
}

/** llvmpipe stores textures in 64x64 tiles, so a side is rounded up before its size is judged. */
std::size_t paddedSide(int side) { return (std::size_t(side) + 63) / 64 * 64; }

/** Refuses sizes that would fail deep inside the driver or outgrow the process's memory: one texture of 2 GiB or more
 *  (GL's byte counts are 32-bit), or a whole run estimated above the memory limit. Both name every flag that makes
 *  the buffers that large (--size, and --supersample for the supersampled ones), not only --size. */
void checkFrameBudget(const Plan& plan, const RenderOptions& options, const Scene* scene = nullptr) {
    for (const PlannedResource& resource : plan.resources) {
        const std::size_t textureBytes = paddedSide(options.width * resource.desc.scale) *
                                         paddedSide(options.height * resource.desc.scale) *
                                         std::size_t(bytesPerPixel(resource.desc.format));
        if (textureBytes < kMaxTextureBytes) continue;
        const std::string size = "--size " + std::to_string(options.width) + "x" + std::to_string(options.height);
        const std::string cause =
            resource.desc.scale > 1 ? size + " with --supersample " + std::to_string(resource.desc.scale) +
                                          " (" + std::to_string(options.width * resource.desc.scale) + "x" +
                                          std::to_string(options.height * resource.desc.scale) + ")"
                                    : size;
        throw UsageError(cause + " makes '" + resource.name + "' " + std::to_string(textureBytes >> 20) +
                         " MiB; one buffer must stay under 2048 MiB (at most 11584x11584 for float RGBA)");
    }
    const std::size_t needed = estimatePlanBytes(plan, options, scene);
    const std::size_t bound = memoryLimitOf(options);
    const std::size_t neededMib = (needed + (1 << 20) - 1) >> 20; // rounded up: "needs 600" never fits a 600 limit
    if (needed > bound)
        throw UsageError(memoryDriversText(plan, options) + " needs about " + std::to_string(neededMib) +
                         " MiB for the whole run; the memory limit is " + std::to_string(bound >> 20) + " MiB" +
                         (options.memoryLimitBytes ? " (--memory-limit)" : ", half this machine's memory") +
                         " (make the image smaller, lower --supersample, or request or dump fewer buffers)");
}

/** How the contact sheet shows a buffer: by the field it is (the G-buffer's), else by its format. */
TileContent tileContentOf(const std::string& resource, Format format, const StillGraph& graph) {
    static const std::map<std::string, TileContent> kGBufferFields = {
        {"gbuffer.normal", TileContent::UnitVector},   {"gbuffer.view", TileContent::UnitVector},
        {"gbuffer.wVec", TileContent::UnitVector},     {"gbuffer.nDotV", TileContent::SignedScalar},
        {"gbuffer.depth", TileContent::Depth},         {"gbuffer.coverage", TileContent::Mask},
        {"gbuffer.baseColor", TileContent::Color},     {"gbuffer.radial", TileContent::Data},
    };
    if (auto field = kGBufferFields.find(resource); field != kGBufferFields.end()) return field->second;
    if (resource == graph.finalResource || resource == graph.shadingResource) return TileContent::Color;
    if (isFloatFormat(format)) return TileContent::Data;
    // The remaining 8-bit one-channel buffers are line layers and mesh-edge skeletons: ink on paper.
    if (format == Format::R8) return TileContent::Lines;
    return TileContent::Color;
}

std::string lookSummary(const RenderOptions& options) {
    std::string lines;
    for (const std::string& type : options.lines) lines += (lines.empty() ? "" : ",") + type;
    return "shading " + shadingModeName(options.shading) + ", lines " + (lines.empty() ? "none" : lines);
}

/** --contact-sheet: every buffer the plan computed (the executor kept them all), in the plan's order, so the
 *  pipeline reads left to right, top to bottom. */
cv::Mat contactSheetOf(const RenderOptions& options, const StillGraph& graph, const Plan& plan,
                       ResourceStore& store) {
    std::vector<ContactTile> tiles;
    for (const PlannedResource& resource : plan.resources) {
        if (!store.contains(resource.name)) continue;
        const cv::Mat& image = store.image(resource.name);
        tiles.push_back({resource.name, describeImage(image) + " by " + resource.writer, image,
                         tileContentOf(resource.name, resource.desc.format, graph)});
    }
    ContactSheetLayout layout;
    layout.title = "inkgraph: '" + std::filesystem::path(options.modelPath).filename().string() + "' " +
                   std::to_string(options.width) + "x" + std::to_string(options.height) + ", " + lookSummary(options);
    return composeContactSheet(tiles, layout);
}

/** --svg: each line type's skeleton traced into simplified polylines. The CPU layers (everything but outline and
 *  silhouette) keep the one-pixel skeleton they stroked, at the data resolution, with sub-pixel points; outline and
 *  silhouette are bands GL drew at the output size, thinned to their centre lines first. */
std::string svgOf(const RenderOptions& options, const StillGraph& graph, ResourceStore& store) {
    std::vector<SvgLineLayer> layers;
    for (const std::string& type : knownLineTypes()) { // the composite's order: later types on top
        if (std::find(options.lines.begin(), options.lines.end(), type) == options.lines.end()) continue;
        const LineStyle& style = options.lineStyles.at(type);
        SvgLineLayer layer;
        layer.type = type;
        layer.widthPixels = style.widthPixels;
        layer.color = {style.color.r, style.color.g, style.color.b, style.color.a};
        TraceSettings trace;
        if (auto cpuLayer = graph.lineLayers.find(type); cpuLayer != graph.lineLayers.end()) {
            layer.supersample = cpuLayer->second->settings().supersample;
            trace.tolerancePixels = options.svgTolerance * layer.supersample;
            layer.polylines = traceSkeleton(cpuLayer->second->skeleton(), trace);
        } else {
            trace.tolerancePixels = options.svgTolerance;
            layer.polylines = traceMask(store.image(type + ".lines"), trace);
        }
        layers.push_back(std::move(layer));
    }
    SvgDocumentOptions document;
    document.title = "inkgraph: '" + std::filesystem::path(options.modelPath).filename().string() + "', " +
                     lookSummary(options);
    return svgDocument(options.width, options.height, layers, document);
}

/** Makes a context and checks the frame against what the driver can allocate. */
void checkDriverLimits(const RenderOptions& options) {
    GLint maxTextureSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTextureSize);
    GLint maxViewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
    const int limit = std::min(maxTextureSize, std::min(maxViewport[0], maxViewport[1]));
    if (options.width > limit || options.height > limit)
        throw UsageError("--size " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                         " exceeds this driver's largest render target side, " + std::to_string(limit));
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
            {"projection_matrix", matrixRows(camera.projectionMatrix())}};
}

Json describeLook(const RenderOptions& options, const StillGraph& graph) {
    Json look;
    if (!options.stylePath.empty()) look["style"] = options.stylePath;
    look["shading"] = shadingModeName(options.shading);
    if (options.shading == ShadingMode::Phong || options.shading == ShadingMode::Comic)
        look["shininess"] = options.shininess;
    if (!graph.shadeMapSource.empty()) look["shademap"] = graph.shadeMapSource;
    if (!graph.meshShadeMapSources.empty()) {
        Json meshMaps = Json::array();
        for (const auto& [mesh, source] : graph.meshShadeMapSources)
            meshMaps.push_back({{"mesh", mesh}, {"shademap", source}});
        look["mesh_shademaps"] = meshMaps;
    }
    look["gbuffer_precision"] = options.gbufferPrecision == GBufferPrecision::Float16 ? "half" : "float";
    Json lines = Json::array();
    for (const std::string& type : knownLineTypes()) {
        if (std::find(options.lines.begin(), options.lines.end(), type) == options.lines.end()) continue;
        const LineStyle& style = options.lineStyles.at(type);
        Json line = {{"type", type},
                     {"width_pixels", style.widthPixels},
                     {"color", Json::array({style.color.r, style.color.g, style.color.b, style.color.a})}};
        if (type == "silhouette" && options.silhouetteObjectWidth)
            line["object_width"] = *options.silhouetteObjectWidth;
        if (type == "silhouette" && graph.silhouette) line["skipped_eye_inside"] = graph.silhouette->skippedEyeInside();
        if (type == "outline" && graph.outline) line["skipped_eye_inside"] = graph.outline->skippedEyeInside();
        if (type == "crease" || type == "normal-edge") line["crease_angle_degrees"] = options.creaseAngleDegrees;
        if (isImageSpaceLineType(type) || isObjectSpaceLineType(type)) line["depth_jump"] = options.depthJump;
        if (isImageSpaceLineType(type) || isMeshEdgeLineType(type) || isObjectSpaceLineType(type))
            line["supersample"] = options.supersample;
        if (isMeshEdgeLineType(type) && graph.meshEdges) {
            const MeshEdgesPass::EdgeCounts& counts = graph.meshEdges->edgesDrawn();
            const auto& drawn = type == "crease" ? counts.crease : type == "border" ? counts.border : counts.silhouette;
            if (drawn) line["edges_drawn"] = *drawn;
        }
        if (type == "suggestive" || type == "suggestive-object") {
            const SuggestiveSettings& settings = graph.lineLayers.at(type)->settings().suggestive;
            line["threshold"] = settings.threshold;
            line["fade"] = settings.fade;
            // In model units: the image-space fs is stored in units of the radial field's length.
            line["feature_size"] = type == "suggestive" ? settings.featureSize * graph.radialLengthUnit
                                                        : double(settings.featureSize);
            if (type == "suggestive") {
                line["min_sin_theta"] = settings.minSinTheta;
                line["stencil_points"] = settings.stencil == DifferenceStencil::Central5 ? 5 : 3;
            }
        }
        lines.push_back(line);
    }
    look["lines"] = lines;
    return look;
}

/** The CPU line passes that ran: what they found and where the time went. "kernels_ms" is the post stage proper
 *  (finding and stroking every line type, without bringing the G-buffer to the CPU); "composite_ms" follows it. */
Json describePostStage(const StillGraph& graph, const std::vector<PassTiming>& timings) {
    Json layers = Json::array();
    double kernels = 0.0, readback = 0.0, composite = 0.0;
    for (const PassTiming& timing : timings) {
        if (timing.pass == "composite") composite = timing.milliseconds;
        const auto layer = graph.lineLayers.find(timing.pass);
        if (layer == graph.lineLayers.end()) continue;
        const LineLayerReport& report = layer->second->report();
        Json entry = {{"type", timing.pass},
                      {"skeleton_pixels", report.skeletonPixels},
                      {"points", report.points},
                      {"readback_ms", report.readbackMilliseconds},
                      {"kernel_ms", report.kernelMilliseconds},
                      {"stroke_ms", report.strokeMilliseconds}};
        if (layer->second->settings().source == LineSource::SuggestiveObject) {
            // The curvature is derived once per scene, before the pass's clock (in prepare): kernel_ms is per view.
            entry["segments"] = report.segments;
            entry["curvature_derived"] = report.curvatureDerived;
            entry["curvature_ms"] = report.curvatureMilliseconds;
        }
        layers.push_back(entry);
        kernels += report.kernelMilliseconds + report.strokeMilliseconds;
        readback += report.readbackMilliseconds;
    }
    return {{"lines", layers}, {"kernels_ms", kernels}, {"readback_ms", readback}, {"composite_ms", composite}};
}

/** Standard output that cannot be written (--print-plan > /dev/full, a closed pipe) fails the run. */
void requireStandardOutputWritten(std::ostream& out) {
    errno = 0;
    out.flush();
    if (!out || (&out == &std::cout && (std::fflush(stdout) != 0 || std::ferror(stdout))))
        throw FileError(std::string("renderStill(): cannot write the standard output") +
                        (errno ? std::string(": ") + std::strerror(errno) : ""));
}

/** The files the run read that only loading the model revealed: its buffers and images, and the shade maps its
 *  materials name. No output may be one of them (OutputSet::refuseInputs). */
std::vector<RunInput> inputsFoundByLoading(const RenderOptions& options, const Scene& scene) {
    // Appended, not "'" + name: GCC 12 warns falsely (-Wrestrict, bug 105329) on that inlined.
    std::string model = "'";
    model.append(std::filesystem::path(options.modelPath).filename().string()).append("'");
    std::vector<RunInput> inputs;
    for (const std::string& file : scene.report.inputFiles)
        inputs.push_back({file, "a file the model " + model + " reads"});
    for (const Mesh& mesh : scene.meshes)
        if (!mesh.shadeMapPath.empty())
            inputs.push_back({mesh.shadeMapPath, "the shade map of mesh '" + mesh.name + "' of " + model});
    return inputs;
}

/** Seed 000's numbers (Figure 8 plus holes and time) for --stats; only for comic, where the methods apply. */
Json describeOrientation(SceneOrientation& orientation) {
    const OrientationReport& report = orientation.report();
    return {{"method", report.method},
            {"view_vector", report.viewVector},
            {"fell_back_to_exact", report.fellBack},
            {"fall_back_reason", report.fallBackReason},
            {"sin_alpha", report.sinAlpha},
            {"beta_max_degrees", report.betaMaxDegrees},
            {"cutoff", report.cutoff},
            {"triangles", report.triangles},
            {"vertices", report.vertices},
            {"front_triangles", report.frontTriangles},
            {"front_vertices", report.frontVertices},
            {"front_triangle_share", report.triangles ? double(report.frontTriangles) / double(report.triangles) : 0.0},
            {"front_vertex_share", report.vertices ? double(report.frontVertices) / double(report.vertices) : 0.0},
            {"exact_front_triangles", report.exactFrontTriangles},
            {"missed_triangles", report.missedTriangles},
            {"derive_ms", report.deriveMilliseconds},
            {"mark_ms", report.markMilliseconds},
            {"upload_ms", report.uploadMilliseconds}};
}

} // namespace

std::size_t memoryLimitOf(const RenderOptions& options) {
    if (options.memoryLimitBytes) return *options.memoryLimitBytes;
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long pageSize = ::sysconf(_SC_PAGE_SIZE);
    const std::size_t physical = pages > 0 && pageSize > 0 ? std::size_t(pages) * std::size_t(pageSize) : 0;
    return std::max<std::size_t>(physical / 2, std::size_t(1) << 30);
}

ShadeMap readShadeMapFile(const std::string& path, bool oneDimensional) {
    cv::Mat image;
    try {
        // PNG only, by its own reader (fuzz_shademap found OpenEXR allocating 1.6 GB for a 600-byte header), without
        // ancillary chunks (and libpng 1.9 GB for a 342-byte file's tEXt), and the header's size is judged before
        // the pixels are allocated: a map is at most 4096 a side, its file at most 64 MiB (4096² RGBA is 64 MiB raw).
        image = readPngImage(path, std::size_t(kMaxShadeMapSide) * kMaxShadeMapSide, std::size_t(64) << 20);
    } catch (const FileError& error) {
        throw InputFileError(std::string("--shademap: ") + error.what());
    }
    if (image.depth() != CV_8U)
        throw InputFileError("--shademap: '" + path + "' stores 16-bit pixels; a shade map is an 8-bit PNG");
    try {
        return shadeMapFromImage(image, path, oneDimensional);
    } catch (const std::invalid_argument& error) {
        throw InputFileError(std::string("--shademap: ") + error.what());
    }
}

std::string dumpFileName(const std::string& resource, bool isFloat, const std::string& shadingResource) {
    static const std::map<std::string, std::string> kFixedNames = {
        {"gbuffer.normal", "normal.exr"},       {"gbuffer.view", "view.exr"},   {"gbuffer.wVec", "w.exr"},
        {"gbuffer.nDotV", "ndotv.exr"},         {"gbuffer.depth", "depth.exr"}, {"gbuffer.coverage", "coverage.png"},
        {"gbuffer.baseColor", "basecolor.png"}, {"gbuffer.radial", "radial.exr"},  {"composite.final", "final.png"},
    };
    if (auto fixed = kFixedNames.find(resource); fixed != kFixedNames.end()) return fixed->second;
    if (!shadingResource.empty() && resource == shadingResource) return "shading.png";
    const ResourceName name = ResourceName::split(resource);
    if (name.field == "lines") return "lines-" + name.pass + ".png";
    return name.pass + "-" + name.field + (isFloat ? ".exr" : ".png");
}

CameraRequest cameraRequestOf(const RenderOptions& options) {
    CameraRequest request;
    request.eye = options.eye;
    request.target = options.target;
    request.up = options.up;
    request.fovYDegrees = options.fovYDegrees;
    if (options.clipRange) {
        request.zNear = options.clipRange->x;
        request.zFar = options.clipRange->y;
    }
    request.width = options.width;
    request.height = options.height;
    return request;
}

FrameParams frameParamsOf(const RenderOptions& options, const Scene& scene, const Camera& camera,
                          const BoundingSphere& sphere) {
    FrameParams frame;
    frame.camera = camera;
    frame.worldOrigin = sphere.center;
    frame.towardLightWorld = options.towardLight ? *options.towardLight
                             : scene.light        ? scene.light->towardLight
                                                  : defaultLight(camera);
    frame.background = glm::vec4(glm::vec3(options.background), 1.0f);
    // A point (or empty) model has no radius; 1 keeps the radial field finite there.
    frame.radialLengthUnit = sphere.radius > 0.0 ? sphere.radius : 1.0;
    return frame;
}

RenderSession::RenderSession(std::ostream& out, std::ostream& log) : mOut(out), mLog(log) {
    mShaders.keepPrograms(true);
}

RenderSession::~RenderSession() = default;

StillReport RenderSession::render(const RenderOptions& options, const BatchPosition* batch) {
    const auto processStart = std::chrono::steady_clock::now();
    std::ostream& out = mOut;
    std::ostream& log = mLog;
    const bool renders = rendersImages(options);
    // In a batch the progress line per still replaces the lines of one still.
    const bool talks = !options.quiet && batch == nullptr;
    // OpenImageIO's ~0.2 s of dynamic linking overlaps loading the model. (Not rendering: on llvmpipe, LLVM's symbol
    // look-ups wait for the dynamic loader's lock, so they would queue behind it.)
    if (renders) preloadImageIo();
    StillReport report;

    // Every output place is checked before any work; outputs are staged and put in place only at the end.
    OutputSet outputs(options);
    std::optional<ShadeMap> shadeMap;
    if (!options.shadeMapPath.empty())
        shadeMap = readShadeMapFile(options.shadeMapPath, options.shading == ShadingMode::Cel);

    const auto loadStart = std::chrono::steady_clock::now();
    LoadOptions loadOptions;
    loadOptions.memoryLimitBytes = memoryLimitOf(options);
    const Scene scene = loadScene(options.modelPath, loadOptions);
    const double loadMs = millisecondsSince(loadStart);
    report.triangles = scene.triangleCount();
    for (const std::string& warning : scene.report.warnings)
        log << "inkgraph: warning: " << (talks ? "" : "'" + options.modelPath + "': ") << warning << "\n";
    if (talks) {
        log << std::fixed << std::setprecision(1) << "inkgraph: loaded '" << options.modelPath << "': " << scene.triangleCount() << " triangles, "
            << scene.vertexCount() << " vertices (" << scene.report.degenerateDropped << " degenerate dropped) in "
            << loadMs << " ms\n";
    }

    // The maps the model's materials name (glTF extras), each file read once; exit 3 like --shademap.
    std::vector<std::string> shadeMapWarnings;
    std::vector<std::optional<ShadeMap>> meshShadeMaps = readSceneShadeMaps(scene, options.shading, &shadeMapWarnings);
    for (const std::string& warning : shadeMapWarnings)
        log << "inkgraph: warning: " << (talks ? "" : "'" + options.modelPath + "': ") << warning << "\n";
    outputs.refuseInputs(inputsFoundByLoading(options, scene));

    const BoundingSphere sphere = computeBoundingSphere(scene);
    const CameraRequest request = cameraRequestOf(options);
    Camera camera;
    try {
        camera = resolveCamera(request, scene);
    } catch (const std::invalid_argument& error) {
        throw UsageError(error.what()); // the loader has validated the file's camera: what is left is the flags
    }

    const FrameParams frame = frameParamsOf(options, scene, camera, sphere);

    GpuScene gpuScene(scene, sphere.center);
    StillGraphSetup setup{options, mShaders, scene, sphere, gpuScene, frame, std::move(shadeMap)};
    setup.meshShadeMaps = std::move(meshShadeMaps);
    const StillGraph graph = buildStillGraph(setup);

    std::vector<std::string> requested = {graph.finalResource};
    // --svg traces the GL-drawn layers (outline, silhouette) from their masks, so those must outlive the composite.
    if (!options.svgPath.empty())
        for (const std::string& type : options.lines)
            if (!graph.lineLayers.count(type)) requested.push_back(type + ".lines");
    for (const std::string& extra : expandWildcards(options.extraOutputs, graph))
        if (std::find(requested.begin(), requested.end(), extra) == requested.end()) requested.push_back(extra);
    std::optional<Plan> compiled;
    try {
        compiled = compile(graph.view(), requested);
    } catch (const GraphError& error) {
        // The registered passes are consistent (tests/graph, tests/app); a problem here comes from --request.
        throw UsageError(std::string("--request: ") + error.what());
    }
    const Plan& plan = *compiled;
    if (options.printPlan) {
        out << plan.describe();
        requireStandardOutputWritten(out); // before the commit: a run that fails puts no file in place
    }
    if (!options.graphvizPath.empty()) outputs.stageGraphviz(plan.graphviz());
    if (!renders) {
        outputs.commit();
        return report;
    }
    checkFrameBudget(plan, options, &scene);

    // One context for every still of the process: the first that renders makes it (the platform flag is the same
    // for all of them), later ones find it current with the programs the earlier ones compiled.
    const bool contextReused = mContext.has_value();
    double contextMs = 0.0;
    if (!contextReused) {
        HeadlessContextOptions contextOptions;
        if (options.eglPlatform == "device") contextOptions.platform = EglPlatform::Device;
        if (options.eglPlatform == "surfaceless") contextOptions.platform = EglPlatform::Surfaceless;
        const auto contextStart = std::chrono::steady_clock::now();
        mContext.emplace(contextOptions);
        contextMs = millisecondsSince(contextStart);
        if (!options.quiet) log << "inkgraph: " << mContext->describe() << "\n";
    }
    const HeadlessContext& context = *mContext;
    checkDriverLimits(options);
    const std::size_t programsCompiledBefore = mShaders.compiledCount();
    const std::size_t programsReusedBefore = mShaders.reusedCount();

    TexturePool pool;
    GraphExecutor executor(pool);
    ExecuteOptions executeOptions;
    executeOptions.frameWidth = options.width;
    executeOptions.frameHeight = options.height;
    executeOptions.keepAllResources = keepsEveryBuffer(options);
    std::vector<PassTiming> timings;
    try {
        timings = executor.run(plan, graph.mutableView(), executeOptions);
    } catch (const GlOutOfMemoryError& error) {
        throw UsageError("--size " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                         ": the driver ran out of memory (" + error.what() + "); make the image smaller");
    } catch (const OutOfMemoryError& error) {
        throw UsageError("--size " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                         " with --supersample " + std::to_string(options.supersample) + ": out of memory (" +
                         error.what() + "); make the image smaller, or give the process more memory");
    }

    const auto writeStart = std::chrono::steady_clock::now();
    ResourceStore& store = executor.store();
    if (!options.outputPath.empty()) outputs.stageFinalImage(store.image(graph.finalResource));
    if (!options.contactSheetPath.empty())
        outputs.stageContactSheet(contactSheetOf(options, graph, plan, store));
    if (!options.svgPath.empty()) outputs.stageSvg(svgOf(options, graph, store));

    Json passTimes = Json::array();
    for (const PassTiming& timing : timings)
        passTimes.push_back(
            {{"name", timing.pass}, {"ms", timing.milliseconds}, {"prepare_ms", timing.prepareMilliseconds}});

    if (!options.dumpDirectory.empty()) {
        Json files = Json::array();
        std::set<std::string> usedNames;
        for (const PlannedResource& resource : plan.resources) {
            if (!store.contains(resource.name)) continue;
            const bool isFloat = isFloatFormat(resource.desc.format);
            const std::string fileName = dumpFileName(resource.name, isFloat, graph.shadingResource);
            if (!usedNames.insert(fileName).second)
                throw std::logic_error("renderStill(): two resources dump to '" + fileName + "'");
            outputs.stageDumpImage(fileName, store.image(resource.name));
            // Written buffers are not needed again: freeing them keeps the dump's peak memory to one copy.
            if (resource.name != graph.finalResource) store.release(resource.name);
            files.push_back({{"file", fileName},
                             {"resource", resource.name},
                             {"pass", resource.writer},
                             {"format", std::string(formatName(resource.desc.format))},
                             {"requested", resource.requested}});
        }
        Json manifest;
        manifest["inkgraph"] = INKGRAPH_VERSION;
        manifest["model"] = options.modelPath;
        manifest["size"] = {options.width, options.height};
        manifest["conventions"] = "right-handed world; OpenGL lookAt/perspective; row 0 at the top; pixel centres at "
                                  "(col+0.5, row+0.5); matrices as rows; 8-bit images sRGB, float images linear data";
        manifest["camera"] = describeCamera(camera);
        manifest["toward_light_world"] = vectorJson(frame.towardLightWorld);
        manifest["look"] = describeLook(options, graph);
        manifest["files"] = files;
        manifest["passes"] = passTimes;
        outputs.stageDumpManifest(jsonText(manifest));
    }

    if (!options.statsPath.empty()) {
        Json culled = Json::array();
        for (const CulledPass& pass : plan.culled) culled.push_back({{"name", pass.name}, {"reason", pass.reason}});
        Json stats;
        stats["model"] = options.modelPath;
        stats["scene"] = {{"format", scene.report.format},
                          {"meshes", scene.meshes.size()},
                          {"triangles", scene.triangleCount()},
                          {"vertices", scene.vertexCount()},
                          {"triangles_read", scene.report.trianglesRead},
                          {"degenerate_dropped", scene.report.degenerateDropped},
                          {"vertices_before_weld", scene.report.verticesBeforeWeld},
                          {"normals_computed", scene.report.normalsComputed}};
        stats["size"] = {options.width, options.height};
        stats["camera_source"] = camera.source;
        stats["clip"] = {{"near", camera.zNear},
                         {"far", camera.zFar},
                         {"far_over_near", camera.zFar / camera.zNear},
                         {"source", camera.clipSource},
                         {"depth", "reversed-z float32"}};
        if (batch) stats["batch"] = {{"position", batch->model.position + 1}, {"list_length", batch->listLength}};
        stats["gl"] = {{"platform", context.platform()},
                       {"renderer", context.renderer()},
                       {"version", context.version()},
                       {"vendor", context.vendor()}};
        stats["load_ms"] = loadMs;
        stats["context_ms"] = contextMs;
        stats["context_reused"] = contextReused;
        // Programs this still compiled, and those it took from an earlier still of the process.
        stats["programs_compiled"] = mShaders.compiledCount() - programsCompiledBefore;
        stats["programs_reused"] = mShaders.reusedCount() - programsReusedBefore;
        stats["look"] = describeLook(options, graph);
        if (options.shading == ShadingMode::Comic) stats["face_orientation"] = describeOrientation(*graph.orientation);
        stats["passes"] = passTimes;
        stats["post_stage"] = describePostStage(graph, timings);
        stats["culled"] = culled;
        stats["write_ms"] = millisecondsSince(writeStart);
        stats["textures_created"] = pool.createdCount();
        stats["textures_reused"] = pool.reusedCount();
        stats["estimated_peak_mib"] = double(estimatePlanBytes(plan, options, &scene)) / (1 << 20);
        // Measured so far (the outputs above are encoded): what the estimate bounds, to compare.
        stats["peak_rss_mib"] = double(peakResidentBytes()) / (1 << 20);
        stats["total_ms"] = millisecondsSince(processStart);
        outputs.stageStats(jsonText(stats));
    }
    outputs.commit();
    report.milliseconds = millisecondsSince(processStart);
    if (talks) {
        log << "inkgraph: rendered " << options.width << "x" << options.height << " in "
            << millisecondsSince(processStart) << " ms";
        if (!options.outputPath.empty()) log << " -> '" << options.outputPath << "'";
        log << "\n";
    }
    return report;
}

void renderStill(const RenderOptions& options, std::ostream& out, std::ostream& log) {
    RenderSession session(out, log);
    session.render(options);
}

int renderBatch(const RenderOptions& options, std::istream& standardInput, std::ostream& out, std::ostream& log) {
    const BatchList list = batchList(options, standardInput);
    checkBatchOutputs(options, list);
    RenderSession session(out, log);
    const std::string share =
        options.shard ? " (shard " + std::to_string(options.shard->index) + "/" + std::to_string(options.shard->count) +
                            " of " + std::to_string(list.total) + ")"
                      : "";
    // Only --shard can leave a share empty (a list of no models is refused): with N above the list's length some
    // shards have nothing to do, which is not an error in an array job.
    if (list.models.empty()) {
        if (!options.quiet) log << "inkgraph: no models in this share" << share << "\n";
        return kExitOk;
    }
    if (!list.isBatch) {
        session.render(stillOptions(options, list.models.front(), list.total));
        return kExitOk;
    }
    const auto batchStart = std::chrono::steady_clock::now();
    int exitCode = kExitOk;
    std::vector<std::string> failed;
    for (std::size_t i = 0; i < list.models.size(); ++i) {
        const BatchModel& model = list.models[i];
        const RenderOptions still = stillOptions(options, model, list.total);
        const std::string counter =
            "inkgraph: [" + std::to_string(i + 1) + "/" + std::to_string(list.models.size()) + "] '" + model.path + "'";
        try {
            const BatchPosition position{model, list.total};
            const StillReport report = session.render(still, &position);
            if (!options.quiet) {
                log << counter;
                if (!still.outputPath.empty()) log << " -> '" << still.outputPath << "'";
                log << ": " << report.triangles << " triangles, " << std::fixed << std::setprecision(0)
                    << report.milliseconds << " ms\n";
            }
        } catch (const SceneError& error) {
            // Bad input stops one still, not the batch: the other models' work is not lost.
            log << counter << " failed: " << error.what() << "\n";
            failed.push_back(model.path);
            if (exitCode == kExitOk) exitCode = kExitBadInput;
        } catch (const InputFileError& error) {
            log << counter << " failed: " << error.what() << "\n";
            failed.push_back(model.path);
            if (exitCode == kExitOk) exitCode = kExitBadInput;
        }
    }
    if (!options.quiet || !failed.empty()) {
        log << "inkgraph: rendered " << list.models.size() - failed.size() << " of " << list.models.size()
            << " models" << share << " in " << std::fixed << std::setprecision(1)
            << millisecondsSince(batchStart) / 1000.0 << " s";
        if (!failed.empty()) {
            log << "; " << failed.size() << " failed:";
            for (const std::string& path : failed) log << " '" << path << "'";
        }
        log << "\n";
    }
    return exitCode;
}

namespace {

int runRenderCommand(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err) {
    try {
        std::error_code noFolder;
        (void)std::filesystem::current_path(noFolder);
        if (noFolder)
            throw FileError("runCommandLine(): the working folder cannot be found (" + noFolder.message() +
                            "; was it deleted?); run inkgraph from an existing folder");
        const SourcedArguments expanded = expandStyleFile(arguments);
        const RenderOptions options = parseRenderOptions(expanded.arguments, expanded.origins);
        if (options.help) {
            out << renderHelp();
            return kExitOk;
        }
        return renderBatch(options, std::cin, out, err);
    } catch (const UsageError& error) {
        err << "inkgraph: " << error.what() << "\n(see: inkgraph help render)\n";
        return kExitUsage;
    } catch (const SceneError& error) {
        err << "inkgraph: " << error.what() << "\n";
        return kExitBadInput;
    } catch (const InputFileError& error) {
        err << "inkgraph: " << error.what() << "\n";
        return kExitBadInput;
    } catch (const HeadlessContextError& error) {
        err << "inkgraph: " << error.what() << "\n";
        return kExitNoGl;
    } catch (const FileError& error) {
        err << "inkgraph: " << error.what() << "\n";
        return kExitOutput;
    } catch (const ShaderSourceError& error) {
        err << "inkgraph: " << error.what() << "\n";
        return kExitNoGl;
    } catch (const std::bad_alloc&) {
        err << "inkgraph: out of memory; make the image smaller (--size, --supersample) or request and dump fewer "
               "buffers\n(see: inkgraph help render)\n";
        return kExitUsage;
    } catch (const cv::Exception& error) {
        if (error.code != cv::Error::StsNoMem) {
            err << "inkgraph: internal error: " << error.what() << "\n";
            return kExitInternal;
        }
        err << "inkgraph: out of memory (" << error.err << "); make the image smaller (--size, --supersample) or "
               "request and dump fewer buffers\n(see: inkgraph help render)\n";
        return kExitUsage;
    } catch (const std::exception& error) {
        err << "inkgraph: internal error: " << error.what() << "\n";
        return kExitInternal;
    }
}

} // namespace

int runCommandLine(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    std::vector<std::string> arguments(argv + std::min(argc, 1), argv + argc);
    if (arguments.empty()) {
        err << mainHelp();
        return kExitUsage;
    }
    if (arguments[0] == "--help" || arguments[0] == "-h" || arguments[0] == "help") {
        if (arguments.size() > 1 && arguments[1] != "render") {
            err << "inkgraph: no help on '" << arguments[1] << "' (topics: render)\n";
            return kExitUsage;
        }
        out << (arguments.size() > 1 ? renderHelp() : mainHelp());
        return kExitOk;
    }
    if (arguments[0] == "--version") {
        out << "inkgraph " << INKGRAPH_VERSION << "\n";
        return kExitOk;
    }
    if (arguments[0] != "render") {
        err << "inkgraph: unknown command '" << arguments[0] << "' (try: inkgraph --help)\n";
        return kExitUsage;
    }
    arguments.erase(arguments.begin());
    removeTemporariesOnSignals();
    const int exitCode = runRenderCommand(arguments, out, err);
    // Output that cannot be written (--help > /dev/full, a closed pipe) is a failed run, not a silent one.
    try {
        requireStandardOutputWritten(out);
    } catch (const FileError& error) {
        if (exitCode == kExitOk) err << "inkgraph: " << error.what() << "\n";
        return exitCode == kExitOk ? kExitOutput : exitCode;
    }
    return exitCode;
}

} // namespace inkgraph
