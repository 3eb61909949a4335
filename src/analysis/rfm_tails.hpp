// velocity distributions of the RFM (thesis appendix A and §5.1): a fixed-width histogram
// of one Cartesian component (x and y pooled in 2D) with Poisson errors (T.A.3–A.6);
// the stretched-exponential tail fit A·exp(−B|v|^α) (T.A.8, T.5.5) scanned over a grid of
// α, each a weighted straight line of ln P against |v|^α on the bins whose counts lie in
// a window (default 50…5000), accepting α while χ²_r < 1.2; the crossover form
//   P₀(v) = D·exp(−(v/v_r)² / (1 + |v/v_c|^(2−α)))   (T.5.32)
// as a nonlinear fit; and the ln–ln tail plot ln(−ln(P/A)) against ln|v| (§5.3.3).
#pragma once
#include <filesystem>
#include <span>
#include <vector>

#include "analysis/rfm_hist.hpp"
#include "core/records.hpp"
#include "core/vec.hpp"

namespace gs::rfm {

/// an empty symmetric velocity histogram on [−v_max, v_max) with n_bins bins (T.A.3)
Histogram velocity_histogram(double v_max, int n_bins);
/// adds both Cartesian components of every velocity (pooled x and y)
void add_components(Histogram& h, std::span<const Vec2> v);
/// adds scalar velocities (1D)
void add_values(Histogram& h, std::span<const double> v);

/// options of the stretched-exponential scan (appendix A)
struct TailFitOptions {
  double count_lo = 50.0;    ///< smallest bin count used, samples
  double count_hi = 5000.0;  ///< largest bin count used, samples
  double v_abs_min = 0.0;    ///< ignore bins with |v| below this (keeps the core out), m/s
  double alpha_lo = 0.3;     ///< first α of the grid
  double alpha_hi = 3.0;     ///< last α of the grid
  double alpha_step = 0.01;  ///< grid step of α
  double chi2_accept = 1.2;  ///< accept α while χ²_r is below this
  double error_scale = 1.0;  ///< s in σ = s√X (T.A.4); the thesis uses 2 for its † rows
};

/// one trial α of the scan
struct TailTrial {
  double alpha = 0.0;   ///< exponent, dimensionless
  double a = 0.0;       ///< amplitude of the density, s/m
  double b = 0.0;       ///< B, (s/m)^α
  double chi2_r = 0.0;  ///< reduced χ² of the line, dimensionless
};

/// the scan: every trial, the best α and the accepted range
struct TailFit {
  std::vector<TailTrial> trials;  ///< one per grid α
  TailTrial best;                 ///< the trial with the smallest χ²_r
  bool any_accepted = false;      ///< some α had χ²_r < chi2_accept
  double alpha_lo = 0.0;          ///< smallest accepted α
  double alpha_hi = 0.0;          ///< largest accepted α
  bool contiguous = true;         ///< the accepted α form one interval of the grid
  int points = 0;                 ///< bins in the window
  double v_lo = 0.0;              ///< smallest |v| of the window's bins, m/s
  double v_hi = 0.0;              ///< largest |v| of the window's bins, m/s
};

/// the appendix-A scan; throws gs::InputError with fewer than three bins in the window
TailFit fit_tail(const Histogram& h, const TailFitOptions& opt = {});
/// A·exp(−B|v|^α)
double stretched_exponential(double v, double a, double b, double alpha);

/// the crossover fit of T.5.32
struct CrossoverFit {
  double d = 0.0, d_err = 0.0;          ///< D, peak density, s/m
  double v_r = 0.0, v_r_err = 0.0;      ///< Gaussian velocity scale, m/s
  double v_c = 0.0, v_c_err = 0.0;      ///< crossover velocity, m/s
  double alpha = 1.0, alpha_err = 0.0;  ///< asymptotic exponent (fixed unless fitted)
  double chi2_r = 0.0;                  ///< reduced χ², dimensionless
  int points = 0;                       ///< bins used
  /// the tail scale v_A: P₀ → D·exp(−|v/v_A|^α) for |v| ≫ v_c (v_A = v_r²/v_c at α = 1)
  double v_a() const;
};

/// D·exp(−(v/v_r)²/(1 + |v/v_c|^(2−α))) (T.5.32)
double crossover_density(double v, double d, double v_r, double v_c, double alpha);
/// fits T.5.32 to the density of every bin with at least min_count samples (Poisson σ);
/// α stays at `alpha` unless fit_alpha
CrossoverFit fit_crossover(const Histogram& h, double alpha = 1.0, bool fit_alpha = false,
                           double min_count = 10.0);

/// one point of the ln–ln tail plot
struct LnLnPoint {
  double ln_v = 0.0;   ///< ln(|v|/v_scale)
  double y = 0.0;      ///< ln(−ln(P/A)); slope α for a stretched exponential
  double y_err = 0.0;  ///< propagated Poisson error
};
/// the bins with count ≥ min_count, v ≠ 0 and 0 < P < A (§5.3.3: use A = A₀ of the tail,
/// not P(0), or the asymptotic slope is distorted)
std::vector<LnLnPoint> lnln_tail(const Histogram& h, double amplitude, double v_scale = 1.0,
                                 double min_count = 1.0);

/// columns v, count, P, P_err, P_tail (inside the tail window only), P_cross (NaN when absent);
/// metadata with the fit parameters
void write_velocity_csv(const RecordSink& sink, const std::filesystem::path& path,
                        const Histogram& h, const TailFit* tail = nullptr,
                        const CrossoverFit* cross = nullptr);
/// columns alpha, chi2_r, A, B of the scan; metadata alpha_best, alpha_lo, alpha_hi
void write_tail_scan_csv(const RecordSink& sink, const std::filesystem::path& path,
                         const TailFit& fit);
/// columns ln_v, y, y_err; metadata A and v_scale
void write_lnln_csv(const RecordSink& sink, const std::filesystem::path& path,
                    std::span<const LnLnPoint> pts, double amplitude, double v_scale);

}  // namespace gs::rfm
