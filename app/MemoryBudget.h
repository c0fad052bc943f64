#pragma once
/** @file The whole run's peak memory for one still, estimated before any GL work from what the plan declares (its
 *  resources with formats and scales, its passes and what they read) and the options (size, supersampling, dumps),
 *  so --memory-limit bounds the process and not only the plan's textures. docs/batch.md ("Memory") gives the model,
 *  the measurements it was calibrated on (peak resident set on llvmpipe) and how to size a batch task from it.
 *
 *  The estimate is a bound: every term is what the run holds at its worst (llvmpipe keeps textures in process
 *  memory; the texture pool keeps every texture it made until the still ends; a stroke may take the
 *  nearest-point path that needs 8 bytes per data pixel), and the post stage is charged at its largest moment. */

#include <cstddef>
#include <string>

namespace inkgraph {

struct Plan;
struct RenderOptions;
struct Scene;

/** What the meshes cost, by count: the loaded scene, its GPU copy, and what llvmpipe bins per triangle. */
struct SceneSize {
    std::size_t vertices = 0;
    std::size_t triangles = 0;
};

SceneSize sceneSizeOf(const Scene& scene);

/** The peak of one still, by part, in bytes. */
struct MemoryEstimate {
    std::size_t baseline = 0;  ///< the process before any buffer: libraries (OpenImageIO's when the run loads it),
                               ///< llvmpipe, LLVM's compiled shaders
    std::size_t scene = 0;     ///< the meshes, their GPU copies and per-triangle driver data
    std::size_t glTargets = 0; ///< every texture of the plan and each drawing pass's depth attachment
    std::size_t cpuImages = 0; ///< at the post stage's (or the output's) largest moment: read-backs, the line
                               ///< kernels' working images and skeletons, the composite, encoder buffers
    std::size_t total() const { return baseline + scene + glTargets + cpuImages; }
};

/** The estimate for `plan` rendered with `options`; `scene` may be {} when not known yet (it then adds nothing). */
MemoryEstimate estimateRunMemory(const Plan& plan, const RenderOptions& options, const SceneSize& scene);

/** The flags that make the buffers as large as they are, for messages: "--size 2048x2048", then
 *  " with --supersample 8 (--lines suggestive works at 16384x16384)", " and --dump (every buffer is kept)". */
std::string memoryDriversText(const Plan& plan, const RenderOptions& options);

/** The process's peak resident set so far (getrusage's ru_maxrss), in bytes. */
std::size_t peakResidentBytes();

} // namespace inkgraph
