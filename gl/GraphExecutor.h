#pragma once
/** @file Runs a compiled Plan: hands each pass its resources, times it, and frees what nothing reads any more.
 *  A resource lives on the GPU (a GlTexture), on the CPU (a cv::Mat, row 0 at the top), or both; it is moved
 *  across only when a pass or the caller asks for the other side, through gl/Readback. */

#include "gl/GlObjects.h"
#include "gl/Readback.h"
#include "gl/TexturePool.h"
#include "graph/Executor.h"
#include "graph/Plan.h"

#include <opencv2/core.hpp>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <typeindex>
#include <typeinfo>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {

/** The resources of one run, by full name. */
class ResourceStore {
public:
    explicit ResourceStore(TexturePool& pool) : mPool(pool) {}
    ~ResourceStore() { clear(); }
    ResourceStore(const ResourceStore&) = delete;
    ResourceStore& operator=(const ResourceStore&) = delete;

    /** A GPU target for a pass to render into (multisampled with `samples` above 1); the CPU copy, if any, is
     *  discarded. */
    GlTexture& writeTexture(const std::string& name, Format format, int width, int height, int samples = 1);
    /** A CPU image for a pass to fill; the GPU copy, if any, is discarded. */
    cv::Mat& writeImage(const std::string& name, Format format, int width, int height);
    /** The GPU side, uploading the CPU image on first use. */
    const GlTexture& texture(const std::string& name);
    /** The CPU side (row 0 = top), reading the texture back on first use (only its readRegion() when one is set);
     *  an object's picture (setPicture()). */
    const cv::Mat& image(const std::string& name);
    /** Reads only `region` of `name`'s texture back (readTexture()'s region; until the texture is written again):
     *  its writer drew nothing outside it that anyone reads. A later image() leaves the other pixels unspecified. */
    void setReadRegion(const std::string& name, PixelRect region);

    /** A typed CPU object (ResourceKind::Object) for a pass to fill, value-initialised; replaces what was there. */
    template <class T>
    T& writeObject(const std::string& name) {
        Entry& target = mEntries[name];
        if (target.texture) mPool.release(std::move(*target.texture));
        target = Entry{};
        auto object = std::make_shared<T>();
        T& value = *object;
        target.object = std::move(object);
        target.objectType = typeid(T);
        return value;
    }
    /** The object `name` holds. Throws std::logic_error when it holds another type or a texture. */
    template <class T>
    const T& object(const std::string& name) {
        Entry& source = entry(name);
        if (!source.object || source.objectType != typeid(T)) throw wrongObject(name, typeid(T));
        return *static_cast<const T*>(source.object.get());
    }
    /** An object's picture for --dump and the contact sheet (ObjectDesc::hasPicture), row 0 at the top. */
    void setPicture(const std::string& name, Format format, cv::Mat picture);
    bool holdsObject(const std::string& name) const {
        auto found = mEntries.find(name);
        return found != mEntries.end() && found->second.object != nullptr;
    }

    bool contains(const std::string& name) const { return mEntries.count(name) != 0; }
    /** Whether `name` has a GPU side (a texture) now. */
    bool holdsTexture(const std::string& name) const {
        auto found = mEntries.find(name);
        return found != mEntries.end() && found->second.texture.has_value();
    }
    /** Begins reading `name`'s texture back without waiting (PendingReadback), for a later image() to finish; nothing
     *  when it has a CPU image already, is being read, or is multisampled. */
    void beginReadback(const std::string& name);
    /** Keeps only the CPU side of `name`, reading the texture back first if it has no CPU image yet, and hands the
     *  texture back to the pool: what remains is plain memory any thread may read. */
    void moveToHost(const std::string& name);
    std::vector<std::string> names() const;
    void release(const std::string& name);
    void clear();

private:
    struct Entry {
        Format format = Format::RGBA8;
        int width = 0;
        int height = 0;
        int samples = 1;
        std::optional<GlTexture> texture;
        cv::Mat image;                             ///< a texture's CPU side, or an object's picture
        std::unique_ptr<PendingReadback> readback; ///< the texture on its way to `image` (beginReadback())
        std::optional<PixelRect> readRegion;       ///< what image() reads back (setReadRegion()), else all of it
        std::shared_ptr<void> object;              ///< kind Object: the value, of objectType
        std::type_index objectType = typeid(void);
    };
    Entry& entry(const std::string& name);
    std::logic_error wrongObject(const std::string& name, const std::type_info& wanted) const;

