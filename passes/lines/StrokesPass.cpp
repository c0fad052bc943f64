#include "passes/lines/StrokesPass.h"

#include "gl/GraphExecutor.h"
#include "graph/Milliseconds.h"
#include "passes/LineMaskTarget.h"
#include "passes/lines/LineLayerPass.h"
#include "postfx/LineTracing.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace inkgraph {
namespace {

/** --stats counts the strokes decided within this share of a rule's limit (issue 39 asks for 10%). */
constexpr double kNearLimitShare = 0.1;
/** What the stage holds per data pixel while it runs, for one line type at a time: the pixel strengths and the kept
 *  widths (float each), the tracer's padded copies (2), the kept mask (1), and the stroke canvas and nearest-point
 *  ints (9); and until it ends, each type's thinned mask (a byte each; four counted, the comic look's types);
 *  the chains and the thinned skeletons' points stay until it ends, within the skeletons' own bytes. */
constexpr std::size_t kScratchBytesPerPixel = 24;
/** The kept strokes handed on for --svg: their points, within a skeleton's bytes. */
constexpr std::size_t kDrawnStrokesBytesPerPixel = 2;

/** Line weight's fixed shapes (docs/lines.md, "Line weight"). */
constexpr double kFarWidth = 0.5;      ///< the width at the far side of the model, as a share of the near side's
constexpr double kStrengthShare = 0.5; ///< a line of strength s is (0.5 + 0.5 s) wide
constexpr double kTaperLength = 0.03;  ///< the taper's length, a share of the height
constexpr double kTaperStart = 0.25;   ///< the width share at a stroke's very end

/** Data pixels (the frame at `dataScale`, --supersample) per pixel of `resource`, a skeleton or band at its own scale
 *  and divisor (TextureDesc). A resource whose pixels are not whole blocks of data pixels is a bug upstream. */
int dataPixelsPerPixelOf(const GlPassContext& gl, const std::string& resource, int dataScale) {
    const int divisor = gl.divisorOf(resource);
    const int numerator = dataScale * divisor;
    const int denominator = gl.scaleOf(resource);
    if (denominator < 1 || numerator % denominator != 0)
        throw std::logic_error("StrokesPass::execute(): '" + resource + "' is at " + std::to_string(denominator) + "/" +
                               std::to_string(divisor) + " of the frame, not a whole fraction of the data size (x" +
                               std::to_string(dataScale) + ")");
    return numerator / denominator;
}

/** Points either side of a stroke point whose band widths are averaged with its own: the band's edge is GL's
 *  rasterised trapezoids (the outline) or hull, a pixel ragged, which the widths read along the middle line would
 *  otherwise draw as blots. */
constexpr int kBandWidthSmoothingPoints = 3;

/** Each point of a stroke on a band of varying width (`bandWidths[layer]` not empty) takes the band's local width
 *  there, averaged over kBandWidthSmoothingPoints points either side, as its share of `drawnWidths[layer]`; a point
 *  off the band (a bridge across a gap) takes the previous point's. Whether any stroke lies on such a band. */
bool takeBandWidths(Strokes& strokes, const std::vector<StrokeLayer>& layers, const std::vector<cv::Mat1f>& bandWidths,
                    const std::vector<float>& drawnWidths) {
    bool any = false;
    for (Stroke& stroke : strokes.strokes) {
        const std::size_t layer = std::size_t(stroke.layer);
        if (layer >= bandWidths.size() || bandWidths[layer].empty() || stroke.points.empty()) continue;
        any = true;
        const cv::Mat1f& widths = bandWidths[layer];
        const double bandPixel = 1.0 / layers[layer].scale; // a band is at the output size, the points in data pixels
        std::vector<float> read(stroke.points.size());
        float last = drawnWidths[layer];
        for (std::size_t index = 0; index < stroke.points.size(); ++index) {
            const cv::Point2f& position = stroke.points[index].position;
            const int col = int(std::floor((double(position.x) + 0.5) * bandPixel));
            const int row = int(std::floor((double(position.y) + 0.5) * bandPixel));
            if (col >= 0 && row >= 0 && col < widths.cols && row < widths.rows && widths(row, col) > 0.0f)
                last = widths(row, col);
            read[index] = last;
        }
        const int count = int(read.size());
        for (int index = 0; index < count; ++index) {
            const int from = std::max(0, index - kBandWidthSmoothingPoints);
            const int to = std::min(count - 1, index + kBandWidthSmoothingPoints);
            float sum = 0.0f;
            for (int other = from; other <= to; ++other) sum += read[std::size_t(other)];
            const float width = sum / float(to - from + 1);
            stroke.points[std::size_t(index)].width = std::clamp(width / drawnWidths[layer], 0.02f, 1.0f);
        }
    }
    return any;
}

} // namespace

