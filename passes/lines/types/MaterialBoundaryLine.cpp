// material-boundary and object-boundary: where the visible material or object changes (Pencil+'s material and object
// lines, Blender Freestyle's material boundaries), found in one G-buffer id field each by one kernel
// (postfx/MaterialBoundaries.h) and stroked at a constant width. The two differ only in the field they read.
#include "passes/lines/LineType.h"
#include "postfx/MaterialBoundaries.h"

#include <nlohmann/json.hpp>

namespace inkgraph {
namespace {

class IdBoundaryKernel : public LineKernel {
public:
    /** `field`: the G-buffer field of ids, "materialId" or "objectId". */
    IdBoundaryKernel(std::string gbuffer, std::string field) : mGBuffer(std::move(gbuffer)), mField(std::move(field)) {}
    std::vector<std::string> inputs() const override { return {mGBuffer + "." + mField}; }
    LineSkeleton find(const std::vector<cv::Mat>& inputs) override { return extractIdBoundaries(inputs[0], mField); }

private:
    std::string mGBuffer;
    std::string mField;
};

LineType idBoundaryLineType(std::string name, std::string field, std::string help) {
    LineType type;
    type.name = std::move(name);
    type.help = std::move(help);
    type.build = [field](const std::string& layer, LineGraphBuilder& builder) {
        builder.addLayer(layer, std::make_unique<IdBoundaryKernel>(builder.setup().gbuffer, field));
    };
    type.describe = [](const LineStatsSource& source, nlohmann::ordered_json& entry) {
        entry["supersample"] = source.look.supersample;
    };
    return type;
}

} // namespace

LineType materialBoundaryLineType() {
    return idBoundaryLineType("material-boundary", "materialId",
                              "where the visible material changes between two surfaces of the model\n"
                              "(its material name, colour or shade map), as Pencil+ and Freestyle draw them");
}

LineType objectBoundaryLineType() {
    // Objects are node instances (scene/ObjectIds.h); like material-boundary, nothing is drawn against the
    // background, where the contour is.
    return idBoundaryLineType("object-boundary", "objectId",
                              "where the visible object (glTF node instance) changes between two surfaces of the\n"
                              "model, even of one material, as Pencil+'s object lines");
}

} // namespace inkgraph
