// the temperature T(t) of an RFM run in blocks of fixed duration: the coarse series a report
// reads and ships in place of every sample. Blocks are [kΔ, (k+1)Δ) of the run's clock, split
// where the steady state begins, so any period made of whole blocks has its mean exactly (the
// counts weigh the block means) and its variance exactly (from the within-block spreads); the
// error of a mean comes with the integrated autocorrelation time of the steady samples
// themselves, which blocks of Δ cannot resolve when T decorrelates within Δ.
#pragma once
#include <filesystem>
#include <span>
#include <vector>

#include "core/records.hpp"

namespace gs::rfm {

/// one block of a series
struct TimeBlock {
  double t = 0.0;     ///< time of the block's first sample, s
  double n = 0.0;     ///< samples in the block
  double mean = 0.0;  ///< mean of the samples, units of the series
  double sd = 0.0;    ///< their standard deviation (n − 1 in the denominator; 0 for one sample)
  bool steady = false;
};

/// the blocks of duration `block` (s) of samples x at times t, in time order; `steady` flags
/// each sample (empty: all steady), and a block never mixes steady and transient samples.
/// Throws gs::InputError when the lengths differ, the times go back or block ≤ 0
std::vector<TimeBlock> time_blocks(std::span<const double> t, std::span<const double> x,
                                   std::span<const double> steady, double block);

/// columns t, n, T, T_sd, steady; metadata: block (s), sample_interval (s), samples (steady),
/// tau_int (samples, Sokal's window over the steady samples at times steady_t), T_mean,
/// T_err = sd·√(2τ_int/n) of the steady samples, and tau_int_first / tau_int_second, the same
/// over the steady samples before and from the middle time (t_first + t_last)/2: a trend
/// across the halves inflates τ_int of the whole but not theirs
void write_temperature_blocks_csv(const RecordSink& sink, const std::filesystem::path& path,
                                  const std::vector<TimeBlock>& blocks, double block,
                                  double sample_interval, std::span<const double> steady_t,
                                  std::span<const double> steady_values);

}  // namespace gs::rfm
