#pragma once
/** @file One line type's skeleton on the CPU, found by a LineKernel (in the G-buffer, in a skeleton a GL pass drew,
 *  or on the mesh itself). The stroke stage (StrokesPass) chains every type's skeleton into strokes and draws them.
 *  The pass knows no line type: the kernel says what it reads.
 *
 *  | resource        | format | need     | content                                                              |
 *  |-----------------|--------|----------|----------------------------------------------------------------------|
 *  | reads           |        |          | the kernel's inputs(), at the data resolution                        |
 *  | <name>.skeleton | object | required | "line-skeleton" (LineSkeleton): the one-pixel skeleton at the data   |
 *  |                 |        |          | resolution (S x the frame) with its sub-pixel points and strengths;  |
 *  |                 |        |          | its picture (--dump's skeleton-<name>.png) is the mask, r8           |
 *
 *  The inputs are S times the frame size (--supersample); the kernel runs there, with the working memory it declares
 *  (LineKernel::scratchBytesPerPixel()). */

#include "gl/GlPass.h"
#include "passes/lines/LineKernel.h"
#include "postfx/LineSkeleton.h"

#include <memory>
#include <string>

namespace inkgraph {

/** The object type of a line skeleton (postfx/LineSkeleton.h) in the graph. */
inline constexpr const char* kLineSkeletonType = "line-skeleton";
/** What a skeleton costs per data pixel at most: its mask (1) and its sub-pixel points (12 bytes each, at most one per
 *  12 pixels). */
inline constexpr std::size_t kLineSkeletonBytesPerPixel = 2;

/** What the last execute() did, for --stats. */
struct LineLayerReport {
    int supersample = 1;               ///< the inputs' scale ...
    int divisor = 1;                   ///< ... over this (a field coarser than the frame)
    std::size_t skeletonPixels = 0;    ///< pixels the kernel marked, at the data resolution
    std::size_t points = 0;            ///< sub-pixel samples stroked
    double readbackMilliseconds = 0.0; ///< bringing the inputs to the CPU (shared with other layers: the first pays)
    double kernelMilliseconds = 0.0;   ///< finding the skeleton
};

class LineLayerPass : public GlPass {
public:
    /** `supersample`: the data resolution's scale (the kernel's inputs are that many times the frame size), over
     *  `divisor` where the kernel reads a coarser field (TextureDesc::divisor): its skeleton is at that size. Throws
     *  std::invalid_argument for a supersample or divisor below 1, a null kernel or one that reads nothing. */
    LineLayerPass(std::string name, std::unique_ptr<LineKernel> kernel, int supersample, int divisor = 1);

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    /** The kernel's own preparation (deriving scene data), outside the timed execute(). */
    void prepare(GlPassContext& context) override;
    void execute(GlPassContext& context) override;
    /** post_stage.lines' entry: type, skeleton_pixels, points, readback_ms, kernel_ms and the kernel's. */
    void describe(nlohmann::ordered_json& report) const override;

    const LineKernel& kernel() const { return *mKernel; }
    LineKernel& kernel() { return *mKernel; }
    const LineLayerReport& report() const { return mReport; }

private:
    std::string mName;
    std::unique_ptr<LineKernel> mKernel;
    int mSupersample;
    int mDivisor;
    LineLayerReport mReport;
};

} // namespace inkgraph
