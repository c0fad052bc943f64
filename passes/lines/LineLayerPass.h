#pragma once
/** @file One line type's layer on the CPU: its one-pixel skeleton found by a postfx kernel (in the G-buffer, or in a
 *  skeleton a GL pass drew) or on the mesh itself, stroked at the user's width, anti-aliased, and area-downsampled
 *  when the data buffers are supersampled.
 *
 *  | source           | reads                                   | kernel                                      |
 *  |------------------|-----------------------------------------|---------------------------------------------|
 *  | Contour          | gbuffer.nDotV, gbuffer.depth            | postfx/Contour.h extractContours            |
 *  | Suggestive       | gbuffer.radial, gbuffer.depth           | postfx/SuggestiveContours.h                 |
 *  | SuggestiveObject | gbuffer.depth (visibility); the meshes' | scene/ObjectSuggestiveContours.h, projected |
 *  |                  | curvature from GpuScene                 | and depth-tested (see below)                |
 *  | DepthEdge        | gbuffer.depth                           | postfx/ImageEdges.h extractDepthEdges       |
 *  | NormalEdge       | gbuffer.normal, gbuffer.depth           | postfx/ImageEdges.h extractNormalEdges      |
 *  | Skeleton         | the `skeletonResource` (r8, 1-px lines) | postfx/LineSkeleton.h skeletonFromMask      |
 *
 *  | resource      | format | need     | content                                                   |
 *  |---------------|--------|----------|-----------------------------------------------------------|
 *  | <name>.lines  | r8     | required | frame-sized line coverage, 255 = full line, anti-aliased  |
 *
 *  The inputs are `supersample` times the frame size (their writers' scale); the kernel runs there and only the
 *  stroked line image is area-downsampled.
 *
 *  SuggestiveObject: the curvature of every mesh (GpuScene::meshCurvature()) is derived in prepare() the first time
 *  the pass runs, so a plan that culls the pass derives nothing. Per frame, the segments seen from the camera's eye
 *  are projected with the camera's own view and projection (in double: the G-buffer's matrices before rounding to
 *  float), clipped to the near and far planes, and sampled along the image every <= 0.5 data pixels (the depth
 *  perspective-correct, the strength linear along the 3-D segment). A sample is visible when one of the four pixel
 *  centres around it holds the model (depth > 0) at a linear depth d with z <= d (1 + suggestive.depthJump): a
 *  point on the surface it lies on passes (its own pixel is at most a pixel's depth slope away), a point behind a
 *  nearer surface fails, background pixels beside a silhouette do not vote, and visibility is decided to within a
 *  pixel of an occluder's outline, as for the mesh edges. */

#include "graph/Pass.h"
#include "postfx/Contour.h"
#include "postfx/ImageEdges.h"
#include "postfx/SuggestiveContours.h"
#include "scene/ObjectSuggestiveContours.h"

#include <string>

namespace inkgraph {

class GpuScene;
struct FrameParams;

enum class LineSource { Contour, Suggestive, SuggestiveObject, DepthEdge, NormalEdge, Skeleton };

struct LineLayerSettings {
    LineSource source = LineSource::Contour;
    float widthPixels = 2.0f; ///< in output pixels
    int supersample = 1;      ///< the inputs' scale
    std::string gbuffer = "gbuffer";  ///< the G-buffer pass's name
    std::string skeletonResource;     ///< Skeleton: the mask to stroke ("mesh-edges.crease")
    ContourSettings contour;
    /** Suggestive and SuggestiveObject: threshold, fade and feature size mean the same for both (the strength
     *  q = fs^2 tan(theta) D_w^ kappa_r); SuggestiveObject also takes depthJump as its visibility tolerance. */
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
    // SuggestiveObject only:
    std::size_t segments = 0;           ///< segments on the mesh (before visibility), over all meshes
    bool curvatureDerived = false;      ///< whether this run derived the curvature (else it was cached)
    double curvatureMilliseconds = 0.0; ///< deriving it, in prepare(); 0 when cached
};

/** What an object-space source needs besides the graph's resources; both must outlive the pass. */
struct LineSceneInputs {
    GpuScene* scene = nullptr;
    const FrameParams* frame = nullptr;
};

class LineLayerPass : public Pass {
public:
    /** Throws std::invalid_argument for a non-positive width or supersample, a Skeleton source without a
     *  resource, or a SuggestiveObject source without `sceneInputs`. */
    LineLayerPass(std::string name, LineLayerSettings settings, LineSceneInputs sceneInputs = {});

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    /** SuggestiveObject: derives the meshes' curvature if no pass has yet. */
    void prepare(PassContext& context) override;
    void execute(PassContext& context) override;

    const LineLayerSettings& settings() const { return mSettings; }
    const LineLayerReport& report() const { return mReport; }
    /** The skeleton the last execute() found, at the data resolution (for tests and vector output). */
    const LineSkeleton& skeleton() const { return mSkeleton; }

private:
    std::string input(const char* field) const { return mSettings.gbuffer + "." + field; }
    /** SuggestiveObject's kernel: every mesh's segments, projected and depth-tested against `depth`. */
    LineSkeleton findObjectSuggestiveContours(const cv::Mat& depth);

    std::string mName;
    LineLayerSettings mSettings;
    LineSceneInputs mSceneInputs;
    LineLayerReport mReport;
    bool mCurvatureDerived = false;         ///< by the last prepare()
    double mCurvatureMilliseconds = 0.0;    ///< by the last prepare()
    LineSkeleton mSkeleton;
};

} // namespace inkgraph
