// moments and temperatures of the RFM (thesis §2.2.3, §3.1–3.2, §3.3.1):
//   ⟨|v|^m⟩ = (1/(N N_t)) Σ_τ Σ_i |v_i(t_τ)|^m, m = 1…12 (T.3.11), the same for gaps ⟨R^m⟩
//   (T.3.18); the exponents of ⟨|v|^m⟩ ∝ N^(−ξ_m) (T.3.13) and ⟨R^m⟩ ∝ N^(−ζ_m) (T.3.20) by
//   weighted least squares on logarithms across system sizes; the granular temperature
//   T = (1/N) Σ|v_i − ⟨v⟩|² (T.2.19, no ½, no mass) and its block averages (T.2.20).
#pragma once
#include <filesystem>
#include <span>
#include <vector>

#include "core/bytes.hpp"
#include "core/records.hpp"
#include "core/vec.hpp"

namespace gs::rfm {

/// ⟨|x|^m⟩ for m = 1…m_max of one set of values (element m−1 holds moment m)
std::vector<double> abs_moments(std::span<const double> x, int m_max = 12);

/// moments per snapshot (T.3.11) and their mean and standard error over snapshots
class MomentSeries {
 public:
  explicit MomentSeries(int m_max = 12);
  /// one snapshot of scalar values (1D velocities or gaps)
  void add_snapshot(std::span<const double> x);
  /// one snapshot of 2D velocities, both components pooled (|v_x|^m and |v_y|^m)
  void add_components(std::span<const Vec2> v);
  /// one snapshot of 2D speeds |v|
  void add_speeds(std::span<const Vec2> v);

  int m_max() const { return m_max_; }
  long snapshots() const { return static_cast<long>(per_snapshot_.size()); }
  /// ⟨|x|^m⟩ over all snapshots, weighting snapshots by their sample counts
  std::vector<double> mean() const;
  /// standard error of the mean from the scatter of snapshot means (needs ≥ 2 snapshots;
  /// snapshots are taken as independent — block them first if they are correlated)
  std::vector<double> error() const;
  /// the moments of each snapshot, [snapshot][m−1]
  const std::vector<std::vector<double>>& per_snapshot() const { return per_snapshot_; }

  /// checkpoint: every snapshot so far
  void save(ByteWriter& out) const;
  void load(ByteReader& in);

 private:
  int m_max_;
  std::vector<std::vector<double>> per_snapshot_;
  std::vector<double> weights_;
};

/// an exponent of y ∝ N^(−exponent)
struct ExponentFit {
  int m = 0;                  ///< moment order (0 when not set)
  double exponent = 0.0;      ///< ξ_m or ζ_m, dimensionless
  double exponent_err = 0.0;  ///< standard error (inflated by √χ²_r when χ²_r > 1)
  double amplitude = 0.0;     ///< prefactor c of y = c N^(−exponent), units of y
  double chi2_r = 0.0;        ///< reduced χ², dimensionless
};

/// fits y = c·N^(−exponent) by weighted least squares on ln y against ln N
/// (σ_ln y = y_err/y; empty y_err → unit weights)
ExponentFit fit_scaling_exponent(std::span<const double> n, std::span<const double> y,
                                 std::span<const double> y_err = {});
/// one fit per moment order: moments[i][m−1] and errors[i][m−1] for system size n[i]
std::vector<ExponentFit> fit_scaling_exponents(std::span<const double> n,
                                               const std::vector<std::vector<double>>& moments,
                                               const std::vector<std::vector<double>>& errors);

/// granular temperature T = (1/N) Σ|v_i − ⟨v⟩|² (T.2.19), m²/s²
double granular_temperature(std::span<const Vec2> v);
/// the 1D version, m²/s²
double granular_temperature(std::span<const double> v);

/// block averages of a time series (T.2.20 over blocks of equal length)
struct BlockAverage {
  std::vector<double> block_means;  ///< mean of each complete block, units of the series
  std::size_t block_len = 0;        ///< samples per block
  double mean = 0.0;                ///< mean of the complete blocks
  double error = 0.0;               ///< standard error from the block scatter (≥ 2 blocks)
};
/// splits the series into ⌊n/block_len⌋ complete blocks (a trailing partial block is dropped)
BlockAverage block_average(std::span<const double> series, std::size_t block_len);

/// columns t, T and, with blocks, T_block (the mean of the block holding each sample, NaN in
/// a dropped partial block); metadata T_mean and T_err from the blocks
void write_temperature_csv(const RecordSink& sink, const std::filesystem::path& path,
                           std::span<const double> t, std::span<const double> temp,
                           const BlockAverage* blocks = nullptr);
/// columns m, moment, error
void write_moments_csv(const RecordSink& sink, const std::filesystem::path& path,
                       std::span<const double> mean, std::span<const double> err);

}  // namespace gs::rfm
