#pragma once
/** @file Where the post stage's image-space kernels and the composite run (--post-stage): on the CPU over read-back
 *  G-buffer fields (postfx/), or as compute shaders over the G-buffer's textures (passes/lines/types/GpuImageEdges.h,
 *  passes/composite/GpuCompositePass.h), the CPU then reading back only what they found. Which is cheaper depends
 *  on the device: on a software rasterizer the "GPU" is the same CPU cores and the CPU kernels stay faster
 *  (docs/performance.md "The post stage on the GPU"); on a real GPU the read-backs of the float G-buffer dominate. */

#include "gl/HeadlessContext.h" // isSoftwareRasterizer()

#include <string>
#include <string_view>

namespace inkgraph {

enum class PostStageDevice {
    Auto, ///< Cpu on a software rasterizer (gl/HeadlessContext.h isSoftwareRasterizer()), else Gpu
    Cpu,
    Gpu,
};

/** "auto", "cpu" or "gpu": the --post-stage word and --stats' post_stage.device. */
const char* postStageDeviceName(PostStageDevice device);

/** Cpu or Gpu: `requested` itself unless Auto; Auto takes the CPU on a software rasterizer and when the renderer is
 *  not known (empty: no GL context yet, as for a plan that renders nothing), the GPU otherwise. */
PostStageDevice resolvePostStage(PostStageDevice requested, std::string_view glRenderer);

} // namespace inkgraph
