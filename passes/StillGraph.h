#pragma once
/** @file The passes of one still, registered in a fixed order from a Look: the G-buffer, the shading model's pass,
 *  every line type of the registry (passes/lines/LineTypes.h), the composite. Every pass is registered; the compiler
 *  culls what the request does not need, so --stats can say why a pass did not run. The shade pass shades the
 *  G-buffer instead of the meshes when the look's lines make the G-buffer run anyway, as one compile decides
 *  (compilePlan(), ShadePass::forwardReason()). The
 * graph also describes itself for --stats and traces its line layers for --svg, so the app names no pass type. Shared
 * by the renderer (render/StillRenderer.h), the benchmarks and the tests. */

#include "gl/GraphExecutor.h"
#include "gl/ShaderLibrary.h"
#include "gl/GlPass.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/Look.h"
#include "passes/lines/StrokePoints.h"
#include "passes/shade/ShadeMap.h"
#include "postfx/SvgLines.h"
#include "scene/Scene.h"

#include <nlohmann/json_fwd.hpp>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace inkgraph {

class LineLayerPass;
class ShadePass;
class StrokesPass;

/** Names of passes whose outputs are named outside the graph (the library's buffer names, api/): the G-buffer's fields
 *  are "gbuffer.<field>", each drawn line type's layer is "strokes.<type>". */
inline constexpr const char* kGBufferPass = "gbuffer";
inline constexpr const char* kStrokesPass = "strokes";

/** What buildStillGraph() needs; every reference must outlive the graph. */
struct StillGraphSetup {
    const Look& look;
    ShaderLibrary& shaders;
    const Scene& scene;
    BoundingSphere sphere;
    GpuScene& gpuScene;
    const FrameParams& frame;
    std::optional<ShadeMap> shadeMap; ///< --shademap as read; empty: the built-in map of the model
    /** Per scene mesh, the map it names itself (render/SceneShadeMaps.h); empty entries use `shadeMap`. Only the models
     *  with a shade map use them. */
    std::vector<std::optional<ShadeMap>> meshShadeMaps{};
    /** Let the shade pass shade the G-buffer when it runs anyway (deferred); off, it always draws the meshes (the
     *  tests and benchmarks that compare the two). */
    bool allowDeferredShading = true;
    /** The GL context's GL_RENDERER, which --post-stage auto decides by (passes/PostStage.h); empty when the graph is
     *  built before there is a context (auto then takes the CPU). */
    std::string glRenderer{};
};

class StillGraph {
public:
    std::vector<std::unique_ptr<GlPass>> passes;
    std::string shadingResource; ///< the colour the composite reads ("shade.color"), or empty for --shading none
    std::string shadeMapSource;  ///< the shade map's ShadeMap::source ("builtin:bands-5", a path), or empty
    /** The model the shade pass runs: the look's, with auto resolved for the scene (shadingModelFor()). */
    ShadingModel shadingModel = ShadingModel::None;
    /** Mesh name -> ShadeMap::source for each mesh drawn with its own map, in scene order, for --stats. */
    std::vector<std::pair<std::string, std::string>> meshShadeMapSources;
    std::string finalResource = "composite.final";
    /** Where the image-space line kernels run: the look's --post-stage, auto resolved (resolvePostStage()). */
    PostStageDevice postStageDevice = PostStageDevice::Cpu;

    std::vector<const Pass*> view() const;
    std::vector<GlPass*> mutableView() const;
    /** The registered pass of that name, or null. */
    const Pass* findPass(std::string_view name) const;

