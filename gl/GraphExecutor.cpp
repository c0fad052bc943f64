#include "gl/GraphExecutor.h"

#include "gl/GlPass.h"
#include "gl/Readback.h"
#include "gl/ShaderLibrary.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>

namespace inkgraph {
namespace {

/** Back to GL's defaults for what passes touch (but reversed-Z depth: GlObjects.h), so no pass depends on what the one
 *  before it left bound. */
void resetPassState() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    glBindVertexArray(0);
    glDisable(GL_DEPTH_TEST);
    useReversedDepthClipControl();
    glDepthFunc(kDepthNearer);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glLineWidth(1.0f);
    for (GLuint unit = 0; unit < 8; ++unit) {
        glBindTextureUnit(unit, 0);
        glBindSampler(unit, 0); // the materials' samplers (passes/material): a later texture() takes its own state
    }
}

} // namespace

// --- ResourceStore -------------------------------------------------------------------------------------------

ResourceStore::Entry& ResourceStore::entry(const std::string& name) {
    auto found = mEntries.find(name);
    if (found == mEntries.end())
        throw std::out_of_range("ResourceStore: no resource '" + name + "' was computed in this run");
    return found->second;
}

GlTexture& ResourceStore::writeTexture(const std::string& name, Format format, int width, int height, int samples) {
    Entry& target = mEntries[name];
    target.image.release();
    target.readback.reset();
    target.readRegion.reset();
    if (!target.texture || target.format != format || target.width != width || target.height != height ||
        target.samples != samples) {
        if (target.texture) mPool.release(std::move(*target.texture));
        target.texture.emplace(mPool.acquire(format, width, height, name, samples));
    }
    target.format = format;
    target.width = width;
    target.height = height;
    target.samples = samples;
    return *target.texture;
}

cv::Mat& ResourceStore::writeImage(const std::string& name, Format format, int width, int height) {
    Entry& target = mEntries[name];
    target.readback.reset();
    if (target.texture) {
        mPool.release(std::move(*target.texture));
        target.texture.reset();
    }
    target.format = format;
    target.width = width;
    target.height = height;
    target.samples = 1;
    target.image = cv::Mat::zeros(height, width, cvTypeOf(format));
    return target.image;
}

const GlTexture& ResourceStore::texture(const std::string& name) {
    Entry& source = entry(name);
    if (!source.texture) {
        source.texture.emplace(mPool.acquire(source.format, source.width, source.height, name));
        uploadImage(*source.texture, source.image);
    }
    return *source.texture;
}

const cv::Mat& ResourceStore::image(const std::string& name) {
    Entry& source = entry(name);
    if (source.object) {
        if (source.image.empty())
            throw std::logic_error("ResourceStore::image(): '" + name + "' is an object without a picture");
        return source.image;
    }
    if (source.image.empty() && source.readback) {
        source.image = source.readback->finish();
        mPool.releaseReadbackBuffer(source.readback->takeBuffer());
    } else if (source.image.empty()) {
        source.image = readTexture(*source.texture, ReadbackFlip::Fastest, source.readRegion);
    }
    source.readback.reset();
    return source.image;
}

void ResourceStore::setReadRegion(const std::string& name, PixelRect region) {
    Entry& target = entry(name);
    if (!target.texture)
        throw std::logic_error("ResourceStore::setReadRegion(): '" + name + "' has no texture to read back");
    target.readRegion = region;
}

void ResourceStore::beginReadback(const std::string& name) {
    Entry& source = entry(name);
    if (!source.texture || !source.image.empty() || source.readback || source.texture->samples() > 1) return;
    // One glGetTextureImage takes a 32-bit byte count: larger images (half floats read as floats) are read in bands
    // when asked for, as readTexture() does.
    const std::size_t bytes = readbackBytesOf(*source.texture);
    if (bytes > std::size_t(std::numeric_limits<GLsizei>::max())) return;
    // Only the region a pass limited it to (GlPassContext::limitReadback(), set while the pass ran), into a pooled
    // buffer of the whole texture's size, so the next still of this size reuses it.
    source.readback =
        std::make_unique<PendingReadback>(*source.texture, mPool.acquireReadbackBuffer(bytes), source.readRegion);
}

void ResourceStore::moveToHost(const std::string& name) {
    Entry& source = entry(name);
    if (!source.texture) return;
    image(name);
    mPool.release(std::move(*source.texture));
    source.texture.reset();
}

void ResourceStore::setPicture(const std::string& name, Format format, cv::Mat picture) {
    Entry& target = entry(name);
    if (!target.object) throw std::logic_error("ResourceStore::setPicture(): '" + name + "' is not an object");
    target.format = format;
    target.width = picture.cols;
    target.height = picture.rows;
    target.image = std::move(picture);
}

