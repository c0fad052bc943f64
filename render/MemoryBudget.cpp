#include "render/MemoryBudget.h"

#include "graph/Plan.h"
#include "passes/GpuScene.h"
#include "render/StillRenderer.h"
#include "render/UsageError.h"
#include "scene/Scene.h"
#include "scene/TextureImage.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <unistd.h>

namespace inkgraph {
namespace {

constexpr std::size_t kMiB = std::size_t(1) << 20;

// The constants below were measured (peak resident set, /usr/bin/time %M) with llvmpipe (Mesa 22.3, LLVM 15);
// docs/batch.md ("Memory") has the table they were fitted to.

/** The process at a 64x64 still of a 4k-triangle model with every line type, written as PNG: 100 MiB (libraries,
 *  llvmpipe and LLVM, the compiled shaders), with room for the run-to-run spread. */
constexpr std::size_t kBaselineBytes = 108 * kMiB;
/** What the OpenImageIO module adds once loaded (render/ImageIoModule.h), for a run that writes another format than PNG
 *  or a dump: the same still as .exr peaked at 213-218 MiB. */
constexpr std::size_t kImageIoModuleBytes = 116 * kMiB;
/** Each GL context after the first: 10-11 MiB measured (extraContextBytes()), with room for the spread. */
constexpr std::size_t kExtraContextBytes = 12 * kMiB;
/** Per vertex and per triangle, whatever the look: the load's peak (an OBJ's text and its parsed corners), the
 *  meshes and their GPU copies. A 1.3-million-triangle OBJ whose every corner has texture coordinates of its own
 *  (2.9 million vertices, 160 MB of text) peaked 560 MiB over the process at `--lines none`. What the passes derive
 *  from the meshes is charged by their imports (SceneImport::bytesPerTriangle()). */
constexpr std::size_t kBytesPerVertex = 128;
constexpr std::size_t kBytesPerTriangle = 128;
/** What llvmpipe bins per triangle drawn until its scenes are full: `--lines none` peaked 70 MiB over the process
 *  at 208k triangles, 129 at 468k and 147 at 832k (1, 2 and 8 llvmpipe threads alike), the counts' share
 *  included. docs/batch.md has the table. */
constexpr std::size_t kBinnedBytesPerTriangle = 320;
constexpr std::size_t kBinnedBytesAtMost = 112 * kMiB;

/** gl/Readback.cpp moves pixels in bands of at most this many bytes, through one extra buffer. */
constexpr std::size_t kTransferBandBytes = 64 * kMiB;
/** Encoding one image: the encoded bytes in a growing vector (up to twice their size) and the writer's own copy. */
constexpr std::size_t kEncodeCopies = 2;

/** llvmpipe rounds a texture's sides up to its tiles; 64 covers the 4-pixel raster blocks of Mesa 22 and the
 *  64-pixel tiles of older versions. */
std::size_t paddedTextureSide(std::size_t side) { return (side + 63) / 64 * 64; }

} // namespace

int largestFloatRgbaSquareSide() {
    int side = 64;
    while (paddedTextureSide(std::size_t(side) + 64) * paddedTextureSide(std::size_t(side) + 64) * 16 <
           kMaxTextureBytes)
        side += 64;
    return side;
}

namespace {

int channelsOf(Format format) {
    return format == Format::RGBA32F || format == Format::RGBA8 || format == Format::RGBA16F ? 4 : 1;
}

/** Bytes of a resource's CPU image: float formats (half included) are float32 there (gl/Readback.cpp). */
std::size_t cpuBytesPerPixel(Format format) {
    return std::size_t(channelsOf(format)) * (isFloatFormat(format) ? 4 : 1);
}

class PlanSizes {
public:
    PlanSizes(const Plan& plan, const StillRequest& request)
        : mPlan(plan), mWidth(request.camera.width), mHeight(request.camera.height) {
        for (const PlannedResource& resource : plan.resources) mResources[resource.name] = &resource;
    }