    TexturePool& mPool;
    std::map<std::string, Entry> mEntries;
};

/** What a GL or CPU pass (GlPass) sees while it prepares and executes. Reads and writes are checked against the
 *  plan. */
class GlPassContext {
public:
    /** `everyResourceKept`: ExecuteOptions::keepAllResources (every buffer may be handed out whole: --dump). */
    GlPassContext(ResourceStore& store, const PlannedPass& planned, const Plan& plan, int frameWidth, int frameHeight,
                  bool everyResourceKept = false);

    /** True when this pass's field (e.g. "normal") is consumed or requested in the plan. */
    bool isLive(std::string_view field) const;
    /** Whether anything reads the pixels of this pass's live field that the pass does not cover
     *  (PlannedResource::backgroundRead), or the run keeps every buffer to hand out: when not, the pass need not
     *  clear them. */
    bool backgroundIsRead(std::string_view field) const {
        return mEveryResourceKept || liveOutput(field).backgroundRead;
    }
    /** True when the plan has this pass read `resource` (full name): what its declare() chose with compile data. */
    bool reads(std::string_view resource) const;
    /** The frame size (the output image's size). A field with a scale is larger: see widthOf(). */
    int width() const { return mFrameWidth; }
    int height() const { return mFrameHeight; }

    /** Size of one of this pass's live fields (frame size x its scale / its divisor: scaledSide()). */
    int widthOf(std::string_view field) const;
    int heightOf(std::string_view field) const;
    /** The planned scale (TextureDesc::scale) of a declared read (full name, "gbuffer.depth") or of this pass's own
     *  live output (full name, "mesh-edges.crease"), so a reader need not be told how large its inputs are. Throws
     *  std::logic_error for any other resource. */
    int scaleOf(std::string_view resource) const;
    /** The planned divisor (TextureDesc::divisor) of the same resources as scaleOf(): a field sampled coarser than
     *  the frame. */
    int divisorOf(std::string_view resource) const;
    /** The planned sample count (TextureDesc::samples) of a declared read or of this pass's own live output, as
     *  scaleOf(): a reader of a multisampled texture reads it per sample. */
    int samplesOf(std::string_view resource) const;

    /** This pass's live output `field` as a GPU target (multisampled when its TextureDesc says so) or a CPU image.
     *  Throws if the field is not live, and outputImage() for a multisampled field (only GL draws samples). */
    GlTexture& outputTexture(std::string_view field);
    cv::Mat& outputImage(std::string_view field);
    /** Tells the executor that this pass's live texture `field` holds nothing outside `region` (GL window coordinates)
     *  that anyone reads, so a read-back copies the region alone. Only for a field whose background is not read
     *  (backgroundIsRead() false); throws std::logic_error otherwise. */
    void limitReadback(std::string_view field, PixelRect region);
    /** A declared input by full name. Throws on a read the pass did not declare. */
    const GlTexture& inputTexture(std::string_view resource);
    const cv::Mat& inputImage(std::string_view resource);

