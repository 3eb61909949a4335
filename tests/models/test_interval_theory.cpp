// appendix B: the analytic steady state of the 1D absorbing interval against the walk
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/error.hpp"
#include "models/interval_theory.hpp"
#include "models/walks.hpp"

namespace gs::models {
namespace {

TEST(IntervalTheory, HypergeometricAgainstClosedForms) {
  // ₂F₁(½, ½; 3/2; z²) = arcsin z / z on both sides of the z = ½ switch; Gauss's value at 1;
  // F(y) of B.31 against an independent evaluation (scipy.special.hyp2f1) at y = 0.2
  for (double z : {0.1, 0.5, 0.7, 0.95, 0.999}) {
    EXPECT_NEAR(hyp2f1(0.5, 0.5, 1.5, z * z), std::asin(z) / z, 1e-13) << z;
  }
  const double a = -1.0 / 3.0, b = 1.0, c = 5.0 / 6.0;
  EXPECT_NEAR(hyp2f1(a, b, c, 1.0),
              std::tgamma(c) * std::tgamma(c - a - b) / (std::tgamma(c - a) * std::tgamma(c - b)),
              1e-13);
  EXPECT_NEAR(appendix_b_f(0.2), -0.44017082417812314, 1e-12);
  EXPECT_NEAR(appendix_b_f(0.8), 0.44017082417812314, 1e-12);  // odd about ½
  EXPECT_NEAR(appendix_b_f(0.0), -2.0, 1e-12);
  EXPECT_THROW(hyp2f1(1.0, 1.0, 2.0, 0.9), InputError);  // c − a − b = 0
}

TEST(IntervalTheory, QuadratureAndNormalisation) {
  // tanh–sinh on integrable end singularities: ∫₀¹ y^(−1/2) = 2, ∫₀¹ [y(1−y)]^(−1/6) = B(5/6, 5/6)
  EXPECT_NEAR(tanh_sinh([](double, double y, double) { return 1.0 / std::sqrt(y); }, 0.0, 1.0), 2.0,
              1e-12);
  const double beta = std::pow(std::tgamma(5.0 / 6.0), 2) / std::tgamma(5.0 / 3.0);
  EXPECT_NEAR(
      tanh_sinh([](double, double y, double w) { return std::pow(y * w, -1.0 / 6.0); }, 0.0, 1.0),
      beta, 1e-11);
  // the arrival density is normalised (its constant comes from the oddness of F)
  const double total = tanh_sinh(
      [](double u, double, double) { return u > 0.0 ? appendix_b_arrival_density(u) : 0.0; }, 0.0,
      8.0);
  EXPECT_NEAR(total, 1.0, 1e-6);
  // the mean-exit-time coefficient against an independent quadrature (scipy, 1.0190977852)
  EXPECT_NEAR(appendix_b_mean_exit_time_coefficient(), 1.0190977852392704, 1e-8);
}

TEST(IntervalTheory, WalkMatchesAppendixB) {
  // 40 000 walks released at rest at uniform x in (0, L), D_v = 1, L = 1, Δt = 5·10⁻⁴ (≈ 2000
  // steps per walk; the exit is detected up to one step late, +Δt/2 ≈ 0.05 %):
  //  * ⟨τ⟩ within 4σ (+0.1 % for Δt) of c (L²M²/D)^(1/3), c ≈ 1.0191 from B.32;
  //  * the arrival velocities at x = L against f(u) of B.32 (thesis Fig. B.1): every bin with
  //    ≥ 20 expected arrivals within 5σ (Poisson) and χ²_r < 1.5
  WalkParams p;
  p.noise = 1.0;
  p.mass = 1.0;
  p.dt = 5e-4;
  p.walks = 40000;
  p.seed = 77;
  p.v_max = 5.0;
  p.bins = 200;
  const WalkResult r = interval_walk(p, 1.0, IntervalStart::uniform);
  const double c = appendix_b_mean_exit_time_coefficient();
  EXPECT_NEAR(r.mean_exit_time, c, 4.0 * r.exit_time_err + 1e-3 * c);
  const auto bins = r.arrival.bins();
  double arrivals = 0.0;
  for (const auto& b : bins)
    if (b.x > 0.0) arrivals += b.count;
  EXPECT_NEAR(arrivals, 20000.0, 5.0 * std::sqrt(40000 * 0.25));  // half leave at each end
  double chi2 = 0.0;
  int used = 0;
  for (const auto& b : bins) {
    if (!(b.lo >= 0.0)) continue;
    // expected count: the bin integral of f(u) by Simpson's rule
    const double fe = (appendix_b_arrival_density(std::max(b.lo, 1e-9)) +
                       4.0 * appendix_b_arrival_density(b.x) + appendix_b_arrival_density(b.hi)) /
                      6.0 * (b.hi - b.lo);
    const double expected = arrivals * fe;
    if (expected < 20.0) continue;
    EXPECT_NEAR(b.count, expected, 5.0 * std::sqrt(expected)) << "v = " << b.x;
    chi2 += (b.count - expected) * (b.count - expected) / expected;
    ++used;
  }
  EXPECT_GT(used, 50);
  EXPECT_LT(chi2 / used, 1.5);
  std::printf(
      "[ measured ] appendix B: <tau> = %.4f ± %.4f (theory %.4f); arrival chi2_r %.2f over %d "
      "bins\n",
      r.mean_exit_time, r.exit_time_err, c, chi2 / used, used);
}

}  // namespace
}  // namespace gs::models
