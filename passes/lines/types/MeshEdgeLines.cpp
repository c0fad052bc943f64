// The line types drawn from the mesh's own edges (Lander 2000; docs/lines.md): one GL pass, "mesh-edges",
// draws each kind's one-pixel skeleton where the model does not hide it; each type strokes its kind. The hidden-*
// types (--hidden-lines) stroke the same pass's hidden-<kind> outputs: the edges where the model hides them.
#include "passes/edges/MeshEdgesPass.h"
#include "passes/lines/LineType.h"

#include <nlohmann/json.hpp>

namespace inkgraph {
namespace {

constexpr const char* kMeshEdgesPass = "mesh-edges";

/** Crease prominence, decided on the mesh: dense geometric detail (fur, braids, a scan's facets) has many short
 *  creases; an artist draws the long ones. A share of the bounding radius, so the same edges at every size and view.
 *  The default 0.1 (measured on the bunny, armadillo, Lucy, fox, godette and fandisk: docs/lines.md) drops most
 *  fragments of scans and fur while every visible crease of the CAD part stays (at 0.2 fandisk lost a short one). */
const LineParameter kCreaseMinLength{"crease-min-length",
                                     "F",
                                     "draw a crease only where its mesh edges chain into a line (running on\n"
                                     "through a vertex where they turn least, at most 60 degrees) at least F x the\n"
                                     "model's bounding radius long in 3-D, so fur, braids and facets lose their\n"
                                     "short creases; the same at every size and view (default {default}; 0 keeps all)",
                                     {},
                                     0.1,
                                     "",
                                     0.0,
                                     100.0,
                                     false,
                                     false,
                                     "expected a share of the bounding radius from 0 to 100"};

/** Strokes a one-pixel mask another pass drew. */
class SkeletonKernel : public LineKernel {
public:
    explicit SkeletonKernel(std::string resource) : mResource(std::move(resource)) {}
    std::vector<std::string> inputs() const override { return {mResource}; }
    LineSkeleton find(const std::vector<cv::Mat>& inputs) override { return skeletonFromMask(inputs[0]); }

private:
    std::string mResource;
};

/** A type that strokes the mesh-edges pass's output `kind` ("crease", "hidden-crease"). */
LineType meshEdgeType(std::string name, std::string kind, std::string help,
                      std::vector<const LineParameter*> parameters) {
    LineType type;
    type.hiddenLines = kind.rfind("hidden-", 0) == 0;
    type.strokePointsImage = std::string(kMeshEdgesPass) + "." + kind + MeshEdgesPass::kPointsSuffix;
    type.name = std::move(name);
    type.family = LineFamily::MeshEdge;
    type.help = std::move(help);
    type.parameters = std::move(parameters);
    type.build = [kind](const std::string& typeName, LineGraphBuilder& builder) {
        const LineGraphSetup& setup = builder.setup();
        if (!builder.has(kMeshEdgesPass)) {
            MeshEdgesSettings settings;
            settings.creaseAngleDegrees = float(setup.look.lineParameters.number(line_parameters::kCreaseAngle));
            settings.creaseMinLength = float(setup.look.lineParameters.number(kCreaseMinLength) * setup.sphere.radius);
            settings.supersample = setup.look.supersample;
            builder.add(
                std::make_unique<MeshEdgesPass>(kMeshEdgesPass, setup.shaders, setup.scene, setup.frame, settings));
        }
        builder.addLayer(typeName, std::make_unique<SkeletonKernel>(std::string(kMeshEdgesPass) + "." + kind));
    };
    type.describe = [kind](const LineStatsSource& source, nlohmann::ordered_json& entry) {
        if (kind == "crease" || kind == "hidden-crease") {
            entry["crease_angle_degrees"] = source.look.lineParameters.number(line_parameters::kCreaseAngle);
            entry["crease_min_length"] = source.look.lineParameters.number(kCreaseMinLength);
        }
        entry["supersample"] = source.look.supersample;
        if (const Pass* pass = source.pass(kMeshEdgesPass)) {
            nlohmann::ordered_json report;
            pass->describe(report);
            if (report.contains("edges_drawn") && report["edges_drawn"].contains(kind))
                entry["edges_drawn"] = report["edges_drawn"][kind];
            if ((kind == "crease" || kind == "hidden-crease") && report.contains("crease_edges"))
                entry["crease_edges"] = report["crease_edges"];
        }
    };
    return type;
}

} // namespace

LineType creaseLineType() {
    return meshEdgeType("crease", "crease", "mesh edges whose faces meet at more than --crease-angle (object space)",
                        {&line_parameters::kCreaseAngle, &kCreaseMinLength});
}

LineType borderLineType() {
    return meshEdgeType("border", "border", "open (and non-manifold) mesh edges (object space)", {});
}

LineType meshSilhouetteLineType() {
    return meshEdgeType("mesh-silhouette", "silhouette",
                        "mesh edges between a front and a back face (exact perspective test)", {});
}

// The occluded parts of the three kinds (--hidden-lines; docs/lines.md "Hidden lines"): the same edges, the same
// parameters, drawn where the fragment shader's depth test fails.
LineType hiddenCreaseLineType() {
    return meshEdgeType("hidden-crease", "hidden-crease",
                        "the parts of crease the model hides (--hidden-lines crease), dashed",
                        {&line_parameters::kCreaseAngle, &kCreaseMinLength});
}

LineType hiddenBorderLineType() {
    return meshEdgeType("hidden-border", "hidden-border",
                        "the parts of border the model hides (--hidden-lines border), dashed", {});
}

LineType hiddenMeshSilhouetteLineType() {
    return meshEdgeType("hidden-mesh-silhouette", "hidden-silhouette",
                        "the parts of mesh-silhouette the model hides (--hidden-lines\n"
                        "mesh-silhouette), dashed",
                        {});
}

} // namespace inkgraph
