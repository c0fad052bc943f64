#pragma once
/** @file The kernels of the two suggestive-contour line types (DeCarlo et al. 2003): in the G-buffer's radial field
 *  (image space), and on the mesh from per-vertex curvature (Rusinkiewicz 2004), projected and hidden with the
 *  G-buffer depth (object space). Both share one meaning of threshold, fade and feature size: the strength
 *  q = fs^2 tan(theta) D_w kappa_r.
 *
 *  Object space, per frame: the segments seen from the camera's eye are projected, clipped, sampled and hidden by the
 *  G-buffer depth as every object-space line is (passes/lines/ProjectedSegments.h); `hidden-suggestive-object` keeps
 *  the hidden samples instead. The curvature of every mesh (GpuScene::meshCurvature()) is derived in prepare() the
 *  first time the kernel runs, so a plan that culls the layer derives nothing. */

#include "passes/GpuScene.h"
#include "passes/lines/LineKernel.h"
#include "passes/lines/ProjectedSegments.h"
#include "postfx/SuggestiveContours.h"

#include <string>
#include <vector>

namespace inkgraph {

class GpuScene;
struct FrameParams;

/** The feature size fs that makes the strength dimensionless, as a fraction of the bounding radius (rtsc's upper
 *  bound on fs). */
constexpr double kSuggestiveFeatureSizeFraction = 0.05;

/** The fewest rows the image-space kernel samples the surface at: from twice this up, it reads a G-buffer of its own
 *  (kSuggestiveFieldPass) at the picture's size over suggestiveFieldDivisor(), so a picture of 2048 or 4096 rows
 *  finds the lines a picture of 1024 rows finds, drawn at its own size (issue 39). */
inline constexpr int kSuggestiveFieldMinRows = 1024;
/** The G-buffer pass the kernel reads from 2 x kSuggestiveFieldMinRows rows up (where a divisor fits). */
inline constexpr const char* kSuggestiveFieldPass = "suggestive-field";

/** The largest whole divisor of both sides of a `width` x `height` picture that leaves at least
 *  kSuggestiveFieldMinRows rows: 2 at 2048 x 2048 (a field of 1024 rows), 2 at 3840 x 2160 (1080), 4 at 4096 x 4096;
 *  1 (the picture's own G-buffer) when none does, as at 1024 rows or at 2049. Throws std::invalid_argument for a
 *  side under 1. */
int suggestiveFieldDivisor(int width, int height);

/** Image space: reads "<gbuffer>.radial" and "<gbuffer>.depth" (postfx/SuggestiveContours.h). `settings.smoothing`
 *  is in model units (the depth's); the focal length in pixels is taken from `frame`'s camera and the data image's
 *  height when the kernel runs. `frame` must outlive the kernel.
 *
 *  With `surfaces` (a scene whose surfaces meet: GpuScene::surfacesMeet()) it also reads "<gbuffer>.triangleId" and
 *  imports the scene's smooth patches (GpuScene::surfacePatches()), and differentiates and smooths within one patch
 *  only: across a hard edge (a flat-shaded model's facets, a cube's sides) or from one mesh to another the normal
 *  field steps, and D_w(n.v) there would measure the step, not a curvature; the crease and contour lines draw those
 *  edges. Without, the depth alone parts the surfaces. `surfaces` must outlive the kernel. */
class SuggestiveKernel : public LineKernel {
public:
    SuggestiveKernel(std::string gbuffer, SuggestiveSettings settings, const FrameParams& frame,
                     GpuScene* surfaces = nullptr)
        : mGBuffer(std::move(gbuffer)), mSettings(settings), mFrame(frame), mSurfaces(surfaces) {}
    std::vector<std::string> inputs() const override;
    /** The radial field and the triangle ids only where the depth is > 0: the smoothing's windows, the derivatives
     *  and the crossings keep to runs of covered pixels (postfx/SuggestiveContours.cpp). */
    ReadExtent extentOf(std::size_t input) const override {
        return input == 1 ? ReadExtent::WholeImage : ReadExtent::CoveredPixels;
    }
    std::vector<std::string> sceneImports() const override;
    /** `surface_ids`: whether it parted the surfaces by their smooth patches (the scene's surfaces meet); with them,
     *  `seam_edges`: the mesh edges where the normals step (GpuScene::SurfacePatches::seamEdges). */
    void describe(nlohmann::ordered_json& entry) const override;
    /** The wide stencil's and the smoothing's working images. */
    std::size_t scratchBytesPerPixel() const override;
    LineSkeleton find(const std::vector<cv::Mat>& inputs) override;

private:
    std::string mGBuffer;
    SuggestiveSettings mSettings;
    const FrameParams& mFrame;
    GpuScene* mSurfaces;
};

/** What the object-space kernel did, for --stats. */
struct ObjectSuggestiveReport {
    std::size_t segments = 0;           ///< segments on the mesh (before visibility), over all meshes
    bool curvatureDerived = false;      ///< whether this run derived the curvature (else it was cached)
    double curvatureMilliseconds = 0.0; ///< deriving it, in prepare(); 0 when cached
};

/** Object space: reads "<gbuffer>.depth" for visibility; the meshes' curvature comes from `scene`, smoothed over
 *  `curvatureSmoothing` model units. `settings`: featureSize in model units, threshold, fade, and depthJump as the
 *  visibility tolerance. `keep`: the visible samples, or the hidden ones. Both references must outlive the kernel. */
class ObjectSuggestiveKernel : public LineKernel {
public:
    /** `smoothingShare`: --suggestive-object-smoothing's value, which `curvatureSmoothing` is in model units, for
     *  the refusal of a smoothing too costly for the model. */
    ObjectSuggestiveKernel(std::string gbuffer, SuggestiveSettings settings, double curvatureSmoothing, GpuScene& scene,
                           const FrameParams& frame, SegmentVisibility keep = SegmentVisibility::Visible,
                           double smoothingShare = 0.0)
        : mGBuffer(std::move(gbuffer)), mSettings(settings), mCurvatureSmoothing(curvatureSmoothing), mScene(scene),
          mFrame(frame), mKeep(keep), mSmoothingShare(smoothingShare) {}
    std::vector<std::string> inputs() const override { return {mGBuffer + ".depth"}; }
    /** The meshes' curvature (SceneImport::kCurvature), derived here at this kernel's smoothing. */
    std::vector<std::string> sceneImports() const override { return {SceneImport::kCurvature}; }
    void prepare() override;
    LineSkeleton find(const std::vector<cv::Mat>& inputs) override;
    void describe(nlohmann::ordered_json& entry) const override;
    const ObjectSuggestiveReport& report() const { return mReport; }

private:
    std::string mGBuffer;
    SuggestiveSettings mSettings;
    double mCurvatureSmoothing;
    GpuScene& mScene;
    const FrameParams& mFrame;
    SegmentVisibility mKeep;
    double mSmoothingShare;
    ObjectSuggestiveReport mReport;
};

} // namespace inkgraph
