// 1D reduced coordinates (T.3.16), gaps (T.3.17, T.3.23), G_h(R) (T.3.24), ⟨R^m⟩ (T.3.18)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "analysis/rfm_gaps.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace gs::rfm {
namespace {

// n sorted uniform points on [0, lr) with the first moved to 0 (a reference particle)
std::vector<double> uniform_reduced(RngStream& rng, int n, double lr) {
  std::vector<double> r(static_cast<std::size_t>(n));
  for (double& x : r) x = rng.uniform(0.0, lr);
  std::sort(r.begin(), r.end());
  const double r0 = r[0];
  for (double& x : r) x -= r0;
  return r;
}

// C(n, k) as a double
double choose(int n, int k) {
  return std::exp(std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0));
}

// P(R_{i,i+h} ≤ x) for n iid uniform points on a ring of length 1: R ~ Beta(h, n − h), whose
// distribution function is P(Binomial(n − 1, x) ≥ h)
double gap_cdf(double x, int n, int h) {
  if (x >= 1.0) return 1.0;
  double below = 0.0;
  for (int j = 0; j < h; ++j)
    below += choose(n - 1, j) * std::pow(x, j) * std::pow(1.0 - x, n - 1 - j);
  return 1.0 - below;
}

TEST(RfmGaps, ReducedCoordinatesRoundTrip) {
  // point-particles at reduced positions r′ become rods of width d at r_i = r′_i + i d + shift
  // (wrapped on the ring); T.3.16 must give back r′ and the gaps must sum to L′ (T.3.19)
  RngStream rng(71, 0);
  const int n = 50;
  const double d = 0.01, box = 1.3, lr = box - n * d;
  const auto rp = uniform_reduced(rng, n, lr);
  for (double shift : {0.0, 0.77, 1.25}) {
    std::vector<double> r(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
      r[static_cast<std::size_t>(i)] =
          std::fmod(rp[static_cast<std::size_t>(i)] + i * d + shift, box);
    const auto back = reduced_coordinates(r, box, d);
    for (int i = 0; i < n; ++i)
      EXPECT_NEAR(back[static_cast<std::size_t>(i)], rp[static_cast<std::size_t>(i)], 1e-12) << i;
    double sum = 0.0;
    for (double g : neighbour_gaps(back, reduced_length(box, n, d))) sum += g;
    EXPECT_NEAR(sum, lr, 1e-12);
  }
  EXPECT_THROW(reduced_length(0.4, 50, 0.01), InputError);
}

TEST(RfmGaps, PeriodicHthNeighbours) {
  // R_{i,i+h} wraps with r′_{i+N} = r′_i + L′ (T.3.23): three points at 0, 0.2, 0.5 of L′ = 1
  const std::vector<double> r = {0.0, 0.2, 0.5};
  const auto g1 = neighbour_gaps(r, 1.0, 1), g2 = neighbour_gaps(r, 1.0, 2);
  EXPECT_NEAR(g1[2], 0.5, 1e-15);
  EXPECT_NEAR(g2[1], 0.8, 1e-15);
  EXPECT_NEAR(g2[2], 0.7, 1e-15);
  EXPECT_NEAR(neighbour_gaps(r, 1.0, 3)[0], 1.0, 1e-15);  // h = N: once round the ring
}

TEST(RfmGaps, UniformPointsMatchBetaDistributions) {
  // n iid uniform points on a ring of L′ = 1: R_{i,i+h} ~ Beta(h, n − h) exactly. Gaps within a
  // snapshot are dependent, so bin counts are not Poisson: neighbouring h-gaps share h − 1
  // intervals, which inflates the variance by up to ≈ h; the bound is 5·√(h·expected).
  RngStream rng(72, 0);
  const int n = 64, snaps = 3000;
  GapStatistics gs(Binning::linear(0.0, 0.3, 30), {1, 2, 4, 8}, 6);
  for (int s = 0; s < snaps; ++s) gs.add_snapshot(uniform_reduced(rng, n, 1.0), 1.0);
  for (std::size_t k = 0; k < gs.orders().size(); ++k) {
    const int h = gs.orders()[k];
    for (const HistBin& b : gs.g(k)) {
      const double expected =
          static_cast<double>(n) * snaps * (gap_cdf(b.hi, n, h) - gap_cdf(b.lo, n, h));
      if (expected < 20.0) continue;
      EXPECT_NEAR(b.count, expected, 5.0 * std::sqrt(h * expected)) << "h " << h << " R " << b.x;
    }
  }
  // ⟨R^m⟩ = m! Γ(n)/Γ(n + m) for Beta(1, n − 1), within 5σ of the snapshot scatter
  const auto mean = gs.moments().mean(), err = gs.moments().error();
  for (int m = 2; m <= 6; ++m) {
    const double exact = std::exp(std::lgamma(m + 1.0) + std::lgamma(n) - std::lgamma(n + m));
    EXPECT_NEAR(mean[static_cast<std::size_t>(m - 1)], exact,
                5.0 * err[static_cast<std::size_t>(m - 1)])
        << m;
  }
  EXPECT_NEAR(mean[0], 1.0 / n, 1e-12);  // ⟨R⟩ = L′/N exactly (T.3.19)
}

TEST(RfmGaps, DistributionsAreNormalised) {
  // with bins covering [0, L′] every gap is counted: ∫G_h dR = 1 to round-off
  RngStream rng(73, 0);
  GapStatistics gs(Binning::linear(0.0, 1.0, 50));
  for (int s = 0; s < 20; ++s) gs.add_snapshot(uniform_reduced(rng, 32, 1.0), 1.0);
  for (std::size_t k = 0; k < gs.orders().size(); ++k) {
    double integral = 0.0;
    for (const HistBin& b : gs.g(k)) integral += b.p * (b.hi - b.lo);
    EXPECT_NEAR(integral, 1.0, 1e-12) << "h = " << gs.orders()[k];
  }
}

}  // namespace
}  // namespace gs::rfm
