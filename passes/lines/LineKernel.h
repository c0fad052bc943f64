#pragma once
/** @file What finds one line type's one-pixel skeleton on the CPU: a postfx kernel over G-buffer fields, a GL pass's
 *  skeleton mask, or the mesh itself. LineLayerPass reads the kernel's inputs from the graph, runs it, and strokes
 *  what it found; a kernel knows nothing of the graph but the names of what it reads. */

#include "postfx/LineSkeleton.h"

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace inkgraph {

class LineKernel {
public:
    virtual ~LineKernel() = default;
    /** Full names of the graph resources it reads, in the order find() receives them ("gbuffer.nDotV"). At least one:
     *  the first one's scale is the data resolution the skeleton is found at. */
    virtual std::vector<std::string> inputs() const = 0;
    /** Once per run, before the timed find(): derive what the kernel needs from the scene (only kernels that run). */
    virtual void prepare() {}
    /** The skeleton, at the inputs' resolution; `inputs` as inputs() names them, read back to the CPU. */
    virtual LineSkeleton find(const std::vector<cv::Mat>& inputs) = 0;
    /** Adds what the last run found beyond the skeleton to the layer's --stats entry (post_stage.lines). */
    virtual void describe(nlohmann::ordered_json& entry) const { (void)entry; }
};

} // namespace inkgraph
