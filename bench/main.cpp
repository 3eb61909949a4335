// one main for every benchmark file
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
