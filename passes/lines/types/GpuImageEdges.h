#pragma once
/** @file The image-space kernels of contour, depth-edge and normal-edge as compute shaders (--post-stage gpu,
 *  passes/PostStage.h; shaders/post/neighbour_pairs.comp). They find what the CPU kernels of postfx/Contour.h and
 *  postfx/ImageEdges.h find, in the G-buffer's textures where they are: the shader appends one event per marking
 *  pair to a storage buffer, and the CPU reads back only those events (16 bytes each, a few thousand a frame instead
 *  of the 8-20 bytes per pixel of the fields), sorts them into the CPU kernel's order and builds the same skeleton.
 *  Points agree with the CPU kernels' to the float division's rounding (1e-3 px is the tested bound); the order of
 *  the points is the CPU kernels' order. */

#include "gl/ShaderLibrary.h"
#include "passes/lines/LineKernel.h"
#include "postfx/Contour.h"
#include "postfx/ImageEdges.h"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** One of the three kernels over 4-neighbour pairs, on the GPU. */
class GpuNeighbourPairsKernel : public LineKernel {
public:
    enum class Kind { Contour, DepthEdge, NormalEdge };

    /** Contour: reads "<gbuffer>.nDotV" and "<gbuffer>.depth". */
    GpuNeighbourPairsKernel(std::string gbuffer, ContourSettings settings, ShaderLibrary& shaders);
    /** Depth edge: reads "<gbuffer>.depth". */
    GpuNeighbourPairsKernel(std::string gbuffer, DepthEdgeSettings settings, ShaderLibrary& shaders);
    /** Normal edge: reads "<gbuffer>.normal" and "<gbuffer>.depth". Throws std::invalid_argument naming the setting
     *  for a crease angle outside [0, 180] or a negative or non-finite depth jump (as extractNormalEdges()). */
    GpuNeighbourPairsKernel(std::string gbuffer, NormalEdgeSettings settings, ShaderLibrary& shaders);

    std::vector<std::string> inputs() const override;
    /** n.v and the normal only where both pixels of a pair are covered (shaders/post/neighbour_pairs.comp). */
    ReadExtent extentOf(std::size_t input) const override {
        return input == 0 && mKind != Kind::DepthEdge ? ReadExtent::CoveredPixels : ReadExtent::WholeImage;
    }
    /** Builds the compute program (the GL context current). */
    void prepare() override;
    /** The same skeleton by the CPU kernel (postfx/), for a caller that holds the fields as images. */
    LineSkeleton find(const std::vector<cv::Mat>& inputs) override;
    bool readsTextures() const override { return true; }
    /** Runs the shader over the textures (prepare()s first if need be) and builds the skeleton from its events.
     *  Throws std::invalid_argument naming the input for a count, size or multisampled texture it cannot read. */
    LineSkeleton findInTextures(const std::vector<const GlTexture*>& inputs) override;
    /** "device": "gpu", and "events": the events the shader appended in the last run. */
    void describe(nlohmann::ordered_json& entry) const override;

    Kind kind() const { return mKind; }
    /** Events the last run read back (one per point). */
    std::size_t lastEventCount() const { return mLastEvents; }

private:
    GpuNeighbourPairsKernel(Kind kind, std::string gbuffer, float depthJump, ShaderLibrary& shaders);
    /** Dispatches once with the buffer as it is; returns the events found (more than fit, when it overflowed). */
    std::size_t dispatch(const std::vector<const GlTexture*>& inputs, int width, int height);
    void allocateEvents(std::size_t capacity);

    Kind mKind;
    std::string mGBuffer;
    float mDepthJump;
    NormalEdgeSettings mNormalEdge;
    ShaderLibrary& mShaders;
    std::optional<GlProgram> mProgram;
    std::optional<GlBuffer> mEvents; ///< the event count (16 bytes with its padding), then the events
    std::size_t mCapacity = 0;       ///< events mEvents holds
    std::size_t mLastEvents = 0;
};

} // namespace inkgraph
