#pragma once
/** @file The passes of one still, registered in a fixed order. Every pass is registered; the compiler culls what
 *  the request does not need, so --stats can say why a pass did not run. Shared by the CLI and the benchmarks. */

#include "app/Options.h"
#include "gl/ShaderLibrary.h"
#include "graph/Pass.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"

#include <memory>
#include <string>
#include <vector>

namespace inkgraph {

struct StillGraph {
    std::vector<std::unique_ptr<Pass>> passes;
    std::string shadingResource; ///< the colour the composite reads ("shade.color"), or empty for --shading none
    std::string finalResource = "composite.final";

    std::vector<const Pass*> view() const;
    std::vector<Pass*> mutableView() const;
};

StillGraph buildStillGraph(ShadingMode shading, ShaderLibrary& shaders, GpuScene& gpuScene, const FrameParams& frame);

/** "gbuffer.*" -> every field the pass "gbuffer" declares; other names pass through for compile() to check. Throws
 *  UsageError for a wildcard on a pass the graph does not have. */
std::vector<std::string> expandWildcards(const std::vector<std::string>& requests, const StillGraph& graph);

} // namespace inkgraph
