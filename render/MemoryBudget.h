#pragma once
/** @file The whole run's peak memory for one still, estimated before any GL work from what the plan declares (its
 *  resources with formats and scales, its passes and what they read) and the request (size, supersampling, dumps),
 *  so the memory limit (--memory-limit) bounds the process and not only the plan's textures. docs/batch.md ("Memory")
 * gives the model, the measurements it was calibrated on (peak resident set on llvmpipe) and how to size a batch task
 * from it.
 *
 *  The estimate is a bound: every term is what the run holds at its worst (llvmpipe keeps textures in process
 *  memory; the texture pool keeps every texture it made until the still ends; a stroke may take the
 *  nearest-point path that needs 8 bytes per data pixel), and the post stage is charged at its largest moment. */

#include <cstddef>
#include <string>

namespace inkgraph {

struct Plan;
struct StillRequest;
struct PreparedStill;
struct Scene;

/** What the model costs: its counts (the load's peak, the meshes, their GPU copies, what llvmpipe bins per triangle)
 *  and its textures. What the plan's passes derive from the meshes is charged per triangle by what they import
 *  (SceneImport::bytesPerTriangle()). */
struct SceneSize {
    std::size_t vertices = 0;
    std::size_t triangles = 0;
    std::size_t textureBytes = 0; ///< scene/TextureImage.h estimatedTextureBytes(): every image decoded at its peak
};

SceneSize sceneSizeOf(const Scene& scene);

/** The peak of one still, by part, in bytes. */
struct MemoryEstimate {
    std::size_t baseline = 0;  ///< the process before any buffer: libraries (OpenImageIO's when the run loads it),
                               ///< llvmpipe, LLVM's compiled shaders
    std::size_t scene = 0;     ///< the model's load, meshes, GPU copies and driver data, and what the plan derives
                               ///< from it (its imports' bytes per triangle: edge adjacency, curvature, ...)
    std::size_t derived = 0;   ///< of `scene`: what the plan's imports derive
    std::size_t glTargets = 0; ///< every texture of the plan, each drawing pass's depth attachment and the targets
                               ///< passes keep of their own (PassBuilder::ownTarget())
    std::size_t cpuImages = 0; ///< at the post stage's (or the output's) largest moment: read-backs, the line
                               ///< kernels' working images and skeletons, the composite, encoder buffers
    /** The model's textures, decoded and uploaded with their mipmaps (llvmpipe keeps them in process memory). Not
     *  part of what budgetStill() refuses the still for: each texture is charged, and refused naming it, as it is
     *  decoded, against what the rest leaves of the limit. */
    std::size_t textures = 0;
    std::size_t total() const { return baseline + scene + glTargets + cpuImages + textures; }
    /** Of `scene`: the meshes, the same in every look. */
    std::size_t meshes() const { return scene - derived; }
};

/** The estimate for `plan` rendered as `request` asks (its size, look, kept buffers, image module); `scene` may be {}
 * when not known yet (it then adds nothing). */
MemoryEstimate estimateRunMemory(const Plan& plan, const StillRequest& request, const SceneSize& scene);

/** The flags that make the buffers as large as they are, for messages: "--size 2048x2048", then
 *  " with --supersample 8 (--lines suggestive works at 16384x16384)", " and --dump (every buffer is kept)". */
std::string memoryDriversText(const Plan& plan, const StillRequest& request);

/** What each GL context beyond the process's first holds between stills (its compiled programs, the driver's state):
 *  a batch drawing on several threads (--draw-threads) counts it once per thread after the first. With llvmpipe the
 *  comic look's 64x64 stills of a 4k-triangle model peaked 10-11 MiB higher per drawing thread (1, 2, 4 and 8). */
std::size_t extraContextBytes();

/** The process before any still (libraries, llvmpipe, LLVM's compiled shaders), without OpenImageIO's module: the
 *  least any run holds. */
std::size_t processBaselineBytes();

/** Half this machine's memory, at least 1 GiB: the memory limit when none is given. */
std::size_t defaultMemoryLimit();

/** The largest square side whose float RGBA buffer (16 bytes a pixel, padded as llvmpipe pads) stays under
 *  kMaxTextureBytes: 11584. For --help and the refusal of a larger buffer. */
int largestFloatRgbaSquareSide();

/** Between plan and execute: refuses a still whose buffers would not fit (one texture of 2 GiB or more, or the whole
 *  run's estimated peak above the request's memoryLimitBytes), naming the flags that make them large (UsageError),
 *  then gives the textures, decoded during the run, what the estimate leaves of the limit. */
void budgetStill(PreparedStill& still);

/** The whole run's estimated peak for `still`: estimateRunMemory() with its scene, textures included. */
MemoryEstimate estimateStill(const PreparedStill& still);

/** The process's peak resident set so far (getrusage's ru_maxrss), in bytes. */
std::size_t peakResidentBytes();

/** The process's resident memory held in transparent huge pages now (AnonHugePages of /proc/self/smaps_rollup), in
 *  bytes; 0 where the kernel has none or does not say. */
std::size_t hugePageResidentBytes();

} // namespace inkgraph
