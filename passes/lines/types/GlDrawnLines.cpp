// The two line types GL draws at the output size: the outline (after Lander's back faces) and the inflated hull.
#include "passes/lines/LineType.h"
#include "passes/outline/OutlinePass.h"
#include "passes/silhouette/SilhouettePass.h"

#include <nlohmann/json.hpp>

#include <limits>

namespace inkgraph {
namespace {

/** The GL passes say whether they skipped the frame (the eye inside the model would flood the picture), and the
 *  silhouette where its model depth came from. */
void describeSkipped(const LineStatsSource& source, const std::string& passName, nlohmann::ordered_json& entry) {
    if (const Pass* pass = source.pass(passName)) {
        nlohmann::ordered_json report;
        pass->describe(report);
        for (const char* key : {"skipped_eye_inside", "model_depth", "width_map"})
            if (report.contains(key)) entry[key] = report[key];
    }
}

const LineParameter kSilhouetteObjectWidth{
    "silhouette-object-width",
    "D",
    "offset the hull by D model units instead (the width then shrinks with distance)",
    {},
    std::nullopt,
    "",
    // Inside what the shaders' float holds: 1e-46 became 0 there (no silhouette, without a word) and 3.5e38
    // infinity (an internal error).
    1e-37,
    1e38,
    false,
    false,
    "model units must lie from 1e-37 to 1e38 (what the shaders' float holds)"};

/** The stroke rules of a band: of one width unless --outline-width-map (or, for the silhouette, a width in model units)
 *  makes its width vary, where opening it would cut its thin parts. */
LineTypeStrokeRules bandRules(const Look& look, bool objectWidth) {
    LineTypeStrokeRules rules;
    rules.bandOfOneWidth = !look.outlineWidthMap.enabled() && !objectWidth;
    rules.bandWidthInModelUnits = objectWidth;
    return rules;
}

} // namespace

LineType outlineLineType() {
    LineType type;
    type.name = "outline";
    type.family = LineFamily::GlDrawn;
    type.help = "the mesh's contour and border edges as wide bands on their outer side, where\n"
                "the model does not hide them (after Lander 2000's back faces)";
    type.build = [](const std::string& name, LineGraphBuilder& builder) {
        const LineGraphSetup& setup = builder.setup();
        builder.add(std::make_unique<OutlinePass>(name, setup.shaders, setup.scene, setup.frame,
                                                  float(setup.look.styleOf(name).widthPixels),
                                                  setup.look.outlineWidthMap));
    };
    type.describe = [](const LineStatsSource& source, nlohmann::ordered_json& entry) {
        describeSkipped(source, "outline", entry);
    };
    type.strokeRules = [](const Look& look) { return bandRules(look, false); };
    return type;
}

LineType silhouetteLineType() {
    LineType type;
    type.name = "silhouette";
    type.family = LineFamily::GlDrawn;
    type.help = "the inflated hull (Qu, Chen & Zwicker), offset along position-welded smooth\n"
                "normals so hard edges do not crack it";
    type.parameters = {&kSilhouetteObjectWidth};
    type.build = [](const std::string& name, LineGraphBuilder& builder) {
        const LineGraphSetup& setup = builder.setup();
        HullSettings hull;
        hull.widthPixels = float(setup.look.styleOf(name).widthPixels);
        if (auto width = setup.look.lineParameters.numberIfSet(kSilhouetteObjectWidth))
            hull.objectWidth = float(*width);
        hull.modelDepth = setup.modelDepth;
        hull.widthMap = setup.look.outlineWidthMap;
        builder.add(std::make_unique<SilhouettePass>(name, setup.shaders, setup.scene, setup.frame, hull));
    };
    type.describe = [](const LineStatsSource& source, nlohmann::ordered_json& entry) {
        if (auto width = source.look.lineParameters.numberIfSet(kSilhouetteObjectWidth)) entry["object_width"] = *width;
        describeSkipped(source, "silhouette", entry);
    };
    type.strokeRules = [](const Look& look) {
        return bandRules(look, look.lineParameters.numberIfSet(kSilhouetteObjectWidth).has_value());
    };
    return type;
}

} // namespace inkgraph
