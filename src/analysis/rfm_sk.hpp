// structure factor of points in a periodic L×L box (thesis §4.1, T.4.2–T.4.9):
//   S(k) = (1/N) ⟨|Σ_j exp(i k·r_j)|²⟩,  k = (2π/L)(n_x, n_y), integer n, k ≠ 0,
// averaged over shells of equal |k| and over snapshots, and the fractal-dimension fit
// S = A k^(−D_f) below k′ with k_D = (2 − ε_n² − ε_t²)/(8 l₀), l₀ = L²/(2dN) (T.4.5, T.4.7),
// k′ = k_D when L > L_Eff = 2√2·2π/k_D (T.4.6, T.4.9), else 2k_D.
//
// Modes: S(−k) = S(k) for real positions, so only the half plane n_y > 0 or (n_y = 0, n_x > 0)
// is evaluated, every ± pair once. Shells: by default the exact groups of equal n² = n_x² + n_y²
// (each shell one exact |k|); ShellGrouping::rounded groups by the nearest integer |n| instead
// (fewer, fuller shells). Cost: O(N·n_modes) real multiplies per snapshot — the phases
// exp(i 2π n x/L) of each particle come from one complex exponential and a recurrence.
#pragma once
#include <filesystem>
#include <span>
#include <vector>

#include "core/bytes.hpp"
#include "core/records.hpp"
#include "core/vec.hpp"

namespace gs::rfm {

/// how modes are grouped into shells of |k|
enum class ShellGrouping {
  exact,   ///< one shell per distinct n² = n_x² + n_y²
  rounded  ///< one shell per nearest integer |n|
};

/// one shell of the shell-averaged structure factor
struct SkShell {
  double k = 0.0;      ///< mean |k| of the shell's modes, 1/m (or 1/box unit)
  double n = 0.0;      ///< the same in units of 2π/L, dimensionless
  double s = 0.0;      ///< mean S over the shell's modes and all snapshots, dimensionless
  double s_err = 0.0;  ///< standard error of s from the scatter of its samples
  long modes = 0;      ///< distinct half-plane k-vectors in the shell
  long samples = 0;    ///< values averaged: modes × snapshots
};

/// S of one k-vector averaged over snapshots
struct SkMode {
  int nx = 0;      ///< k_x L/2π
  int ny = 0;      ///< k_y L/2π
  double s = 0.0;  ///< mean S, dimensionless
};

/// the half-plane integer modes with 0 < n_x² + n_y² ≤ n_max², in row order (n_y, then n_x)
std::vector<SkMode> half_plane_modes(int n_max);

/// averages values given per mode into shells of |k|
class ShellAccumulator {
 public:
  ShellAccumulator(double box, int n_max, ShellGrouping g = ShellGrouping::exact);
  /// one value of S for the mode (n_x, n_y); modes outside the cutoff are ignored
  void add(int nx, int ny, double s);
  std::vector<SkShell> shells() const;
  int n_max() const { return n_max_; }
  double box() const { return box_; }

  /// checkpoint: the sums (the shell layout comes from box and n_max)
  void save(ByteWriter& out) const;
  void load(ByteReader& in);

 private:
  int key(int nx, int ny) const;
  double box_;
  int n_max_;
  ShellGrouping grouping_;
  std::vector<int> shell_of_key_;  // key → shell index, −1 if none
  std::vector<double> sum_, sum2_, ksum_;
  std::vector<long> count_, modes_;
};

/// accumulates S(k) of point snapshots (T.4.2) on the integer grid |n| ≤ n_max
class StructureFactor2D {
 public:
  StructureFactor2D(double box, int n_max, ShellGrouping g = ShellGrouping::exact);
  /// adds one snapshot; positions may lie in any periodic image
  void add_snapshot(std::span<const Vec2> r);
  /// the shell averages over all snapshots so far
  std::vector<SkShell> shells() const { return shells_.shells(); }
  /// S of every half-plane mode averaged over snapshots
  std::vector<SkMode> modes() const;
  long snapshots() const { return snapshots_; }

  /// checkpoint: the sums over snapshots
  void save(ByteWriter& out) const;
  void load(ByteReader& in);

 private:
  double box_;
  int n_max_;
  std::vector<SkMode> modes_;     // layout of the mode arrays
  std::vector<int> row_begin_;    // first mode index of each n_y row
  std::vector<double> mode_sum_;  // Σ over snapshots of S per mode
  ShellAccumulator shells_;
  long snapshots_ = 0;
};

// ---- fractal dimension of the dissipative regime (T.4.4–T.4.9) -------------------------

/// mean free path l₀ = L²/(2dN) (T.4.7), m
double mean_free_path(double box, double diameter, long n);
/// k_D = (2 − ε_n² − ε_t²)/(8 l₀) (T.4.5), 1/m
double dissipative_wavenumber(double eps_n, double eps_t, double l0);
/// L_Eff = 2√2·L_min with L_min = 2π/k_D (T.4.6, T.4.9), m
double effective_box_size(double k_d);

/// a 2D RFM system as far as the D_f fit needs it
struct RfmSystem {
  double box = 0.2;        ///< L, m
  long n = 2000;           ///< N, particles
  double diameter = 3e-3;  ///< d, m
  double eps_n = 0.6;      ///< normal restitution, dimensionless
  double eps_t = 0.6;      ///< tangential restitution, dimensionless
};

/// a power-law fit S = A k^(−D_f)
struct DfFit {
  double d_f = 0.0;        ///< fractal dimension, dimensionless
  double d_f_err = 0.0;    ///< standard error (inflated by √χ²_r when χ²_r > 1)
  double amplitude = 0.0;  ///< A, units of S·k^D_f
  double chi2_r = 0.0;     ///< reduced χ², dimensionless
  int points = 0;          ///< shells in the fit
  double k_lo = 0.0;       ///< lowest k allowed in the fit, 1/m
  double k_hi = 0.0;       ///< highest k allowed in the fit (k′), 1/m
  double k_d = 0.0;        ///< k_D (0 when not an RFM fit), 1/m
  double l_eff = 0.0;      ///< L_Eff (0 when not an RFM fit), m
};

/// fits S = A k^(−D_f) to the shells with k_lo ≤ k ≤ k_hi, weighted by s_err when every
/// used shell has one; throws gs::InputError with fewer than two usable shells
DfFit fit_df(std::span<const SkShell> shells, double k_lo, double k_hi);
/// the thesis recipe: k′ from k_D and L_Eff of the system, fit over 0 < k ≤ k′ (T.4.5–4.9)
DfFit fit_df_rfm(std::span<const SkShell> shells, const RfmSystem& sys);

/// columns k, n, S, S_err, modes; metadata D_f, D_f_err, A, k_lo, k_hi, k_D, L_eff when a fit
/// is given (gransim.charts.rfm draws the fit line and marks k_D)
void write_sk_csv(const RecordSink& sink, const std::filesystem::path& path,
                  std::span<const SkShell> shells, const DfFit* fit = nullptr);

}  // namespace gs::rfm
