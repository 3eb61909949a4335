// free-path histogram and the fit of P_l = A₀ l^(D_f−2) exp(−C l^(D_f−1)) (T.4.25)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "analysis/rfm_freepath.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace gs::rfm {
namespace {

// T.4.25 over 0 < l < ∞ is a Weibull density: C l^β (β = D_f − 1) is Exp(1), so
// l = (E/C)^(1/β) and the normalised amplitude is A₀ = C β
Histogram weibull_paths(double d_f, double c, long n, std::uint64_t seed) {
  RngStream rng(seed, 0);
  Histogram h = free_path_histogram(1e-7, 1e-1, 60);
  const double beta = d_f - 1.0;
  for (long i = 0; i < n; ++i) h.add(std::pow(-std::log(rng.uniform()) / c, 1.0 / beta));
  return h;
}

TEST(RfmFreePath, FitRecoversTheParameters) {
  // 10⁶ paths with the thesis' D_f = 1.63 and C = 121 m^(−0.63) (§5.3.3, φ = 0.53): the fit over
  // all bins with ≥ 10 counts must return D_f, C and A₀ = Cβ within 4σ of its errors, with
  // χ²_r ≈ 1 (the model is the exact bin average, so no binning bias)
  const double d_f = 1.63, c = 121.0;
  const Histogram h = weibull_paths(d_f, c, 1'000'000, 81);
  const FreePathFit f = fit_free_paths(h);
  EXPECT_NEAR(f.d_f, d_f, 4.0 * f.d_f_err);
  EXPECT_NEAR(f.c, c, 4.0 * f.c_err);
  EXPECT_NEAR(f.a0, c * (d_f - 1.0), 4.0 * f.a0_err);
  EXPECT_LT(f.d_f_err, 0.01);
  EXPECT_NEAR(f.chi2_r, 1.0, 0.5);
  std::printf(
      "[ measured ] free paths: D_f %.4f ± %.4f, C %.2f ± %.2f, A0 %.2f ± %.2f, chi2_r %.2f\n",
      f.d_f, f.d_f_err, f.c, f.c_err, f.a0, f.a0_err, f.chi2_r);
}

TEST(RfmFreePath, TailOnlyFitAndAnotherDimension) {
  // the thesis fits the long-distance tail only: start at the median path and use D_f = 1.4
  const double d_f = 1.4, c = 30.0;
  const Histogram h = weibull_paths(d_f, c, 1'000'000, 82);
  const double median = std::pow(std::log(2.0) / c, 1.0 / (d_f - 1.0));
  const FreePathFit f = fit_free_paths(h, median, 10.0);
  EXPECT_NEAR(f.d_f, d_f, 4.0 * f.d_f_err);
  EXPECT_NEAR(f.c, c, 4.0 * f.c_err);
  EXPECT_LT(f.d_f_err, 0.05);
}

TEST(RfmFreePath, TailStartsWhereTheDensityFallsBelowTheBound) {
  // §4.3.3 fits "the lowest decades of data ... where P < 1": for the Weibull paths the density
  // crosses 1/m once on the tail, so the window must begin in the bin holding that crossing (or
  // the next, as Poisson noise shifts a bin near P = 1)
  const double d_f = 1.63, c = 121.0;
  const Histogram h = weibull_paths(d_f, c, 1'000'000, 83);
  double lo = 1e-4, hi = 1.0;  // bisect A₀ l^(β−1) e^(−C l^β) = 1 on the falling tail
  for (int i = 0; i < 100; ++i) {
    const double mid = std::sqrt(lo * hi);
    (free_path_density(mid, c * (d_f - 1.0), c, d_f) > 1.0 ? lo : hi) = mid;
  }
  const double start = tail_start(h, 1.0);
  const double ratio = h.binning().edge(1) / h.binning().edge(0);  // one log bin
  EXPECT_GT(start, lo / ratio);
  EXPECT_LT(start, lo * ratio * ratio);
  for (const HistBin& b : h.bins()) {  // every occupied bin from the start on is below the bound
    if (b.x >= start && b.count > 0) {
      EXPECT_LT(b.p, 1.0) << "at l = " << b.x;
    }
  }
  // the fit on that window alone recovers the parameters
  const FreePathFit f = fit_free_paths(h, start, 10.0);
  EXPECT_NEAR(f.d_f, d_f, 4.0 * f.d_f_err);
  EXPECT_DOUBLE_EQ(f.l_min, start);
}

TEST(RfmFreePath, BodyOfReContactsIsLeftOutOfTheWindow) {
  // a body of short re-contacts (10⁶ paths spread evenly in ln l from 10⁻⁷ to 10⁻⁴ m) changes
  // the fit from l = 0 but not the tail window's, which starts where it did without them
  const double d_f = 1.4, c = 30.0;
  Histogram h = weibull_paths(d_f, c, 1'000'000, 84);
  RngStream rng(85, 0);
  for (int i = 0; i < 1'000'000; ++i) h.add(1e-7 * std::pow(1e3, rng.uniform()));
  const double start = tail_start(h, 1.0);
  EXPECT_GT(start, 1e-3);
  const FreePathFit tail = fit_free_paths(h, start, 10.0);
  EXPECT_NEAR(tail.d_f, d_f, 4.0 * tail.d_f_err);
  const FreePathFit all = fit_free_paths(h);
  EXPECT_GT(std::abs(all.d_f - d_f), 10.0 * all.d_f_err);  // the body biases a fit over it
}

TEST(RfmFreePath, NoTailBelowTheBoundGivesInfinity) {
  Histogram h = free_path_histogram(1e-3, 1e-1, 10);
  for (int i = 0; i < 100; ++i) h.add(0.05);  // all in one bin of density ≫ 1/m
  EXPECT_TRUE(std::isinf(tail_start(h, 1.0)));
  EXPECT_TRUE(std::isinf(tail_start(Histogram(Binning::log(1e-3, 1e-1, 10)), 1.0)));
}

TEST(RfmFreePath, DensityIsNormalisedWeibull) {
  // ∫ A₀ l^(β−1) exp(−C l^β) dl = A₀/(Cβ): with A₀ = Cβ the density integrates to 1
  const double d_f = 1.63, c = 121.0, a0 = c * (d_f - 1.0);
  double s = 0.0;
  const int n = 400000;
  const double lo = std::log(1e-20), hi = std::log(1.0);
  for (int i = 0; i < n; ++i) {  // midpoint rule in ln l
    const double l = std::exp(lo + (i + 0.5) * (hi - lo) / n);
    s += free_path_density(l, a0, c, d_f) * l * (hi - lo) / n;
  }
  EXPECT_NEAR(s, 1.0, 1e-6);
}

}  // namespace
}  // namespace gs::rfm
