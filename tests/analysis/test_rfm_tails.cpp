// velocity histograms, the appendix-A tail scan, the crossover fit (T.5.32), the ln–ln helper
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "analysis/rfm_fit.hpp"
#include "analysis/rfm_tails.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace gs::rfm {
namespace {

// Gamma(k, 1) by Marsaglia–Tsang (k < 1 through the U^(1/k) boost)
double gamma_sample(RngStream& rng, double k) {
  if (k < 1.0) return gamma_sample(rng, k + 1.0) * std::pow(rng.uniform(), 1.0 / k);
  const double d = k - 1.0 / 3.0, c = 1.0 / std::sqrt(9.0 * d);
  for (;;) {
    double x, v;
    do {
      x = rng.normal();
      v = 1.0 + c * x;
    } while (v <= 0.0);
    v = v * v * v;
    const double u = rng.uniform();
    if (std::log(u) < 0.5 * x * x + d - d * v + d * std::log(v)) return d * v;
  }
}

// samples of P(v) = A exp(−|v|^α): |v|^α is Gamma(1/α, 1), the sign is a coin flip
Histogram stretched_sample(double alpha, long n, double width, std::uint64_t seed) {
  RngStream rng(seed, 0);
  Histogram h = velocity_histogram(6.0, static_cast<int>(std::lround(12.0 / width)));
  for (long i = 0; i < n; ++i) {
    const double u = std::pow(gamma_sample(rng, 1.0 / alpha), 1.0 / alpha);
    h.add(rng.uniform() < 0.5 ? -u : u);
  }
  return h;
}

// the normalisation of exp(−|v|^α) over the line: α / (2 Γ(1/α))
double stretched_norm(double alpha) { return alpha / (2.0 * std::tgamma(1.0 / alpha)); }

TEST(RfmTails, HistogramDensityAndPoissonErrors) {
  // density X/(N_s Δv) and error √X/(N_s Δv) (T.A.5); samples outside go to under/overflow
  Histogram h = velocity_histogram(1.0, 4);
  add_values(h, std::vector<double>{-0.9, -0.1, 0.1, 0.2, 0.3, 2.0});
  const auto b = h.bins();
  EXPECT_DOUBLE_EQ(h.total(), 6.0);
  EXPECT_DOUBLE_EQ(h.overflow(), 1.0);
  EXPECT_DOUBLE_EQ(b[2].count, 3.0);
  EXPECT_DOUBLE_EQ(b[2].p, 3.0 / (6.0 * 0.5));
  EXPECT_DOUBLE_EQ(b[2].p_err, std::sqrt(3.0) / (6.0 * 0.5));
  EXPECT_DOUBLE_EQ(b[2].x, 0.25);
}

class RfmTailAlpha : public ::testing::TestWithParam<double> {};

TEST_P(RfmTailAlpha, ScanAcceptsTheTrueExponent) {
  // 4·10⁶ samples of exp(−|v|^α), Δv = 0.01: the window 50…5000 holds ≈ 200 bins; the true α
  // must be accepted (χ²_r < 1.2: its χ²_r is 1 ± √(2/200) = 1 ± 0.1) and the best α must be
  // close; B must come out 1 and A the exact normalisation (within 4σ of the fit's own spread,
  // here taken as 2 % since A and B are strongly correlated across the accepted range)
  const double alpha = GetParam();
  const Histogram h = stretched_sample(alpha, 4'000'000, 0.01, 31 + static_cast<int>(alpha * 10));
  const TailFit f = fit_tail(h);
  ASSERT_TRUE(f.any_accepted);
  EXPECT_GT(f.points, 150);
  EXPECT_LE(f.alpha_lo, alpha + 1e-9);
  EXPECT_GE(f.alpha_hi, alpha - 1e-9);
  EXPECT_NEAR(f.best.alpha, alpha, 0.1);
  // the trial at the true α
  for (const TailTrial& t : f.trials)
    if (std::abs(t.alpha - alpha) < 1e-9) {
      EXPECT_NEAR(t.b, 1.0, 0.02);
      EXPECT_NEAR(t.a / stretched_norm(alpha), 1.0, 0.03);
    }
  // the accepted range excludes the other candidate shapes of appendix A
  const double other = alpha > 1.75 ? 1.5 : 2.0;
  EXPECT_FALSE(other >= f.alpha_lo && other <= f.alpha_hi);
  EXPECT_FALSE(1.0 >= f.alpha_lo && 1.0 <= f.alpha_hi);
  std::printf("[ measured ] alpha %.2f: accepted [%.2f, %.2f], best %.2f (chi2_r %.3f), %d bins\n",
              alpha, f.alpha_lo, f.alpha_hi, f.best.alpha, f.best.chi2_r, f.points);
}

INSTANTIATE_TEST_SUITE_P(StretchedExponentials, RfmTailAlpha, ::testing::Values(1.5, 2.0));

TEST(RfmTails, LnLnSlopeIsAlpha) {
  // with A the true amplitude, ln(−ln(P/A)) = α ln|v| exactly (B = 1): a weighted line through
  // the ln–ln points of the tail must have slope α within 4σ and intercept 0
  const double alpha = 1.5;
  const Histogram h = stretched_sample(alpha, 2'000'000, 0.02, 41);
  const auto pts = lnln_tail(h, stretched_norm(alpha), 1.0, 50.0);
  std::vector<double> x, y, s;
  for (const LnLnPoint& p : pts)
    if (p.ln_v > 0.0) {  // the tail, |v| > 1, where −ln(P/A) is not tiny
      x.push_back(p.ln_v);
      y.push_back(p.y);
      s.push_back(p.y_err);
    }
  const LineFit lf = fit_line(x, y, s);
  EXPECT_NEAR(lf.b, alpha, 4.0 * lf.b_err + 1e-3);
  EXPECT_NEAR(lf.a, 0.0, 4.0 * lf.a_err + 1e-3);
  EXPECT_LT(lf.b_err, 0.05);
}

// samples of the crossover density by inverting its tabulated distribution function
Histogram crossover_sample(double vr, double vc, long n, std::uint64_t seed, double* norm) {
  const int grid = 400000;
  const double vmax = 40.0, dv = 2.0 * vmax / grid;
  std::vector<double> cdf(static_cast<std::size_t>(grid) + 1, 0.0);
  for (int i = 0; i < grid; ++i) {
    const double a = -vmax + i * dv;
    const double f =
        (crossover_density(a, 1, vr, vc, 1) + 4 * crossover_density(a + 0.5 * dv, 1, vr, vc, 1) +
         crossover_density(a + dv, 1, vr, vc, 1)) /
        6.0 * dv;
    cdf[static_cast<std::size_t>(i) + 1] = cdf[static_cast<std::size_t>(i)] + f;
  }
  *norm = 1.0 / cdf.back();  // D of the normalised density
  RngStream rng(seed, 0);
  Histogram h = velocity_histogram(20.0, 1000);
  for (long k = 0; k < n; ++k) {
    const double u = rng.uniform() * cdf.back();
    const auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    const auto i = static_cast<std::size_t>(it - cdf.begin()) - 1;
    const double frac = (u - cdf[i]) / (cdf[i + 1] - cdf[i]);
    h.add(-vmax + (static_cast<double>(i) + frac) * dv);
  }
  return h;
}

TEST(RfmTails, CrossoverFitRecoversParameters) {
  // 2·10⁶ samples of T.5.32 with v_r = 1, v_c = 1.5, α = 1: the fit must return them within 4σ
  // of its own errors, D within 4σ of the exact normalisation, and χ²_r ≈ 1 (±0.3 for ≈ 300
  // bins: σ(χ²_r) ≈ 0.08)
  double dnorm = 0.0;
  const Histogram h = crossover_sample(1.0, 1.5, 2'000'000, 51, &dnorm);
  const CrossoverFit c = fit_crossover(h, 1.0, false, 10.0);
  EXPECT_NEAR(c.v_r, 1.0, 4.0 * c.v_r_err);
  EXPECT_NEAR(c.v_c, 1.5, 4.0 * c.v_c_err);
  EXPECT_NEAR(c.d, dnorm, 4.0 * c.d_err);
  EXPECT_NEAR(c.chi2_r, 1.0, 0.3);
  EXPECT_LT(c.v_c_err, 0.05);
  // v_A = v_r²/v_c at α = 1
  EXPECT_NEAR(c.v_a(), c.v_r * c.v_r / c.v_c, 1e-12);
  // with α free the exponent must come back too
  const CrossoverFit c4 = fit_crossover(h, 1.3, true, 10.0);
  EXPECT_NEAR(c4.alpha, 1.0, 4.0 * c4.alpha_err);
  EXPECT_LT(c4.alpha_err, 0.1);
}

TEST(RfmTails, CrossoverLimits) {
  // T.5.32: Gaussian exp(−(v/v_r)²) for |v| ≪ v_c, exp(−|v/v_A|^α) for |v| ≫ v_c
  const double d = 2.0, vr = 0.3, vc = 0.9;
  EXPECT_NEAR(crossover_density(1e-4, d, vr, vc, 1.0) / d, std::exp(-std::pow(1e-4 / vr, 2)), 1e-9);
  CrossoverFit c;
  c.v_r = vr;
  c.v_c = vc;
  c.alpha = 1.0;
  // −ln(P/D) = (v/v_r)²/(1 + v/v_c) = (v/v_A)/(1 + v_c/v) exactly at α = 1
  for (double v : {5.0, 50.0}) {
    const double ratio = -std::log(crossover_density(v, d, vr, vc, 1.0) / d) / (v / c.v_a());
    EXPECT_NEAR(ratio, 1.0 / (1.0 + vc / v), 1e-12);
  }
}

}  // namespace
}  // namespace gs::rfm
