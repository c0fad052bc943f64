// Line types found by postfx kernels in the float G-buffer: contours, depth edges, normal edges (Saito & Takahashi
// 1990).
#include "passes/lines/types/ImageEdgeLines.h"

#include "passes/lines/LineType.h"
#include "passes/lines/types/GpuImageEdges.h"

#include <nlohmann/json.hpp>

namespace inkgraph {
namespace {

using line_parameters::kCreaseAngle;
using line_parameters::kDepthJump;

/** --post-stage gpu: the kernels as compute shaders (GpuImageEdges.h), else the postfx kernels on the CPU. */
bool onGpu(const LineGraphBuilder& builder) { return builder.setup().postStage == PostStageDevice::Gpu; }

float depthJumpOf(const LineGraphBuilder& builder) { return float(builder.look().lineParameters.number(kDepthJump)); }

void describeDepthJump(const LineStatsSource& source, nlohmann::ordered_json& entry) {
    entry["depth_jump"] = source.look.lineParameters.number(kDepthJump);
    entry["supersample"] = source.look.supersample;
}

} // namespace

LineType normalEdgeLineType() {
    LineType type;
    type.name = "normal-edge";
    type.help = "creases where neighbouring G-buffer normals differ by more than\n"
                "--crease-angle (Saito & Takahashi 1990)";
    type.parameters = {&kCreaseAngle, &kDepthJump};
    type.build = [](const std::string& name, LineGraphBuilder& builder) {
        NormalEdgeSettings settings;
        settings.creaseAngleDegrees = float(builder.look().lineParameters.number(kCreaseAngle));
        settings.depthJump = depthJumpOf(builder);
        if (onGpu(builder))
            builder.addLayer(name, std::make_unique<GpuNeighbourPairsKernel>(builder.setup().gbuffer, settings,
                                                                             builder.setup().shaders));
        else
            builder.addLayer(name, std::make_unique<NormalEdgeKernel>(builder.setup().gbuffer, settings));
    };
    type.describe = [](const LineStatsSource& source, nlohmann::ordered_json& entry) {
        entry["crease_angle_degrees"] = source.look.lineParameters.number(kCreaseAngle);
        describeDepthJump(source, entry);
    };
    return type;
}

LineType depthEdgeLineType() {
    LineType type;
    type.name = "depth-edge";
    type.help = "jumps in linear depth larger than --depth-jump x the depth";
    type.parameters = {&kDepthJump};
    type.build = [](const std::string& name, LineGraphBuilder& builder) {
        DepthEdgeSettings settings;
        settings.relativeJump = depthJumpOf(builder);
        if (onGpu(builder))
            builder.addLayer(name, std::make_unique<GpuNeighbourPairsKernel>(builder.setup().gbuffer, settings,
                                                                             builder.setup().shaders));
        else
            builder.addLayer(name, std::make_unique<DepthEdgeKernel>(builder.setup().gbuffer, settings));
    };
    type.describe = describeDepthJump;
    return type;
}

LineType contourLineType() {
    LineType type;
    type.name = "contour";
    type.help = "where n.v changes sign, and where the model ends (against the background or\n"
                "in front of a farther surface), as a one-pixel skeleton";
    type.parameters = {&kDepthJump};
    type.build = [](const std::string& name, LineGraphBuilder& builder) {
        ContourSettings settings;
        settings.depthJump = depthJumpOf(builder);
        if (onGpu(builder))
            builder.addLayer(name, std::make_unique<GpuNeighbourPairsKernel>(builder.setup().gbuffer, settings,
                                                                             builder.setup().shaders));
        else
            builder.addLayer(name, std::make_unique<ContourKernel>(builder.setup().gbuffer, settings));
    };
    type.describe = describeDepthJump;
    return type;
}

} // namespace inkgraph
