// material-boundary: where the visible material changes (Pencil+'s and Blender Freestyle's material boundary lines),
// found in the G-buffer's material ids (postfx/MaterialBoundaries.h) and stroked at a constant width.
#include "passes/lines/LineType.h"
#include "postfx/MaterialBoundaries.h"

namespace inkgraph {
namespace {

class MaterialBoundaryKernel : public LineKernel {
public:
    explicit MaterialBoundaryKernel(std::string gbuffer) : mGBuffer(std::move(gbuffer)) {}
    std::vector<std::string> inputs() const override { return {mGBuffer + ".materialId"}; }
    LineSkeleton find(const std::vector<cv::Mat>& inputs) override { return extractMaterialBoundaries(inputs[0]); }

private:
    std::string mGBuffer;
};

} // namespace

LineType materialBoundaryLineType() {
    LineType type;
    type.name = "material-boundary";
    type.help = "where the visible material changes between two surfaces of the model\n"
                "(its material name, colour or shade map), as Pencil+ and Freestyle draw them";
    type.build = [](const std::string& name, LineGraphBuilder& builder) {
        builder.addLayer(name, std::make_unique<MaterialBoundaryKernel>(builder.setup().gbuffer));
    };
    type.describe = [](const LineStatsSource& source, nlohmann::ordered_json& entry) {
        entry["supersample"] = source.look.supersample;
    };
    return type;
}

} // namespace inkgraph