StrokesPass::StrokesPass(std::string name, StrokesPassSettings settings)
    : mName(std::move(name)), mSettings(std::move(settings)) {
    if (mSettings.inputs.empty()) throw std::invalid_argument("StrokesPass(): '" + mName + "' has no line types");
    if (mSettings.supersample < 1) throw std::invalid_argument("StrokesPass(): 'supersample' must be at least 1");
    if (mSettings.weightByDepth && mSettings.depthResource.empty())
        throw std::invalid_argument("StrokesPass(): '" + mName + "' weighs by depth but names no depth resource");
    for (const StrokeInput& input : mSettings.inputs) {
        if (!(std::isfinite(input.widthPixels) && input.widthPixels > 0.0f))
            throw std::invalid_argument("StrokesPass(): '" + input.type + "' width must be positive and finite");
        if (!(std::isfinite(input.minLength) && input.minLength >= 0.0))
            throw std::invalid_argument("StrokesPass(): '" + input.type + "' minimum length must be finite and >= 0");
        if (!(input.seedStrength >= 0.0f && input.seedStrength <= 1.0f))
            throw std::invalid_argument("StrokesPass(): '" + input.type + "' seed strength must lie in [0, 1]");
    }
    const DashPattern& dash = mSettings.dash;
    if (!(std::isfinite(dash.onPixels) && dash.onPixels > 0.0 && std::isfinite(dash.offPixels) &&
          dash.offPixels >= 0.0))
        throw std::invalid_argument("StrokesPass(): 'dash' needs a dash above 0 and a gap of 0 or more pixels");
}

void StrokesPass::declare(PassBuilder& builder) const {
    builder.runsOnHost(); // CPU work over read-back images: a batch runs it while the next still draws
    for (const StrokeInput& input : mSettings.inputs) {
        if (input.skeleton)
            builder.readObject(input.resource, kLineSkeletonType);
        else
            builder.read(input.resource);
    }
    if (mSettings.weightByDepth) builder.read(mSettings.depthResource);
    for (const StrokeInput& input : mSettings.inputs)
        builder.write(
            input.type, {Format::R8}, Need::Required,
            {"lines-" + input.type + ".png", Appearance::Lines,
             "the " + input.type + " layer as drawn from its kept strokes: coverage, 255 on a full line pixel"});
    ObjectDesc paths;
    paths.type = kDrawnStrokesType;
    paths.bytesPerPixel = kDrawnStrokesBytesPerPixel;
    paths.scale = mSettings.supersample;
    builder.writeObject(kStrokePathsField, paths, Need::Optional);
    builder.scratch(kScratchBytesPerPixel, mSettings.supersample);
}