std::logic_error ResourceStore::wrongObject(const std::string& name, const std::type_info& wanted) const {
    const Entry& source = mEntries.at(name);
    return std::logic_error("ResourceStore::object(): '" + name + "' holds " +
                            (source.object ? std::string("an object of another type (") + source.objectType.name() + ")"
                                           : std::string("a texture")) +
                            ", not " + wanted.name());
}

std::vector<std::string> ResourceStore::names() const {
    std::vector<std::string> result;
    for (const auto& [name, unused] : mEntries) result.push_back(name);
    return result;
}

void ResourceStore::release(const std::string& name) {
    auto found = mEntries.find(name);
    if (found == mEntries.end()) return;
    if (found->second.texture) mPool.release(std::move(*found->second.texture));
    mEntries.erase(found);
}

void ResourceStore::clear() {
    while (!mEntries.empty()) release(mEntries.begin()->first);
}

// --- GlPassContext -------------------------------------------------------------------------------------------

GlPassContext::GlPassContext(ResourceStore& store, const PlannedPass& planned, const Plan& plan, int frameWidth,
                             int frameHeight, bool everyResourceKept)
    : mStore(store), mPlanned(planned), mPlan(plan), mFrameWidth(frameWidth), mFrameHeight(frameHeight),
      mEveryResourceKept(everyResourceKept) {}

bool GlPassContext::isLive(std::string_view field) const {
    const std::string resource = mPlanned.name + "." + std::string(field);
    return std::find(mPlanned.liveWrites.begin(), mPlanned.liveWrites.end(), resource) != mPlanned.liveWrites.end();
}

bool GlPassContext::reads(std::string_view resource) const {
    return std::find(mPlanned.reads.begin(), mPlanned.reads.end(), resource) != mPlanned.reads.end();
}

const PlannedResource& GlPassContext::liveOutput(std::string_view field) const {
    const std::string resource = mPlanned.name + "." + std::string(field);
    const PlannedResource* planned = isLive(field) ? mPlan.findResource(resource) : nullptr;
    if (planned == nullptr)
        throw std::logic_error("GlPassContext::output(): pass '" + mPlanned.name + "' writes '" + resource +
                               "', which is not live in this plan (check isLive() first)");
    return *planned;
}

const PlannedResource& GlPassContext::liveObjectOutput(std::string_view field) const {
    const PlannedResource& planned = liveOutput(field);
    if (planned.kind != ResourceKind::Object)
        throw std::logic_error("GlPassContext::outputObject(): '" + planned.name + "' is a texture");
    return planned;
}

void GlPassContext::outputPicture(std::string_view field, cv::Mat picture) {
    const PlannedResource& planned = liveObjectOutput(field);
    if (!planned.object.hasPicture)
        throw std::logic_error("GlPassContext::outputPicture(): '" + planned.name + "' declares no picture");
    if (picture.type() != cvTypeOf(planned.object.pictureFormat) ||
        picture.size() != cv::Size(scaledSide(mFrameWidth, planned.object.scale, planned.object.divisor),
                                   scaledSide(mFrameHeight, planned.object.scale, planned.object.divisor)))
        throw std::logic_error("GlPassContext::outputPicture(): '" + planned.name +
                               "' picture is not of its declared format and size");
    mStore.setPicture(planned.name, planned.object.pictureFormat, std::move(picture));
}

void GlPassContext::requireObjectRead(std::string_view resource) const {
    requireDeclaredRead(resource);
    const std::string name(resource);
    if (!mPlan.isObject(name))
        throw std::logic_error("GlPassContext::inputObject(): pass '" + mPlanned.name + "' reads '" + name +
                               "', which is not an object");
    if (!mStore.holdsObject(name))
        throw std::logic_error("GlPassContext::inputObject(): pass '" + mPlanned.name + "' reads '" + name +
                               "' before its writer wrote it");
}

int GlPassContext::widthOf(std::string_view field) const {
    const TextureDesc& desc = liveOutput(field).desc;
    return scaledSide(mFrameWidth, desc.scale, desc.divisor);
}
int GlPassContext::heightOf(std::string_view field) const {
    const TextureDesc& desc = liveOutput(field).desc;
    return scaledSide(mFrameHeight, desc.scale, desc.divisor);
}

const PlannedResource& GlPassContext::readOrLiveWrite(std::string_view resource, const char* function) const {
    const bool declaredRead = std::find(mPlanned.reads.begin(), mPlanned.reads.end(), resource) != mPlanned.reads.end();
    const bool ownOutput =
        std::find(mPlanned.liveWrites.begin(), mPlanned.liveWrites.end(), resource) != mPlanned.liveWrites.end();
    const PlannedResource* planned = declaredRead || ownOutput ? mPlan.findResource(std::string(resource)) : nullptr;
    if (planned == nullptr)
        throw std::logic_error(std::string(function) + ": pass '" + mPlanned.name + "' neither reads '" +
                               std::string(resource) + "' nor writes it as a live output");
    return *planned;
}

