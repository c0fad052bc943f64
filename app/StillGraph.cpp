#include "app/StillGraph.h"

#include "passes/composite/CompositePass.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/shade/ShadePass.h"

namespace inkgraph {

std::vector<const Pass*> StillGraph::view() const {
    std::vector<const Pass*> result;
    for (const auto& pass : passes) result.push_back(pass.get());
    return result;
}

std::vector<Pass*> StillGraph::mutableView() const {
    std::vector<Pass*> result;
    for (const auto& pass : passes) result.push_back(pass.get());
    return result;
}

StillGraph buildStillGraph(ShadingMode shading, ShaderLibrary& shaders, GpuScene& gpuScene, const FrameParams& frame) {
    StillGraph graph;
    graph.passes.push_back(std::make_unique<GBufferPass>("gbuffer", shaders, gpuScene, frame));
    // Forward shading draws the meshes itself: the G-buffer runs only when something requests one of its fields.
    ShadeSettings lambert;
    lambert.model = ShadingModel::Lambert;
    graph.passes.push_back(
        std::make_unique<ShadePass>("shade", shaders, gpuScene, frame, lambert, std::nullopt, nullptr));
    if (shading == ShadingMode::Lambert) graph.shadingResource = "shade.color";
    graph.passes.push_back(std::make_unique<CompositePass>("composite", frame, graph.shadingResource));
    return graph;
}

std::vector<std::string> expandWildcards(const std::vector<std::string>& requests, const StillGraph& graph) {
    std::vector<std::string> expanded;
    for (const std::string& request : requests) {
        const ResourceName name = ResourceName::split(request);
        if (name.field != "*") {
            expanded.push_back(request);
            continue;
        }
        bool found = false;
        for (const Pass* pass : graph.view()) {
            if (pass->name() != name.pass) continue;
            PassBuilder builder{name.pass};
            pass->declare(builder);
            for (const auto& write : builder.writes()) expanded.push_back(name.pass + "." + write.field);
            found = true;
        }
        if (!found) throw UsageError("--request: no pass named '" + name.pass + "' in this render graph");
    }
    return expanded;
}

} // namespace inkgraph
