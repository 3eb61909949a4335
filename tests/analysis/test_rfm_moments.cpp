// velocity moments (T.3.11), scaling exponents (T.3.13), temperature (T.2.19), blocks (T.2.20)
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "analysis/rfm_moments.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace gs::rfm {
namespace {

// ⟨|v|^m⟩ of a normal distribution N(0, σ²): σ^m 2^(m/2) Γ((m+1)/2)/√π
double normal_abs_moment(double sigma, int m) {
  return std::pow(sigma, m) * std::pow(2.0, 0.5 * m) * std::tgamma(0.5 * (m + 1)) /
         std::sqrt(std::numbers::pi);
}

std::vector<double> normal_values(RngStream& rng, double sigma, int n) {
  std::vector<double> v(static_cast<std::size_t>(n));
  for (double& x : v) x = sigma * rng.normal();
  return v;
}

TEST(RfmMoments, NormalMomentsWithinErrors) {
  // 40 snapshots of 50 000 normal values. |v|^m is heavy-tailed for large m (relative σ of one
  // value: 13.5 at m = 8, 54 at m = 12), so a snapshot mean is skewed; 40 of them average to a
  // near-normal estimate whose scatter gives a fair error. 5σ; the error itself must be the
  // expected size (≈ 0.01 relative at m = 8, ≈ 0.04 at m = 12)
  RngStream rng(61, 0);
  MomentSeries ms(12);
  for (int s = 0; s < 40; ++s) ms.add_snapshot(normal_values(rng, 0.7, 50'000));
  const auto mean = ms.mean(), err = ms.error();
  for (int m = 1; m <= 12; ++m) {
    const double exact = normal_abs_moment(0.7, m);
    EXPECT_NEAR(mean[m - 1], exact, 5.0 * err[m - 1]) << "m = " << m;
    EXPECT_LT(err[m - 1] / exact, m <= 8 ? 0.02 : 0.08) << "m = " << m;
  }
  EXPECT_EQ(ms.snapshots(), 40);
}

TEST(RfmMoments, ComponentsAndSpeeds) {
  // pooled components give ⟨|v_x|^m⟩; speeds of an isotropic normal give
  // ⟨|v|^m⟩ = (2σ²)^(m/2) Γ(1 + m/2) (Rayleigh)
  RngStream rng(62, 0);
  std::vector<Vec2> v(200'000);
  for (Vec2& u : v) rng.normal_pair(u.x, u.y);
  MomentSeries comp(4), speed(4);
  comp.add_components(v);
  speed.add_speeds(v);
  for (int m = 1; m <= 4; ++m) {
    // relative σ of a mean of n values ≈ √(Var/n)/mean < 0.01 here: 5σ bound 0.05
    EXPECT_NEAR(comp.mean()[m - 1] / normal_abs_moment(1.0, m), 1.0, 0.05);
    EXPECT_NEAR(speed.mean()[m - 1] / (std::pow(2.0, 0.5 * m) * std::tgamma(1.0 + 0.5 * m)), 1.0,
                0.05);
  }
}

TEST(RfmMoments, ExponentFitRecoversKnownPowerLaw) {
  // σ(N) = 2 N^(−1/3) makes ⟨|v|^m⟩ ∝ N^(−m/3) exactly: ξ_m = m/3 (the homogeneous
  // Williams–MacKintosh value, T.3.8); each fitted ξ_m within 4σ of its error
  RngStream rng(63, 0);
  const std::vector<double> n = {100, 251, 631, 1585, 3981};
  std::vector<std::vector<double>> mom, err;
  for (double N : n) {
    MomentSeries ms(12);
    for (int s = 0; s < 20; ++s)
      ms.add_snapshot(normal_values(rng, 2.0 * std::pow(N, -1.0 / 3.0), 10'000));
    mom.push_back(ms.mean());
    err.push_back(ms.error());
  }
  const auto fits = fit_scaling_exponents(n, mom, err);
  ASSERT_EQ(fits.size(), 12u);
  for (const ExponentFit& f : fits) {
    EXPECT_NEAR(f.exponent, f.m / 3.0, 4.0 * f.exponent_err + 1e-12) << "m = " << f.m;
    EXPECT_LT(f.exponent_err, 0.02 * f.m) << "m = " << f.m;
  }
  // noise-free data: the exponent and the prefactor exactly, with the sign convention y ∝ N^(−ξ)
  std::vector<double> y;
  for (double N : n) y.push_back(3.0 * std::pow(N, -0.528));
  const ExponentFit exact = fit_scaling_exponent(n, y);
  EXPECT_NEAR(exact.exponent, 0.528, 1e-12);
  EXPECT_NEAR(exact.amplitude, 3.0, 1e-10);
}

TEST(RfmMoments, GranularTemperature) {
  // T = (1/N) Σ|v − ⟨v⟩|² (T.2.19): no ½, no mass, Galilean invariant
  const std::vector<Vec2> v = {{1, 0}, {-1, 0}, {0, 2}, {0, -2}};
  EXPECT_DOUBLE_EQ(granular_temperature(v), 2.5);
  std::vector<Vec2> shifted = v;
  for (Vec2& u : shifted) u += Vec2{3.0, -7.0};
  EXPECT_NEAR(granular_temperature(shifted), 2.5, 1e-12);
  EXPECT_DOUBLE_EQ(granular_temperature(std::vector<double>{1.0, 3.0}), 1.0);
  // normal components of variance σ²: E[T] = 2σ²(N−1)/N; relative σ of T ≈ 1/√N
  RngStream rng(64, 0);
  std::vector<Vec2> g(100'000);
  for (Vec2& u : g) {
    rng.normal_pair(u.x, u.y);
    u *= 0.3;
  }
  EXPECT_NEAR(granular_temperature(g) / (2.0 * 0.09), 1.0, 5.0 / std::sqrt(1e5));
}

TEST(RfmMoments, BlockAverageOfCorrelatedSeries) {
  // AR(1) x_{t+1} = ρ x_t + √(1−ρ²) ε has unit variance and Var(mean) = (1/n)(1+ρ)/(1−ρ) for
  // n ≫ 1/(1−ρ); blocks of 2000 ≫ τ ≈ 10 give that error to ≈ 7 % (100 blocks): allow 25 %
  RngStream rng(65, 0);
  const double rho = 0.9;
  std::vector<double> x(200'000);
  double s = rng.normal();
  for (double& v : x) {
    s = rho * s + std::sqrt(1.0 - rho * rho) * rng.normal();
    v = s;
  }
  const BlockAverage b = block_average(x, 2000);
  const double expected = std::sqrt((1.0 + rho) / (1.0 - rho) / static_cast<double>(x.size()));
  EXPECT_EQ(b.block_means.size(), 100u);
  EXPECT_NEAR(b.error / expected, 1.0, 0.25);
  EXPECT_NEAR(b.mean, 0.0, 4.5 * expected);
  // naive iid error would be √19 ≈ 4.4 times too small
  EXPECT_GT(b.error, 3.0 / std::sqrt(static_cast<double>(x.size())));
  // a partial last block is dropped
  const BlockAverage p = block_average(std::vector<double>{1, 2, 3, 4, 5}, 2);
  EXPECT_EQ(p.block_means.size(), 2u);
  EXPECT_DOUBLE_EQ(p.mean, 2.5);
}

}  // namespace
}  // namespace gs::rfm
