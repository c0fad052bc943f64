#pragma once
/** @file The passes of one still, registered in a fixed order. Every pass is registered; the compiler culls what
 *  the request does not need, so --stats can say why a pass did not run. Shared by the CLI and the benchmarks. */

#include "app/Options.h"
#include "gl/ShaderLibrary.h"
#include "graph/Pass.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/orientation/SceneOrientation.h"
#include "passes/shade/ShadeMap.h"
#include "scene/Scene.h"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace inkgraph {

class LineLayerPass;
class MeshEdgesPass;
class OutlinePass;
class SilhouettePass;

/** The feature size fs that makes the suggestive strength dimensionless, as a fraction of the bounding radius
 *  (rtsc's upper bound on fs). */
constexpr double kSuggestiveFeatureSizeFraction = 0.05;

/** What buildStillGraph() needs; every reference must outlive the graph. */
struct StillGraphSetup {
    const RenderOptions& options;
    ShaderLibrary& shaders;
    const Scene& scene;
    BoundingSphere sphere;
    GpuScene& gpuScene;
    const FrameParams& frame;
    std::optional<ShadeMap> shadeMap; ///< --shademap as read; empty: the built-in map of the mode
    /** Per scene mesh, the map it names itself (readSceneShadeMaps()); empty entries use `shadeMap`. Only cel and
     *  comic use them. */
    std::vector<std::optional<ShadeMap>> meshShadeMaps{};
};

struct StillGraph {
    /** Declared before the passes, which point at it, so it is destroyed after them. */
    std::unique_ptr<SceneOrientation> orientation;
    std::vector<std::unique_ptr<Pass>> passes;
    std::string shadingResource; ///< the colour the composite reads ("shade.color"), or empty for --shading none
    std::string shadeMapSource;  ///< the shade map's ShadeMap::source ("builtin:bands-5", a path), or empty
    /** Mesh name -> ShadeMap::source for each mesh drawn with its own map (cel, comic), in scene order, for --stats. */
    std::vector<std::pair<std::string, std::string>> meshShadeMapSources;
    std::string finalResource = "composite.final";
    double radialLengthUnit = 1.0; ///< the G-buffer's radial field's length unit (model units), for --stats
    OutlinePass* outline = nullptr;       ///< for --stats
    SilhouettePass* silhouette = nullptr; ///< for --stats
    MeshEdgesPass* meshEdges = nullptr;   ///< for --stats
    std::map<std::string, LineLayerPass*> lineLayers; ///< the CPU line passes by line type, for --stats

    std::vector<const Pass*> view() const;
    std::vector<Pass*> mutableView() const;
};

StillGraph buildStillGraph(const StillGraphSetup& setup);

/** "gbuffer.*" -> every field the pass "gbuffer" declares; other names pass through for compile() to check. Throws
 *  UsageError for a wildcard on a pass the graph does not have. */
std::vector<std::string> expandWildcards(const std::vector<std::string>& requests, const StillGraph& graph);

} // namespace inkgraph
