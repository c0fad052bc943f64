// Winnemöller & Bangay 2002's comparison, warm, at 1024x1024 on UV spheres of 1k to 1M triangles (auto-framed, so the
// eye is about 3 radii away and the constant view vector applies): standard comic (Lander: 1-D shade map + back-face
// outline) against specular comic with exact view vectors, with the constant view vector, and with each CPU
// face-orientation method. The time of one case is the shade pass plus the outline pass (prepare() plus execute() to
// glFinish); for the CPU methods the marking, per-vertex lighting and upload run every frame (an animation's camera
// moves), in the first prepare() that asks for them. BM_ComicOverhead runs standard comic and one other case
// alternately, frame by frame, and reports the median overhead over 9 rounds (the hosts are shared; back-to-back runs
// of one case drift by 10-30%).
//   LP_NUM_THREADS=1 ./build/bench/inkgraph_bench --benchmark_filter=ComicOverhead
#include "bench/BenchScene.h"
#include "bench/Median.h"
#include "passes/orientation/SceneOrientation.h"

namespace inkgraph::bench {
namespace {

struct ComicCase {
    const char* name;
    Look look;
};

/** Comic shading (or cel: Lander's standard comic) with Lander's outline. */
Look comicLook(ShadingModel shading, ViewVectorMode viewVector = ViewVectorMode::Exact,
               FaceOrientationMethod method = FaceOrientationMethod::Standard) {
    Look look;
    look.shading = shading;
    look.viewVector = viewVector;
    look.faceOrientation = method;
    look.lines = {"outline"};
    return look;
}

const std::vector<ComicCase>& comicCases() {
    using M = FaceOrientationMethod;
    constexpr ViewVectorMode kConstant = ViewVectorMode::Constant;
    static const std::vector<ComicCase> kCases = {
        {"StandardComic", comicLook(ShadingModel::Cel)},
        {"SpecularExact", comicLook(ShadingModel::Comic)},
        {"SpecularConstant", comicLook(ShadingModel::Comic, kConstant)},
        {"DuringTriangles", comicLook(ShadingModel::Comic, kConstant, M::DuringTriangles)},
        {"DuringVertices", comicLook(ShadingModel::Comic, kConstant, M::DuringVertices)},
        {"AfterVertices", comicLook(ShadingModel::Comic, kConstant, M::AfterVertices)},
        {"AfterVerticesExact", comicLook(ShadingModel::Comic, ViewVectorMode::Exact, M::AfterVertices)},
    };
    return kCases;
}

/** Shade + outline milliseconds of one fresh frame (a CPU method marks again), and the shade pass alone. */
struct FrameTime {
    double shade = 0.0;
    double total = 0.0;
};
FrameTime timeFrame(Bench& bench) {
    if (SceneOrientation* orientation = bench.gpuScene->cpuOrientation()) orientation->invalidate();
    FrameTime time;
    // prepare() counts too: that is where the CPU methods mark, light and upload (once per frame, for both passes).
    for (const PassTiming& timing : bench.run()) {
        const double milliseconds = timing.prepareMilliseconds + timing.milliseconds;
        if (timing.pass == "shade") time.shade = milliseconds;
        if (timing.pass == "shade" || timing.pass == "outline") time.total += milliseconds;
    }
    return time;
}

void runComicCase(benchmark::State& state, const ComicCase& comicCase) {
    Bench bench(sphereScene(int(state.range(0))), comicCase.look, {"composite.final"});
    double shadeSum = 0.0, outlineSum = 0.0;
    timeFrame(bench); // warm-up: llvmpipe compiles shader variants on the first draw
    for (auto _ : state) {
        const FrameTime time = timeFrame(bench);
        shadeSum += time.shade;
        outlineSum += time.total - time.shade;
        state.SetIterationTime(time.total / 1000.0);
    }
    const double iterations = double(std::max<benchmark::IterationCount>(state.iterations(), 1));
    state.counters["triangles"] = double(bench.scene.triangleCount());
    state.counters["shade_ms"] = shadeSum / iterations;
    state.counters["outline_ms"] = outlineSum / iterations;
    if (SceneOrientation* orientation = bench.gpuScene->cpuOrientation()) {
        const OrientationReport& report = orientation->report();
        state.counters["front_share"] = double(report.frontTriangles) / double(report.triangles);
        state.counters["mark_ms"] = report.markMilliseconds;
        state.counters["holes"] = double(report.missedTriangles);
    }
}

/** Winnemöller & Bangay 2002's headline number, robust to a shared host: standard comic and `comicCase` run alternately
 * on the same mesh, frame by frame, so drifts in the machine's speed hit both; the overhead is the median of the
 * per-round ratios. The manual time is the comic case's frame. */
void runOverheadCase(benchmark::State& state, const ComicCase& comicCase) {
    Bench standard(sphereScene(int(state.range(0))), comicCases().front().look, {"composite.final"});
    Bench specular(sphereScene(int(state.range(0))), comicCase.look, {"composite.final"});
    timeFrame(standard); // warm-up: llvmpipe compiles shader variants on the first draw
    timeFrame(specular);
    std::vector<double> totalRatios, shadeRatios, standardTotals, specularTotals;
    for (auto _ : state) {
        const FrameTime a = timeFrame(standard);
        const FrameTime b = timeFrame(specular);
        totalRatios.push_back(b.total / a.total);
        shadeRatios.push_back(b.shade / a.shade);
        standardTotals.push_back(a.total);
        specularTotals.push_back(b.total);
        state.SetIterationTime(b.total / 1000.0);
    }
    state.counters["triangles"] = double(specular.scene.triangleCount());
    state.counters["standard_ms"] = median(standardTotals);
    state.counters["comic_ms"] = median(specularTotals);
    state.counters["overhead_pct"] = 100.0 * (median(totalRatios) - 1.0);
    state.counters["shade_overhead_pct"] = 100.0 * (median(shadeRatios) - 1.0);
}

const bool kRegistered = [] {
    for (const ComicCase& comicCase : comicCases())
        benchmark::RegisterBenchmark((std::string("BM_Comic/") + comicCase.name).c_str(),
                                     [&comicCase](benchmark::State& state) { runComicCase(state, comicCase); })
            ->Arg(1000)
            ->Arg(10000)
            ->Arg(100000)
            ->Arg(1000000)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond)
            ->MinTime(0.5);
    for (const ComicCase& comicCase : comicCases()) {
        if (&comicCase == &comicCases().front()) continue;
        benchmark::RegisterBenchmark((std::string("BM_ComicOverhead/") + comicCase.name).c_str(),
                                     [&comicCase](benchmark::State& state) { runOverheadCase(state, comicCase); })
            ->Arg(1000)
            ->Arg(10000)
            ->Arg(100000)
            ->Arg(1000000)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond)
            ->Iterations(9);
    }
    return true;
}();

} // namespace
} // namespace inkgraph::bench
