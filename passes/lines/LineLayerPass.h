#pragma once
/** @file One line type's layer on the CPU: its one-pixel skeleton found by a postfx kernel (in the G-buffer, or in a
 *  skeleton a GL pass drew), stroked at the user's width, anti-aliased, and area-downsampled when the data buffers
 *  are supersampled.
 *
 *  | source      | reads                                   | kernel                                  |
 *  |-------------|-----------------------------------------|-----------------------------------------|
 *  | Contour     | gbuffer.nDotV, gbuffer.depth            | postfx/Contour.h extractContours        |
 *  | Suggestive  | gbuffer.radial, gbuffer.depth           | postfx/SuggestiveContours.h             |
 *  | DepthEdge   | gbuffer.depth                           | postfx/ImageEdges.h extractDepthEdges   |
 *  | NormalEdge  | gbuffer.normal, gbuffer.depth           | postfx/ImageEdges.h extractNormalEdges  |
 *  | Skeleton    | the `skeletonResource` (r8, 1-px lines) | postfx/LineSkeleton.h skeletonFromMask  |
 *
 *  | resource      | format | need     | content                                                   |
 *  |---------------|--------|----------|-----------------------------------------------------------|
 *  | <name>.lines  | r8     | required | frame-sized line coverage, 255 = full line, anti-aliased  |
 *
 *  The inputs are `supersample` times the frame size (their writers' scale); the kernel runs there and only the
 *  stroked line image is area-downsampled. */

#include "graph/Pass.h"
#include "postfx/Contour.h"
#include "postfx/ImageEdges.h"
#include "postfx/SuggestiveContours.h"

#include <string>

namespace inkgraph {

enum class LineSource { Contour, Suggestive, DepthEdge, NormalEdge, Skeleton };

struct LineLayerSettings {
    LineSource source = LineSource::Contour;
    float widthPixels = 2.0f; ///< in output pixels
    int supersample = 1;      ///< the inputs' scale
    std::string gbuffer = "gbuffer";  ///< the G-buffer pass's name
    std::string skeletonResource;     ///< Skeleton: the mask to stroke ("mesh-edges.crease")
    ContourSettings contour;
    SuggestiveSettings suggestive;
    DepthEdgeSettings depthEdge;
    NormalEdgeSettings normalEdge;
};

/** What the last execute() did, for --stats. */
struct LineLayerReport {
    std::size_t skeletonPixels = 0;   ///< pixels the kernel marked, at the data resolution
    std::size_t points = 0;           ///< sub-pixel samples stroked
    double readbackMilliseconds = 0.0; ///< bringing the inputs to the CPU (shared with other layers: the first pays)
    double kernelMilliseconds = 0.0;   ///< finding the skeleton
    double strokeMilliseconds = 0.0;   ///< drawing it at width, downsampling
};

class LineLayerPass : public Pass {
public:
    /** Throws std::invalid_argument for a non-positive width or supersample, or a Skeleton source without a
     *  resource. */
    LineLayerPass(std::string name, LineLayerSettings settings);

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    void execute(PassContext& context) override;

    const LineLayerSettings& settings() const { return mSettings; }
    const LineLayerReport& report() const { return mReport; }
    /** The skeleton the last execute() found, at the data resolution (for tests and vector output). */
    const LineSkeleton& skeleton() const { return mSkeleton; }

private:
    std::string input(const char* field) const { return mSettings.gbuffer + "." + field; }

    std::string mName;
    LineLayerSettings mSettings;
    LineLayerReport mReport;
    LineSkeleton mSkeleton;
};

} // namespace inkgraph
