#pragma once
/** @file The stroke stage: every drawn line type's lines chained into strokes together (postfx/Strokes.h), the
 *  length rule and the hysteresis applied, line weight set, and each type's layer drawn from its kept strokes. The
 *  --svg paths come from the same strokes (handed on as "<name>.paths", svgLayersOf()), so the raster and the vector
 * output match.
 *
 *  | resource         | format | need     | content                                                           |
 *  |------------------|--------|----------|-------------------------------------------------------------------|
 *  | reads            |        |          | each drawn type's "<type>.skeleton" (a line-skeleton object, with  |
 *  |                  |        |          | its sub-pixel points) or "<type>.lines" (GL-drawn bands, r8,       |
 *  |                  |        |          | thinned to their middle here); the depth, only with line weight    |
 *  |                  |        |          | by depth (StrokesPassSettings::depthResource)                      |
 *  | <name>.<type>    | r8     | required | the type's line layer, frame-sized, 255 = full line, anti-aliased |
 *  | <name>.paths     | object | optional | "drawn-strokes" (DrawnStrokes): the kept strokes, for --svg        |
 *
 *  Where two types draw the same line (the contour along the outline's band), the type earlier in the composite's
 *  order draws it and the later one gives way there (mergeOverlaps()) when the look asks for it.
 *
 *  Everything is chained at the data resolution (--supersample S) on one-pixel skeletons: a kernel's skeleton is
 *  thinned where it marked a line two pixels wide, and a GL band, drawn at the output size, is thinned there and
 *  its middle line mapped up. Each layer is stroked at its type's width in output pixels and then
 *  area-downsampled, as every CPU line layer always was (strokeLines). */

#include "gl/GlPass.h"
#include "postfx/StrokeDashes.h"
#include "postfx/Strokes.h"
#include "postfx/SvgLines.h"

#include <string>
#include <vector>

namespace inkgraph {

/** The object type of the stroke stage's strokes in the graph. */
inline constexpr const char* kDrawnStrokesType = "drawn-strokes";
/** The stroke stage's output field of its strokes: "<name>.paths". */
inline constexpr const char* kStrokePathsField = "paths";

/** One drawn type, as the stroke stage takes it. */
struct StrokeInput {
    std::string type;          ///< "contour": the output field and --svg layer
    std::string resource;      ///< "contour.skeleton" or, for a GL band, "outline.lines"
    bool skeleton = true;      ///< `resource` is a line-skeleton object (LineLayerPass); false: an r8 band to thin
    float widthPixels = 2.0f;  ///< output pixels
    double minLength = 0.0;    ///< share of the height a chain holding this type needs
    float seedStrength = 0.0f; ///< hysteresis (LineTypeStrokeRules)
    /** A GL band of one width (LineTypeStrokeRules::bandOfOneWidth): opened by bandOpeningPixels() before thinning. */
    bool bandOfOneWidth = false;
    /** A GL band of varying width that is the line's own width (LineTypeStrokeRules::bandWidthInModelUnits); the
     *  others vary as bandWidthPixels() of `widthPixels` times a width map. */
    bool bandWidthInModelUnits = false;
    /** A hidden-lines type (LineType::hiddenLines): its kept strokes are cut into StrokesPassSettings::dash's dashes,
     *  in its layer and its --svg paths alike; with mergeOverlaps it gives way only to other dashed types. */
    bool dashed = false;
};

struct StrokesPassSettings {
    std::vector<StrokeInput> inputs; ///< in composite order
    int supersample = 1;             ///< the data resolution's scale (Look::supersample)
    bool weightByDepth = false;      ///< reads depthResource; the width falls to half across the model's depth
    std::string depthResource;       ///< the linear depth at the data resolution ("gbuffer.depth"), for weightByDepth
    bool weightByStrength = false;
    bool taperEnds = false;
    bool mergeOverlaps = false;             ///< a later type is not drawn where an earlier one draws the same line
    double nearDepth = 0.0, farDepth = 0.0; ///< the model's nearest and farthest linear depth (its bounding sphere)
    /** The dashed inputs' pattern in output pixels (--hidden-dash); scaled to data pixels by `supersample`. */
    DashPattern dash;
};

/** What the last execute() did, for --stats. */
struct StrokesReport {
    std::size_t chains = 0, strokes = 0, kept = 0, droppedShort = 0, droppedWeak = 0;
    std::size_t junctionJoins = 0, gapJoins = 0, crossTypeJoins = 0, absorbedFragments = 0, overlapStrokes = 0;
    double thinMilliseconds = 0.0, chainMilliseconds = 0.0, strokeMilliseconds = 0.0;
    std::vector<std::size_t> keptPerInput;  ///< per input, strokes kept
    std::vector<std::size_t> foundPerInput; ///< per input, strokes chained, kept or not
    /** Per input, strokes dropped by the length rule, and (long enough) by the hysteresis: what lines-empty blames on
     *  --min-stroke-length or a seed setting (StillGraph::emptyLineWarnings()). */
    std::vector<std::size_t> droppedShortPerInput, droppedWeakPerInput;
    std::vector<double> lengthPixelsPerInput; ///< per input, their length in output pixels
    std::vector<std::size_t> dashesPerInput;  ///< per input, the dashes its kept strokes were cut into (0: solid)
    /** Per input, strokes decided within kNearLimitShare of the length rule's or the seed rule's limit
     *  (strokesNearLimits()): the ones that may flip between sizes or views. */
    std::vector<std::size_t> nearLengthLimitPerInput, nearSeedLimitPerInput;
};

/** The kept strokes as the graph hands them on ("<name>.paths"): what --svg traces, so the raster and the vector
 *  output match. */
struct DrawnStrokes {
    Strokes strokes;
    std::vector<StrokeInput> inputs; ///< in composite order: a stroke's layer indexes it
    int supersample = 1;
    bool weighted = false; ///< line weight by depth, strength or tapering: each vertex has its width
};

/** --svg: each input type's kept strokes as a layer of polylines (in composite order), simplified to within
 *  `tolerancePixels` output pixels; with line weight, each vertex's width. `colors`: one per input. */
std::vector<SvgLineLayer> svgLayersOf(const DrawnStrokes& drawn, double tolerancePixels,
                                      const std::vector<std::array<double, 4>>& colors);

class StrokesPass : public GlPass {
public:
    /** Throws std::invalid_argument for no inputs, a non-positive or non-finite width, a negative length or a seed
     *  outside [0, 1], naming the type. */
    StrokesPass(std::string name, StrokesPassSettings settings);

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    void execute(GlPassContext& context) override;
    /** post_stage.strokes: counts (chains, strokes kept, dropped by the length rule and by the hysteresis, joins by
     *  kind), lengths in output pixels and milliseconds. */
    void describe(nlohmann::ordered_json& report) const override;

    const StrokesPassSettings& settings() const { return mSettings; }
    const StrokesReport& report() const { return mReport; }

private:
    /** --overlapping-lines merge: mergeOverlaps() over the dashed inputs and over the others, apart. */
    void mergeOverlapsWithinKind(Strokes& strokes, const std::vector<StrokeLayer>& layers,
                                 const std::vector<float>& drawnWidths) const;
    /** The kept strokes' counts and lengths per input, into mReport. */
    void reportKept(const Strokes& strokes, const std::vector<StrokeLayer>& layers);

    std::string mName;
    StrokesPassSettings mSettings;
    StrokesReport mReport;
};

} // namespace inkgraph