    /** Compiles the graph for `requested` (the final picture and what the caller keeps), deciding what depends on
     *  what runs anyway (deferred shading, the silhouette's depth) for the final picture alone: a --request of a
     *  G-buffer field does not change how the still is drawn (graph/GraphCompiler.h). */
    Plan compilePlan(const std::vector<std::string>& requested) const;
    /** "deferred" (the shade pass shades the G-buffer the lines need anyway, as `plan` has it), "forward", or empty
     *  for --shading none. */
    std::string shadingModeIn(const Plan& plan) const;
    /** Why `plan` shades forward ("no line type reads the G-buffer"), for --stats; empty when deferred. */
    std::string shadingForwardReasonIn(const Plan& plan) const;
    /** --print-plan's line on shading: "shading: deferred\n", "shading: forward (<why>)\n", or empty without a shade
     *  pass. */
    std::string describeShading(const Plan& plan) const;
    /** --stats look.lines: one entry per drawn type in composite order, with its style and what its type reports. */
    nlohmann::ordered_json describeLines() const;
    /** What the line passes that ran had to say, after a run: a lines-skipped warning for each drawn type that left
     *  this view out (its describeLines() entry says "skipped_eye_inside"), so neither an empty picture nor --strict
     *  passes over it in silence. */
    std::vector<Warning> lineWarnings() const;
    /** After the post stage: a lines-empty warning for each drawn type the picture shows nothing of because of a
     *  setting the user gave: its colour's alpha is 0; --min-stroke-length dropped every stroke it had as too short,
     *  or its seed setting every one as too weak; or, at parameters of its own given, it found none (not said for a
     *  hidden-lines type, whose emptiness is the view's). An empty type at the defaults is the model's (a sphere has
     *  no creases) and is not said. */
    std::vector<Warning> emptyLineWarnings() const;
    /** --stats post_stage: the device the image-space kernels ran on ("device", and "requested": the flag's word),
     *  what each CPU line layer that ran found and where its time went; "kernels_ms" is the post
     *  stage proper (finding and stroking, without bringing the G-buffer to the CPU), "composite_ms" follows it. */
    nlohmann::ordered_json describePostStage(const std::vector<PassTiming>& timings) const;
    /** The stroke stage's kept strokes ("strokes.paths", a drawn-strokes object), which --svg requests; empty when no
     *  line is drawn. */
    std::string strokePathsResource() const;
    /** --svg: each drawn type's kept strokes as simplified polylines (to within `tolerancePixels` output pixels),
     *  in composite order: the strokes the line layers were drawn from, as `store` holds them after a plan that
     *  requested strokePathsResource(). Empty when no line is drawn. */
    std::vector<SvgLineLayer> svgLayers(ResourceStore& store, double tolerancePixels) const;
    /** --strokes: what strokeRecords() reads, for the plan to compute and keep: the kept strokes, the G-buffer's depth
     *  and triangle ids, each object-space type's skeleton and each mesh-edge type's
     *  point image. Empty when no line is drawn. */
    std::vector<std::string> strokePointResources() const;
    /** --strokes: every kept stroke with its points' 3-D points (passes/lines/StrokePoints.h), from `store` after a
     *  plan that requested strokePointResources(). Empty when no line is drawn. */
    std::vector<StrokeRecord> strokeRecords(ResourceStore& store, const Camera& camera, const Scene& scene) const;
    /** The stroke stage, or null when no line type is drawn. */
    const StrokesPass* strokes() const { return mStrokes; }
    /** The CPU line layer of `type` (what its last run did: report(), kernel(); its skeleton is the graph's
     *  "<type>.skeleton"), or null for GL-drawn types. */
    const LineLayerPass* lineLayer(const std::string& type) const;

private:
    friend StillGraph buildStillGraph(const StillGraphSetup& setup);
    const Look* mLook = nullptr;
    BoundingSphere mSphere;
    double mRadialLengthUnit = 1.0;
    std::map<std::string, LineLayerPass*> mLineLayers; ///< the CPU line layers by type
    StrokesPass* mStrokes = nullptr;                   ///< the stroke stage, when a line type is drawn
    ShadePass* mShade = nullptr;                       ///< the shading model's pass, or null for --shading none
};

/** Builds the passes of `setup.look`. Changes nothing of `setup.gpuScene`: the scene data the passes import is
 *  configured where the GpuScene is made (makeSceneImport()) and derived by the executor's importer. */
StillGraph buildStillGraph(const StillGraphSetup& setup);

/** The face orientation `look` draws with: comic's CPU methods (Winnemöller & Bangay 2002), Standard for the others. */
OrientationSettings orientationSettingsOf(const Look& look);
/** The scene import of one still: its meshes and the data derived from them as `look` asks (its face orientation);
 *  `frame` must outlive it. `derived`: the view-independent data other stills of `scene` derived (GpuScene's
 *  constructor), or null. Throws std::invalid_argument for orientation settings out of range. */
std::unique_ptr<GpuScene> makeSceneImport(const Scene& scene, glm::dvec3 worldOrigin, const FrameParams& frame,
                                          const Look& look, std::shared_ptr<SceneDerivedData> derived = nullptr);

} // namespace inkgraph
