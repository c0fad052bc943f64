#include "app/Render.h"

#include "app/ImageFiles.h"
#include "gl/GraphExecutor.h"
#include "gl/HeadlessContext.h"
#include "gl/ShaderLibrary.h"
#include "gl/TexturePool.h"
#include "graph/GraphCompiler.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/composite/CompositePass.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/lambert/LambertPass.h"
#include "scene/Camera.h"
#include "scene/Scene.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <set>

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

/** Default key light: from the upper left, behind the camera, fixed in view space so every auto-framed still is lit
 *  the same way. */
glm::dvec3 defaultLight(const Camera& camera) {
    const glm::dvec3 towardLightView = glm::normalize(glm::dvec3(-0.4, 0.5, 0.77));
    return glm::normalize(glm::transpose(glm::dmat3(camera.viewMatrix())) * towardLightView);
}

/** The passes of one still, in registration order. Every pass is registered; the compiler culls what the request
 *  does not need, so the stats say why a pass did not run. */
struct PassSet {
    std::vector<std::unique_ptr<Pass>> owned;
    std::string shadingResource; ///< the colour the composite reads, or empty

    std::vector<const Pass*> view() const {
        std::vector<const Pass*> passes;
        for (const auto& pass : owned) passes.push_back(pass.get());
        return passes;
    }
    std::vector<Pass*> mutableView() const {
        std::vector<Pass*> passes;
        for (const auto& pass : owned) passes.push_back(pass.get());
        return passes;
    }
};

PassSet buildPasses(const RenderOptions& options, ShaderLibrary& shaders, GpuScene& gpuScene, const FrameParams& frame) {
    PassSet set;
    set.owned.push_back(std::make_unique<GBufferPass>("gbuffer", shaders, gpuScene, frame));
    set.owned.push_back(
        std::make_unique<LambertPass>("lambert", shaders, frame, "gbuffer.normal", "gbuffer.baseColor"));
    if (options.shading == ShadingMode::Lambert) set.shadingResource = "lambert.color";
    set.owned.push_back(std::make_unique<CompositePass>("composite", frame, set.shadingResource));
    return set;
}

/** "gbuffer.*" -> every field gbuffer declares; plain names must be declared by some pass. */
std::vector<std::string> expandRequests(const std::vector<std::string>& requests, const PassSet& passes) {
    std::map<std::string, std::vector<std::string>> fieldsOfPass;
    for (const Pass* pass : passes.view()) {
        PassBuilder builder{std::string(pass->name())};
        pass->declare(builder);
        for (const auto& write : builder.writes())
            fieldsOfPass[builder.passName()].push_back(builder.passName() + "." + write.field);
    }
    std::vector<std::string> expanded;
    for (const std::string& request : requests) {
        const ResourceName name = ResourceName::split(request);
        auto pass = fieldsOfPass.find(name.pass);
        if (pass == fieldsOfPass.end()) throw UsageError("--request: no pass named '" + name.pass + "' in this graph");
        if (name.field == "*") {
            expanded.insert(expanded.end(), pass->second.begin(), pass->second.end());
        } else if (std::find(pass->second.begin(), pass->second.end(), request) != pass->second.end()) {
            expanded.push_back(request);
        } else {
            std::string known;
            for (const std::string& resource : pass->second) known += (known.empty() ? "" : ", ") + resource;
            throw UsageError("--request: pass '" + name.pass + "' writes no '" + request + "' (it writes " + known +
                             ")");
        }
    }
    return expanded;
}

void ensureWritableDirectory(const std::filesystem::path& directory, const std::string& what) {
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    if (error || !std::filesystem::is_directory(directory))
        throw FileError("renderStill(): cannot create the " + what + " folder '" + directory.string() + "'" +
                        (error ? ": " + error.message() : ""));
    // A probe file is the only reliable test of writability (permissions, read-only mounts, ACLs).
    const std::filesystem::path probe = temporarySibling(directory / "probe.tmp");
    try {
        writeTextFile(probe, "");
    } catch (const FileError&) {
        throw FileError("renderStill(): the " + what + " folder '" + directory.string() + "' is not writable");
    }
    std::filesystem::remove(probe, error);
}

} // namespace

