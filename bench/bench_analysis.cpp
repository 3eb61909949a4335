// the tapping analysis (gs::run_tap_analysis, the statistics `gransim analyze` writes) on n taps
// in all, 10⁴ … 10⁶, split three ways: one series; one beside a 50-tap series; ten series of
// n/10. Complexity is fitted over n, so the report reads whether the work stays linear in the
// taps; the counters give taps per second and the joint fit's cells.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "analysis/tap_analysis.hpp"
#include "one_thread.hpp"

namespace gs {
namespace {

// a series of n taps of φ around `mean` (σ_φ = 0.002, independent taps)
TapRunInput series(int n, double mean, int k) {
  std::mt19937_64 rng(1000 + k);
  std::normal_distribution<double> noise(0.0, 0.002);
  TapRunInput r;
  r.label = "s" + std::to_string(k);
  for (int i = 0; i < n; ++i) r.series.phi.push_back(mean + noise(rng));
  return r;
}

// range(0): taps in all; split: 0 one series, 1 beside a 50-tap one, 2 ten series
void BM_TapAnalysis(benchmark::State& st, int split) {
  const OneThread one;
  const int n = static_cast<int>(st.range(0));
  std::vector<TapRunInput> runs;
  if (split == 2) {
    for (int k = 0; k < 10; ++k) runs.push_back(series(n / 10, 0.815 + 0.001 * k, k));
  } else {
    runs.push_back(series(n, 0.82, 0));
    if (split == 1) runs.push_back(series(60, 0.821, 1));
  }
  TapAnalysisOptions opts;
  opts.test_area = 0.01;
  int cells = 0;
  for (auto _ : st) {
    const TapAnalysisResult r = run_tap_analysis(runs, opts);
    cells = r.multi.values;
    benchmark::DoNotOptimize(r.runs.data());
  }
  st.SetComplexityN(n);
  st.counters["taps/s"] =
      benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
  st.counters["cells"] = cells;
}
BENCHMARK_CAPTURE(BM_TapAnalysis, one_series, 0)
    ->RangeMultiplier(10)
    ->Range(10000, 1000000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Complexity(benchmark::oN);
BENCHMARK_CAPTURE(BM_TapAnalysis, beside_50_taps, 1)
    ->RangeMultiplier(10)
    ->Range(10000, 1000000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Complexity(benchmark::oN);
BENCHMARK_CAPTURE(BM_TapAnalysis, ten_series, 2)
    ->RangeMultiplier(10)
    ->Range(10000, 1000000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Complexity(benchmark::oN);

}  // namespace
}  // namespace gs
