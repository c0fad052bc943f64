#pragma once
/** @file Runs a compiled Plan: hands each pass its resources, times it, and frees what nothing reads any more.
 *  A resource lives on the GPU (a GlTexture), on the CPU (a cv::Mat, row 0 at the top), or both; it is moved
 *  across only when a pass or the caller asks for the other side, through gl/Readback. */

#include "gl/GlObjects.h"
#include "gl/TexturePool.h"
#include "graph/Pass.h"
#include "graph/Plan.h"

#include <opencv2/core.hpp>

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {

/** The resources of one run, by full name. */
/** A pass's CPU work ran out of memory (std::bad_alloc or OpenCV's out-of-memory error), named by the pass. The
 *  driver running out is GlOutOfMemoryError. */
class OutOfMemoryError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class ResourceStore {
public:
    explicit ResourceStore(TexturePool& pool) : mPool(pool) {}
    ~ResourceStore() { clear(); }
    ResourceStore(const ResourceStore&) = delete;
    ResourceStore& operator=(const ResourceStore&) = delete;

    /** A GPU target for a pass to render into; the CPU copy, if any, is discarded. */
    GlTexture& writeTexture(const std::string& name, Format format, int width, int height);
    /** A CPU image for a pass to fill; the GPU copy, if any, is discarded. */
    cv::Mat& writeImage(const std::string& name, Format format, int width, int height);
    /** The GPU side, uploading the CPU image on first use. */
    const GlTexture& texture(const std::string& name);
    /** The CPU side (row 0 = top), reading the texture back on first use. */
    const cv::Mat& image(const std::string& name);

    bool contains(const std::string& name) const { return mEntries.count(name) != 0; }
    Format format(const std::string& name) const;
    std::vector<std::string> names() const;
    void release(const std::string& name);
    void clear();

private:
    struct Entry {
        Format format = Format::RGBA8;
        int width = 0;
        int height = 0;
        std::optional<GlTexture> texture;
        cv::Mat image;
    };
    Entry& entry(const std::string& name);

    TexturePool& mPool;
    std::map<std::string, Entry> mEntries;
};

/** What a GL or CPU pass sees while it executes. Reads and writes are checked against the plan. */
class GlPassContext : public PassContext {
public:
    GlPassContext(ResourceStore& store, const PlannedPass& planned, const Plan& plan, int frameWidth, int frameHeight);

    /** The backend context of a pass executed by GraphExecutor; throws for any other context. */
    static GlPassContext& from(PassContext& context);

    bool isLive(std::string_view field) const override;
    int width() const override { return mFrameWidth; }
    int height() const override { return mFrameHeight; }

    /** Size of one of this pass's fields (frame size x its scale). */
    int widthOf(std::string_view field) const;
    int heightOf(std::string_view field) const;

    /** This pass's live output `field` as a GPU target or a CPU image. Throws if the field is not live. */
    GlTexture& outputTexture(std::string_view field);
    cv::Mat& outputImage(std::string_view field);
    /** A declared input by full name. Throws on a read the pass did not declare. */
    const GlTexture& inputTexture(std::string_view resource);
    const cv::Mat& inputImage(std::string_view resource);

private:
    const PlannedResource& liveOutput(std::string_view field) const;
    void requireDeclaredRead(std::string_view resource) const;

    ResourceStore& mStore;
    const PlannedPass& mPlanned;
    const Plan& mPlan;
    int mFrameWidth;
    int mFrameHeight;
};

struct PassTiming {
    std::string pass;
    double prepareMilliseconds = 0.0; ///< shader compilation and uploads, once per run
    double milliseconds = 0.0;        ///< execute(): CPU wall time from the call to glFinish() returning
};

struct ExecuteOptions {
    int frameWidth = 1024;
    int frameHeight = 1024;
    /** Keep every computed resource to the end (for --dump). Never changes which passes run. */
    bool keepAllResources = false;
};

class GraphExecutor {
public:
    explicit GraphExecutor(TexturePool& pool) : mStore(pool) {}

    /** Executes `plan` with the given pass objects (looked up by name). Throws std::runtime_error naming the pass
     *  when a pass fails, leaves a live output unwritten, or raises a GL error. */
    std::vector<PassTiming> run(const Plan& plan, const std::vector<Pass*>& passes, const ExecuteOptions& options);

    /** Resources kept after run(): the requested ones, or every computed one with keepAllResources. */
    ResourceStore& store() { return mStore; }

private:
    ResourceStore mStore;
};

} // namespace inkgraph
