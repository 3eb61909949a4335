// two-sample tests for tap series: are two runs (e.g. fixed-period and early-rest relaxation,
// or two integrators) samples of the same φ distribution? Taps are correlated, so every test
// uses effective sample sizes n_eff = n/(2 τ_int) (stats.hpp) instead of the tap counts.
#pragma once
#include <vector>

namespace gs {

/// the two-sample Kolmogorov–Smirnov statistic D = sup |F_a − F_b| (empirical CDFs)
double ks_statistic(std::vector<double> a, std::vector<double> b);
/// Kolmogorov's asymptotic tail Q_KS(λ) = 2 Σ_{k≥1} (−1)^{k−1} e^{−2k²λ²}
double kolmogorov_q(double lambda);
/// p-value of D for effective sizes na, nb (Stephens' small-sample correction:
/// λ = (√n_e + 0.12 + 0.11/√n_e) D with n_e = na nb/(na + nb))
double ks_p_value(double d, double na, double nb);

/// the comparison of two samples
struct TwoSampleTest {
  double n_eff_a = 0.0, n_eff_b = 0.0;  ///< effective sizes n/(2 τ_int)
  double mean_diff = 0.0;               ///< mean(b) − mean(a)
  double mean_diff_err = 0.0;           ///< its standard error √(s_a²/n_eff,a + s_b²/n_eff,b)
  double p_mean = 1.0;       ///< two-sided p of the difference (Welch, Satterthwaite dof)
  double sigma_ratio = 1.0;  ///< s_b / s_a
  double p_sigma = 1.0;      ///< two-sided F-test p of s_b² / s_a² (dof n_eff − 1)
  double ks_d = 0.0;         ///< Kolmogorov–Smirnov D
  double ks_p = 1.0;         ///< its p-value with the effective sizes
};

/// compare samples a and b with integrated autocorrelation times tau_a, tau_b (0.5:
/// independent). Needs at least 3 values in each.
TwoSampleTest two_sample_test(const std::vector<double>& a, double tau_a,
                              const std::vector<double>& b, double tau_b);

}  // namespace gs
