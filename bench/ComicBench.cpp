// Seed 000's comparison, warm, at 1024x1024 on UV spheres of 1k to 1M triangles (auto-framed, so the eye is about
// 3 radii away and the constant view vector applies): standard comic (Lander: 1-D shade map + back-face outline)
// against specular comic with exact view vectors, with the constant view vector, and with each CPU face-orientation
// method. The time of one case is the shade pass plus the outline pass (execute() to glFinish); for the CPU
// methods the marking and per-vertex lighting run every frame (the camera of an animation moves), inside the passes.
//   LP_NUM_THREADS=1 ./build/bench/inkgraph_bench --benchmark_filter=Comic
#include "bench/BenchScene.h"

namespace inkgraph::bench {
namespace {

struct ComicCase {
    const char* name;
    std::vector<std::string> arguments;
};

const std::vector<ComicCase>& comicCases() {
    static const std::vector<ComicCase> kCases = {
        {"StandardComic", {"--shading", "cel", "--lines", "outline"}},
        {"SpecularExact", {"--shading", "comic", "--lines", "outline"}},
        {"SpecularConstant", {"--shading", "comic", "--view-vector", "constant", "--lines", "outline"}},
        {"DuringTriangles",
         {"--shading", "comic", "--view-vector", "constant", "--face-orientation", "during-triangles", "--lines",
          "outline"}},
        {"DuringVertices",
         {"--shading", "comic", "--view-vector", "constant", "--face-orientation", "during-vertices", "--lines",
          "outline"}},
        {"AfterVertices",
         {"--shading", "comic", "--view-vector", "constant", "--face-orientation", "after-vertices", "--lines",
          "outline"}},
        {"AfterVerticesExact",
         {"--shading", "comic", "--face-orientation", "after-vertices", "--lines", "outline"}},
    };
    return kCases;
}

void runComicCase(benchmark::State& state, const ComicCase& comicCase) {
    Bench bench(sphereScene(int(state.range(0))), benchOptions(comicCase.arguments), {"composite.final"});
    auto frameMilliseconds = [&](double& shade, double& outline) {
        bench.graph.orientation->invalidate(); // a new frame: the CPU methods mark again
        shade = outline = 0.0;
        for (const PassTiming& timing : bench.run()) {
            if (timing.pass == "shade") shade = timing.milliseconds;
            if (timing.pass == "outline") outline = timing.milliseconds;
        }
    };
    double shade = 0.0, outline = 0.0, shadeSum = 0.0, outlineSum = 0.0;
    frameMilliseconds(shade, outline); // warm-up: llvmpipe compiles shader variants on the first draw
    for (auto _ : state) {
        frameMilliseconds(shade, outline);
        shadeSum += shade;
        outlineSum += outline;
        state.SetIterationTime((shade + outline) / 1000.0);
    }
    const double iterations = double(std::max<benchmark::IterationCount>(state.iterations(), 1));
    state.counters["triangles"] = double(bench.scene.triangleCount());
    state.counters["shade_ms"] = shadeSum / iterations;
    state.counters["outline_ms"] = outlineSum / iterations;
    if (bench.graph.orientation->usesCpuMarking()) {
        const OrientationReport& report = bench.graph.orientation->report();
        state.counters["front_share"] = double(report.frontTriangles) / double(report.triangles);
        state.counters["mark_ms"] = report.markMilliseconds;
        state.counters["holes"] = double(report.missedTriangles);
    }
}

const bool kRegistered = [] {
    for (const ComicCase& comicCase : comicCases())
        benchmark::RegisterBenchmark((std::string("BM_Comic/") + comicCase.name).c_str(),
                                     [&comicCase](benchmark::State& state) { runComicCase(state, comicCase); })
            ->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000)
            ->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.5);
    return true;
}();

} // namespace
} // namespace inkgraph::bench
