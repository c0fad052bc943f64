#include "passes/PostStage.h"

#include "gl/HeadlessContext.h"

namespace inkgraph {

const char* postStageDeviceName(PostStageDevice device) {
    switch (device) {
    case PostStageDevice::Auto: return "auto";
    case PostStageDevice::Cpu: return "cpu";
    case PostStageDevice::Gpu: return "gpu";
    }
    return "auto";
}

PostStageDevice resolvePostStage(PostStageDevice requested, std::string_view glRenderer) {
    if (requested != PostStageDevice::Auto) return requested;
    // Measured on llvmpipe (docs/performance.md): its compute shaders run on the cores the CPU kernels would use,
    // and the read-backs they save are memory copies there, not bus transfers.
    if (glRenderer.empty() || isSoftwareRasterizer(glRenderer)) return PostStageDevice::Cpu;
    return PostStageDevice::Gpu;
}

} // namespace inkgraph