    /** Pixels of a resource at `scale` / `divisor` of the frame (a side rounded up: an estimate never refuses a
     *  divisor that does not divide; the executor does, scaledSide()). */
    std::size_t pixels(int scale, int divisor = 1) const {
        return sideOf(mWidth, scale, divisor) * sideOf(mHeight, scale, divisor);
    }
    std::size_t paddedPixels(int scale, int divisor = 1) const {
        return paddedTextureSide(sideOf(mWidth, scale, divisor)) * paddedTextureSide(sideOf(mHeight, scale, divisor));
    }
    std::size_t textureBytes(const PlannedResource& resource) const {
        return paddedPixels(resource.desc.scale, resource.desc.divisor) *
               std::size_t(bytesPerPixel(resource.desc.format)) * std::size_t(resource.desc.samples);
    }
    /** A texture's CPU image; an object's own bytes as its writer declares them, and its picture. */
    std::size_t imageBytes(const PlannedResource& resource) const {
        if (resource.kind == ResourceKind::Object)
            return pixels(resource.object.scale, resource.object.divisor) *
                   (resource.object.bytesPerPixel +
                    (resource.object.hasPicture ? cpuBytesPerPixel(resource.object.pictureFormat) : 0));
        return pixels(resource.desc.scale, resource.desc.divisor) * cpuBytesPerPixel(resource.desc.format);
    }
    /** The working memory `pass` declared (PassBuilder::scratch()). */
    std::size_t scratchBytes(const PlannedPass& pass) const {
        std::size_t bytes = 0;
        for (const PassBuilder::Scratch& scratch : pass.scratch)
            if (!scratch.kept) bytes += scratch.bytesPerPixel * pixels(scratch.scale, scratch.divisor);
        return bytes;
    }
    /** The targets `pass` keeps (PassBuilder::ownTarget()), padded as the driver pads textures. */
    std::size_t ownTargetBytes(const PlannedPass& pass) const {
        std::size_t bytes = 0;
        for (const PassBuilder::Scratch& scratch : pass.scratch)
            if (scratch.kept) bytes += scratch.bytesPerPixel * paddedPixels(scratch.scale, scratch.divisor);
        return bytes;
    }
    static std::size_t sideOf(int frameSide, int scale, int divisor) {
        const std::size_t over = std::size_t(std::max(divisor, 1));
        return (std::size_t(frameSide) * std::size_t(scale) + over - 1) / over;
    }
    const PlannedResource* resource(const std::string& name) const {
        auto found = mResources.find(name);
        return found == mResources.end() ? nullptr : found->second;
    }
    /** The scale a pass works at: its largest read or write. */
    int scaleOf(const PlannedPass& pass) const {
        int scale = 1;
        for (const auto* names : {&pass.reads, &pass.liveWrites})
            for (const std::string& name : *names)
                if (const PlannedResource* found = resource(name)) scale = std::max(scale, found->desc.scale);
        return scale;
    }

private:
    const Plan& mPlan;
    int mWidth = 0;
    int mHeight = 0;
    std::map<std::string, const PlannedResource*> mResources;
};

/** Passes that write a texture and read nothing from the graph but a depth (the G-buffer's z-buffer, which never leaves
 *  GL) or objects (the scene's imports) draw the scene with GL, into a depth attachment of their own or that one
 *  (counted as their own: a little high); the others (line layers, strokes, composite) work on the CPU on what they
 *  read. */
bool drawsTheScene(const PlannedPass& pass, const PlanSizes& sizes) {
    const bool writesTexture =
        std::any_of(pass.liveWrites.begin(), pass.liveWrites.end(), [&](const std::string& name) {
            const PlannedResource* written = sizes.resource(name);
            return written != nullptr && written->kind == ResourceKind::Texture;
        });
    return writesTexture && std::all_of(pass.reads.begin(), pass.reads.end(), [&](const std::string& name) {
               const PlannedResource* read = sizes.resource(name);
               return read != nullptr && (read->desc.format == Format::Depth32F || read->kind == ResourceKind::Object);
           });
}

/** A CPU pass that finds a line skeleton (a line layer, named after its --lines type). */
bool findsSkeleton(const PlannedPass& pass, const PlanSizes& sizes) {
    return std::any_of(pass.liveWrites.begin(), pass.liveWrites.end(), [&](const std::string& name) {
        const PlannedResource* written = sizes.resource(name);
        return written != nullptr && written->kind == ResourceKind::Object && written->object.hasPicture;
    });
}

/** What the post stage holds while pass `index` runs (or, for index == passes.size(), while the outputs are
 *  written): the CPU images then alive, the skeletons of the post passes so far, and the pass's working images. */
std::size_t cpuBytesAt(std::size_t index, const Plan& plan, const PlanSizes& sizes, bool keepAll) {
    const bool writing = index == plan.passes.size();
    std::size_t bytes = 0;
    // An image exists on the CPU from the first post pass that reads it (or writes it) to its last use; requested
    // ones, and all with --dump or --contact-sheet, to the end. While outputs are written every image may be read.
    for (const PlannedResource& resource : plan.resources) {
        bool onCpu = writing && (keepAll || resource.requested);
        for (std::size_t at = 0; at < plan.passes.size() && at <= index && !onCpu; ++at) {
            const PlannedPass& pass = plan.passes[at];
            if (drawsTheScene(pass, sizes)) continue;
            const bool touches = std::find(pass.reads.begin(), pass.reads.end(), resource.name) != pass.reads.end() ||
                                 resource.writer == pass.name;
            onCpu = touches;
        }
        const bool alive = keepAll || resource.requested || resource.lastUse >= index;
        if (onCpu && alive) bytes += sizes.imageBytes(resource);
    }

    std::size_t largestImage = 0;
    for (const PlannedResource& resource : plan.resources)
        largestImage = std::max(largestImage, sizes.imageBytes(resource));
    if (writing) {
        // One image encoded at a time: the final picture, or with --dump the largest buffer.
        std::size_t encoded = 0;
        for (const PlannedResource& resource : plan.resources)
            if (keepAll || resource.requested) encoded = std::max(encoded, sizes.imageBytes(resource));
        return bytes + kEncodeCopies * encoded + std::min(kTransferBandBytes, largestImage);
    }
    const PlannedPass& pass = plan.passes[index];
    if (drawsTheScene(pass, sizes)) return bytes + sizes.scratchBytes(pass);
    // A CPU pass works in the images it reads and writes, counted above, and the working memory it declares.
    return bytes + sizes.scratchBytes(pass) + std::min(kTransferBandBytes, largestImage);
}

std::string sizeText(std::size_t width, std::size_t height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

std::string mibText(std::size_t bytes) { return std::to_string((bytes + kMiB - 1) / kMiB) + " MiB"; }

/** The model's part of the estimate, for a refusal it dominates: "its meshes take about 148 MiB, the edge-adjacency
 *  and curvature the passes derive from them about 148 MiB". */
std::string modelShareText(const Plan& plan, const MemoryEstimate& estimate) {
    std::string text = "its meshes take about " + mibText(estimate.meshes());
    std::vector<std::string> names;
    for (const std::string& import : plan.imports()) {
        if (SceneImport::bytesPerTriangle(import) == 0) continue;
        const std::string_view prefix = "scene.";
        names.push_back(import.rfind(prefix, 0) == 0 ? import.substr(prefix.size()) : import);
    }
    if (names.empty()) return text;
    text += ", the ";
    for (std::size_t index = 0; index < names.size(); ++index)
        text += (index == 0 ? "" : index + 1 == names.size() ? " and " : ", ") + names[index];
    return text + " the passes derive from them about " + mibText(estimate.derived);
}

} // namespace

std::size_t extraContextBytes() { return kExtraContextBytes; }

std::size_t processBaselineBytes() { return kBaselineBytes; }

SceneSize sceneSizeOf(const Scene& scene) {
    return {scene.vertexCount(), scene.triangleCount(), estimatedTextureBytes(scene)};
}

MemoryEstimate estimateRunMemory(const Plan& plan, const StillRequest& request, const SceneSize& scene) {
    const PlanSizes sizes(plan, request);
    const bool keepAll = request.keepEveryBuffer;
    MemoryEstimate estimate;
    estimate.baseline = kBaselineBytes + (request.loadsImageIo ? kImageIoModuleBytes : 0);
    // Summed with the load's peak, though the load frees its text before anything is derived: the allocator may keep
    // what was freed, so only the sum bounds the run.
    for (const std::string& import : plan.imports())
        estimate.derived += scene.triangles * SceneImport::bytesPerTriangle(import);
    estimate.scene = scene.vertices * kBytesPerVertex + scene.triangles * kBytesPerTriangle +
                     std::min(scene.triangles * kBinnedBytesPerTriangle, kBinnedBytesAtMost) + estimate.derived;
    estimate.textures = scene.textureBytes;
    // The texture pool keeps every texture it made until the still ends, so they all count at once.
    for (const PlannedResource& resource : plan.resources)
        if (resource.kind == ResourceKind::Texture) estimate.glTargets += sizes.textureBytes(resource);
    for (const PlannedPass& pass : plan.passes) {
        if (drawsTheScene(pass, sizes)) estimate.glTargets += sizes.paddedPixels(sizes.scaleOf(pass)) * 4; // DEPTH32F
        // Kept to the still's end like the pool's textures (counted as working memory at the post stage's largest
        // moment only, a still at --msaa 4 and 1536x1536 peaked 20 MiB above its estimate).
        estimate.glTargets += sizes.ownTargetBytes(pass);
    }
    for (std::size_t index = 0; index <= plan.passes.size(); ++index)
        estimate.cpuImages = std::max(estimate.cpuImages, cpuBytesAt(index, plan, sizes, keepAll));
    return estimate;
}

std::string memoryDriversText(const Plan& plan, const StillRequest& request) {
    const int width = request.camera.width;
    const int height = request.camera.height;
    const Look& look = request.look;
    std::string text = "--size " + sizeText(std::size_t(width), std::size_t(height));
    if (look.supersample > 1) {
        const PlanSizes sizes(plan, request);
        std::string supersampled;
        int count = 0;
        for (const std::string& type : look.lines) { // in the order the user gave them
            const PlannedPass* pass = plan.findPass(type);
            if (pass == nullptr || !findsSkeleton(*pass, sizes)) continue;
            if (sizes.scaleOf(*pass) < look.supersample) continue;
            supersampled += (count++ ? "," : "") + type;
        }
        text += " with --supersample " + std::to_string(look.supersample);
        if (count > 0)
            text += " (--lines " + supersampled + (count == 1 ? " works" : " work") + " at " +
                    sizeText(std::size_t(width) * look.supersample, std::size_t(height) * look.supersample) + ")";
    }
    for (const std::string& keeper : request.keepEveryBufferFor) text += " and " + keeper;
    if (!request.keepEveryBufferFor.empty()) text += " (every buffer is kept)";
    return text;
}

std::size_t defaultMemoryLimit() {
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long pageSize = ::sysconf(_SC_PAGE_SIZE);
    const std::size_t physical = pages > 0 && pageSize > 0 ? std::size_t(pages) * std::size_t(pageSize) : 0;
    return std::max<std::size_t>(physical / 2, std::size_t(1) << 30);
}

MemoryEstimate estimateStill(const PreparedStill& still) {
    return estimateRunMemory(still.plan, still.request, sceneSizeOf(still.scene()));
}

void budgetStill(PreparedStill& still) {
    const StillRequest& request = still.request;
    const int width = request.camera.width;
    const int height = request.camera.height;
    // One texture of 2 GiB or more fails deep inside the driver (GL's byte counts are 32-bit); the message names
    // every flag that makes the buffer that large (--size, and --supersample for the supersampled ones).
    const PlanSizes sizes(still.plan, request);
    for (const PlannedResource& resource : still.plan.resources) {
        const std::size_t textureBytes = sizes.textureBytes(resource);
        if (textureBytes < kMaxTextureBytes) continue;
        const std::string size = "--size " + sizeText(std::size_t(width), std::size_t(height));
        const std::string cause =
            (resource.desc.scale > 1
                 ? size + " with --supersample " + std::to_string(resource.desc.scale) + " (" +
                       sizeText(std::size_t(width) * resource.desc.scale, std::size_t(height) * resource.desc.scale) +
                       ")"
                 : size) +
            (resource.desc.samples > 1 ? " and --msaa " + std::to_string(resource.desc.samples) : std::string());
        throw UsageError(cause + " makes '" + resource.name + "' " + std::to_string(textureBytes >> 20) +
                         " MiB; one buffer must stay under " + std::to_string(kMaxTextureBytes >> 20) +
                         " MiB (at most " + std::to_string(largestFloatRgbaSquareSide()) + "x" +
                         std::to_string(largestFloatRgbaSquareSide()) + " for float RGBA)");
    }
    // The textures are left out here: each is refused by name when it is decoded (decodeSceneImage()), which says
    // more than "the run needs N MiB" would.
    const MemoryEstimate estimate = estimateStill(still);
    const std::size_t needed = estimate.total() - estimate.textures;
    const std::size_t bound = request.memoryLimitBytes;
    const std::size_t neededMib = (needed + kMiB - 1) / kMiB; // rounded up: "needs 600" never fits a 600 limit
    if (needed > bound) {
        // A large model at a small size: saying "--size 256x256 needs" and advising a smaller image would mislead.
        const bool modelDominates = estimate.scene > estimate.glTargets + estimate.cpuImages;
        const std::string drivers = memoryDriversText(still.plan, request);
        throw UsageError(
            (modelDominates ? "the model's " + std::to_string(still.scene().triangleCount()) + " triangles and " +
                                  std::to_string(still.scene().vertexCount()) + " vertices at " + drivers
                            : drivers) +
            " need" + (modelDominates ? "" : "s") + " about " + std::to_string(neededMib) +
            " MiB for the whole run; the memory limit is " + std::to_string(bound >> 20) + " MiB" +
            (request.memoryLimitGiven ? " (--memory-limit)" : ", half this machine's memory") +
            (modelDominates ? " (" + modelShareText(still.plan, estimate) + "; a model this large needs a higher limit)"
                            : " (make the image smaller, lower --supersample, or request or dump fewer buffers)"));
    }
    // The textures are decoded during the run, only those a pass samples: they get what the estimate leaves.
    still.gpuScene->materials().setTextureMemoryLimit(bound > needed ? bound - needed : 0);
}

std::size_t peakResidentBytes() {
    rusage usage{};
    if (::getrusage(RUSAGE_SELF, &usage) != 0) return 0;
    return std::size_t(usage.ru_maxrss) * 1024; // Linux reports kilobytes
}

std::size_t hugePageResidentBytes() {
    std::ifstream rollup("/proc/self/smaps_rollup");
    std::string line;
    while (std::getline(rollup, line)) {
        std::size_t kilobytes = 0;
        if (std::sscanf(line.c_str(), "AnonHugePages: %zu kB", &kilobytes) == 1) return kilobytes * 1024;
    }
    return 0;
}

} // namespace inkgraph
