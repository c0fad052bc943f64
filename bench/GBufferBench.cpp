// Speed of the pieces of one still, measured warm (programs built and meshes uploaded once, as in a batch):
//   - loading the 70k-triangle bunny (OBJ parse + weld + normals);
//   - the G-buffer pass alone at 1024x1024, over sphere meshes from 1k to 1M triangles and the bunny, with the two
//     outputs Lambert needs and with all seven;
//   - the default cel shading and composite passes at 1024x1024.
// Times are the pass's own execute() up to glFinish (manual time), which is what --stats reports.
#include "bench/BenchScene.h"

namespace inkgraph::bench {
namespace {

// The two buffers deferred Lambert read (the size of the smallest useful G-buffer).
const std::vector<std::string> kLambertOutputs = {"gbuffer.normal", "gbuffer.baseColor"};
const std::vector<std::string> kAllOutputs = {"gbuffer.normal", "gbuffer.view",     "gbuffer.wVec",     "gbuffer.nDotV",
                                              "gbuffer.depth",  "gbuffer.coverage", "gbuffer.baseColor"};

void BM_LoadBunny(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(loadScene(kBunnyPath));
}
BENCHMARK(BM_LoadBunny)->Unit(benchmark::kMillisecond);

void BM_GBufferSphere_LambertOutputs(benchmark::State& state) {
    Bench bench(sphereScene(int(state.range(0))), Look{}, kLambertOutputs);
    reportPass(state, bench, "gbuffer");
}
BENCHMARK(BM_GBufferSphere_LambertOutputs)
    ->Arg(1000)
    ->Arg(100000)
    ->Arg(1000000)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

void BM_GBufferSphere_AllOutputs(benchmark::State& state) {
    Bench bench(sphereScene(int(state.range(0))), Look{}, kAllOutputs);
    reportPass(state, bench, "gbuffer");
}
BENCHMARK(BM_GBufferSphere_AllOutputs)
    ->Arg(1000)
    ->Arg(100000)
    ->Arg(1000000)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

void BM_GBufferBunny_AllOutputs(benchmark::State& state) {
    Bench bench(loadScene(kBunnyPath), Look{}, kAllOutputs);
    reportPass(state, bench, "gbuffer");
}
BENCHMARK(BM_GBufferBunny_AllOutputs)->UseManualTime()->Unit(benchmark::kMillisecond);

void BM_CelBunny(benchmark::State& state) {
    Bench bench(loadScene(kBunnyPath), Look{}, {"composite.final"});
    reportPass(state, bench, "shade");
}
BENCHMARK(BM_CelBunny)->UseManualTime()->Unit(benchmark::kMillisecond);

void BM_CompositeBunny(benchmark::State& state) {
    Bench bench(loadScene(kBunnyPath), Look{}, {"composite.final"});
    reportPass(state, bench, "composite");
}
BENCHMARK(BM_CompositeBunny)->UseManualTime()->Unit(benchmark::kMillisecond);

} // namespace
} // namespace inkgraph::bench
