// Speed of the pieces of one still, measured warm (programs built and meshes uploaded once, as in a batch):
//   - loading the 70k-triangle bunny (OBJ parse + weld + normals);
//   - the G-buffer pass alone at 1024x1024, over sphere meshes from 1k to 1M triangles and the bunny, with the two
//     outputs Lambert needs and with all seven;
//   - the default cel shading and composite passes at 1024x1024;
//   - the bunny's suggestive-contour layer (`--lines suggestive`, default smoothing): reading gbuffer.radial and
//     gbuffer.depth back and the CPU kernel, as the pass's one time;
//   - reading a 1024x1024 RGBA32F texture back (gl/Readback), turned over by the driver and by the CPU.
// Times are the pass's own execute() up to glFinish (manual time), which is what --stats reports.
#include "bench/BenchScene.h"
#include "gl/Readback.h"

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

void BM_SuggestiveLayerBunny(benchmark::State& state) {
    Look look;
    look.lines = {"suggestive"};
    Bench bench(loadScene(kBunnyPath), look, {"suggestive.skeleton"});
    reportPass(state, bench, "suggestive");
}
BENCHMARK(BM_SuggestiveLayerBunny)->UseManualTime()->Unit(benchmark::kMillisecond);

/** The radial field's size and format. Warm: after the first read the allocator hands the same memory back, so this
 *  is the copy alone, not the first touch of fresh memory a still pays. */
void BM_ReadbackRgba32f(benchmark::State& state) {
    context();
    GlTexture texture(Format::RGBA32F, kFrameSize, kFrameSize, "readback bench");
    uploadImage(texture, cv::Mat(kFrameSize, kFrameSize, CV_32FC4, cv::Scalar(0.5, -0.25, 2.0, 1.0)));
    const ReadbackFlip flip = state.range(0) == 0 ? ReadbackFlip::Fastest : ReadbackFlip::Cpu;
    for (auto _ : state) benchmark::DoNotOptimize(readTexture(texture, flip));
    state.counters["MiB/s"] = benchmark::Counter(double(kFrameSize) * kFrameSize * 16.0 / (1 << 20),
                                                 benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ReadbackRgba32f)->Arg(0)->Arg(1)->ArgName("cpu_flip")->Unit(benchmark::kMillisecond);

} // namespace
} // namespace inkgraph::bench
