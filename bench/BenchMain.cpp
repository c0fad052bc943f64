// The benchmarks of bench/*Bench.cpp in one program: inkgraph_bench --benchmark_filter=REGEX
#include "render/BackgroundThreads.h"

#include <benchmark/benchmark.h>

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    // The end every inkgraph process shares (render/BackgroundThreads.h).
    inkgraph::finishProcess();
    return 0;
}
