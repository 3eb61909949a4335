// least-squares helpers (T.A.7)
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "analysis/rfm_fit.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace gs::rfm {
namespace {

TEST(RfmFit, LineExactAndItsErrors) {
  // exact data: a and b to round-off; the error of b for equal σ is σ/√Σ(x − x̄)²
  std::vector<double> x, y, s;
  for (int i = 0; i < 11; ++i) {
    x.push_back(100.0 + i);  // far from 0: centred sums keep the precision
    y.push_back(-3.0 + 0.25 * x.back());
    s.push_back(0.1);
  }
  const LineFit f = fit_line(x, y, s);
  EXPECT_NEAR(f.a, -3.0, 1e-10);
  EXPECT_NEAR(f.b, 0.25, 1e-12);
  EXPECT_NEAR(f.b_err, 0.1 / std::sqrt(110.0), 1e-12);  // Σ(x − x̄)² = 110 for 11 points
  EXPECT_NEAR(f.chi2, 0.0, 1e-18);
  EXPECT_THROW(fit_line(std::vector<double>{1, 1}, std::vector<double>{1, 2}), InputError);
}

TEST(RfmFit, PowerLawSkipsNonPositive) {
  const std::vector<double> x = {0.0, 1.0, 2.0, 4.0, 8.0}, y = {5.0, 3.0, 1.5, 0.75, -1.0};
  const PowerLawFit p = fit_power_law(x, y);
  EXPECT_EQ(p.points, 3);
  EXPECT_NEAR(p.exponent, -1.0, 1e-12);
  EXPECT_NEAR(p.amplitude, 3.0, 1e-12);
}

TEST(RfmFit, LevenbergMarquardtPullsAreUnitNormal) {
  // y = a exp(−x/τ) + c with Gaussian noise of known σ, refitted 300 times: the pulls
  // (p − p_true)/err must have mean 0 and standard deviation 1 (±0.15 ≈ 2.6σ of an estimated
  // standard deviation from 300 samples; mean within ±0.2 ≈ 3.5σ)
  const Model model = [](double x, const Eigen::VectorXd& p) {
    return p[0] * std::exp(-x / p[1]) + p[2];
  };
  Eigen::VectorXd truth(3);
  truth << 2.0, 1.5, 0.3;
  RngStream rng(91, 0);
  std::vector<double> x, s;
  for (int i = 0; i < 40; ++i) {
    x.push_back(0.1 * i);
    s.push_back(0.02);
  }
  const int reps = 300;
  std::vector<double> sum(3, 0.0), sum2(3, 0.0);
  for (int r = 0; r < reps; ++r) {
    std::vector<double> y;
    for (double xi : x) y.push_back(model(xi, truth) + 0.02 * rng.normal());
    Eigen::VectorXd p0(3);
    p0 << 1.0, 1.0, 0.0;
    const LmResult f = fit_lm(model, x, y, s, p0);
    ASSERT_TRUE(f.converged);
    for (int k = 0; k < 3; ++k) {
      const double pull = (f.p[k] - truth[k]) / f.err[k];
      sum[static_cast<std::size_t>(k)] += pull;
      sum2[static_cast<std::size_t>(k)] += pull * pull;
    }
  }
  for (int k = 0; k < 3; ++k) {
    const double m = sum[static_cast<std::size_t>(k)] / reps;
    const double sd = std::sqrt(sum2[static_cast<std::size_t>(k)] / reps - m * m);
    EXPECT_NEAR(m, 0.0, 0.2) << "parameter " << k;
    EXPECT_NEAR(sd, 1.0, 0.15) << "parameter " << k;
  }
}

}  // namespace
}  // namespace gs::rfm
