// The benchmarks of bench/*Bench.cpp in one program: inkgraph_bench --benchmark_filter=REGEX
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
