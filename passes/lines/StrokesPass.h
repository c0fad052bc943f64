#pragma once
/** @file The stroke stage: every drawn line type's lines chained into strokes together (postfx/Strokes.h), the
 *  length rule and the hysteresis applied, line weight set, and each type's layer drawn from its kept strokes. The
 *  --svg paths come from the same strokes (strokes(), layers()), so the raster and the vector output match.
 *
 *  | resource         | format | need     | content                                                           |
 *  |------------------|--------|----------|-------------------------------------------------------------------|
 *  | reads            |        |          | each drawn type's "<type>.skeleton" (CPU types: its LineLayerPass) |
 *  |                  |        |          | or "<type>.lines" (GL-drawn bands, thinned to their middle here)  |
 *  |                  |        |          | "gbuffer.depth", only with line weight by depth                   |
 *  | <name>.<type>    | r8     | required | the type's line layer, frame-sized, 255 = full line, anti-aliased |
 *
 *  Where two types draw the same line (the contour along the outline's band), the type earlier in the composite's
 *  order draws it and the later one gives way there (mergeOverlaps()) when the look asks for it.
 *
 *  Everything is chained at the data resolution (--supersample S): a GL band, drawn at the output size, is thinned
 *  there and its middle line mapped up. Each layer is stroked at its type's width in output pixels and then
 *  area-downsampled, as every CPU line layer always was (strokeLines). */

#include "gl/GlPass.h"
#include "postfx/Strokes.h"
#include "postfx/SvgLines.h"

#include <string>
#include <vector>

namespace inkgraph {

class LineLayerPass;

/** One drawn type, as the stroke stage takes it. */
struct StrokeInput {
    std::string type;     ///< "contour": the output field and --svg layer
    std::string resource; ///< "contour.skeleton" or, for a GL band, "outline.lines"
    const LineLayerPass* layer =
        nullptr;               ///< the CPU layer that found the skeleton (its sub-pixel points); null: a band
    float widthPixels = 2.0f;  ///< output pixels
    double minLength = 0.0;    ///< share of the height a chain holding this type needs
    float seedStrength = 0.0f; ///< hysteresis (LineTypeStrokeRules)
};

struct StrokesPassSettings {
    std::vector<StrokeInput> inputs; ///< in composite order
    int supersample = 1;             ///< the data resolution's scale (Look::supersample)
    bool weightByDepth = false;      ///< reads "gbuffer.depth"; the width falls to half across the model's depth
    bool weightByStrength = false;
    bool taperEnds = false;
    bool mergeOverlaps = false;             ///< a later type is not drawn where an earlier one draws the same line
    double nearDepth = 0.0, farDepth = 0.0; ///< the model's nearest and farthest linear depth (its bounding sphere)
};

/** What the last execute() did, for --stats. */
struct StrokesReport {
    std::size_t chains = 0, strokes = 0, kept = 0, droppedShort = 0, droppedWeak = 0;
    std::size_t junctionJoins = 0, gapJoins = 0, crossTypeJoins = 0, absorbedFragments = 0, overlapStrokes = 0;
    double thinMilliseconds = 0.0, chainMilliseconds = 0.0, strokeMilliseconds = 0.0;
};

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

    /** --svg: each input type's kept strokes as a layer of polylines (in composite order), simplified to within
     *  `tolerancePixels` output pixels; with line weight, each vertex's width. Valid after execute(). */
    std::vector<SvgLineLayer> svgLayers(double tolerancePixels, const std::vector<std::array<double, 4>>& colors) const;
    const Strokes& strokes() const { return mStrokes; }
    const StrokesPassSettings& settings() const { return mSettings; }
    const StrokesReport& report() const { return mReport; }

private:
    std::string mName;
    StrokesPassSettings mSettings;
    Strokes mStrokes;
    StrokesReport mReport;
};

} // namespace inkgraph