int GlPassContext::scaleOf(std::string_view resource) const {
    return readOrLiveWrite(resource, "GlPassContext::scaleOf()").desc.scale;
}

int GlPassContext::divisorOf(std::string_view resource) const {
    return readOrLiveWrite(resource, "GlPassContext::divisorOf()").desc.divisor;
}

int GlPassContext::samplesOf(std::string_view resource) const {
    return readOrLiveWrite(resource, "GlPassContext::samplesOf()").desc.samples;
}

GlTexture& GlPassContext::outputTexture(std::string_view field) {
    const PlannedResource& planned = liveOutput(field);
    return mStore.writeTexture(planned.name, planned.desc.format, widthOf(field), heightOf(field),
                               planned.desc.samples);
}

void GlPassContext::limitReadback(std::string_view field, PixelRect region) {
    const PlannedResource& planned = liveOutput(field);
    if (backgroundIsRead(field))
        throw std::logic_error("GlPassContext::limitReadback(): '" + planned.name +
                               "' is read outside what its writer covers (or kept whole): it is read back whole");
    mStore.setReadRegion(planned.name, region);
}

cv::Mat& GlPassContext::outputImage(std::string_view field) {
    const PlannedResource& planned = liveOutput(field);
    if (planned.desc.samples != 1)
        throw std::logic_error("GlPassContext::outputImage(): '" + planned.name + "' is multisampled (" +
                               std::to_string(planned.desc.samples) + " samples); only GL draws it");
    return mStore.writeImage(planned.name, planned.desc.format, widthOf(field), heightOf(field));
}

void GlPassContext::requireDeclaredRead(std::string_view resource) const {
    if (std::find(mPlanned.reads.begin(), mPlanned.reads.end(), resource) == mPlanned.reads.end())
        throw std::logic_error("GlPassContext::input(): pass '" + mPlanned.name + "' reads '" + std::string(resource) +
                               "' without declaring it");
}

const GlTexture& GlPassContext::inputTexture(std::string_view resource) {
    requireDeclaredRead(resource);
    return mStore.texture(std::string(resource));
}

const cv::Mat& GlPassContext::inputImage(std::string_view resource) {
    requireDeclaredRead(resource);
    return mStore.image(std::string(resource));
}

// --- GraphExecutor -------------------------------------------------------------------------------------------

namespace {

/** The failures the GL executor reports by cause: the installation (shaders that cannot be read) as it is; memory
 *  running out, on the GPU or in OpenCV, keeps its type so the caller can say how to fix it. Returns for others. */
void rethrowGlFailureByCause(const std::exception_ptr& failure, const std::string& where) {
    try {
        std::rethrow_exception(failure);
    } catch (const ShaderSourceError&) {
        throw;
    } catch (const GlOutOfMemoryError& error) {
        throw GlOutOfMemoryError(where + ": " + error.what());
    } catch (const cv::Exception& error) {
        if (error.code == cv::Error::StsNoMem) throw OutOfMemoryError(where + " ran out of memory: " + error.err);
    } catch (...) {
    }
}

/** graph/Executor's loop on GL: one GlPassContext per step over the executor's store. */
class GlBackend final : public ExecutorBackend {
public:
    GlBackend(ResourceStore& store, const Plan& plan, const std::vector<GlPass*>& passes, const ExecuteOptions& options)
        : mStore(store), mPlan(plan), mPasses(passes), mOptions(options) {}

    void runPass(std::size_t passIndex, const PlannedPass& planned, PassPhase phase) override {
        GlPassContext context(mStore, planned, mPlan, mOptions.frameWidth, mOptions.frameHeight,
                              mOptions.keepAllResources);
        if (phase == PassPhase::Prepare)
            mPasses[passIndex]->prepare(context);
        else
            mPasses[passIndex]->execute(context);
    }

    void finishStep(const PlannedPass&, PassPhase) override {
        if (mOptions.waitForEachPass) glFinish();
    }

    std::string afterPass(const PlannedPass& planned) override {
        resetPassState();
        // The pass's own error first, so a read-back begun after it is not blamed for it.
        if (const GLenum error = glGetError(); error != GL_NO_ERROR) return "raised " + glErrorName(error);
        if (mOptions.readBackEarly) beginHostReadbacks(planned);
        return {};
    }

    void rethrowByCause(const std::exception_ptr& failure, const std::string& where) const override {
        rethrowGlFailureByCause(failure, where);
    }

