#pragma once
/** @file What finds one line type's one-pixel skeleton on the CPU: a postfx kernel over G-buffer fields, a GL pass's
 *  skeleton mask, or the mesh itself. LineLayerPass reads the kernel's inputs from the graph, runs it, and hands its
 *  skeleton on; a kernel knows nothing of the graph but the names of what it reads, and the memory it works in.
 *  A GPU kernel (--post-stage gpu, passes/PostStage.h) is handed its inputs as textures instead, and reads back only
 *  what it found. */

#include "gl/GlObjects.h"
#include "graph/Resource.h"
#include "postfx/LineSkeleton.h"

#include <nlohmann/json_fwd.hpp>
#include <opencv2/core.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {

class LineKernel {
public:
    virtual ~LineKernel() = default;
    /** Full names of the graph resources it reads, in the order find() receives them ("gbuffer.nDotV"). At least one:
     *  the first one's scale is the data resolution the skeleton is found at. */
    virtual std::vector<std::string> inputs() const = 0;
    /** Which pixels of inputs()[input] the kernel reads: ReadExtent::CoveredPixels for a field it reads only where
     *  its depth input says the model covers the frame (the G-buffer may then leave the rest uncleared). */
    virtual ReadExtent extentOf(std::size_t input) const {
        (void)input;
        return ReadExtent::WholeImage;
    }
    /** The scene data it takes from outside the graph (passes/GpuScene.h SceneImport), declared by its layer. */
    virtual std::vector<std::string> sceneImports() const { return {}; }
    /** Working memory per data pixel while find() runs, beyond its inputs and its skeleton (for the memory budget). */
    virtual std::size_t scratchBytesPerPixel() const { return 0; }
    /** Once per run, before the timed find(): derive what it needs of its sceneImports() (only kernels that run). */
    virtual void prepare() {}
    /** The skeleton, at the inputs' resolution; `inputs` as inputs() names them, read back to the CPU. */
    virtual LineSkeleton find(const std::vector<cv::Mat>& inputs) = 0;
    /** True for a kernel that runs on the GPU: LineLayerPass then calls findInTextures(), not find(), and reads
     *  nothing back itself. */
    virtual bool readsTextures() const { return false; }
    /** A GPU kernel's skeleton from its inputs as GL textures (bottom row first, as GL has them), in the order of
     *  inputs(), with the GL context current. Throws std::logic_error unless readsTextures(). */
    virtual LineSkeleton findInTextures(const std::vector<const GlTexture*>& inputs) {
        (void)inputs;
        throw std::logic_error("LineKernel::findInTextures(): this kernel runs on the CPU (find())");
    }
    /** Adds what the last run found beyond the skeleton to the layer's --stats entry (post_stage.lines). */
    virtual void describe(nlohmann::ordered_json& entry) const { (void)entry; }
};

} // namespace inkgraph