std::string dumpFileName(const std::string& resource, bool isFloat, const std::string& shadingResource) {
    static const std::map<std::string, std::string> kFixedNames = {
        {"gbuffer.normal", "normal.exr"},     {"gbuffer.view", "view.exr"},   {"gbuffer.wVec", "w.exr"},
        {"gbuffer.nDotV", "ndotv.exr"},       {"gbuffer.depth", "depth.exr"}, {"gbuffer.coverage", "coverage.png"},
        {"gbuffer.baseColor", "basecolor.png"}, {"composite.final", "final.png"},
    };
    if (auto fixed = kFixedNames.find(resource); fixed != kFixedNames.end()) return fixed->second;
    if (!shadingResource.empty() && resource == shadingResource) return "shading.png";
    const ResourceName name = ResourceName::split(resource);
    if (name.field == "lines") return "lines-" + name.pass + ".png";
    return name.pass + "-" + name.field + (isFloat ? ".exr" : ".png");
}

void renderStill(const RenderOptions& options, std::ostream& out, std::ostream& log) {
    const auto processStart = std::chrono::steady_clock::now();
    // Declared first so it is destroyed last, after every GL object below.
    std::optional<HeadlessContext> context;
    // OpenImageIO's ~0.2 s of dynamic linking overlaps loading the model. (Not rendering: on llvmpipe, LLVM's symbol
    // look-ups wait for the dynamic loader's lock, so they would queue behind it.)
    if (!options.outputPath.empty() || !options.dumpDirectory.empty()) preloadImageIo();

    const auto loadStart = std::chrono::steady_clock::now();
    const Scene scene = loadScene(options.modelPath);
    const double loadMs = millisecondsSince(loadStart);
    if (!options.quiet)
        log << "inkgraph: loaded '" << options.modelPath << "': " << scene.triangleCount() << " triangles, "
            << scene.vertexCount() << " vertices (" << scene.report.degenerateDropped << " degenerate dropped) in "
            << loadMs << " ms\n";
    for (const std::string& warning : scene.report.warnings)
        if (!options.quiet) log << "inkgraph: warning: " << warning << "\n";

    const BoundingSphere sphere = computeBoundingSphere(scene);
    CameraRequest request;
    request.eye = options.eye;
    request.target = options.target;
    request.up = options.up;
    request.fovYDegrees = options.fovYDegrees;
    request.width = options.width;
    request.height = options.height;
    Camera camera;
    try {
        camera = resolveCamera(request, scene);
    } catch (const std::invalid_argument& error) {
        throw UsageError(error.what());
    }

    FrameParams frame;
    frame.camera = camera;
    frame.worldOrigin = sphere.center;
    frame.towardLightWorld = options.towardLight ? *options.towardLight
                             : scene.light        ? scene.light->towardLight
                                                  : defaultLight(camera);
    frame.background = glm::vec4(glm::vec3(options.background), 1.0f);

    ShaderLibrary shaders;
    GpuScene gpuScene(scene, sphere.center);
    const PassSet passes = buildPasses(options, shaders, gpuScene, frame);

    std::vector<std::string> requested = {"composite.final"};
    for (const std::string& extra : expandRequests(options.extraOutputs, passes))
        if (std::find(requested.begin(), requested.end(), extra) == requested.end()) requested.push_back(extra);
    const Plan plan = compile(passes.view(), requested);
    if (options.printPlan) out << plan.describe();
    if (!options.graphvizPath.empty()) writeTextFile(options.graphvizPath, plan.graphviz());
    if (options.outputPath.empty() && options.dumpDirectory.empty()) return;

    // Fail before rendering if an output cannot be written.
    if (!options.outputPath.empty()) {
        const std::filesystem::path parent = std::filesystem::absolute(options.outputPath).parent_path();
        if (!std::filesystem::is_directory(parent))
            throw FileError("renderStill(): the folder of '" + options.outputPath + "' does not exist");
        if (std::filesystem::is_directory(options.outputPath))
            throw FileError("renderStill(): -o '" + options.outputPath + "' is a folder; give a file name");
        // Common extensions need no look-up; anything else asks OpenImageIO now rather than after rendering.
        static const std::set<std::string> kKnownExtensions = {".png", ".exr", ".tif", ".tiff", ".jpg", ".jpeg"};
        if (kKnownExtensions.count(std::filesystem::path(options.outputPath).extension().string()) == 0)
            requireImageWriter(options.outputPath);
    }
    if (!options.dumpDirectory.empty()) ensureWritableDirectory(options.dumpDirectory, "--dump");

    HeadlessContextOptions contextOptions;
    if (options.eglPlatform == "device") contextOptions.platform = EglPlatform::Device;
    if (options.eglPlatform == "surfaceless") contextOptions.platform = EglPlatform::Surfaceless;
    const auto contextStart = std::chrono::steady_clock::now();
    context.emplace(contextOptions);
    const double contextMs = millisecondsSince(contextStart);
    if (!options.quiet) log << "inkgraph: " << context->describe() << "\n";

    TexturePool pool;
    GraphExecutor executor(pool);
    ExecuteOptions executeOptions;
    executeOptions.frameWidth = options.width;
    executeOptions.frameHeight = options.height;
    executeOptions.keepAllResources = !options.dumpDirectory.empty();
    const std::vector<PassTiming> timings = executor.run(plan, passes.mutableView(), executeOptions);

    const auto writeStart = std::chrono::steady_clock::now();
    ResourceStore& store = executor.store();
    if (!options.outputPath.empty()) writeImage(options.outputPath, store.image("composite.final"));

    Json passTimes = Json::array();
    for (const PassTiming& timing : timings)
        passTimes.push_back(
            {{"name", timing.pass}, {"ms", timing.milliseconds}, {"prepare_ms", timing.prepareMilliseconds}});

    if (!options.dumpDirectory.empty()) {
        const std::filesystem::path directory(options.dumpDirectory);
        Json files = Json::array();
        std::set<std::string> usedNames;
        for (const PlannedResource& resource : plan.resources) {
            if (!store.contains(resource.name)) continue;
            const bool isFloat = resource.desc.format == Format::RGBA32F || resource.desc.format == Format::R32F;
            const std::string fileName = dumpFileName(resource.name, isFloat, passes.shadingResource);
            if (!usedNames.insert(fileName).second)
                throw std::logic_error("renderStill(): two resources dump to '" + fileName + "'");
            writeImage(directory / fileName, store.image(resource.name));
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
                                  "(col+0.5, row+0.5); matrices as rows";
        manifest["camera"] = {{"source", camera.source},
                              {"eye", vectorJson(camera.eye)},
                              {"target", vectorJson(camera.target)},
                              {"up", vectorJson(camera.up)},
                              {"fov_y_degrees", camera.fovYDegrees},
                              {"near", camera.zNear},
                              {"far", camera.zFar},
                              {"focal_pixels", camera.focalPixels()},
                              {"view_matrix", matrixRows(camera.viewMatrix())},
                              {"projection_matrix", matrixRows(camera.projectionMatrix())}};
        manifest["toward_light_world"] = vectorJson(frame.towardLightWorld);
        manifest["files"] = files;
        manifest["passes"] = passTimes;
        writeTextFile(directory / "manifest.json", manifest.dump(2) + "\n");
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
        stats["gl"] = {{"platform", context->platform()},
                       {"renderer", context->renderer()},
                       {"version", context->version()},
                       {"vendor", context->vendor()}};
        stats["load_ms"] = loadMs;
        stats["context_ms"] = contextMs;
        stats["passes"] = passTimes;
        stats["culled"] = culled;
        stats["write_ms"] = millisecondsSince(writeStart);
        stats["textures_created"] = pool.createdCount();
        stats["textures_reused"] = pool.reusedCount();
        stats["total_ms"] = millisecondsSince(processStart);
        writeTextFile(options.statsPath, stats.dump(2) + "\n");
    }
    if (!options.quiet) {
        log << "inkgraph: rendered " << options.width << "x" << options.height << " in "
            << millisecondsSince(processStart) << " ms";
        if (!options.outputPath.empty()) log << " -> '" << options.outputPath << "'";
        log << "\n";
    }
}

int runCommandLine(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
    std::vector<std::string> arguments(argv + std::min(argc, 1), argv + argc);
    if (arguments.empty() || arguments[0] == "--help" || arguments[0] == "-h" || arguments[0] == "help") {
        (arguments.empty() ? err : out) << mainHelp();
        return arguments.empty() ? kExitUsage : kExitOk;
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
    if (std::find(arguments.begin(), arguments.end(), "--help") != arguments.end() ||
        std::find(arguments.begin(), arguments.end(), "-h") != arguments.end()) {
        out << renderHelp();
        return kExitOk;
    }
    try {
        renderStill(parseRenderOptions(arguments), out, err);
        return kExitOk;
    } catch (const UsageError& error) {
        err << "inkgraph: " << error.what() << "\n(see: inkgraph render --help)\n";
        return kExitUsage;
    } catch (const SceneError& error) {
        err << "inkgraph: " << error.what() << "\n";
        return kExitBadInput;
    } catch (const HeadlessContextError& error) {
        err << "inkgraph: " << error.what() << "\n";
        return kExitNoGl;
    } catch (const FileError& error) {
        err << "inkgraph: " << error.what() << "\n";
        return kExitOutput;
    } catch (const std::exception& error) {
        err << "inkgraph: internal error: " << error.what() << "\n";
        return kExitInternal;
    }
}

} // namespace inkgraph
