#pragma once
// Shared by the benchmarks: one GL context per process, procedural scenes, and the CLI's graph compiled once and run
// warm (programs built and meshes uploaded once, as in a batch).
#include "passes/StillGraph.h"
#include "gl/GraphExecutor.h"
#include "gl/HeadlessContext.h"
#include "gl/TexturePool.h"
#include "graph/GraphCompiler.h"
#include "scene/Camera.h"
#include "scene/mesh/Procedural.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace inkgraph::bench {

inline constexpr int kFrameSize = 1024;
inline const std::string kBunnyPath = std::string(INKGRAPH_SOURCE_ROOT) + "/models/bunny_c3d_70k.obj";

inline HeadlessContext& context() {
    static HeadlessContext instance;
    return instance;
}

/** A sphere of about `triangleCount` triangles: 2 x segments x (rings - 1) with segments = 2 x rings. */
inline Scene sphereScene(int triangleCount) {
    const int rings = std::max(3, int(std::sqrt(triangleCount / 4.0)));
    return makeScene(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 2 * rings, rings));
}

/** One scene with the CLI's passes (auto-framed camera, default light), compiled for `requested`. */
struct Bench {
    Look look;
    Scene scene;
    BoundingSphere sphere;
    FrameParams frame;
    ShaderLibrary shaders;
    std::unique_ptr<GpuScene> gpuScene;
    StillGraph graph;
    TexturePool pool;
    GraphExecutor executor{pool};
    Plan plan;

    /** `allowDeferredShading` false: the shade pass always draws the meshes (StillGraphSetup). */
    Bench(Scene loaded, Look benchLook, const std::vector<std::string>& requested, bool allowDeferredShading = true)
        : look(std::move(benchLook)), scene(std::move(loaded)) {
        context();
        CameraRequest request;
        request.width = kFrameSize;
        request.height = kFrameSize;
        frame.camera = resolveCamera(request, scene);
        sphere = computeBoundingSphere(scene);
        frame.worldOrigin = sphere.center;
        frame.towardLightWorld = glm::normalize(glm::dvec3(-0.4, 0.5, 0.77));
        gpuScene = makeSceneImport(scene, frame.worldOrigin, frame, look);
        StillGraphSetup setup{look, shaders, scene, sphere, *gpuScene, frame, std::nullopt};
        setup.allowDeferredShading = allowDeferredShading;
        graph = buildStillGraph(setup);
        plan = graph.compilePlan(requested);
    }

    /** Runs the plan; returns the execute() milliseconds of every pass by name. */
    std::vector<PassTiming> run() { return executor.run(plan, graph.mutableView(), {kFrameSize, kFrameSize, false}); }

    double run(const std::string& passName) {
        for (const PassTiming& timing : run())
            if (timing.pass == passName) return timing.milliseconds;
        return 0.0;
    }
};

inline void reportPass(benchmark::State& state, Bench& bench, const std::string& passName) {
    bench.run(passName); // warm-up: llvmpipe compiles shader variants on the first draw
    for (auto _ : state) state.SetIterationTime(bench.run(passName) / 1000.0);
    state.counters["triangles"] = double(bench.scene.triangleCount());
    state.counters["Mpixel/s"] =
        benchmark::Counter(double(kFrameSize) * kFrameSize * state.iterations() / 1e6, benchmark::Counter::kIsRate);
}

} // namespace inkgraph::bench