    bool wrote(const std::string& resource) const override { return mStore.contains(resource); }
    void release(const std::string& resource) override { mStore.release(resource); }

private:
    /** Starts reading back what `planned` wrote that a host pass will read. */
    void beginHostReadbacks(const PlannedPass& planned) {
        for (const std::string& written : planned.liveWrites) {
            const PlannedResource* resource = mPlan.findResource(written);
            if (resource == nullptr || resource->kind != ResourceKind::Texture) continue;
            const bool hostReads =
                std::any_of(resource->readers.begin(), resource->readers.end(), [this](const std::string& reader) {
                    const PlannedPass* pass = mPlan.findPass(reader);
                    return pass != nullptr && pass->runsOnHost;
                });
            if (hostReads && mStore.holdsTexture(written)) mStore.beginReadback(written);
        }
    }

    ResourceStore& mStore;
    const Plan& mPlan;
    const std::vector<GlPass*>& mPasses;
    const ExecuteOptions& mOptions;
};

/** The host tail's backend: the GL one's loop without GL (no glFinish, no state to reset, no error to query), for a
 *  thread that holds no context. Releasing a resource with a GPU side would hand a texture to the pool, which is the
 *  context thread's: the hand-off left none, so finding one is a bug. */
class HostBackend final : public ExecutorBackend {
public:
    HostBackend(ResourceStore& store, const Plan& plan, const std::vector<GlPass*>& passes,
                const ExecuteOptions& options)
        : mStore(store), mPlan(plan), mPasses(passes), mOptions(options) {}

    void runPass(std::size_t passIndex, const PlannedPass& planned, PassPhase phase) override {
        if (phase == PassPhase::Prepare)
            throw std::logic_error("HostBackend::runPass(): '" + planned.name + "' prepares on the context's thread");
        GlPassContext context(mStore, planned, mPlan, mOptions.frameWidth, mOptions.frameHeight,
                              mOptions.keepAllResources);
        mPasses[passIndex]->execute(context);
    }

    void rethrowByCause(const std::exception_ptr& failure, const std::string& where) const override {
        rethrowGlFailureByCause(failure, where);
    }

    bool wrote(const std::string& resource) const override { return mStore.contains(resource); }

    void release(const std::string& resource) override {
        if (mStore.holdsTexture(resource))
            throw std::logic_error("HostBackend::release(): '" + resource + "' still has a texture off the GL thread");
        mStore.release(resource);
    }

private:
    ResourceStore& mStore;
    const Plan& mPlan;
    const std::vector<GlPass*>& mPasses;
    const ExecuteOptions& mOptions;
};

std::vector<std::string_view> passNamesOf(const std::vector<GlPass*>& passes) {
    std::vector<std::string_view> names;
    for (const GlPass* pass : passes) names.push_back(pass->name());
    return names;
}

} // namespace

std::vector<PassTiming> GraphExecutor::run(const Plan& plan, const std::vector<GlPass*>& passes,
                                           const ExecuteOptions& options) {
    runUntilHostTail(plan, passes, options);
    return runHostTail();
}

void GraphExecutor::runUntilHostTail(const Plan& plan, const std::vector<GlPass*>& passes,
                                     const ExecuteOptions& options) {
    mStore.clear();
    mImportMilliseconds.clear();
    mTail = std::make_unique<TailRun>();
    mTail->plan = &plan;
    mTail->passes = passes;
    mTail->options = options;
    if (options.importData)
        for (const std::string& name : plan.imports()) {
            const auto start = std::chrono::steady_clock::now();
            try {
                options.importData(name);
            } catch (const std::bad_alloc&) {
                throw OutOfMemoryError("GraphExecutor::run(): importing '" + name + "' ran out of memory");
            }
            mImportMilliseconds.emplace_back(
                name, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }
    PlanRun& run =
        mTail->run.emplace("GraphExecutor::run()", plan, passNamesOf(mTail->passes), options.keepAllResources);
    GlBackend backend(mStore, plan, mTail->passes, mTail->options);
    run.prepare(backend);
    const std::size_t tailStart = plan.hostTailStart();
    run.execute(backend, tailStart);
    // The hand-off: what the tail reads comes to the CPU here, on the context's thread.
    for (std::size_t index = tailStart; index < plan.passes.size(); ++index)
        for (const std::string& read : plan.passes[index].reads)
            if (mStore.holdsTexture(read)) mStore.moveToHost(read);
}

std::vector<PassTiming> GraphExecutor::runHostTail() {
    if (!mTail || !mTail->run)
        throw std::logic_error("GraphExecutor::runHostTail(): no run was begun (runUntilHostTail())");
    const std::unique_ptr<TailRun> tail = std::move(mTail);
    HostBackend backend(mStore, *tail->plan, tail->passes, tail->options);
    tail->run->execute(backend, tail->plan->passes.size());
    return tail->run->timings();
}

} // namespace inkgraph