void StrokesPass::execute(GlPassContext& gl) {
    mReport = {};
    const int scale = mSettings.supersample;
    const cv::Size dataSize(gl.width() * scale, gl.height() * scale);

    // Each type's skeleton at the data resolution, or a GL band's middle line at the output size, one pixel wide.
    auto start = std::chrono::steady_clock::now();
    // Per input, the skeleton the layer is chained on; the layers point into it while they are chained.
    std::vector<LineSkeleton> thinned(mSettings.inputs.size());
    // Per input, the width its strokes are drawn at: the type's, or a band of varying width's widest (bandWidths).
    std::vector<float> drawnWidths(mSettings.inputs.size());
    // Per input, a band of varying width's local widths (bandLocalWidths()); empty for the others.
    std::vector<cv::Mat1f> bandWidths(mSettings.inputs.size());
    std::vector<StrokeLayer> layers;
    const double heightPixels = double(gl.height()) * scale;
    for (std::size_t index = 0; index < mSettings.inputs.size(); ++index) {
        const StrokeInput& input = mSettings.inputs[index];
        StrokeLayer layer;
        if (input.skeleton) {
            // A kernel marks a line two pixels wide in places: a contour's depth break (its nearer pixel) beside the
            // sign change of n.v a pixel inside it, a ladder with one-pixel holes. Traced as it is, such a stretch
            // falls into rungs a pixel long that the length rule drops, at one size and not at another (issue 39:
            // the torus knot's contours 0.924 F1 between 1024 and 2048 pixels). Thinned, it is one chain; the
            // thinned-away pixels' points still belong to their kept neighbour (pixelOfPoint()) and are drawn.
            const LineSkeleton& found = gl.inputObject<LineSkeleton>(input.resource);
            thinned[index].mask = thinToSkeleton(found.mask, 1);
            thinned[index].points = found.points;
        } else {
            // Slivers narrower than a pixel at the band's reference size go; the band's own width stays.
            const cv::Mat& band = gl.inputImage(input.resource);
            thinned[index] =
                skeletonFromMask(thinToSkeleton(input.bandOfOneWidth ? openedBand(band, input.widthPixels) : band));
            // A band whose width the model sets is drawn again at its own width along its middle line, not at the
            // type's (which left paper between the model and a --silhouette-object-width line, and lost the map).
            if (!input.bandOfOneWidth) bandWidths[index] = bandLocalWidths(band);
            // A width map's band is bandWidthPixels() wide where the map is 1: wider than the line from 1024 rows up.
            if (!bandWidths[index].empty() && !input.bandWidthInModelUnits)
                bandWidths[index] *= input.widthPixels / bandWidthPixels(input.widthPixels, band.rows);
        }
        drawnWidths[index] = input.widthPixels;
        if (!bandWidths[index].empty()) {
            double widest = 0.0;
            cv::minMaxLoc(bandWidths[index], nullptr, &widest);
            drawnWidths[index] = std::max(input.widthPixels, float(widest));
        }
        // A kernel may find its lines on a field coarser than the data (the suggestive contours' one sampling at
        // every size, SuggestiveLines.h): its skeleton's pixels are then whole blocks of data pixels.
        layer.scale = dataPixelsPerPixelOf(gl, input.resource, scale);
        layer.skeleton = &thinned[index];
        if (layer.skeleton->mask.size() * layer.scale != dataSize)
            throw std::runtime_error("StrokesPass::execute(): '" + input.resource + "' is not at the data size " +
                                     std::to_string(dataSize.width) + "x" + std::to_string(dataSize.height));
        // A layer sampled coarser measures its lines by samples further apart: its own bias (Strokes.h).
        layer.minLengthPixels = strokeLengthLimitPixels(input.minLength, heightPixels, layer.scale);
        layer.joinAllowancePixels = strokeJoinAllowancePixels(heightPixels, layer.scale);
        layer.seedStrength = input.seedStrength;
        layers.push_back(layer);
    }
    mReport.thinMilliseconds = millisecondsSince(start);

    start = std::chrono::steady_clock::now();
    Strokes strokes = chainStrokes(layers, strokeSettingsFor(gl.height(), scale));
    const bool bandsVary = takeBandWidths(strokes, layers, bandWidths, drawnWidths);
    if (mSettings.mergeOverlaps) mergeOverlapsWithinKind(strokes, layers, drawnWidths);
    LineWeightSettings weight;
    if (mSettings.weightByDepth) {
        weight.farWidth = kFarWidth;
        weight.nearDepth = mSettings.nearDepth;
        weight.farDepth = mSettings.farDepth;
    }
    if (mSettings.weightByStrength) weight.strengthShare = kStrengthShare;
    if (mSettings.taperEnds) {
        weight.taperPixels = kTaperLength * heightPixels;
        weight.taperStart = kTaperStart;
    }
    weighStrokes(strokes, weight, mSettings.weightByDepth ? gl.inputImage(mSettings.depthResource) : cv::Mat(),
                 dataSize);
    mReport.chainMilliseconds = millisecondsSince(start);

    // What was kept, counted before the dashes cut the hidden types' strokes into pieces.
    reportKept(strokes, layers);

    start = std::chrono::steady_clock::now();
    // The hidden types' strokes cut into dashes by arc length in data pixels (the pattern is in output pixels), so
    // the layers below and the --svg paths draw the same dashes.
    mReport.dashesPerInput.assign(mSettings.inputs.size(), 0);
    const DashPattern dataDash{mSettings.dash.onPixels * scale, mSettings.dash.offPixels * scale};
    for (std::size_t index = 0; index < mSettings.inputs.size(); ++index)
        if (mSettings.inputs[index].dashed) mReport.dashesPerInput[index] = dashStrokes(strokes, int(index), dataDash);
    for (std::size_t index = 0; index < mSettings.inputs.size(); ++index) {
        const StrokeInput& input = mSettings.inputs[index];
        const LineSkeleton kept = keptSkeleton(strokes, layers, int(index));
        gl.outputImage(input.type) = strokeLines(kept, drawnWidths[index], scale);
    }
    mReport.strokeMilliseconds = millisecondsSince(start);

    if (gl.isLive(kStrokePathsField)) {
        DrawnStrokes& drawn = gl.outputObject<DrawnStrokes>(kStrokePathsField);
        drawn.strokes = std::move(strokes);
        drawn.inputs = mSettings.inputs;
        for (std::size_t index = 0; index < drawn.inputs.size(); ++index)
            drawn.inputs[index].widthPixels = drawnWidths[index];
        drawn.supersample = scale;
        drawn.weighted = mSettings.weightByDepth || mSettings.weightByStrength || mSettings.taperEnds || bandsVary;
    }
}

