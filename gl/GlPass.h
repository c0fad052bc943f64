#pragma once
/** @file A pass the GL executor runs: it gets the GL context (textures, images, live fields, planned sizes) typed,
 *  so no pass casts what it is handed. */

#include "gl/GraphExecutor.h"
#include "graph/Pass.h"

namespace inkgraph {

class GlPass : public Pass {
public:
    /** Once per run, before anything executes and outside the timed execute(): build programs, upload meshes.
     *  May ask the context which outputs are live and their sizes; must not touch resources. */
    virtual void prepare(GlPassContext& context) { (void)context; }
    /** Runs the pass: writes every live output through the context. */
    virtual void execute(GlPassContext& context) = 0;
};

} // namespace inkgraph
