// Speed of the pieces of one still, measured warm (programs built and meshes uploaded once, as in a batch):
//   - loading the 70k-triangle bunny (OBJ parse + weld + normals);
//   - the G-buffer pass alone at 1024x1024, over sphere meshes from 1k to 1M triangles and the bunny, with two
//     outputs (normal and base colour, what the deferred Lambert read) and with all seven;
//   - the shading pass (forward, lambert model) and the composite pass at 1024x1024.
// Times are the pass's own execute() up to glFinish (manual time), which is what --stats reports.
#include "app/StillGraph.h"
#include "gl/GraphExecutor.h"
#include "gl/HeadlessContext.h"
#include "graph/GraphCompiler.h"
#include "scene/Camera.h"
#include "scene/Procedural.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

namespace inkgraph {
namespace {

constexpr int kFrameSize = 1024;
const std::string kBunnyPath = std::string(INKGRAPH_SOURCE_ROOT) + "/models/bunny_c3d_70k.obj";

HeadlessContext& context() {
    static HeadlessContext instance;
    return instance;
}

/** A sphere of about `triangleCount` triangles: 2 x segments x (rings - 1) with segments = 2 x rings. */
Scene sphereScene(int triangleCount) {
    const int rings = std::max(3, int(std::sqrt(triangleCount / 4.0)));
    return makeScene(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 2 * rings, rings));
}

/** One scene with the CLI's passes, compiled for `requested`, ready to run repeatedly. */
struct Bench {
    Scene scene;
    FrameParams frame;
    ShaderLibrary shaders;
    std::unique_ptr<GpuScene> gpuScene;
    StillGraph graph;
    TexturePool pool;
    GraphExecutor executor{pool};
    Plan plan;

    Bench(Scene loaded, const std::vector<std::string>& requested) : scene(std::move(loaded)) {
        context();
        CameraRequest request;
        request.width = kFrameSize;
        request.height = kFrameSize;
        frame.camera = resolveCamera(request, scene);
        frame.worldOrigin = computeBoundingSphere(scene).center;
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
        graph = buildStillGraph(ShadingMode::Lambert, shaders, *gpuScene, frame);
        plan = compile(graph.view(), requested);
    }

    /** Runs the plan and returns the execute() milliseconds of `passName`. */
    double run(const std::string& passName) {
        for (const PassTiming& timing : executor.run(plan, graph.mutableView(), {kFrameSize, kFrameSize, false}))
            if (timing.pass == passName) return timing.milliseconds;
        return 0.0;
    }
};

void reportPass(benchmark::State& state, Bench& bench, const std::string& passName) {
    bench.run(passName); // warm-up: llvmpipe compiles shader variants on the first draw
    for (auto _ : state) state.SetIterationTime(bench.run(passName) / 1000.0);
    state.counters["triangles"] = double(bench.scene.triangleCount());
    state.counters["Mpixel/s"] = benchmark::Counter(double(kFrameSize) * kFrameSize * state.iterations() / 1e6,
                                                    benchmark::Counter::kIsRate);
}

const std::vector<std::string> kLambertOutputs = {"gbuffer.normal", "gbuffer.baseColor"};
const std::vector<std::string> kAllOutputs = {"gbuffer.normal", "gbuffer.view",     "gbuffer.wVec",
                                              "gbuffer.nDotV",  "gbuffer.depth",    "gbuffer.coverage",
                                              "gbuffer.baseColor"};

void BM_LoadBunny(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(loadScene(kBunnyPath));
}
BENCHMARK(BM_LoadBunny)->Unit(benchmark::kMillisecond);

void BM_GBufferSphere_LambertOutputs(benchmark::State& state) {
    Bench bench(sphereScene(int(state.range(0))), kLambertOutputs);
    reportPass(state, bench, "gbuffer");
}
BENCHMARK(BM_GBufferSphere_LambertOutputs)->Arg(1000)->Arg(100000)->Arg(1000000)->UseManualTime()
    ->Unit(benchmark::kMillisecond);

void BM_GBufferSphere_AllOutputs(benchmark::State& state) {
    Bench bench(sphereScene(int(state.range(0))), kAllOutputs);
    reportPass(state, bench, "gbuffer");
}
BENCHMARK(BM_GBufferSphere_AllOutputs)->Arg(1000)->Arg(100000)->Arg(1000000)->UseManualTime()
    ->Unit(benchmark::kMillisecond);

void BM_GBufferBunny_AllOutputs(benchmark::State& state) {
    Bench bench(loadScene(kBunnyPath), kAllOutputs);
    reportPass(state, bench, "gbuffer");
}
BENCHMARK(BM_GBufferBunny_AllOutputs)->UseManualTime()->Unit(benchmark::kMillisecond);

void BM_LambertBunny(benchmark::State& state) {
    Bench bench(loadScene(kBunnyPath), {"composite.final"});
    reportPass(state, bench, "shade");
}
BENCHMARK(BM_LambertBunny)->UseManualTime()->Unit(benchmark::kMillisecond);

void BM_CompositeBunny(benchmark::State& state) {
    Bench bench(loadScene(kBunnyPath), {"composite.final"});
    reportPass(state, bench, "composite");
}
BENCHMARK(BM_CompositeBunny)->UseManualTime()->Unit(benchmark::kMillisecond);

} // namespace
} // namespace inkgraph

BENCHMARK_MAIN();
