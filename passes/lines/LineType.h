#pragma once
/** @file A line type: one entry of the registry (passes/lines/LineTypes.h) that says everything about it: its name,
 *  family and --help text, its parameters, the passes that find its lines, what it reports to --stats, and how
 *  --svg traces it. The command line, style files, the still graph, the composite, the stats and the SVG writer all
 *  iterate the registry, so a new line type is one function in passes/lines/types/ and its registration in
 *  LineTypes.cpp (docs/contributing.md). */

#include "gl/GlPass.h"
#include "passes/Look.h"
#include "passes/lines/LineKernel.h"
#include "passes/lines/LineLayerPass.h"
#include "passes/lines/LineParameter.h"
#include "scene/Camera.h"

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace inkgraph {

class GpuScene;
class ShaderLibrary;
struct FrameParams;

/** Where a line type's lines come from. Every family but GlDrawn finds a one-pixel skeleton at the data resolution
 *  (--supersample) and strokes it on the CPU (LineLayerPass); GlDrawn types are bands GL draws at the output size. */
enum class LineFamily {
    GlDrawn,     ///< drawn by a GL pass at the output size (outline, silhouette)
    ImageSpace,  ///< found by a postfx kernel in the G-buffer
    MeshEdge,    ///< mesh edges GL draws as a one-pixel skeleton (the shared "mesh-edges" pass)
    ObjectSpace, ///< found on the mesh on the CPU, projected, hidden with the G-buffer depth
};

/** What every line type's passes are built from; every reference outlives the graph. */
struct LineGraphSetup {
    const Look& look;
    ShaderLibrary& shaders;
    GpuScene& scene;
    const FrameParams& frame;
    BoundingSphere sphere;
    std::string gbuffer = "gbuffer"; ///< the G-buffer pass's name: fields are "<gbuffer>.<field>"
    /** The model's depth a GL-drawn band may test against instead of drawing its own, when its writer runs anyway
     *  ("gbuffer.zBuffer"), or empty when the G-buffer's z-buffer cannot stand for it (HullSettings::modelDepth). */
    std::string modelDepth{};
    /** Where the image-space kernels run (Cpu or Gpu, resolved: passes/PostStage.h); a type without a GPU kernel
     *  runs on the CPU either way. */
    PostStageDevice postStage = PostStageDevice::Cpu;
};

/** Hands a line type's build() the setup and the graph's pass list. */
class LineGraphBuilder {
public:
    LineGraphBuilder(const LineGraphSetup& setup, std::vector<std::unique_ptr<GlPass>>& passes)
        : mSetup(setup), mPasses(passes) {}
    const LineGraphSetup& setup() const { return mSetup; }
    const Look& look() const { return mSetup.look; }
    /** Whether a pass of that name is registered already (a pass several types share is added once). */
    bool has(std::string_view passName) const;
    /** A GL pass, registered at once: every type's GL passes come before every CPU line layer. */
    void add(std::unique_ptr<GlPass> pass);
    /** The usual ending: a LineLayerPass named `type` that runs `kernel` and strokes its skeleton at the type's width;
     *  `divisor` above 1 when the kernel reads a field coarser than the data (TextureDesc::divisor).
     *  Registered by finish(), after the GL passes of every type. */
    void addLayer(const std::string& type, std::unique_ptr<LineKernel> kernel, int divisor = 1);
    /** Registers the layers in the order they were added; returns them by type (for the stats and the SVG). */
    std::map<std::string, LineLayerPass*> finish();

private:
    const LineGraphSetup& mSetup;
    std::vector<std::unique_ptr<GlPass>>& mPasses;
    std::vector<std::unique_ptr<LineLayerPass>> mLayers; ///< addLayer()'s, until finish()
};

/** What a line type's describe() sees after the run. */
struct LineStatsSource {
    const Look& look;
    BoundingSphere sphere;
    double radialLengthUnit = 1.0; ///< FrameParams::radialLengthUnit: the G-buffer's radial field's length unit
    /** A registered pass by name (what it did: Pass::describe()), or null. */
    std::function<const Pass*(std::string_view)> pass;
};

/** A line type's own stroke rules beyond the look's (postfx/Strokes.h). */
struct LineTypeStrokeRules {
    float seedStrength = 0.0f; ///< hysteresis: a chain needs a point of this type this strong; 0: every point seeds
    /** A GL band of one width everywhere (bandWidthPixels() of the type's width; no width map, no width in model
     *  units): the stroke stage opens away its slivers thinner than bandOpeningPixels() before thinning it. */
    bool bandOfOneWidth = false;
    /** A GL band whose width is the line's own, in model units (--silhouette-object-width), not bandWidthPixels() of
     *  the type's width times a width map: the stroke stage draws it as wide as it is. */
    bool bandWidthInModelUnits = false;
};

struct LineType {
    std::string name; ///< "contour": --lines contour, --contour-width, lines-contour.png
    LineFamily family = LineFamily::ImageSpace;
    std::string help;                             ///< --help, after "<name>: "; '\n' breaks a help line
    std::vector<const LineParameter*> parameters; ///< settings besides width and colour, each --<name> and a style name
    /** Registers the passes that find its lines: a GL-drawn type's pass writes "<name>.lines" (r8, frame-sized, 255 =
     *  line), a CPU type's layer (addLayer()) "<name>.skeleton"; the stroke stage draws either as "strokes.<name>".
     *  Called for every registered type: the compiler culls the ones not drawn, and --stats says so. */
    std::function<void(const std::string& type, LineGraphBuilder& builder)> build;
    /** Adds its settings and what it did to its entry of --stats look.lines (after type, width and colour). */
    std::function<void(const LineStatsSource& source, nlohmann::ordered_json& entry)> describe;
    /** Its stroke rules (a seed strength), from the look; not set: the look's rules alone. */
    std::function<LineTypeStrokeRules(const Look& look)> strokeRules;

    /** Draws the occluded part of another type's lines (`hidden-<type>`, --hidden-lines): its strokes are dashed by
     *  --hidden-dash, in the raster and in the SVG. */
    bool hiddenLines = false;

    /** --strokes (passes/lines/StrokePoints.h): the image of this type's line fragments' view positions and
     *  triangles its 3-D points come from (the mesh edges' "mesh-edges.<kind>-points"); empty for the others, whose
     *  family says where (the skeleton's own points in object space, else the G-buffer's depth). */
    std::string strokePointsImage;

    /** Found as a skeleton at the data resolution (so --supersample applies, and --svg traces the skeleton). */
    bool strokedOnCpu() const { return family != LineFamily::GlDrawn; }
};

} // namespace inkgraph