void StrokesPass::mergeOverlapsWithinKind(Strokes& strokes, const std::vector<StrokeLayer>& layers,
                                          const std::vector<float>& drawnWidths) const {
    // Hidden lines lie under the visible ones (docs/lines.md, "Hidden lines"): a visible line does not give way to a
    // dashed one drawn earlier, nor a dashed one to a visible one where the two meet at an occluder's outline. So the
    // dashed inputs and the others are merged apart, each in composite order: mergeOverlaps() sees only one kind's
    // layers, renumbered, and every other stroke's layer is out of its range while it runs.
    const int scale = mSettings.supersample;
    for (const bool dashed : {true, false}) {
        std::vector<int> ofKind; // the kind's inputs, in order
        for (std::size_t index = 0; index < mSettings.inputs.size(); ++index)
            if (mSettings.inputs[index].dashed == dashed) ofKind.push_back(int(index));
        if (ofKind.size() < 2) continue;
        std::vector<StrokeLayer> kindLayers;
        std::vector<double> halfWidths;
        std::vector<int> renumbered(mSettings.inputs.size(), -1);
        for (std::size_t position = 0; position < ofKind.size(); ++position) {
            kindLayers.push_back(layers[std::size_t(ofKind[position])]);
            halfWidths.push_back(0.5 * drawnWidths[std::size_t(ofKind[position])] * scale);
            renumbered[std::size_t(ofKind[position])] = int(position);
        }
        const int outOfRange = int(mSettings.inputs.size());
        for (Stroke& stroke : strokes.strokes)
            stroke.layer = renumbered[std::size_t(stroke.layer)] >= 0 ? renumbered[std::size_t(stroke.layer)]
                                                                      : outOfRange + stroke.layer;
        mergeOverlaps(strokes, kindLayers, halfWidths);
        for (Stroke& stroke : strokes.strokes)
            stroke.layer = stroke.layer >= outOfRange ? stroke.layer - outOfRange : ofKind[std::size_t(stroke.layer)];
    }
}

