// two-sample tests: Kolmogorov's distribution against tabulated values, the KS statistic on
// hand-checked samples, and the false-alarm rate and power on synthetic normal and AR(1)
// series — where the τ_int correction is what keeps correlated taps from false alarms
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "analysis/stats.hpp"
#include "analysis/two_sample.hpp"

namespace gs {
namespace {

TEST(TwoSample, KolmogorovTailMatchesTables) {
  // critical values of the Kolmogorov distribution: Q(1.224) = 0.10, Q(1.358) = 0.05,
  // Q(1.628) = 0.01 (Smirnov's table), and Q(0.5) = 0.9639
  EXPECT_NEAR(kolmogorov_q(1.2238), 0.10, 2e-4);
  EXPECT_NEAR(kolmogorov_q(1.3581), 0.05, 1e-4);
  EXPECT_NEAR(kolmogorov_q(1.6276), 0.01, 1e-4);
  EXPECT_NEAR(kolmogorov_q(0.5), 0.9639, 1e-4);
  EXPECT_EQ(kolmogorov_q(0.0), 1.0);
}

TEST(TwoSample, KsStatisticByHand) {
  EXPECT_DOUBLE_EQ(ks_statistic({0, 1}, {2, 3}), 1.0);
  EXPECT_DOUBLE_EQ(ks_statistic({1, 2, 3}, {1, 2, 3}), 0.0);
  // F_a: 1/2 at 1, 1 at 3; F_b: 1/4 at 2, 1/2 at 4, …: the largest gap is 3/4, at x = 3
  EXPECT_DOUBLE_EQ(ks_statistic({1, 3}, {2, 4, 5, 6}), 0.75);
}

std::vector<double> normal_sample(std::mt19937_64& g, int n, double mu, double sd, double rho) {
  std::normal_distribution<double> z(0.0, 1.0);
  std::vector<double> x(static_cast<std::size_t>(n));
  double prev = z(g);
  for (double& v : x) {  // AR(1) with unit stationary variance
    prev = rho * prev + std::sqrt(1.0 - rho * rho) * z(g);
    v = mu + sd * prev;
  }
  return x;
}

// same distribution: each p-value is below 0.05 in about 5% of trials (binomial bounds for
// 400 trials: 5% ± 3.3σ → [1.4%, 8.6%])
TEST(TwoSample, FalseAlarmRateIsTheLevelForIndependentTaps) {
  std::mt19937_64 g(7);
  int mean_alarm = 0, sigma_alarm = 0, ks_alarm = 0;
  const int trials = 400;
  for (int k = 0; k < trials; ++k) {
    const auto a = normal_sample(g, 150, 0.84, 0.003, 0.0);
    const auto b = normal_sample(g, 150, 0.84, 0.003, 0.0);
    const TwoSampleTest t = two_sample_test(a, 0.5, b, 0.5);
    mean_alarm += t.p_mean < 0.05;
    sigma_alarm += t.p_sigma < 0.05;
    ks_alarm += t.ks_p < 0.05;
  }
  for (int n : {mean_alarm, sigma_alarm, ks_alarm}) {
    EXPECT_GT(n, 0.014 * trials);
    EXPECT_LT(n, 0.086 * trials);
  }
}

// correlated taps (AR(1), ρ = 0.8, τ_int = (1+ρ)/(2(1−ρ)) = 4.5): treated as independent the
// tests cry wolf far too often; with the measured τ_int they keep (about) their level
TEST(TwoSample, AutocorrelationCorrectionKeepsTheLevel) {
  std::mt19937_64 g(11);
  int naive = 0, corrected = 0;
  const int trials = 300;
  for (int k = 0; k < trials; ++k) {
    const auto a = normal_sample(g, 300, 0.84, 0.003, 0.8);
    const auto b = normal_sample(g, 300, 0.84, 0.003, 0.8);
    naive += two_sample_test(a, 0.5, b, 0.5).p_mean < 0.05;
    const double ta = autocorr_time(a).tau_int, tb = autocorr_time(b).tau_int;
    corrected += two_sample_test(a, ta, b, tb).p_mean < 0.05;
  }
  EXPECT_GT(naive, 0.25 * trials);      // ≈ 1 − erf-level for a 3× too small error: ~40%
  EXPECT_LT(corrected, 0.12 * trials);  // τ_int estimated from 300 taps: a little above 5%
}

// a shift of one σ_φ/2 in 150 independent taps is found nearly always (power of the t test
// ≈ 0.99) and so is a doubled spread
TEST(TwoSample, FindsRealDifferences) {
  std::mt19937_64 g(3);
  int shift_found = 0, spread_found = 0;
  for (int k = 0; k < 100; ++k) {
    const auto a = normal_sample(g, 150, 0.84, 0.003, 0.0);
    const auto b = normal_sample(g, 150, 0.8415, 0.003, 0.0);
    const auto c = normal_sample(g, 150, 0.84, 0.006, 0.0);
    const TwoSampleTest s = two_sample_test(a, 0.5, b, 0.5);
    shift_found += s.p_mean < 0.05 && s.ks_p < 0.2;
    const TwoSampleTest w = two_sample_test(a, 0.5, c, 0.5);
    spread_found += w.p_sigma < 0.01;
    EXPECT_NEAR(w.sigma_ratio, 2.0, 0.5);
  }
  EXPECT_GE(shift_found, 90);
  EXPECT_GE(spread_found, 97);
}

}  // namespace
}  // namespace gs
