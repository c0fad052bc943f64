#pragma once
/** @file What a GL test needs to run passes as the app does: a scene, its frame parameters, shaders, and an executor
 *  over a texture pool. Test fixtures derive from it. */

#include "gl/GraphExecutor.h"
#include "gl/ShaderLibrary.h"
#include "gl/TexturePool.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "scene/Scene.h"

#include <memory>

namespace inkgraph::test {

struct PassHarness {
    Scene scene;
    FrameParams frame;
    ShaderLibrary shaders;
    TexturePool pool;
    GraphExecutor executor{pool};
    std::unique_ptr<GpuScene> gpuScene; ///< made by the fixture once `scene` is set
};

} // namespace inkgraph::test
