// What --msaa costs (issue 34, docs/performance.md "Multisampling"): the still at 1024x1024 with 1, 2, 4 and 8 samples
// per pixel (those the driver draws), with the default lines (silhouette + contour) and cel or mtoon (the models the
// default `auto` gives an OBJ and a VRM's MToon materials; godette's outline shells with mtoon), on godette.vrm and
// the bunny. The sample counts alternate round by round; a round's time is the sum of the passes' own execute() up to
// glFinish (what --stats reports), warm. Counters: the median per count (`msaaN_ms`, and the shade pass alone,
// `msaaN_shade_ms`), and `ratioN`, the median of the per-round ratios to one sample, which a shared host's drift
// skews less.
#include "bench/BenchScene.h"
#include "bench/Median.h"
#include "render/DefaultLook.h"

#include <map>

namespace inkgraph::bench {
namespace {

const std::string kGodettePath = std::string(INKGRAPH_SOURCE_ROOT) + "/models/characters/godette.vrm";

struct StillTime {
    double total = 0.0;
    double shade = 0.0;
};

StillTime timeStill(Bench& bench) {
    StillTime time;
    for (const PassTiming& timing : bench.run()) {
        time.total += timing.milliseconds;
        if (timing.pass == "shade") time.shade = timing.milliseconds;
    }
    return time;
}

void BM_Msaa(benchmark::State& state, const std::string& modelPath, ShadingModel model) {
    context();
    std::vector<int> counts;
    for (const int samples : {1, 2, 4, 8})
        if (samples <= maxSamples()) counts.push_back(samples);
    std::vector<std::unique_ptr<Bench>> benches;
    for (const int samples : counts) {
        Look look = defaultLook();
        look.shading = model;
        look.msaa = samples;
        benches.push_back(
            std::make_unique<Bench>(loadScene(modelPath), look, std::vector<std::string>{"composite.final"}));
        timeStill(*benches.back()); // warm-up: llvmpipe compiles shader variants on the first draw
    }
    std::map<int, std::vector<double>> totals, shades, ratios;
    for (auto _ : state) {
        double single = 0.0;
        for (std::size_t i = 0; i < counts.size(); ++i) {
            const StillTime time = timeStill(*benches[i]);
            if (counts[i] == 1) single = time.total;
            totals[counts[i]].push_back(time.total);
            shades[counts[i]].push_back(time.shade);
            if (counts[i] > 1 && single > 0.0) ratios[counts[i]].push_back(time.total / single);
            if (counts[i] == 4) state.SetIterationTime(time.total / 1000.0);
        }
    }
    for (const int samples : counts) {
        const std::string n = std::to_string(samples);
        state.counters["msaa" + n + "_ms"] = median(totals[samples]);
        state.counters["msaa" + n + "_shade_ms"] = median(shades[samples]);
        if (samples > 1) state.counters["ratio" + n] = median(ratios[samples]);
    }
    state.counters["max_samples"] = maxSamples();
}
BENCHMARK_CAPTURE(BM_Msaa, cel_bunny, kBunnyPath, ShadingModel::Cel)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(7);
BENCHMARK_CAPTURE(BM_Msaa, cel_godette, kGodettePath, ShadingModel::Cel)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(7);
BENCHMARK_CAPTURE(BM_Msaa, mtoon_bunny, kBunnyPath, ShadingModel::MToon)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(7);
BENCHMARK_CAPTURE(BM_Msaa, mtoon_godette, kGodettePath, ShadingModel::MToon)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(7);

} // namespace
} // namespace inkgraph::bench
