#include "gl/GraphExecutor.h"

#include "gl/Readback.h"
#include "gl/ShaderLibrary.h"

#include <algorithm>
#include <chrono>
#include <new>
#include <cstdio>
#include <stdexcept>

namespace inkgraph {
namespace {

/** Runs a pass's prepare or execute, naming the pass in what it throws. Failures the caller reports by their cause
 *  keep their type: shaders that cannot be read (the installation), and memory running out, on the GPU or the CPU. */
template <class Step>
void runPassStep(const std::string& pass, const char* failed, Step&& step) {
    const std::string where = "GraphExecutor::run(): pass '" + pass + "'";
    try {
        step();
    } catch (const ShaderSourceError&) {
        throw;
    } catch (const GlOutOfMemoryError& error) {
        throw GlOutOfMemoryError(where + ": " + error.what());
    } catch (const std::bad_alloc&) {
        throw OutOfMemoryError(where + " ran out of memory");
    } catch (const cv::Exception& error) {
        if (error.code == cv::Error::StsNoMem) throw OutOfMemoryError(where + " ran out of memory: " + error.err);
        throw std::runtime_error(where + " " + failed + ": " + error.what());
    } catch (const std::exception& error) {
        throw std::runtime_error(where + " " + failed + ": " + error.what());
    }
}

double nowMilliseconds() {
    using Clock = std::chrono::steady_clock;
    return std::chrono::duration<double, std::milli>(Clock::now().time_since_epoch()).count();
}


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
    for (GLuint unit = 0; unit < 8; ++unit) glBindTextureUnit(unit, 0);
}

} // namespace

// --- ResourceStore -------------------------------------------------------------------------------------------

ResourceStore::Entry& ResourceStore::entry(const std::string& name) {
    auto found = mEntries.find(name);
    if (found == mEntries.end())
        throw std::out_of_range("ResourceStore: no resource '" + name + "' was computed in this run");
    return found->second;
}

GlTexture& ResourceStore::writeTexture(const std::string& name, Format format, int width, int height) {
    Entry& target = mEntries[name];
    target.image.release();
    if (!target.texture || target.format != format || target.width != width || target.height != height) {
        if (target.texture) mPool.release(std::move(*target.texture));
        target.texture.emplace(mPool.acquire(format, width, height, name));
    }
    target.format = format;
    target.width = width;
    target.height = height;
    return *target.texture;
}

cv::Mat& ResourceStore::writeImage(const std::string& name, Format format, int width, int height) {
    Entry& target = mEntries[name];
    if (target.texture) {
        mPool.release(std::move(*target.texture));
        target.texture.reset();
    }
    target.format = format;
    target.width = width;
    target.height = height;
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
    if (source.image.empty()) source.image = readTexture(*source.texture);
    return source.image;
}

Format ResourceStore::format(const std::string& name) const {
    auto found = mEntries.find(name);
    if (found == mEntries.end()) throw std::out_of_range("ResourceStore: no resource '" + name + "'");
    return found->second.format;
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
                             int frameHeight)
    : mStore(store), mPlanned(planned), mPlan(plan), mFrameWidth(frameWidth), mFrameHeight(frameHeight) {}

GlPassContext& GlPassContext::from(PassContext& context) {
    auto* backend = dynamic_cast<GlPassContext*>(&context);
    if (backend == nullptr)
        throw std::logic_error("GlPassContext::from(): this pass needs the GL executor's context");
    return *backend;
}

bool GlPassContext::isLive(std::string_view field) const {
    const std::string resource = mPlanned.name + "." + std::string(field);
    return std::find(mPlanned.liveWrites.begin(), mPlanned.liveWrites.end(), resource) != mPlanned.liveWrites.end();
}

const PlannedResource& GlPassContext::liveOutput(std::string_view field) const {
    const std::string resource = mPlanned.name + "." + std::string(field);
    const PlannedResource* planned = isLive(field) ? mPlan.findResource(resource) : nullptr;
    if (planned == nullptr)
        throw std::logic_error("GlPassContext::output(): pass '" + mPlanned.name + "' writes '" + resource +
                               "', which is not live in this plan (check isLive() first)");
    return *planned;
}

int GlPassContext::widthOf(std::string_view field) const { return mFrameWidth * liveOutput(field).desc.scale; }
int GlPassContext::heightOf(std::string_view field) const { return mFrameHeight * liveOutput(field).desc.scale; }

GlTexture& GlPassContext::outputTexture(std::string_view field) {
    const PlannedResource& planned = liveOutput(field);
    return mStore.writeTexture(planned.name, planned.desc.format, mFrameWidth * planned.desc.scale,
                               mFrameHeight * planned.desc.scale);
}

cv::Mat& GlPassContext::outputImage(std::string_view field) {
    const PlannedResource& planned = liveOutput(field);
    return mStore.writeImage(planned.name, planned.desc.format, mFrameWidth * planned.desc.scale,
                             mFrameHeight * planned.desc.scale);
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

std::vector<PassTiming> GraphExecutor::run(const Plan& plan, const std::vector<Pass*>& passes,
                                           const ExecuteOptions& options) {
    mStore.clear();
    std::vector<Pass*> ordered;
    for (const PlannedPass& planned : plan.passes) {
        auto found = std::find_if(passes.begin(), passes.end(),
                                  [&](const Pass* pass) { return pass->name() == planned.name; });
        if (found == passes.end())
            throw std::logic_error("GraphExecutor::run(): the plan names pass '" + planned.name +
                                   "' but no such pass object was given");
        ordered.push_back(*found);
    }

    std::vector<PassTiming> timings(plan.passes.size());
    for (std::size_t index = 0; index < plan.passes.size(); ++index) {
        const PlannedPass& planned = plan.passes[index];
        GlPassContext context(mStore, planned, plan, options.frameWidth, options.frameHeight);
        const double start = nowMilliseconds();
        runPassStep(planned.name, "failed to prepare", [&] { ordered[index]->prepare(context); });
        glFinish();
        timings[index].pass = planned.name;
        timings[index].prepareMilliseconds = nowMilliseconds() - start;
    }

    for (std::size_t index = 0; index < plan.passes.size(); ++index) {
        const PlannedPass& planned = plan.passes[index];
        GlPassContext context(mStore, planned, plan, options.frameWidth, options.frameHeight);
        const double start = nowMilliseconds();
        runPassStep(planned.name, "failed", [&] { ordered[index]->execute(context); });
        // Waiting here makes the milliseconds mean the pass's own work, not whatever the driver queued.
        glFinish();
        timings[index].milliseconds = nowMilliseconds() - start;
        resetPassState();

        if (const GLenum error = glGetError(); error != GL_NO_ERROR)
            throw std::runtime_error("GraphExecutor::run(): pass '" + planned.name + "' raised " + glErrorName(error));
        for (const std::string& written : planned.liveWrites)
            if (!mStore.contains(written))
                throw std::logic_error("GraphExecutor::run(): pass '" + planned.name + "' did not write its live output '" +
                                       written + "'");

        if (options.keepAllResources) continue;
        for (const PlannedResource& resource : plan.resources)
            if (!resource.requested && resource.lastUse == index) mStore.release(resource.name);
    }
    return timings;
}

} // namespace inkgraph
