#include "api/Internal.h"

#include "render/MemoryBudget.h"

#include <charconv>

namespace inkgraph::api {
namespace {

/** The shortest text that reads back as `value` (what --time would be given). */
std::string exactText(double value) {
    char text[64];
    const auto [end, error] = std::to_chars(text, text + sizeof text, value);
    return std::string(text, error == std::errc() ? end : text);
}

} // namespace

Scene Scene::load(const std::string& path, const SceneOptions& options) {
    return translated("Scene::load()", [&] {
        // --animation and --time's own checks and messages.
        std::vector<std::string> flags;
        if (!options.animation.empty()) flags.insert(flags.end(), {"--animation", options.animation});
        if (options.time != 0.0) flags.insert(flags.end(), {"--time", exactText(options.time)});
        RenderOptions pose = parseRenderFlags(flags);
        if (options.memoryLimitBytes != 0) pose.memoryLimitBytes = options.memoryLimitBytes;

        LoadOptions load;
        load.memoryLimitBytes = pose.memoryLimitBytes ? *pose.memoryLimitBytes : defaultMemoryLimit();
        load.animation = pose.animation;
        load.time = pose.animationTime;
        auto impl = std::make_shared<Impl>();
        impl->path = path;
        impl->options = options;
        impl->scene = std::make_shared<const inkgraph::Scene>(loadScene(path, load));
        return Scene(std::move(impl));
    });
}

const std::string& Scene::path() const { return mImpl->path; }
std::size_t Scene::triangleCount() const { return mImpl->scene->triangleCount(); }
std::size_t Scene::vertexCount() const { return mImpl->scene->vertexCount(); }
std::size_t Scene::meshCount() const { return mImpl->scene->meshes.size(); }
std::vector<std::string> Scene::warnings() const {
    std::vector<std::string> messages;
    for (const inkgraph::Warning& warning : mImpl->scene->report.warnings) messages.push_back(warning.message);
    return messages;
}

} // namespace inkgraph::api
