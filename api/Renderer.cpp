#include "api/Internal.h"

#include "render/ImageFiles.h"
#include "render/InputFiles.h"
#include "render/MemoryBudget.h"
#include "render/StillRenderer.h"
#include "passes/StillGraph.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/lines/LineTypes.h"
#include "postfx/Composite.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <optional>
#include <sstream>
#include <mutex>

#include <unistd.h>

namespace inkgraph::api {
namespace {

const std::string kLinesPrefix = "lines.";

bool startsWith(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

std::string joined(const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
    return text;
}

/** The name people use for a resource: bufferResourceName() backwards. */
std::string bufferNameOf(const std::string& resource, const StillGraph& graph) {
    if (resource == graph.finalResource) return "picture";
    const ResourceName name = ResourceName::split(resource);
    if (name.pass == kStrokesPass) return kLinesPrefix + name.field;
    if (name.pass == kGBufferPass)
        for (const GBufferPass::Field& field : GBufferPass::fields())
            if (name.field == field.name) return name.field;
    return resource;
}

/** Every image resource the graph's passes write (objects without a picture are data, not buffers), by full name, in
 *  registration order. */
std::vector<std::string> writtenResources(const StillGraph& graph) {
    std::vector<std::string> resources;
    for (const Pass* pass : graph.view()) {
        PassBuilder builder{std::string(pass->name())};
        pass->declare(builder);
        for (const PassBuilder::Write& write : builder.writes())
            if (write.isImage()) resources.push_back(builder.passName() + "." + write.field);
    }
    return resources;
}

/** Throws UsageError for the first of `names` the graph does not write, naming the buffers it has; returns when every
 *  name is one (the failure was another). */
void refuseUnknownBuffers(const StillGraph& graph, const std::vector<std::string>& names) {
    const std::vector<std::string> resources = writtenResources(graph);
    for (const std::string& name : names) {
        const std::string resource = bufferResourceName(name);
        const ResourceName parts = ResourceName::split(resource);
        const bool known = parts.field == "*"
                               ? graph.findPass(parts.pass) != nullptr
                               : std::find(resources.begin(), resources.end(), resource) != resources.end();
        if (known) continue;
        std::vector<std::string> available;
        for (const std::string& written : resources) available.push_back(bufferNameOf(written, graph));
        std::string why;
        if (startsWith(name, kLinesPrefix) && findLineType(name.substr(kLinesPrefix.size())) != nullptr)
            why = " ('" + name.substr(kLinesPrefix.size()) + "' is not in the look's --lines)";
        throw UsageError("no buffer '" + name + "' in this look" + why + "; it has: " + joined(available));
    }
}

const PlannedResource* plannedResource(const Plan& plan, const std::string& name) {
    const auto found = std::find_if(plan.resources.begin(), plan.resources.end(),
                                    [&](const PlannedResource& entry) { return entry.name == name; });
    return found != plan.resources.end() ? &*found : nullptr;
}

/** The resources a name asked for stands for: the fields of a wildcard ("gbuffer.*", "lines.*") the plan computed,
 *  in the order their pass declares them, else the one resource. */
std::vector<std::string> resourcesAskedBy(const std::string& name, const PreparedStill& still) {
    const std::string resource = bufferResourceName(name);
    const ResourceName parts = ResourceName::split(resource);
    if (parts.field != "*") return {resource};
    std::vector<std::string> fields;
    for (const std::string& written : writtenResources(still.graph)) {
        const PlannedResource* planned = plannedResource(still.plan, written);
        if (startsWith(written, parts.pass + ".") && planned != nullptr && planned->requested)
            fields.push_back(written);
    }
    return fields;
}

/** The warnings a still's log holds ("inkgraph: warning: " lines: StillRenderer::load()). */
std::vector<std::string> warningsIn(const std::string& log) {
    const std::string marker = "inkgraph: warning: ";
    std::vector<std::string> warnings;
    std::istringstream lines(log);
    for (std::string line; std::getline(lines, line);)
        if (startsWith(line, marker)) warnings.push_back(line.substr(marker.size()));
    return warnings;
}

/** The camera the flags ask for (cameraRequestOf() of the command line, app/Render.h). */
CameraRequest cameraRequestOf(const RenderOptions& options) {
    CameraRequest request;
    request.eye = options.eye;
    request.orbit = options.orbit;
    request.target = options.target;
    request.frameNodes = options.frameNodes;
    request.up = options.up;
    request.fovYDegrees = options.fovYDegrees;
    request.ignoreFileCamera = options.autoCamera;
    if (options.clipRange) {
        request.zNear = options.clipRange->x;
        request.zFar = options.clipRange->y;
    }
    request.width = options.width;
    request.height = options.height;
    return request;
}

/** The renderer whose StillRenderer holds the process's GL context, or null (Renderer's comment says why one). */
std::atomic<const void*> gContextHolder{nullptr};

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

struct Still::Impl {
    struct Buffer {
        std::string name;     ///< as first asked for
        std::string resource; ///< the graph's name
        Image image;
    };
    Image picture;
    std::vector<Buffer> buffers;
    std::vector<RunInput> inputs; ///< the files the render read: write() never replaces one
    std::vector<std::string> warnings;
    double milliseconds = 0.0;
};

struct Renderer::Impl {
    std::string eglPlatform;
    /** Held by pointer so that a child forked after the context was made can leave it alone: freeing it would call
     *  into a driver whose threads exist only in the parent. */
    std::unique_ptr<StillRenderer> renderer = std::make_unique<StillRenderer>();
    std::mutex rendering; ///< one render at a time; any thread, since each render releases the context at its end

    explicit Impl(std::string platform) : eglPlatform(std::move(platform)) {}
    ~Impl() {
        if (HeadlessContext* context = renderer->context()) {
            if (context->owningProcess() != int(getpid())) {
                (void)renderer.release(); // a forked child: its copy of the parent's driver state is never touched
            } else {
                try {
                    context->makeCurrent(); // the GL objects are freed on this thread, maybe not the renderer's last
                } catch (const HeadlessContextError&) {
                    // The context is current on a thread that is still rendering: nothing safe to do but leak it.
                    (void)renderer.release();
                }
            }
        }
        const void* self = this;
        gContextHolder.compare_exchange_strong(self, nullptr);
    }
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    /** Takes the process's GL context for this renderer and makes it current on this thread; UsageError while another
     *  renderer holds it, or when the context was made in the process this one was forked from. */
    void holdContext() {
        const void* holder = nullptr;
        if (!gContextHolder.compare_exchange_strong(holder, this) && holder != this)
            throw UsageError("another Renderer of this process holds the GL context (EGL shares one display per "
                             "process); render with that one, or destroy it first");
        refuseForkedContext();
        if (HeadlessContext* context = renderer->context()) context->makeCurrent();
    }

    /** UsageError when the context was made in the process this one was forked from. */
    void refuseForkedContext() const {
        if (const HeadlessContext* context = renderer->context(); context && context->owningProcess() != int(getpid()))
            throw UsageError("this Renderer's GL context was made in process " +
                             std::to_string(context->owningProcess()) +
                             ", which forked this one; make renderers after the fork (Python: multiprocessing's "
                             "'spawn' or 'forkserver'), or close them before it");
    }

    /** Leaves the calling thread without the context at the end of a render, so the next may run on any thread. */
    void releaseContext() {
        if (HeadlessContext* context = renderer->context(); context && context->owningProcess() == int(getpid()))
            context->releaseThread();
    }

    /** The command line's options for this still: the look's flags, the frame's camera flags and size, checked
     *  together as the command line checks them. */
    RenderOptions optionsOf(const Scene& scene, const Look& look, const Frame& frame) const {
        const SourcedArguments camera{frame.camera, {}};
        try {
            refuseOtherFlags(camera, FlagOwner::Camera);
            // Alone first: a flag at the end without its value would otherwise take the "--size" appended below.
            parseRenderFlags(frame.camera, {}, FlagChecks::Values);
        } catch (const UsageError& error) {
            throw UsageError(std::string("Frame::camera: ") + error.what());
        }
        const std::string size = std::to_string(frame.width) + "x" + std::to_string(frame.height);
        try {
            parseRenderFlags({"--size", size});
        } catch (const UsageError& error) {
            throw UsageError(std::string("Frame::width and height: ") + error.what());
        }
        std::vector<std::string> arguments = look.arguments();
        arguments.insert(arguments.end(), frame.camera.begin(), frame.camera.end());
        arguments.insert(arguments.end(), {"--size", size, "--egl-platform", eglPlatform});
        RenderOptions options = parseRenderFlags(arguments);
        const SceneOptions& sceneOptions = scene.impl().options;
        options.modelPath = scene.path();
        options.modelPaths = {scene.path()};
        options.animation = sceneOptions.animation;
        options.animationTime = sceneOptions.time;
        if (sceneOptions.memoryLimitBytes != 0) options.memoryLimitBytes = sceneOptions.memoryLimitBytes;
        return options;
    }

    std::shared_ptr<Still::Impl> render(const Scene& scene, const Look& look, const Frame& frame,
                                        const std::vector<std::string>& buffers) {
        const std::lock_guard<std::mutex> oneAtATime(rendering);
        // Declared first, so it runs last: after the still's GL objects have gone back to the pool on this thread.
        struct ReleaseAtEnd {
            Impl& impl;
            ~ReleaseAtEnd() { impl.releaseContext(); }
        } releaseAtEnd{*this};
        const auto start = std::chrono::steady_clock::now();
        refuseForkedContext();
        RenderOptions options = optionsOf(scene, look, frame);
        for (const std::string& name : buffers) {
            const std::string resource = bufferResourceName(name);
            if (std::find(options.extraOutputs.begin(), options.extraOutputs.end(), resource) ==
                options.extraOutputs.end())
                options.extraOutputs.push_back(resource);
        }
        StillRequest request;
        request.modelPath = options.modelPath;
        request.look = options.look;
        request.camera = cameraRequestOf(options);
        request.extraOutputs = options.extraOutputs;
        request.memoryLimitBytes = options.memoryLimitBytes ? *options.memoryLimitBytes : defaultMemoryLimit();
        request.memoryLimitGiven = options.memoryLimitBytes.has_value();
        if (options.eglPlatform == "device") request.eglPlatform = EglPlatform::Device;
        if (options.eglPlatform == "surfaceless") request.eglPlatform = EglPlatform::Surfaceless;
        request.loadedScene = scene.impl().scene;
        request.timePasses = false; // no per-pass timings to report: passes may overlap

        std::ostringstream log;
        const StillLog stillLog{log, false, true};
        const std::unique_ptr<PreparedStill> still = renderer->load(std::move(request), stillLog);
        try {
            renderer->plan(*still, stillLog);
        } catch (const UsageError&) {
            refuseUnknownBuffers(still->graph, buffers);
            throw;
        }
        budgetStill(*still);
        holdContext();
        StillResult result = renderer->execute(*still, stillLog);

        auto made = std::make_shared<Still::Impl>();
        ResourceStore& store = result.store();
        // The picture as -o writes it; the buffers as --dump does (colour with straight alpha).
        made->picture = imageOf(store.image(still->graph.finalResource));
        for (const std::string& name : buffers) {
            for (const std::string& resource : resourcesAskedBy(name, *still)) {
                const auto same = [&](const Still::Impl::Buffer& kept) { return kept.resource == resource; };
                if (std::any_of(made->buffers.begin(), made->buffers.end(), same)) continue;
                const PlannedResource* planned = plannedResource(still->plan, resource);
                const bool colour = planned != nullptr && planned->presentation.appearance == Appearance::Color;
                const cv::Mat& image = store.image(resource);
                const std::string shownName = bufferResourceName(name) == resource ? name : resource;
                made->buffers.push_back({shownName, resource, imageOf(colour ? straightAlphaOf(image) : image)});
            }
        }
        // Absolute, as the render saw them: the still may be written after the working folder changed.
        made->inputs = {{options.modelPath, "the model itself"}};
        if (!options.look.shadeMapPath.empty())
            made->inputs.push_back({options.look.shadeMapPath, "the --shademap itself"});
        if (!options.stylePath.empty()) made->inputs.push_back({options.stylePath, "the --style file"});
        for (RunInput& input : inputsFoundByLoading(options.modelPath, still->scene()))
            made->inputs.push_back(std::move(input));
        for (RunInput& input : made->inputs) input.path = resolvedPath(input.path).string();
        made->warnings = warningsIn(log.str());
        made->milliseconds = millisecondsSince(start);
        return made;
    }
};

std::string bufferResourceName(const std::string& name) {
    if (name == "picture") return StillGraph{}.finalResource;
    if (startsWith(name, kLinesPrefix)) return std::string(kStrokesPass) + "." + name.substr(kLinesPrefix.size());
    for (const GBufferPass::Field& field : GBufferPass::fields())
        if (name == field.name) return std::string(kGBufferPass) + "." + name;
    return name;
}

const Image& Still::picture() const { return mImpl->picture; }

const Image& Still::buffer(const std::string& name) const {
    for (const Impl::Buffer& kept : mImpl->buffers)
        if (kept.name == name) return kept.image;
    const std::string resource = bufferResourceName(name);
    for (const Impl::Buffer& kept : mImpl->buffers)
        if (kept.resource == resource) return kept.image;
    throw Error(Error::Kind::Usage, "Still::buffer(): no buffer '" + name + "' in this still (it has: " +
                                        (mImpl->buffers.empty() ? std::string("none") : joined(bufferNames())) +
                                        "; ask for buffers in Renderer::render())");
}

std::vector<std::string> Still::bufferNames() const {
    std::vector<std::string> names;
    for (const Impl::Buffer& kept : mImpl->buffers) names.push_back(kept.name);
    return names;
}

void Still::write(const std::string& path) const {
    translated("Still::write()", [&] {
        refuseInputAsOutput(path, "'" + path + "'", mImpl->inputs);
        writeImage(path, matOf(mImpl->picture));
    });
}

std::vector<std::string> Still::warnings() const { return mImpl->warnings; }

double Still::milliseconds() const { return mImpl->milliseconds; }

Renderer::Renderer(const std::string& eglPlatform) {
    translated("Renderer()", [&] {
        parseRenderFlags({"--egl-platform", eglPlatform});
        mImpl = std::make_unique<Impl>(eglPlatform);
    });
}

Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

Still Renderer::render(const Scene& scene, const Look& look, const Frame& frame,
                       const std::vector<std::string>& buffers) {
    return translated("Renderer::render()", [&] {
        if (!mImpl) throw UsageError("a Renderer moved from");
        return Still(mImpl->render(scene, look, frame, buffers));
    });
}

std::string Renderer::glDescription() const {
    const HeadlessContext* context = mImpl ? mImpl->renderer->context() : nullptr;
    return context != nullptr ? context->describe() : "";
}

} // namespace inkgraph::api
