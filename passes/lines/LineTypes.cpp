#include "passes/lines/LineTypes.h"

#include "passes/lines/LineLayerPass.h"

#include <algorithm>

namespace inkgraph {

// Each is defined in its room, passes/lines/types/<Name>Line.cpp.
LineType outlineLineType();
LineType silhouetteLineType();
LineType normalEdgeLineType();
LineType depthEdgeLineType();
LineType creaseLineType();
LineType borderLineType();
LineType materialBoundaryLineType();
LineType objectBoundaryLineType();
LineType suggestiveLineType();
LineType suggestiveObjectLineType();
LineType contourLineType();
LineType meshSilhouetteLineType();
LineType intersectionLineType();
LineType hiddenIntersectionLineType();
LineType hiddenSuggestiveObjectLineType();
LineType hiddenMeshSilhouetteLineType();
LineType hiddenCreaseLineType();
LineType hiddenBorderLineType();

const std::vector<LineType>& lineTypes() {
    // The composite order: later types are drawn over earlier ones. The hidden-lines types (LineType::hiddenLines)
    // come first, so every visible line is drawn over the dashed hidden ones (docs/lines.md, "Hidden lines").
    static const std::vector<LineType> kTypes = {
        // Hidden lines first: under every visible line.
        hiddenMeshSilhouetteLineType(),
        hiddenCreaseLineType(),
        hiddenBorderLineType(),
        hiddenIntersectionLineType(),
        hiddenSuggestiveObjectLineType(),
        outlineLineType(),
        silhouetteLineType(),
        normalEdgeLineType(),
        depthEdgeLineType(),
        creaseLineType(),
        borderLineType(),
        intersectionLineType(),
        materialBoundaryLineType(),
        objectBoundaryLineType(),
        suggestiveLineType(),
        suggestiveObjectLineType(),
        contourLineType(),
        meshSilhouetteLineType(),
    };
    return kTypes;
}

const LineType* findLineType(std::string_view name) {
    for (const LineType& type : lineTypes())
        if (type.name == name) return &type;
    return nullptr;
}

std::vector<const LineParameter*> lineParameters() {
    std::vector<const LineParameter*> parameters;
    for (const LineType& type : lineTypes())
        for (const LineParameter* parameter : type.parameters)
            if (std::find(parameters.begin(), parameters.end(), parameter) == parameters.end())
                parameters.push_back(parameter);
    return parameters;
}

std::vector<std::string> lineTypesUsing(const LineParameter* parameter) {
    std::vector<std::string> names;
    for (const LineType& type : lineTypes()) {
        const bool uses =
            parameter ? std::find(type.parameters.begin(), type.parameters.end(), parameter) != type.parameters.end()
                      : type.strokedOnCpu();
        if (uses) names.push_back(type.name);
    }
    return names;
}

bool LineGraphBuilder::has(std::string_view passName) const {
    auto named = [&](const auto& pass) { return pass->name() == passName; };
    return std::any_of(mPasses.begin(), mPasses.end(), named) || std::any_of(mLayers.begin(), mLayers.end(), named);
}

void LineGraphBuilder::add(std::unique_ptr<GlPass> pass) { mPasses.push_back(std::move(pass)); }

void LineGraphBuilder::addLayer(const std::string& type, std::unique_ptr<LineKernel> kernel, int divisor) {
    mLayers.push_back(std::make_unique<LineLayerPass>(type, std::move(kernel), mSetup.look.supersample, divisor));
}

std::map<std::string, LineLayerPass*> LineGraphBuilder::finish() {
    // The GL passes first, then the CPU layers, as the plan breaks ties by registration: GL work is queued before
    // the post stage reads anything back.
    std::map<std::string, LineLayerPass*> layers;
    for (std::unique_ptr<LineLayerPass>& layer : mLayers) {
        layers[std::string(layer->name())] = layer.get();
        mPasses.push_back(std::move(layer));
    }
    mLayers.clear();
    return layers;
}

} // namespace inkgraph