void StrokesPass::reportKept(const Strokes& strokes, const std::vector<StrokeLayer>& layers) {
    mReport.chains = strokes.chains.size();
    mReport.strokes = strokes.strokes.size();
    mReport.kept = strokes.keptStrokes();
    mReport.droppedShort = strokes.droppedShort();
    mReport.droppedWeak = strokes.droppedWeak();
    mReport.junctionJoins = strokes.junctionJoins;
    mReport.gapJoins = strokes.gapJoins;
    mReport.crossTypeJoins = strokes.crossTypeJoins;
    mReport.absorbedFragments = strokes.absorbedFragments;
    mReport.overlapStrokes = strokes.overlapsMerged;
    const std::size_t inputs = mSettings.inputs.size();
    mReport.keptPerInput.assign(inputs, 0);
    mReport.foundPerInput.assign(inputs, 0);
    mReport.droppedShortPerInput.assign(inputs, 0);
    mReport.droppedWeakPerInput.assign(inputs, 0);
    mReport.lengthPixelsPerInput.assign(inputs, 0.0);
    for (const Stroke& stroke : strokes.strokes) {
        if (stroke.layer < 0 || std::size_t(stroke.layer) >= inputs) continue;
        const std::size_t input = std::size_t(stroke.layer);
        ++mReport.foundPerInput[input];
        const StrokeChain& chain = strokes.chains[stroke.chain];
        if (!chain.longEnough)
            ++mReport.droppedShortPerInput[input];
        else if (!chain.seeded)
            ++mReport.droppedWeakPerInput[input];
        if (stroke.kept) {
            ++mReport.keptPerInput[input];
            mReport.lengthPixelsPerInput[input] += stroke.lengthPixels;
        }
    }
    for (double& length : mReport.lengthPixelsPerInput) length /= mSettings.supersample; // data to output pixels
    const StrokesNearLimits near = strokesNearLimits(strokes, layers, kNearLimitShare);
    mReport.nearLengthLimitPerInput = near.length;
    mReport.nearSeedLimitPerInput = near.seed;
}

void StrokesPass::describe(nlohmann::ordered_json& report) const {
    report["chains"] = mReport.chains;
    report["strokes"] = mReport.strokes;
    report["strokes_kept"] = mReport.kept;
    report["dropped_short"] = mReport.droppedShort;
    report["dropped_weak"] = mReport.droppedWeak;
    report["junction_joins"] = mReport.junctionJoins;
    report["gap_joins"] = mReport.gapJoins;
    report["cross_type_joins"] = mReport.crossTypeJoins;
    report["absorbed_fragments"] = mReport.absorbedFragments;
    report["overlap_strokes_merged"] = mReport.overlapStrokes;
    nlohmann::ordered_json types = nlohmann::ordered_json::object();
    for (std::size_t index = 0; index < mSettings.inputs.size(); ++index) {
        nlohmann::ordered_json type = {
            {"strokes_kept", index < mReport.keptPerInput.size() ? mReport.keptPerInput[index] : 0},
            {"length_pixels", index < mReport.lengthPixelsPerInput.size() ? mReport.lengthPixelsPerInput[index] : 0.0},
            {"near_length_limit",
             index < mReport.nearLengthLimitPerInput.size() ? mReport.nearLengthLimitPerInput[index] : 0},
            {"near_seed_limit",
             index < mReport.nearSeedLimitPerInput.size() ? mReport.nearSeedLimitPerInput[index] : 0}};
        if (mSettings.inputs[index].dashed)
            type["dashes"] = index < mReport.dashesPerInput.size() ? mReport.dashesPerInput[index] : 0;
        types[mSettings.inputs[index].type] = type;
    }
    report["types"] = types;
    report["thin_ms"] = mReport.thinMilliseconds;
    report["chain_ms"] = mReport.chainMilliseconds;
    report["stroke_ms"] = mReport.strokeMilliseconds;
}

std::vector<SvgLineLayer> svgLayersOf(const DrawnStrokes& drawn, double tolerancePixels,
                                      const std::vector<std::array<double, 4>>& colors) {
    if (colors.size() != drawn.inputs.size())
        throw std::invalid_argument("svgLayersOf(): 'colors' must hold one colour per line type");
    std::vector<SvgLineLayer> layers;
    for (std::size_t index = 0; index < drawn.inputs.size(); ++index) {
        const StrokeInput& input = drawn.inputs[index];
        SvgLineLayer layer;
        layer.type = input.type;
        layer.supersample = drawn.supersample;
        layer.widthPixels = input.widthPixels;
        layer.color = colors[index];
        std::vector<std::vector<float>> shares;
        layer.polylines = strokePolylines(drawn.strokes, int(index), tolerancePixels * drawn.supersample,
                                          drawn.weighted ? &shares : nullptr, input.widthPixels * drawn.supersample);
        for (const float opacity : strokeOpacities(drawn.strokes, int(index))) layer.opacities.push_back(opacity);
        for (const std::vector<float>& vertexShares : shares) {
            std::vector<double> widths;
            for (const float share : vertexShares) widths.push_back(double(share) * input.widthPixels);
            layer.widths.push_back(std::move(widths));
        }
        layers.push_back(std::move(layer));
    }
    return layers;
}

} // namespace inkgraph