    /** This pass's live object output `field` (ObjectDesc), value-initialised for the pass to fill. An object may be
     *  written in prepare(): later passes may then read it in theirs (the scene's imports, passes/SceneImportPass.h).
     *  Throws std::logic_error when the field is not live or not an object. */
    template <class T>
    T& outputObject(std::string_view field) {
        return mStore.writeObject<T>(liveObjectOutput(field).name);
    }
    /** The picture of this pass's object output `field` (for --dump), at the object's scale. */
    void outputPicture(std::string_view field, cv::Mat picture);
    /** A declared object read by full name. Throws std::logic_error for an undeclared read, a texture, another type, or
     *  an object not written yet (in prepare(), only objects their writer wrote in its prepare() are there). */
    template <class T>
    const T& inputObject(std::string_view resource) {
        requireObjectRead(resource);
        return mStore.object<T>(std::string(resource));
    }

private:
    const PlannedResource& liveOutput(std::string_view field) const;
    const PlannedResource& liveObjectOutput(std::string_view field) const;
    /** The planned resource `resource` when the pass reads it or writes it live; throws naming `function` otherwise. */
    const PlannedResource& readOrLiveWrite(std::string_view resource, const char* function) const;
    void requireDeclaredRead(std::string_view resource) const;
    void requireObjectRead(std::string_view resource) const;

    ResourceStore& mStore;
    const PlannedPass& mPlanned;
    const Plan& mPlan;
    int mFrameWidth;
    int mFrameHeight;
    bool mEveryResourceKept;
};

struct ExecuteOptions {
    int frameWidth = 1024;
    int frameHeight = 1024;
    /** Begin reading back each texture a host pass reads as soon as the pass writing it has run (PendingReadback),
     *  instead of when the host pass asks for it. */
    bool readBackEarly = false;
    /** Keep every computed resource to the end (for --dump). Never changes which passes run. */
    bool keepAllResources = false;
    /** glFinish() at the end of each pass, so its milliseconds are its own work (--stats, --dump's manifest, the
     *  benchmarks). Off, a pass's timing counts only what it submitted, and the driver may still be drawing it while
     *  the next pass submits (llvmpipe rasterises on its own threads): a still without stats ends sooner. */
    bool waitForEachPass = true;
    /** Derives one scene import (PassBuilder::import()) before any pass prepares; not set: the passes' data is
     *  derived on demand (passes/GpuScene.h). */
    std::function<void(const std::string& name)> importData;
};

class GlPass;

/** The GL backend of graph/Executor's loop: a GlPassContext per pass over one ResourceStore, glFinish() inside each
 *  pass's time (ExecuteOptions::waitForEachPass), GL state reset and glGetError() after each execute. */
class GraphExecutor {
public:
    explicit GraphExecutor(TexturePool& pool) : mStore(pool) {}

    /** Executes `plan` with the given pass objects (looked up by name; graph/Executor.h has the loop). Throws naming
     *  the pass when a pass fails, leaves a live output unwritten, or raises a GL error; ShaderSourceError,
     *  GlOutOfMemoryError and OutOfMemoryError keep their types. */
    std::vector<PassTiming> run(const Plan& plan, const std::vector<GlPass*>& passes, const ExecuteOptions& options);
    /** run() in two halves. The first, on the thread that holds the context: the imports, every prepare, the passes
     *  before the plan's host tail (Plan::hostTailStart()), and then every texture a tail pass reads moved to the CPU
     *  (ResourceStore::moveToHost()), so the tail touches no GL object. `plan`, `passes` and `options` must outlive
     *  runHostTail(). */
    void runUntilHostTail(const Plan& plan, const std::vector<GlPass*>& passes, const ExecuteOptions& options);
    /** The second half: executes the host tail on the calling thread, which need not hold the context (nothing else
     *  may use this executor meanwhile), and returns every pass's timing. Throws as run() does. */
    std::vector<PassTiming> runHostTail();

    /** Resources kept after run(): the requested ones, or every computed one with keepAllResources. */
    ResourceStore& store() { return mStore; }
    /** What the last run() spent deriving the plan's imports (ExecuteOptions::importData), by name. */
    const std::vector<std::pair<std::string, double>>& importMilliseconds() const { return mImportMilliseconds; }

private:
    /** The half-done run between runUntilHostTail() and runHostTail(). */
    struct TailRun {
        const Plan* plan = nullptr;
        std::vector<GlPass*> passes;
        ExecuteOptions options;
        std::optional<PlanRun> run;
    };

    ResourceStore mStore;
    std::vector<std::pair<std::string, double>> mImportMilliseconds;
    std::unique_ptr<TailRun> mTail;
};

} // namespace inkgraph
