// The post stage on either device (--post-stage, passes/PostStage.h): each image-space kernel that has a GPU version
// (contour, depth-edge, normal-edge), on the ray-cast torus G-buffer of PostfxBench uploaded as textures (the torus
// fills about 40% of the frame), as the still graph would run it:
// - Cpu: read the fields back (gl/Readback readTexture, as the executor does) and run the postfx kernel;
// - Gpu: the compute shader over the textures, the events read back and the skeleton built
//   (passes/lines/types/GpuImageEdges.h).
// Counters: readback_ms and kernel_ms (medians over the repetitions' iterations are what docs/performance.md quotes).
//   ./build/bench/inkgraph_bench --benchmark_filter=PostStage --benchmark_repetitions=5
#include "bench/BenchScene.h"
#include "gl/Readback.h"
#include "gl/ShaderLibrary.h"
#include "passes/lines/types/GpuImageEdges.h"
#include "tests/support/SyntheticGBuffer.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <map>
#include <memory>

namespace inkgraph::bench {
namespace {

using Kind = GpuNeighbourPairsKernel::Kind;

/** The torus of PostfxBench (ring 1, tube 0.4, 30 degrees above its plane), its fields as GL textures. */
struct TorusTextures {
    GlTexture nDotV;
    GlTexture depth;
    GlTexture normal;
};

const TorusTextures& torusTextures(int size) {
    context(); // made before the textures, so it outlives them at exit
    static std::map<int, std::unique_ptr<TorusTextures>> kept;
    auto found = kept.find(size);
    if (found != kept.end()) return *found->second;
    test::SyntheticCamera camera;
    camera.width = camera.height = size;
    camera.eye = 4.2 * glm::dvec3(std::cos(glm::radians(30.0)), 0.0, std::sin(glm::radians(30.0)));
    camera.up = {0.0, 0.0, 1.0};
    const test::SyntheticGBuffer buffer = test::renderTorus(camera, glm::dvec3(0.0), 1.0, 0.4);
    auto textures = std::make_unique<TorusTextures>(TorusTextures{GlTexture(Format::R32F, size, size, "nDotV"),
                                                                  GlTexture(Format::R32F, size, size, "depth"),
                                                                  GlTexture(Format::RGBA32F, size, size, "normal")});
    uploadImage(textures->nDotV, buffer.nDotV);
    uploadImage(textures->depth, buffer.depth);
    uploadImage(textures->normal, buffer.normal);
    return *kept.emplace(size, std::move(textures)).first->second;
}

std::unique_ptr<GpuNeighbourPairsKernel> kernelOf(Kind kind, ShaderLibrary& shaders) {
    switch (kind) {
    case Kind::Contour: return std::make_unique<GpuNeighbourPairsKernel>("gbuffer", ContourSettings{}, shaders);
    case Kind::DepthEdge: return std::make_unique<GpuNeighbourPairsKernel>("gbuffer", DepthEdgeSettings{}, shaders);
    case Kind::NormalEdge: return std::make_unique<GpuNeighbourPairsKernel>("gbuffer", NormalEdgeSettings{}, shaders);
    }
    return nullptr;
}

std::vector<const GlTexture*> inputsOf(Kind kind, const TorusTextures& textures) {
    switch (kind) {
    case Kind::Contour: return {&textures.nDotV, &textures.depth};
    case Kind::DepthEdge: return {&textures.depth};
    case Kind::NormalEdge: return {&textures.normal, &textures.depth};
    }
    return {};
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void runOn(benchmark::State& state, Kind kind, bool gpu) {
    const int size = int(state.range(0));
    const TorusTextures& textures = torusTextures(size);
    static ShaderLibrary shaders;
    std::unique_ptr<GpuNeighbourPairsKernel> kernel = kernelOf(kind, shaders);
    kernel->prepare();
    const std::vector<const GlTexture*> inputs = inputsOf(kind, textures);
    double readback = 0.0, work = 0.0;
    std::size_t points = 0;
    for (auto _ : state) {
        auto start = std::chrono::steady_clock::now();
        LineSkeleton skeleton;
        if (gpu) {
            skeleton = kernel->findInTextures(inputs);
            const double total = millisecondsSince(start);
            work += total;
            state.SetIterationTime(total * 1e-3);
        } else {
            std::vector<cv::Mat> images;
            for (const GlTexture* input : inputs) images.push_back(readTexture(*input));
            const double fetched = millisecondsSince(start);
            start = std::chrono::steady_clock::now();
            skeleton = kernel->find(images); // the postfx kernel
            const double found = millisecondsSince(start);
            readback += fetched;
            work += found;
            state.SetIterationTime((fetched + found) * 1e-3);
        }
        points = skeleton.points.size();
        benchmark::DoNotOptimize(skeleton);
    }
    const double iterations = double(state.iterations());
    state.counters["readback_ms"] = readback / iterations;
    state.counters["kernel_ms"] = work / iterations;
    state.counters["points"] = double(points);
}

void BM_PostStageCpu_Contour(benchmark::State& state) { runOn(state, Kind::Contour, false); }
void BM_PostStageGpu_Contour(benchmark::State& state) { runOn(state, Kind::Contour, true); }
void BM_PostStageCpu_DepthEdge(benchmark::State& state) { runOn(state, Kind::DepthEdge, false); }
void BM_PostStageGpu_DepthEdge(benchmark::State& state) { runOn(state, Kind::DepthEdge, true); }
void BM_PostStageCpu_NormalEdge(benchmark::State& state) { runOn(state, Kind::NormalEdge, false); }
void BM_PostStageGpu_NormalEdge(benchmark::State& state) { runOn(state, Kind::NormalEdge, true); }

void sizes(benchmark::internal::Benchmark* benchmark) {
    benchmark->Arg(512)->Arg(1024)->ArgName("size")->UseManualTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_PostStageCpu_Contour)->Apply(sizes);
BENCHMARK(BM_PostStageGpu_Contour)->Apply(sizes);
BENCHMARK(BM_PostStageCpu_DepthEdge)->Apply(sizes);
BENCHMARK(BM_PostStageGpu_DepthEdge)->Apply(sizes);
BENCHMARK(BM_PostStageCpu_NormalEdge)->Apply(sizes);
BENCHMARK(BM_PostStageGpu_NormalEdge)->Apply(sizes);

} // namespace
} // namespace inkgraph::bench
