#include "api/Internal.h"

#include "render/MemoryBudget.h"
#include "scene/MeshArrays.h"
#include "scene/MeshLabels.h"
#include "scene/MeshNumbering.h"
#include "scene/ObjectIds.h"
#include "scene/MessageText.h"

namespace inkgraph::api {
inline namespace INKGRAPH_ABI_NAMESPACE {
namespace {

/** The loader's options for `options`, checked by --animation's and --time's own rules and messages. */
LoadOptions loadOptionsOf(const SceneOptions& options) {
    std::vector<std::string> flags;
    if (!options.animation.empty()) flags.insert(flags.end(), {"--animation", options.animation});
    if (options.time != 0.0) flags.insert(flags.end(), {"--time", exactText(options.time)});
    if (!options.pose.empty()) flags.insert(flags.end(), {"--pose", options.pose});
    // A scene's time is its pose's (the UV animation's clock is the frame's): without an animation it poses nothing.
    if (options.animation.empty() && options.time != 0.0) throw UsageError("--time has no effect without --animation");
    const RenderOptions pose = parseRenderFlags(flags);
    LoadOptions load;
    load.memoryLimitBytes = options.memoryLimitBytes != 0 ? options.memoryLimitBytes : defaultMemoryLimit();
    load.animation = pose.animation;
    load.time = pose.animationTime;
    load.pose = pose.pose;
    if (options.weldDistance != kDefaultWeldTolerance) { // checked by the flag's rule; the default is no one's text
        try {
            load.weldTolerance = parseRenderFlags({"--weld-distance", exactText(options.weldDistance)}).weldTolerance;
        } catch (const UsageError& error) {
            throw UsageError(std::string("SceneOptions::weldDistance: ") + error.what());
        }
    }
    applyFace(options.expressions, options.lookAt, "SceneOptions::", load.expressions, load.lookAt);
    return load;
}

} // namespace

void applyFace(const std::map<std::string, double>& expressions, const std::optional<Vec3>& lookAt,
               const std::string& field, std::vector<ExpressionWeight>& expressionsOut,
               std::optional<glm::dvec3>& lookAtOut) {
    // Checked here, not through --expression's parser: a name is taken as it is, which the flag's syntax could not
    // hold when it has a ','.
    for (const auto& [name, weight] : expressions) {
        if (!(weight >= 0.0 && weight <= 1.0))
            throw UsageError(field + "expressions: the weight of '" + name + "' must lie in [0, 1], got " +
                             exactText(weight));
        expressionsOut.push_back({name, weight});
    }
    if (lookAt) {
        try {
            lookAtOut = parseRenderFlags({"--look-at", vectorText(*lookAt)}).lookAt;
        } catch (const UsageError& error) {
            throw UsageError(field + "lookAt: " + error.what());
        }
    }
}

Scene Scene::load(const std::string& path, const SceneOptions& options) {
    return translated("Scene::load()", [&] {
        auto impl = std::make_shared<Impl>();
        impl->path = path;
        impl->options = options;
        impl->scene = std::make_shared<const inkgraph::Scene>(loadScene(path, loadOptionsOf(options)));
        impl->derived = std::make_shared<inkgraph::SceneDerivedData>(*impl->scene);
        const std::vector<inkgraph::Warning>& warnings = impl->scene->report.warnings;
        if (options.strict && !warnings.empty())
            throw SceneError("SceneOptions::strict: " + detail::quotedFileName(path) + ": " + warnings.front().message +
                             (warnings.size() > 1 ? " (and " + std::to_string(warnings.size() - 1) + " more)" : ""));
        return Scene(std::move(impl));
    });
}

Scene Scene::fromArrays(const MeshArrays& arrays, const std::string& name, const SceneOptions& options) {
    return translated("Scene::fromArrays()", [&] {
        if (!options.animation.empty() || options.time != 0.0)
            throw UsageError("SceneOptions::animation and time: a scene made from arrays has no animations");
        if (!options.pose.empty()) throw UsageError("SceneOptions::pose: a scene made from arrays has no humanoid");
        if (!options.expressions.empty() || options.lookAt)
            throw UsageError("SceneOptions::expressions and lookAt: a scene made from arrays has no VRM face");
        inkgraph::MeshArrays mesh;
        mesh.vertices = arrays.vertices;
        mesh.vertexCount = arrays.vertexCount;
        mesh.faces = arrays.faces;
        mesh.faceCount = arrays.faceCount;
        mesh.normals = arrays.normals;
        mesh.uvs = arrays.uvs;
        mesh.colors = arrays.colors;
        mesh.colorChannels = arrays.colorChannels;
        mesh.name = name;
        mesh.caller = "Scene::fromArrays()";
        auto impl = std::make_shared<Impl>();
        impl->options = options;
        impl->scene = std::make_shared<const inkgraph::Scene>(sceneFromArrays(mesh, loadOptionsOf(options)));
        impl->derived = std::make_shared<inkgraph::SceneDerivedData>(*impl->scene);
        return Scene(std::move(impl));
    });
}

const std::string& Scene::path() const { return mImpl->path; }
std::size_t Scene::triangleCount() const { return mImpl->scene->triangleCount(); }
std::size_t Scene::vertexCount() const { return mImpl->scene->vertexCount(); }
std::size_t Scene::meshCount() const { return mImpl->scene->meshes.size(); }

std::vector<SceneObject> objectsOf(const inkgraph::Scene& scene) {
    const SceneObjects found = sceneObjects(scene);
    const MeshNumbering numbering(scene);
    std::vector<SceneObject> objects;
    for (std::size_t index = 0; index < found.objects.size(); ++index) {
        const inkgraph::SceneObject& object = found.objects[index];
        SceneObject entry{std::uint32_t(index + 1), object.name, object.nodePath, {}};
        for (const std::size_t mesh : object.meshes) entry.meshes.push_back(numbering.mesh(mesh).name);
        objects.push_back(std::move(entry));
    }
    return objects;
}

std::vector<SceneMesh> meshesOf(const inkgraph::Scene& scene) {
    const SceneLabels labels = sceneLabels(scene);
    std::vector<SceneMesh> meshes;
    for (const MeshLabel& mesh : labels.meshes)
        meshes.push_back({mesh.id, mesh.drawn, mesh.name, mesh.nodePath, mesh.objectId, mesh.materialId,
                          labels.materials.at(mesh.materialId - 1).name, mesh.firstTriangle, mesh.triangleCount});
    return meshes;
}

std::vector<SceneObject> Scene::objects() const { return objectsOf(*mImpl->scene); }
std::vector<SceneMesh> Scene::meshes() const { return meshesOf(*mImpl->scene); }

std::vector<Warning> Scene::warnings() const {
    std::vector<Warning> warnings;
    for (const inkgraph::Warning& warning : mImpl->scene->report.warnings)
        warnings.push_back({warning.code, warning.message, warning.file, warning.item});
    return warnings;
}

} // namespace INKGRAPH_ABI_NAMESPACE
} // namespace inkgraph::api
