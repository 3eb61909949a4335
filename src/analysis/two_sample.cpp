#include "analysis/two_sample.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/stats.hpp"
#include "core/error.hpp"

namespace gs {

double ks_statistic(std::vector<double> a, std::vector<double> b) {
  // samples compared many times are sorted once by the caller
  if (!std::is_sorted(a.begin(), a.end())) std::sort(a.begin(), a.end());
  if (!std::is_sorted(b.begin(), b.end())) std::sort(b.begin(), b.end());
  const double na = static_cast<double>(a.size()), nb = static_cast<double>(b.size());
  std::size_t i = 0, j = 0;
  double d = 0.0;
  // walk both sorted samples; ties advance together so the CDFs are compared after each value
  while (i < a.size() && j < b.size()) {
    const double x = std::min(a[i], b[j]);
    while (i < a.size() && a[i] <= x) ++i;
    while (j < b.size() && b[j] <= x) ++j;
    d = std::max(d, std::abs(static_cast<double>(i) / na - static_cast<double>(j) / nb));
  }
  return d;
}

double kolmogorov_q(double lambda) {
  // the alternating series converges fast for λ ≳ 0.3; below 0.2, 1 − Q < 1e-15
  if (lambda < 0.2) return 1.0;
  double sum = 0.0, sign = 1.0;
  for (int k = 1; k <= 100; ++k) {
    const double term = sign * std::exp(-2.0 * k * k * lambda * lambda);
    sum += term;
    if (std::abs(term) < 1e-16 * std::abs(sum)) break;
    sign = -sign;
  }
  return std::clamp(2.0 * sum, 0.0, 1.0);
}

double ks_p_value(double d, double na, double nb) {
  const double ne = na * nb / (na + nb);
  const double s = std::sqrt(ne);
  return kolmogorov_q((s + 0.12 + 0.11 / s) * d);
}

TwoSampleTest two_sample_test(const std::vector<double>& a, double tau_a,
                              const std::vector<double>& b, double tau_b) {
  if (a.size() < 3 || b.size() < 3)
    throw InputError("two_sample_test", "", "needs at least 3 values in each sample");
  TwoSampleTest t;
  t.n_eff_a = std::max(2.0, static_cast<double>(a.size()) / (2.0 * std::max(tau_a, 0.5)));
  t.n_eff_b = std::max(2.0, static_cast<double>(b.size()) / (2.0 * std::max(tau_b, 0.5)));
  const double va = variance(a), vb = variance(b);
  // means: Welch's t with the Satterthwaite degrees of freedom
  const double ea = va / t.n_eff_a, eb = vb / t.n_eff_b;
  t.mean_diff = mean(b) - mean(a);
  t.mean_diff_err = std::sqrt(ea + eb);
  if (t.mean_diff_err > 0) {
    const double nu =
        (ea + eb) * (ea + eb) / (ea * ea / (t.n_eff_a - 1.0) + eb * eb / (t.n_eff_b - 1.0));
    t.p_mean = 2.0 * (1.0 - student_t_cdf(std::abs(t.mean_diff) / t.mean_diff_err, nu));
  }
  // spreads: F = s_b²/s_a² with (n_eff,b − 1, n_eff,a − 1) degrees of freedom
  if (va > 0 && vb > 0) {
    t.sigma_ratio = std::sqrt(vb / va);
    const double d1 = t.n_eff_b - 1.0, d2 = t.n_eff_a - 1.0, f = vb / va;
    const double cdf = beta_inc(0.5 * d1, 0.5 * d2, d1 * f / (d1 * f + d2));
    t.p_sigma = std::min(1.0, 2.0 * std::min(cdf, 1.0 - cdf));
  }
  t.ks_d = ks_statistic(a, b);
  t.ks_p = ks_p_value(t.ks_d, t.n_eff_a, t.n_eff_b);
  return t;
}

}  // namespace gs
