// the uniform multiplicative bisection process (T.3.26–T.3.38)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "analysis/rfm_moments.hpp"
#include "core/error.hpp"
#include "models/bisection.hpp"

namespace gs::models {
namespace {

TEST(Bisection, ExactDensityIsNormalisedAndMatchesItsCdf) {
  // ∫P_n = 1, dF/dx = P_n, and ⟨x^m⟩ = (1+m)^(−n) by quadrature in t = −ln x
  for (int n : {1, 2, 5, 9}) {
    double norm = 0.0, m2 = 0.0;
    const int steps = 200000;
    const double tmax = 80.0;
    for (int i = 0; i < steps; ++i) {  // x = e^(−t), dx = x dt
      const double t = (i + 0.5) * tmax / steps, x = std::exp(-t);
      norm += bisection_density(x, n) * x * tmax / steps;
      m2 += x * x * bisection_density(x, n) * x * tmax / steps;
    }
    // midpoint rule with 2·10⁵ steps over 0 < t < 80: relative error below 1e-6
    EXPECT_NEAR(norm, 1.0, 1e-6) << n;
    EXPECT_NEAR(m2 / bisection_moment(2, n), 1.0, 1e-6) << n;
    // central differences with h = 10⁻⁵x: truncation and round-off far below 1e-5 where the
    // density is not tiny (near x = 1 and large n, F is 1 − O(10⁻¹²) and differences lose digits)
    for (double x : {1e-6, 0.01, 0.3, 0.9}) {
      if (bisection_density(x, n) < 1e-3) continue;
      const double h = 1e-5 * x;
      const double deriv = (bisection_cdf(x + h, n) - bisection_cdf(x - h, n)) / (2 * h);
      EXPECT_NEAR(deriv / bisection_density(x, n), 1.0, 1e-5) << n << " " << x;
    }
    EXPECT_DOUBLE_EQ(bisection_cdf(1.0, n), 1.0);
  }
  EXPECT_DOUBLE_EQ(bisection_density(0.3, 1), 1.0);  // one split: a uniform length
  // the length-biased density integrates to 1 as well (⟨x⟩ = 2^(−n))
  double lb = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double t = (i + 0.5) * 80.0 / 200000, x = std::exp(-t);
    lb += bisection_density_length_biased(x, 6) * x * 80.0 / 200000;
  }
  EXPECT_NEAR(lb, 1.0, 1e-8);
}

TEST(Bisection, SegmentsSumToOne) {
  RngStream rng(5, 0);
  const auto seg = bisect(10, rng);
  ASSERT_EQ(seg.size(), 1024u);
  double s = 0.0;
  for (double x : seg) s += x;
  EXPECT_NEAR(s, 1.0, 1e-12);
}

TEST(Bisection, HistogramAndMomentsMatchTheExactForms) {
  // n = 9 as in thesis Fig. 3.15, 2000 realisations (10⁶ segments). Errors come from the
  // scatter between realisations, which accounts for the correlation of sibling segments;
  // every bin within 5σ of the exact bin average of P_n, the moments within 5σ of (1+m)^(−n)
  BisectionParams p;
  p.levels = 9;
  p.realisations = 2000;
  p.bins = 40;
  p.x_min = 1e-10;
  const BisectionResult r = run_bisection(p);
  double chi2 = 0.0;
  int used = 0;
  for (const BisectionBin& b : r.bins) {
    if (b.p_err <= 0.0) continue;
    EXPECT_NEAR(b.p, b.p_exact, 5.0 * b.p_err) << "x = " << b.x;
    chi2 += std::pow((b.p - b.p_exact) / b.p_err, 2);
    ++used;
    // the boundaries read as 1D particles: G₁ of the gaps is the same histogram (T.3.21)
    EXPECT_NEAR(b.g1, b.p, 1e-9 * b.p + 1e-12) << "x = " << b.x;
  }
  EXPECT_GT(used, 30);
  EXPECT_LT(chi2 / used, 2.0);
  // ⟨x⟩ = 2^(−n) exactly since the segments fill [0, 1]
  EXPECT_NEAR(r.moments[0], std::ldexp(1.0, -9), 1e-15);
  for (std::size_t m = 1; m < r.moments.size(); ++m)
    EXPECT_NEAR(r.moments[m], r.moment_exact[m], 5.0 * r.moment_err[m]) << "m = " << m + 1;
  // the renormalisation idea of T.3.25: G₂ at level n against P_(n−1) (not exact: half the
  // second-neighbour pairs are not siblings); printed for the record
  double worst = 0.0;
  for (const BisectionBin& b : r.bins)
    if (b.x > 1e-4 && b.x < 0.05)
      worst = std::max(worst, std::abs(std::log(b.g2 / b.p_exact_prev)));
  std::printf(
      "[ measured ] bisection n=9: chi2_r %.2f over %d bins; max |ln(G2/P_8)| on 1e-4..0.05 = "
      "%.3f\n",
      chi2 / used, used, worst);
}

TEST(Bisection, MomentExponentsAreLog2OfOnePlusM) {
  // ⟨x^m⟩ = N^(−ζ_m) with ζ_m = log₂(1+m) (T.3.38, Table 3.1 "predicted"): the exponent fit of
  // the analysis code over n = 4…9 must return them within 4σ
  std::vector<double> n_part;
  std::vector<std::vector<double>> mom, err;
  for (int n = 4; n <= 9; ++n) {
    BisectionParams p;
    p.levels = n;
    p.realisations = 1500;
    p.bins = 10;
    p.m_max = 5;
    p.seed = 100 + n;
    const BisectionResult r = run_bisection(p);
    n_part.push_back(std::ldexp(1.0, n));
    mom.push_back(r.moments);
    std::vector<double> e = r.moment_err;
    e[0] = 1e-3 * r.moments[0];  // m = 1 is exact (zero scatter): give it a small weight
    err.push_back(e);
  }
  const auto fits = rfm::fit_scaling_exponents(n_part, mom, err);
  for (const auto& f : fits) {
    EXPECT_NEAR(f.exponent, std::log2(1.0 + f.m), 4.0 * f.exponent_err + 1e-9) << "m = " << f.m;
    std::printf("[ measured ] zeta_%d = %.4f ± %.4f (exact %.4f)\n", f.m, f.exponent,
                f.exponent_err, std::log2(1.0 + f.m));
  }
}

TEST(Bisection, RejectsBadParameters) {
  BisectionParams p;
  p.levels = 0;
  EXPECT_THROW(run_bisection(p), InputError);
  p.levels = 5;
  p.x_min = 2.0;
  EXPECT_THROW(run_bisection(p), InputError);
}

}  // namespace
}  // namespace gs::models
