#include "api/Frame.h"
#include "api/Internal.h"
#include "graph/Milliseconds.h"

#include "render/BackgroundThreads.h"
#include "render/ImageFiles.h"
#include "render/InputFiles.h"
#include "render/MemoryBudget.h"
#include "render/StillRenderer.h"
#include "passes/StillGraph.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/lines/LineTypes.h"
#include "postfx/Composite.h"
#include "scene/MessageText.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <optional>
#include <mutex>
#include <sstream>

#include <unistd.h>

namespace inkgraph::api {
inline namespace INKGRAPH_ABI_NAMESPACE {
namespace {

const std::string kLinesPrefix = "lines.";

bool startsWith(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

/** The graph resource a buffer name stands for: "normal" -> "gbuffer.normal", "lines.contour" -> the strokes' layer
 *  "strokes.contour", "picture" -> "composite.final"; a graph resource's own name as it is. */
std::string bufferResourceName(const std::string& name) {
    if (name == "picture") return StillGraph{}.finalResource;
    if (startsWith(name, kLinesPrefix)) return std::string(kStrokesPass) + "." + name.substr(kLinesPrefix.size());
    for (const GBufferPass::Field& field : GBufferPass::fields())
        if (name == field.name) return std::string(kGBufferPass) + "." + name;
    return name;
}

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

/** Throws UsageError for the first of `names` the graph does not write, naming the buffers `look` has
 *  (bufferNames()); returns when every name is one (the failure was another). */
void refuseUnknownBuffers(const StillGraph& graph, const std::vector<std::string>& names, const Look& look) {
    const std::vector<std::string> resources = writtenResources(graph);
    for (const std::string& name : names) {
        const std::string resource = bufferResourceName(name);
        const ResourceName parts = ResourceName::split(resource);
        const bool known = parts.field == "*"
                               ? graph.findPass(parts.pass) != nullptr
                               : std::find(resources.begin(), resources.end(), resource) != resources.end();
        if (known) continue;
        // The public names: the graph registers every line type's passes (the plan culls those not drawn), whose
        // own names listed ran to 2 KB of buffers this look never makes.
        const std::vector<std::string> available = bufferNames(look);
        std::string why;
        if (startsWith(name, kLinesPrefix) && findLineType(name.substr(kLinesPrefix.size())) != nullptr)
            why = " ('" + name.substr(kLinesPrefix.size()) + "' is not in the look's --lines)";
        throw UsageError("no buffer '" + name + "' in this look" + why + "; it has: " + joined(available) +
                         ", and the images the graph computes for it, by the names `inkgraph render --print-plan` "
                         "shows");
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

template <int Columns, int Rows>
std::array<std::array<double, Columns>, Rows> rowsOf(const glm::mat<Columns, Rows, double>& matrix) {
    std::array<std::array<double, Columns>, Rows> rows{};
    for (int row = 0; row < Rows; ++row)
        for (int column = 0; column < Columns; ++column) rows[row][column] = matrix[column][row]; // glm: [column][row]
    return rows;
}

/** The name in render()'s buffers that asks for Still::strokes(). */
constexpr const char* kStrokesName = "strokes";

std::vector<StillStroke> stillStrokesOf(const std::vector<StrokeRecord>& records) {
    std::vector<StillStroke> strokes;
    strokes.reserve(records.size());
    for (const StrokeRecord& record : records) {
        StillStroke stroke{record.type, record.visible, record.closed, {}};
        stroke.points.reserve(record.points.size());
        for (const StrokePointRecord& point : record.points) {
            StillStrokePoint out{point.x, point.y, std::nullopt, point.mesh, point.triangle};
            if (point.world) out.world = vec3Of(*point.world);
            stroke.points.push_back(out);
        }
        strokes.push_back(std::move(stroke));
    }
    return strokes;
}

/** The camera a still was drawn with, in world coordinates (Camera keeps the scene's local frame). */
StillCamera stillCameraOf(const Camera& camera) {
    StillCamera still;
    still.view = rowsOf(camera.worldViewMatrix());
    still.projection = rowsOf(camera.projectionMatrix());
    still.intrinsics = rowsOf(camera.openCvIntrinsics());
    still.extrinsics = rowsOf(camera.openCvExtrinsics());
    still.eye = vec3Of(camera.worldEye());
    still.target = vec3Of(camera.worldTarget());
    still.up = vec3Of(camera.up);
    still.fovY = camera.fovYDegrees;
    still.near = camera.zNear;
    still.far = camera.zFar;
    still.clipGiven = camera.clipSource == "flags";
    still.width = camera.width;
    still.height = camera.height;
    still.source = camera.source == "gltf"    ? CameraSource::File
                   : camera.source == "orbit" ? CameraSource::Orbit
                   : camera.source == "flags" ? CameraSource::Eye
                                              : CameraSource::Auto;
    return still;
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
    StillCamera camera;
    /** The meshes and objects of the scene it drew: the Scene's, or the frame's pose's where that loaded it again. */
    std::vector<SceneMesh> meshes;
    std::vector<SceneObject> objects;
    std::optional<std::vector<StillStroke>> strokes; ///< when asked for ("strokes")
    std::vector<Warning> warnings;
    double milliseconds = 0.0;
};

struct Renderer::Impl {
    EglPlatform eglPlatform;
    /** Held by pointer so that a child forked after the context was made can leave it alone: freeing it would call
     *  into a driver whose threads exist only in the parent. */
    std::unique_ptr<StillRenderer> renderer = std::make_unique<StillRenderer>();
    std::mutex rendering; ///< one render at a time; any thread, since each render releases the context at its end
    const int madeInProcess = int(getpid());

    explicit Impl(EglPlatform platform) : eglPlatform(platform) {}
    ~Impl() {
        if (HeadlessContext* context = renderer->context()) {
            if (context->owningProcess() != int(getpid())) {
                (void)renderer.release(); // a forked child: its copy of the parent's driver state is never touched
            } else {
                // The caller's own GL context, if any, current again once the renderer and its context are gone.
                const CallersEglState callersContext;
                try {
                    context->makeCurrent(); // the GL objects are freed on this thread, maybe not the renderer's last
                    renderer.reset();
                } catch (const HeadlessContextError&) {
                    // The context is current on a thread that is still rendering: nothing safe to do but leak it.
                    (void)renderer.release();
                }
            }
        }
    }
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    /** Makes this renderer's GL context current on this thread (each renderer has its own, so renderers on other
     *  threads render meanwhile); UsageError when the context was made in the process this one was forked from. */
    void holdContext() {
        refuseForkedContext();
        if (HeadlessContext* context = renderer->context()) context->makeCurrent();
    }

    /** UsageError when the context was made in the process this one was forked from; ContextRefusal when this
     *  renderer has none yet and this process was forked after another renderer started the driver (refused here,
     *  not by HeadlessContext(), so that the message starts with the function called, as the first refusal's does). */
    void refuseForkedContext() const {
        const HeadlessContext* context = renderer->context();
        if (context && context->owningProcess() != int(getpid()))
            throw UsageError("this Renderer's GL context was made in process " +
                             std::to_string(context->owningProcess()) +
                             ", which forked this one; make renderers after the fork (Python: multiprocessing's "
                             "'spawn' or 'forkserver'), or close them before it");
        const std::string refusal = context == nullptr ? forkedDriverRefusal() : std::string();
        if (!refusal.empty()) throw ContextRefusal(refusal);
    }

    /** Leaves the calling thread without the context at the end of a render, so the next may run on any thread. */
    void releaseContext() {
        if (HeadlessContext* context = renderer->context(); context && context->owningProcess() == int(getpid()))
            context->releaseThread();
    }

    /** The still's request: the look's flags and the frame's fields as the command line's options, checked together
     *  as the command line checks them, and the scene posed as the frame asks. */
    StillRequest requestOf(const Scene& scene, const Look& look, const Frame& frame,
                           const std::vector<std::string>& buffers, std::string& reloadedFor) const {
        const Look::Impl& lookImpl = LookAccess::impl(look);
        RenderOptions options = lookImpl.parsed;
        std::vector<std::string> given = lookImpl.givenFlags();
        applyFrame(frame, options, given);
        checkFlagRules(options, given);

        const Scene::Impl& sceneImpl = SceneAccess::impl(scene);
        StillRequest request;
        request.modelPath = sceneImpl.path.empty() ? "arrays" : sceneImpl.path;
        request.loadedScene = sceneImpl.scene;
        request.loadedSceneDerived = sceneImpl.derived;
        request.look = options.look;
        request.camera = cameraRequestOf(options);
        request.memoryLimitBytes =
            sceneImpl.options.memoryLimitBytes != 0 ? sceneImpl.options.memoryLimitBytes : defaultMemoryLimit();
        request.memoryLimitGiven = sceneImpl.options.memoryLimitBytes != 0;
        request.strict = sceneImpl.options.strict;
        request.weldTolerance = sceneImpl.scene->report.weldTolerance; // as loaded, for a load again (a new pose)
        request.eglPlatform = eglPlatform;
        request.timePasses = false; // no per-pass timings to report: passes may overlap
        for (const std::string& name : buffers) {
            const std::string resource = bufferResourceName(name);
            if (std::find(request.extraOutputs.begin(), request.extraOutputs.end(), resource) ==
                request.extraOutputs.end())
                request.extraOutputs.push_back(resource);
        }
        // The frame's time is the UV animation's clock (FrameParams::time); it poses the scene only with an animation.
        request.animationTime = frame.time.value_or(sceneImpl.options.time);
        const bool posed = !frame.animation.empty();
        // A time alone moves the scene's own animation to it, as it does with a face or pose given beside it.
        const bool retimed =
            !posed && !sceneImpl.options.animation.empty() && frame.time && *frame.time != sceneImpl.options.time;
        // Unset, the frame's time is the scene's, also beside an animation the frame names.
        const double frameTime = frame.time.value_or(sceneImpl.options.time);
        const bool animated =
            (posed && (frame.animation != sceneImpl.options.animation || frameTime != sceneImpl.options.time)) ||
            retimed;
        // Without an animation the scene's load poses nothing, so a time only clocks the UV animation.
        request.loadedWithoutAnimation = sceneImpl.options.animation.empty();
        request.timeSetting = "Frame::time";
        request.animationSetting = "SceneOptions::animation or Frame::animation";
        const bool reposed = !frame.pose.empty() && frame.pose != sceneImpl.options.pose;
        const bool refaced = !frame.expressions.empty() || frame.lookAt;
        if (animated || reposed || refaced) {
            if (sceneImpl.path.empty())
                throw UsageError(animated  ? "Frame::animation and time: a scene made from arrays has no animations"
                                 : reposed ? "Frame::pose: a scene made from arrays has no humanoid"
                                           : "Frame::expressions and lookAt: a scene made from arrays has no VRM face");
            // Another pose or face than the scene's: the file is loaded again, by the renderer's own load, with what
            // the frame gives and the scene's own options for the rest.
            std::vector<std::string> fields;
            if (animated)
                fields.push_back(retimed      ? "Frame::time"
                                 : frame.time ? "Frame::animation and time"
                                              : "Frame::animation");
            if (reposed) fields.push_back("Frame::pose");
            if (!frame.expressions.empty()) fields.push_back("Frame::expressions");
            if (frame.lookAt) fields.push_back("Frame::lookAt");
            reloadedFor = joined(fields);
            request.loadedScene.reset();
            request.loadedSceneDerived.reset();
            request.animation = posed ? options.animation : sceneImpl.options.animation;
            request.animationTime = frameTime;
            request.pose = reposed ? options.pose : sceneImpl.options.pose;
            applyFace(sceneImpl.options.expressions, sceneImpl.options.lookAt, "SceneOptions::", request.expressions,
                      request.lookAt);
            if (!options.expressions.empty()) request.expressions = options.expressions;
            if (options.lookAt) request.lookAt = options.lookAt;
        }
        return request;
    }

    std::shared_ptr<Still::Impl> render(const Scene& scene, const Look& look, const Frame& frame,
                                        const std::vector<std::string>& buffers, std::uint8_t* pictureOut,
                                        std::size_t pictureRowBytes) {
        // A child forked while another thread rendered has `rendering` locked by a thread it lacks: refused first.
        if (int(getpid()) != madeInProcess) refuseForkedContext();
        const std::lock_guard<std::mutex> oneAtATime(rendering);
        const ParallelWork rendersInParallel; // a fork() meanwhile leaves oneTBB's workers alone
        // The caller's own GL context, if any, current again once this render has let go of the renderer's.
        const CallersEglState callersContext;
        // Declared first, so it runs last: after the still's GL objects have gone back to the pool on this thread.
        struct ReleaseAtEnd {
            Impl& impl;
            ~ReleaseAtEnd() { impl.releaseContext(); }
        } releaseAtEnd{*this};
        const auto start = std::chrono::steady_clock::now();
        refuseForkedContext();
        if (pictureOut != nullptr && pictureRowBytes < std::size_t(std::max(frame.width, 0)) * 4)
            throw UsageError("the picture's rows are " + std::to_string(pictureRowBytes) + " bytes apart; " +
                             std::to_string(frame.width) + " RGBA8 pixels need " +
                             std::to_string(std::size_t(std::max(frame.width, 0)) * 4));
        // The last row's end must be an address: rows farther apart than memory wrapped the offsets around and the
        // copy wrote before the buffer.
        if (pictureOut != nullptr && frame.height > 1 &&
            double(pictureRowBytes) * double(frame.height - 1) + double(frame.width) * 4.0 > double(PTRDIFF_MAX))
            throw UsageError("the picture's rows are " + std::to_string(pictureRowBytes) +
                             " bytes apart: " + std::to_string(frame.height) + " of them reach beyond any memory");
        // "strokes" is no image: it asks for the strokes' 3-D points (Still::strokes()).
        std::vector<std::string> images;
        for (const std::string& name : buffers)
            if (name != kStrokesName) images.push_back(name);
        const bool strokes = images.size() != buffers.size();
        std::string reloadedFor; // the frame's fields that load the scene again, when they do
        StillRequest request = requestOf(scene, look, frame, images, reloadedFor);
        request.keepStrokePoints = strokes;
        const std::string modelPath = request.modelPath;

        std::ostringstream log; // the command line's lines; the library returns the warnings as records
        const StillLog stillLog{log, false, true};
        std::unique_ptr<PreparedStill> still;
        try {
            still = renderer->load(std::move(request), stillLog);
        } catch (const SceneError& error) {
            // The loader's refusal of what the frame asks (an expression or a pose of a model that is not a VRM, an
            // animation it lacks) is said in the caller's name and the frame's field's, not the loader's: the
            // caller called no loadScene().
            if (reloadedFor.empty()) throw;
            std::string message = error.what();
            const std::string loader = "loadScene(): ";
            if (message.rfind(loader, 0) == 0) message.erase(0, loader.size());
            throw InputRefusal(reloadedFor + ": " + message);
        }
        try {
            renderer->plan(*still, stillLog);
        } catch (const UsageError&) {
            // A buffer the look does not make is the likelier cause, named better than the plan's words; but a
            // refusal before the graph was built (the camera's up along the view) is the plan's to tell.
            if (!writtenResources(still->graph).empty()) refuseUnknownBuffers(still->graph, images, look);
            throw;
        }
        if (strokes && still->graph.strokes() == nullptr)
            throw UsageError("'strokes' needs a look that draws lines (Look::lines)");
        budgetStill(*still);
        holdContext();
        StillResult result;
        try {
            result = renderer->execute(*still, stillLog);
        } catch (...) {
            const std::unique_lock<std::mutex> driver = renderer->driverTurn(); // its GL objects go in a turn too
            still.reset();
            throw;
        }
        // The read-backs below, and the still's GL objects freed at the end, in a turn at a software driver
        // (StillRenderer::driverTurn()): llvmpipe is not safe with several renderers' contexts working at once.
        const std::unique_lock<std::mutex> driver = renderer->driverTurn();
        struct FreedInTurn {
            StillResult& result;
            std::unique_ptr<PreparedStill>& still;
            ~FreedInTurn() {
                result = StillResult();
                still.reset();
            }
        } freedInTurn{result, still};

        auto made = std::make_shared<Still::Impl>();
        ResourceStore& store = result.store();
        // The picture as -o writes it; the buffers as --dump does (colour with straight alpha). Each image shares the
        // store's pixels, which the store gives up when the result goes.
        const cv::Mat& picture = store.image(still->graph.finalResource);
        if (pictureOut != nullptr) {
            cv::Mat target(picture.rows, picture.cols, picture.type(), pictureOut, pictureRowBytes);
            picture.copyTo(target);
            made->picture = ImageAccess::view(picture.cols, picture.rows, picture.channels(), Image::Type::UInt8,
                                              pictureOut, pictureRowBytes, nullptr);
        } else {
            made->picture = imageOf(picture);
        }
        if (strokes) made->strokes = stillStrokesOf(still->graph.strokeRecords(store, still->camera, still->scene()));
        for (const std::string& name : images) {
            for (const std::string& resource : resourcesAskedBy(name, *still)) {
                const auto same = [&](const Still::Impl::Buffer& kept) { return kept.resource == resource; };
                if (std::any_of(made->buffers.begin(), made->buffers.end(), same)) continue;
                const PlannedResource* planned = plannedResource(still->plan, resource);
                const bool colour = planned != nullptr && planned->presentation.appearance == Appearance::Color;
                const cv::Mat& image = store.image(resource);
                const std::string shownName =
                    bufferResourceName(name) == resource ? name : bufferNameOf(resource, still->graph);
                made->buffers.push_back({shownName, resource, imageOf(colour ? straightAlphaOf(image) : image)});
            }
        }
        // Absolute, as the render saw them: the still may be written after the working folder changed.
        const Look::Impl& lookImpl = LookAccess::impl(look);
        if (!SceneAccess::impl(scene).path.empty()) made->inputs.push_back({modelPath, "the model itself"});
        if (!lookImpl.parsed.look.shadeMapPath.empty())
            made->inputs.push_back({lookImpl.parsed.look.shadeMapPath, "the look's shade map"});
        if (!lookImpl.parsed.stylePath.empty())
            made->inputs.push_back({lookImpl.parsed.stylePath, "the look's style file"});
        for (RunInput& input : inputsFoundByLoading(modelPath, still->scene()))
            made->inputs.push_back(std::move(input));
        for (RunInput& input : made->inputs) input.path = resolvedPath(input.path).string();
        made->camera = stillCameraOf(still->camera);
        made->meshes = meshesOf(still->scene());
        made->objects = objectsOf(still->scene());
        for (const inkgraph::Warning& warning : still->warnings)
            made->warnings.push_back({warning.code, warning.message, warning.file, warning.item});
        made->milliseconds = millisecondsSince(start);
        return made;
    }
};

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
        refuseInputAsOutput(path, detail::quotedFileName(path), mImpl->inputs);
        writeImage(path, matOf(mImpl->picture));
    });
}

const StillCamera& Still::camera() const { return mImpl->camera; }
const std::vector<SceneMesh>& Still::meshes() const { return mImpl->meshes; }
const std::vector<SceneObject>& Still::objects() const { return mImpl->objects; }

const std::vector<StillStroke>& Still::strokes() const {
    if (!mImpl->strokes)
        throw Error(Error::Kind::Usage, "Still::strokes(): no strokes in this still; ask for \"strokes\" in "
                                        "Renderer::render()");
    return *mImpl->strokes;
}

const std::vector<Warning>& Still::warnings() const { return mImpl->warnings; }

double Still::milliseconds() const { return mImpl->milliseconds; }

namespace {

/** The EGL platform a Renderer asks for; Error(Usage) for a value that names no Platform. */
EglPlatform eglPlatformOf(Renderer::Platform platform) {
    switch (platform) {
    case Renderer::Platform::Auto: return EglPlatform::Any;
    case Renderer::Platform::Device: return EglPlatform::Device;
    case Renderer::Platform::Surfaceless: return EglPlatform::Surfaceless;
    }
    throw Error(Error::Kind::Usage,
                "Renderer::Renderer(): no Platform has the value " + std::to_string(static_cast<int>(platform)));
}

} // namespace

Renderer::Renderer(Platform platform) : mImpl(std::make_unique<Impl>(eglPlatformOf(platform))) {
    // A render starts oneTBB's workers; a child forked after it must not inherit them (render/BackgroundThreads.h).
    stopParallelWorkersAtEachFork();
}

Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

Still Renderer::render(const Scene& scene, const Look& look, const Frame& frame,
                       const std::vector<std::string>& buffers) {
    return translated("Renderer::render()", [&] {
        if (!mImpl) throw UsageError("a Renderer moved from");
        return Still(mImpl->render(scene, look, frame, buffers, nullptr, 0));
    });
}

Still Renderer::renderInto(std::uint8_t* picture, std::size_t rowBytes, const Scene& scene, const Look& look,
                           const Frame& frame, const std::vector<std::string>& buffers) {
    return translated("Renderer::renderInto()", [&] {
        if (!mImpl) throw UsageError("a Renderer moved from");
        if (picture == nullptr) throw UsageError("no picture buffer (null)");
        return Still(mImpl->render(scene, look, frame, buffers, picture, rowBytes));
    });
}

std::vector<std::string> bufferNames(const Look& look) {
    std::vector<std::string> names;
    for (const GBufferPass::Field& field : GBufferPass::fields()) names.push_back(field.name);
    names.push_back("gbuffer.*");
    const std::vector<std::string>& lines = LookAccess::impl(look).parsed.look.lines;
    for (const std::string& type : lines) names.push_back(kLinesPrefix + type);
    // A look without lines has no line layer for "lines.*" to stand for (render() refused it).
    if (!lines.empty()) names.push_back("lines.*");
    names.push_back("picture");
    return names;
}

std::string Renderer::glDescription() const {
    const HeadlessContext* context = mImpl ? mImpl->renderer->context() : nullptr;
    return context != nullptr ? context->describe() : "";
}

} // namespace INKGRAPH_ABI_NAMESPACE
} // namespace inkgraph::api
