// T(t) in blocks of fixed duration, with the autocorrelation time of the samples
#include "analysis/rfm_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "analysis/stats.hpp"
#include "core/error.hpp"

namespace gs::rfm {

std::vector<TimeBlock> time_blocks(std::span<const double> t, std::span<const double> x,
                                   std::span<const double> steady, double block) {
  if (!(block > 0.0) || !std::isfinite(block))
    throw InputError("time_blocks", "block", "must be a positive duration");
  if (t.size() != x.size() || (!steady.empty() && steady.size() != t.size()))
    throw InputError("time_blocks", "", "times, values and steady flags differ in length");
  std::vector<TimeBlock> out;
  // sums of x − shift, the shift being the block's first value (no cancellation in the spread)
  double k_open = 0.0, shift = 0.0, s = 0.0, s2 = 0.0;
  const auto close = [&] {
    if (out.empty()) return;
    TimeBlock& b = out.back();
    b.mean = shift + s / b.n;
    b.sd = b.n > 1.0 ? std::sqrt(std::max(0.0, (s2 - s * s / b.n) / (b.n - 1.0))) : 0.0;
  };
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(t[i]) || (i > 0 && t[i] < t[i - 1]))
      throw InputError("time_blocks", "t",
                       "times must be finite and never go back (sample " + std::to_string(i) + ")");
    // the slack takes a sample written at kΔ less a rounding error into block k
    const double k = std::floor(t[i] / block + 1e-9);
    const bool st = steady.empty() || steady[i] != 0.0;
    if (out.empty() || k != k_open || st != out.back().steady) {
      close();
      out.push_back({t[i], 0.0, 0.0, 0.0, st});
      k_open = k;
      shift = x[i];
      s = s2 = 0.0;
    }
    const double d = x[i] - shift;
    s += d;
    s2 += d * d;
    out.back().n += 1.0;
  }
  close();
  return out;
}

void write_temperature_blocks_csv(const RecordSink& sink, const std::filesystem::path& path,
                                  const std::vector<TimeBlock>& blocks, double block,
                                  double sample_interval, std::span<const double> steady_t,
                                  std::span<const double> steady_values) {
  if (steady_t.size() != steady_values.size())
    throw InputError(path.string(), "", "steady times and values differ in length");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto tau_of = [&](const std::vector<double>& v) {
    return v.size() >= 2 ? autocorr_time(v).tau_int : nan;
  };
  const std::size_t n = steady_values.size();
  const std::vector<double> v(steady_values.begin(), steady_values.end());
  double mean = nan, err = nan, tau = tau_of(v), tau_first = nan, tau_second = nan;
  if (n >= 2) {
    mean = 0.0;
    for (double x : v) mean += x;
    mean /= static_cast<double>(n);
    double ss = 0.0;
    for (double x : v) ss += (x - mean) * (x - mean);
    err = std::sqrt(ss / static_cast<double>(n - 1) * 2.0 * tau / static_cast<double>(n));
    const double mid = 0.5 * (steady_t.front() + steady_t.back());
    std::vector<double> first, second;
    for (std::size_t i = 0; i < n; ++i) (steady_t[i] < mid ? first : second).push_back(v[i]);
    tau_first = tau_of(first);
    tau_second = tau_of(second);
  }
  const auto w = sink.create(path.string(), {"t", "n", "T", "T_sd", "steady"},
                             {{"block", block},
                              {"sample_interval", sample_interval},
                              {"samples", static_cast<double>(n)},
                              {"tau_int", tau},
                              {"T_mean", mean},
                              {"T_err", err},
                              {"tau_int_first", tau_first},
                              {"tau_int_second", tau_second}});
  for (const TimeBlock& b : blocks) w->row({b.t, b.n, b.mean, b.sd, b.steady ? 1.0 : 0.0});
}

}  // namespace gs::rfm
