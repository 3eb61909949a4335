// kernel density estimation (appendix B): kernels, Silverman's bandwidth, and the estimate of
// a normal sample against the true density
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "analysis/kde.hpp"
#include "analysis/stats.hpp"
#include "core/rng.hpp"

namespace gs {
namespace {

const double kSqrt2Pi = std::sqrt(2.0 * std::numbers::pi);

// each kernel integrates to one (B2) and has the roughness R(K) = ∫K² we use for errors
TEST(Kde, KernelsAreNormalised) {
  for (Kernel k : {Kernel::Normal, Kernel::Epanechnikov, Kernel::Box}) {
    // midpoint rule on [−10, 10], 2·10⁵ cells: error ≪ 1e-6 for these piecewise-smooth kernels
    const int n = 200000;
    const double du = 20.0 / n;
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; ++i) {
      const double v = kernel_value(k, -10.0 + (i + 0.5) * du);
      s += v * du;
      s2 += v * v * du;
    }
    EXPECT_NEAR(s, 1.0, 1e-6) << kernel_name(k);
    EXPECT_NEAR(s2, kernel_roughness(k), 1e-6) << kernel_name(k);
    EXPECT_EQ(kernel_from_name(kernel_name(k)), k);
  }
  // (B3) with the corrected normalisation
  EXPECT_NEAR(kernel_value(Kernel::Normal, 0.0), 1.0 / kSqrt2Pi, 1e-15);
}

TEST(Kde, SilvermanBandwidth) {
  // (B7): h = 1.06 σ n^{−1/5}; for this sample σ = √(32/7), n = 8
  const std::vector<double> x{2, 4, 4, 4, 5, 5, 7, 9};
  EXPECT_NEAR(silverman_bandwidth(x), 1.06 * std::sqrt(32.0 / 7.0) * std::pow(8.0, -0.2), 1e-14);
}

// a single point: the estimate is the kernel itself, scaled by h
// canonical bandwidth ratios δ_K/δ_normal, δ = (R(K)/μ₂²)^{1/5}: (15·2√π)^{1/5} and (144·2√π)^{1/5}
TEST(Kde, EquivalentBandwidths) {
  const double two_sqrt_pi = 2.0 * std::sqrt(std::numbers::pi);
  EXPECT_NEAR(equivalent_bandwidth(Kernel::Epanechnikov, 1.0), std::pow(15.0 * two_sqrt_pi, 0.2),
              1e-12);
  EXPECT_NEAR(equivalent_bandwidth(Kernel::Box, 1.0), std::pow(144.0 * two_sqrt_pi, 0.2), 1e-12);
  EXPECT_NEAR(equivalent_bandwidth(Kernel::Epanechnikov, 1.0), 2.214, 1e-3);
  EXPECT_NEAR(equivalent_bandwidth(Kernel::Box, 1.0), 3.480, 1e-3);
  EXPECT_DOUBLE_EQ(equivalent_bandwidth(Kernel::Normal, 0.3), 0.3);
}

TEST(Kde, SinglePointIsTheKernel) {
  const std::vector<double> grid{-0.3, 0.0, 0.1, 0.45, 2.0};
  for (Kernel k : {Kernel::Normal, Kernel::Epanechnikov, Kernel::Box}) {
    const auto p = kde({0.5}, grid, 0.5, k);
    for (std::size_t i = 0; i < grid.size(); ++i)
      EXPECT_NEAR(p[i], kernel_value(k, (grid[i] - 0.5) / 0.5) / 0.5, 1e-15);
  }
}

// KDE of n = 5000 standard normal values against the true density: the integrated squared
// error ISE = ∫(P̂ − P)² must be near its asymptotic mean
//   AMISE(h) = R(K)/(n h) + h⁴ μ₂(K)² R(P'')/4,  R(P'') = 3/(8√π) for N(0,1)
// (Silverman 1986, eq. 3.20). ISE fluctuates around MISE by a few tens of percent at this n;
// we require ISE < 3·AMISE, and that a 10× oversmoothed estimate fails that bound.
TEST(Kde, NormalSampleIntegratedSquaredError) {
  RngStream rng(4242, 1);
  const int n = 5000;
  std::vector<double> x(n);
  for (auto& v : x) v = rng.normal();
  const double h = silverman_bandwidth(x);
  const auto grid = linspace(-6.0, 6.0, 1201);
  const double dx = grid[1] - grid[0];
  const double rf2 = 3.0 / (8.0 * std::sqrt(std::numbers::pi));
  auto ise = [&](Kernel k, double hh) {
    const auto p = kde(x, grid, hh, k);
    double s = 0.0;
    for (std::size_t i = 0; i < grid.size(); ++i) {
      const double d = p[i] - std::exp(-0.5 * grid[i] * grid[i]) / kSqrt2Pi;
      s += d * d * dx;
    }
    return s;
  };
  // μ₂(K) = ∫u²K: 1 (normal), 1/5 (Epanechnikov), 1/12 (box)
  const struct {
    Kernel k;
    double mu2;
  } cases[] = {{Kernel::Normal, 1.0}, {Kernel::Epanechnikov, 0.2}, {Kernel::Box, 1.0 / 12.0}};
  for (const auto& c : cases) {
    const double amise = kernel_roughness(c.k) / (n * h) + std::pow(h, 4) * c.mu2 * c.mu2 * rf2 / 4;
    const double e = ise(c.k, h);
    std::printf("kde %-12s h = %.4f  ISE = %.3e  AMISE = %.3e\n", kernel_name(c.k).c_str(), h, e,
                amise);
    EXPECT_LT(e, 3.0 * amise) << kernel_name(c.k);
    EXPECT_GT(e, 0.1 * amise) << kernel_name(c.k);
  }
  // with the equivalent (canonical) bandwidths the compact kernels smooth like the normal
  // one: their AMISE at h_eq is within 7 % of the normal kernel's (kernel efficiencies), and
  // the realised ISE obeys the same bound
  const double amise_n = kernel_roughness(Kernel::Normal) / (n * h) + std::pow(h, 4) * rf2 / 4;
  for (const auto& c : cases) {
    const double he = equivalent_bandwidth(c.k, h);
    const double amise =
        kernel_roughness(c.k) / (n * he) + std::pow(he, 4) * c.mu2 * c.mu2 * rf2 / 4;
    EXPECT_NEAR(amise / amise_n, 1.0, 0.07) << kernel_name(c.k);
    EXPECT_LT(ise(c.k, he), 3.0 * amise) << kernel_name(c.k);
  }
  // the check can fail: ten times Silverman's h smears the density far beyond 3·AMISE(h)
  EXPECT_GT(ise(Kernel::Normal, 10.0 * h), 3.0 * amise_n);
}

// kde_auto spans the sample with padding and the estimate integrates to ≈ 1
TEST(Kde, AutoGridIntegratesToOne) {
  RngStream rng(5, 2);
  std::vector<double> x(2000);
  for (auto& v : x) v = 0.82 + 0.003 * rng.normal();
  const KdeCurve c = kde_auto(x, 400);
  double s = 0.0;
  for (std::size_t i = 1; i < c.x.size(); ++i)
    s += 0.5 * (c.density[i] + c.density[i - 1]) * (c.x[i] - c.x[i - 1]);
  // the grid reaches 3h beyond the extreme samples: the mass lost is Φ(−3) per edge sample
  // at most, ≪ 1e-3; trapezoid error with ≈ 60 points per h is negligible
  EXPECT_NEAR(s, 1.0, 1e-3);
  EXPECT_NEAR(c.bandwidth, silverman_bandwidth(x), 1e-15);
}

// the estimate on bins (linear binning on a grid h/32 fine) against the exact sum: within the
// binning's (δ/h)²/12 ≈ 1e-4 of the peak wherever the density is, for a bandwidth much larger
// and one much smaller than the bins; the short-ranged kernels are summed exactly
TEST(Kde, OnBinsAgreesWithTheExactSum) {
  RngStream rng(7, 1);
  std::vector<double> x(20000);
  for (auto& v : x) v = 1.2 + 0.01 * rng.normal();
  const auto [lo_it, hi_it] = std::minmax_element(x.begin(), x.end());
  const double lo = *lo_it, hi = *hi_it;
  for (const int nb : {40, 3000}) {
    const double width = (hi - lo) / nb, h = silverman_bandwidth(x);
    std::vector<double> grid(nb);
    for (int j = 0; j < nb; ++j) grid[j] = lo + (j + 0.5) * width;
    const auto exact = kde(x, grid, h, Kernel::Normal);
    const auto fast = kde_on_bins(x, lo, width, nb, h, Kernel::Normal);
    ASSERT_EQ(fast.size(), exact.size());
    const double peak = *std::max_element(exact.begin(), exact.end());
    for (int j = 0; j < nb; ++j) EXPECT_NEAR(fast[j], exact[j], 2e-4 * peak) << nb << " " << j;
    for (Kernel k : {Kernel::Epanechnikov, Kernel::Box}) {
      const auto a = kde(x, grid, h, k), b = kde_on_bins(x, lo, width, nb, h, k);
      EXPECT_EQ(a, b);
    }
  }
}

}  // namespace
}  // namespace gs
