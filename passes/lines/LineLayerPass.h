#pragma once
/** @file One line type's layer on the CPU: its one-pixel skeleton found by a LineKernel (in the G-buffer, in a
 *  skeleton a GL pass drew, or on the mesh itself), stroked at the user's width, anti-aliased, and area-downsampled
 *  when the data buffers are supersampled. The pass knows no line type: the kernel says what it reads.
 *
 *  | resource      | format | need     | content                                                   |
 *  |---------------|--------|----------|-----------------------------------------------------------|
 *  | reads         |        |          | the kernel's inputs(), at the data resolution             |
 *  | <name>.lines  | r8     | required | frame-sized line coverage, 255 = full line, anti-aliased  |
 *
 *  The inputs are S times the frame size, S their writers' scale as the plan records it (--supersample); the kernel
 *  runs there and only the stroked line image is area-downsampled. */

#include "gl/GlPass.h"
#include "passes/lines/LineKernel.h"
#include "postfx/LineSkeleton.h"

#include <memory>
#include <string>

namespace inkgraph {

/** What the last execute() did, for --stats. */
struct LineLayerReport {
    int supersample = 1;               ///< the inputs' scale
    std::size_t skeletonPixels = 0;    ///< pixels the kernel marked, at the data resolution
    std::size_t points = 0;            ///< sub-pixel samples stroked
    double readbackMilliseconds = 0.0; ///< bringing the inputs to the CPU (shared with other layers: the first pays)
    double kernelMilliseconds = 0.0;   ///< finding the skeleton
    double strokeMilliseconds = 0.0;   ///< drawing it at width, downsampling
};

class LineLayerPass : public GlPass {
public:
    /** Throws std::invalid_argument for a non-positive or non-finite width, a null kernel or one that reads
     *  nothing. */
    LineLayerPass(std::string name, std::unique_ptr<LineKernel> kernel, float widthPixels);

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    /** The kernel's own preparation (deriving scene data), outside the timed execute(). */
    void prepare(GlPassContext& context) override;
    void execute(GlPassContext& context) override;
    /** post_stage.lines' entry: type, skeleton_pixels, points, readback_ms, kernel_ms, stroke_ms and the kernel's. */
    void describe(nlohmann::ordered_json& report) const override;

    float widthPixels() const { return mWidthPixels; }
    const LineKernel& kernel() const { return *mKernel; }
    LineKernel& kernel() { return *mKernel; }
    const LineLayerReport& report() const { return mReport; }
    /** The skeleton the last execute() found, at the data resolution (for tests and vector output). */
    const LineSkeleton& skeleton() const { return mSkeleton; }

private:
    std::string mName;
    std::unique_ptr<LineKernel> mKernel;
    float mWidthPixels;
    LineLayerReport mReport;
    LineSkeleton mSkeleton;
};

} // namespace inkgraph
