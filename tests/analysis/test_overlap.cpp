// overlapping histograms (P.19, P.20, P.39; appendix A) on samples with known answers:
// exactly Boltzmann-weighted volumes with a gamma-shaped density of states, and Gaussians
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "analysis/overlap_hist.hpp"
#include "analysis/stats.hpp"
#include "core/rng.hpp"

namespace gs {
namespace {

// a gamma variate of shape k ≥ 1 and unit rate (Marsaglia & Tsang 2000)
double gamma_variate(RngStream& rng, double k) {
  const double d = k - 1.0 / 3.0;
  const double c = 1.0 / std::sqrt(9.0 * d);
  for (;;) {
    const double x = rng.normal();
    double v = 1.0 + c * x;
    if (v <= 0.0) continue;
    v = v * v * v;
    const double u = rng.uniform();
    if (std::log(u) < 0.5 * x * x + d - d * v + d * std::log(v)) return d * v;
  }
}

// Boltzmann-weighted volumes with Ω(V) ∝ (V − V₀)^{k−1}: P(V; β) ∝ (V − V₀)^{k−1} e^{−βV} is
// a gamma law of shape k and rate β shifted by V₀, with Z(β) = Γ(k) β^{−k} e^{−βV₀}
struct GammaEnsemble {
  double k = 50.0;   ///< shape, dimensionless
  double v0 = 0.15;  ///< lowest volume, m²
  std::vector<double> volumes(RngStream& rng, double beta, int n) const {
    std::vector<double> v(n);
    for (auto& x : v) x = v0 + gamma_variate(rng, k) / beta;
    return v;
  }
  double lnz(double beta) const { return std::lgamma(k) - k * std::log(beta) - beta * v0; }
};

std::vector<double> to_phi(const std::vector<double>& v, double v_g) {
  std::vector<double> p(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) p[i] = v_g / v[i];
  return p;
}

std::vector<double> normal_sample(RngStream& rng, int n, double mu, double sigma) {
  std::vector<double> x(n);
  for (auto& v : x) v = mu + sigma * rng.normal();
  return x;
}

// Δβ and Δln Z from φ = V_g/V of two exactly canonical samples (n = 3000, the paper's run
// length) over 20 seeds: each within 3σ of its reported error, and the errors calibrated
// (rms pull within 0.6–1.5; 20 pulls give an rms uncertainty of ≈ 0.16)
TEST(Overlap, GammaEnsembleRecoversBetaAndLnZ) {
  const GammaEnsemble g;
  const double v_g = 0.13;
  const double b0 = 6250.0;  // mean V = 0.158 m², φ ≈ 0.82
  const double b1 = 5900.0;
  const double dbeta = b1 - b0;
  const double dlnz = g.lnz(b1) - g.lnz(b0);
  double sum_pb = 0.0, sum_pz = 0.0;
  const int seeds = 20;
  for (int s = 0; s < seeds; ++s) {
    RngStream rng(1000 + s, 7);
    const auto ref = to_phi(g.volumes(rng, b0, 3000), v_g);
    const auto smp = to_phi(g.volumes(rng, b1, 3000), v_g);
    const BetaEstimate e = beta_from_phi(ref, smp, v_g);
    ASSERT_TRUE(e.valid) << e.fit.note;
    const double pb = (e.dbeta - dbeta) / e.dbeta_err;
    const double pz = (e.dlnz - dlnz) / e.dlnz_err;
    if (s == 0)
      std::printf(
          "overlap gamma: dbeta = %.1f +- %.1f (true %.1f), dlnZ = %.2f +- %.2f (true "
          "%.2f), %zu points, R2 = %.4f\n",
          e.dbeta, e.dbeta_err, dbeta, e.dlnz, e.dlnz_err, dlnz, e.fit.points.size(), e.fit.r2);
    EXPECT_LT(std::abs(pb), 3.0) << "seed " << s;
    EXPECT_LT(std::abs(pz), 3.0) << "seed " << s;
    sum_pb += pb * pb;
    sum_pz += pz * pz;
  }
  const double rms_b = std::sqrt(sum_pb / seeds);
  const double rms_z = std::sqrt(sum_pz / seeds);
  std::printf("overlap gamma: rms pull dbeta %.2f, dlnZ %.2f\n", rms_b, rms_z);
  EXPECT_GT(rms_b, 0.6);
  EXPECT_LT(rms_b, 1.5);
  EXPECT_GT(rms_z, 0.6);
  EXPECT_LT(rms_z, 1.5);
}

// the volume form (P.20) and the φ form (P.39) agree: Q against V has slope −Δβ directly
TEST(Overlap, VolumeAndPhiFormsAgree) {
  const GammaEnsemble g;
  RngStream rng(31, 1);
  const auto v0 = g.volumes(rng, 6250.0, 5000);
  const auto v1 = g.volumes(rng, 6600.0, 5000);
  const BetaEstimate ev = beta_from_volume(v0, v1);
  ASSERT_TRUE(ev.valid);
  EXPECT_NEAR(ev.dbeta, 350.0, 3.0 * ev.dbeta_err);
  EXPECT_NEAR(ev.dlnz, g.lnz(6600.0) - g.lnz(6250.0), 3.0 * ev.dlnz_err);
  // bins sit at the same volumes when V_g = 1 and V = 1/φ: the same line, to round-off
  const BetaEstimate ep = beta_from_phi(to_phi(v0, 1.0), to_phi(v1, 1.0), 1.0);
  EXPECT_NEAR(ep.dbeta, ev.dbeta, 1e-6 * std::abs(ev.dbeta));
}

// the points used are those where both densities exceed 5 % of their maxima: check against
// the analytic gamma densities (allowing 2.5–10 %: the region comes from kernel estimates,
// whose smoothing and noise move the 5 % points by a fraction of a bin)
TEST(Overlap, UsesOnlyTheCommonSupport) {
  const GammaEnsemble g;
  RngStream rng(77, 2);
  const double b0 = 6250.0, b1 = 5900.0;
  const auto v0 = g.volumes(rng, b0, 20000);
  const auto v1 = g.volumes(rng, b1, 20000);
  const QFit f = q_fit(v0, v1);
  ASSERT_TRUE(f.valid);
  auto logp = [&](double v, double b) {
    return (g.k - 1.0) * std::log(v - g.v0) - b * (v - g.v0);  // up to a constant
  };
  auto rel = [&](double v, double b) {
    const double mode = g.v0 + (g.k - 1.0) / b;
    return std::exp(logp(v, b) - logp(mode, b));
  };
  double lo = 1e9, hi = -1e9;
  for (const auto& p : f.points) {
    EXPECT_GT(rel(p.x, b0), 0.025);
    EXPECT_GT(rel(p.x, b1), 0.025);
    lo = std::min(lo, p.x);
    hi = std::max(hi, p.x);
  }
  // and the used range reaches close to where the first density drops below 5 %
  EXPECT_LT(std::min(rel(lo, b0), rel(lo, b1)), 0.10);
  EXPECT_LT(std::min(rel(hi, b0), rel(hi, b1)), 0.10);
}

// β̂ from two references differ by the constant β_B − β_A (P.39, paper Fig. 7c)
TEST(Overlap, TwoReferencesDifferByAConstant) {
  const GammaEnsemble g;
  const double v_g = 0.13;
  RngStream rng(2024, 3);
  const double ba = 6250.0, bb = 6000.0;
  const auto ref_a = to_phi(g.volumes(rng, ba, 3000), v_g);
  const auto ref_b = to_phi(g.volumes(rng, bb, 3000), v_g);
  std::vector<std::vector<double>> samples;
  for (double b : {6400.0, 6100.0, 5800.0}) samples.push_back(to_phi(g.volumes(rng, b, 3000), v_g));
  const auto ea = betas_from_phi(ref_a, samples, v_g);
  const auto eb = betas_from_phi(ref_b, samples, v_g);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    ASSERT_TRUE(ea[i].valid && eb[i].valid);
    const double d = ea[i].dbeta - eb[i].dbeta;
    const double err = std::hypot(ea[i].dbeta_err, eb[i].dbeta_err);
    EXPECT_NEAR(d, bb - ba, 3.0 * err) << "sample " << i;
  }
}

// the KDE density option (the paper's choice) also recovers Δβ. Its smoothing widens both
// densities by h², which lowers |Δβ| by ≈ h²/σ² ≈ 1.12 n^{−2/5} ≈ 4.5 % at n = 3000 — inside
// the ≈ 10 % statistical error, so 3σ still holds
TEST(Overlap, KdeOptionRecoversBeta) {
  const GammaEnsemble g;
  const double v_g = 0.13;
  OverlapOptions o;
  o.method = DensityMethod::Kde;
  for (int s = 0; s < 5; ++s) {
    RngStream rng(500 + s, 4);
    const auto ref = to_phi(g.volumes(rng, 6250.0, 3000), v_g);
    const auto smp = to_phi(g.volumes(rng, 5900.0, 3000), v_g);
    const BetaEstimate e = beta_from_phi(ref, smp, v_g, o);
    ASSERT_TRUE(e.valid) << e.fit.note;
    if (s == 0)
      std::printf("overlap kde: dbeta = %.1f +- %.1f (true -350)\n", e.dbeta, e.dbeta_err);
    EXPECT_NEAR(e.dbeta, -350.0, 3.0 * e.dbeta_err) << "seed " << s;
  }
}

// appendix A: two Gaussians give the parabola (A1), Q = −(V−V₁)²/2σ₁² + (V−V₀)²/2σ₀² + …, so the
// quadratic coefficient is c = (1/σ₀² − 1/σ₁²)/2: positive when the sample is wider than the
// reference, negative when narrower. With n = 2·10⁵ the curvature is significant (> 5σ) and
// within 3σ of (A1) (the binning bias, c·(w²/12)(1/σ₀² + 1/σ₁²) < 0.1 %, is negligible).
// (The weighted R² of the straight line is printed only: with errors this small it mostly
// measures the noise level, which is why the quadratic coefficient is the linearity test.)
TEST(Overlap, GaussianSamplesGiveAppendixACurvature) {
  RngStream rng(8080, 5);
  const int n = 200000;
  const double m0 = 1.20, s0 = 0.014;
  for (double s1 : {0.018, 0.011}) {
    const double m1 = 1.21;
    const auto ref = normal_sample(rng, n, m0, s0);
    const auto smp = normal_sample(rng, n, m1, s1);
    const QFit f = q_fit(ref, smp);
    ASSERT_TRUE(f.valid);
    const double c = 0.5 * (1.0 / (s0 * s0) - 1.0 / (s1 * s1));
    std::printf("appendix A: sigma1 = %.3f  quad = %.1f +- %.1f (A1: %.1f), R2 = %.4f\n", s1,
                f.quad, f.quad_err, c, f.r2);
    EXPECT_NEAR(f.quad, c, 3.0 * f.quad_err);
    EXPECT_GT(std::abs(f.quad) / f.quad_err, 5.0);
    EXPECT_EQ(f.quad > 0.0, s1 > s0);
  }
}

// an exactly canonical pair at the same n shows no curvature (within 3σ), unlike Gaussians
TEST(Overlap, CanonicalPairHasNoCurvature) {
  const GammaEnsemble g;
  RngStream rng(9090, 6);
  const auto v0 = g.volumes(rng, 6250.0, 200000);
  const auto v1 = g.volumes(rng, 5600.0, 200000);
  const QFit f = q_fit(v0, v1);
  ASSERT_TRUE(f.valid);
  std::printf("canonical pair: quad = %.1f +- %.1f, chi2/dof = %.1f/%d\n", f.quad, f.quad_err,
              f.chi2, f.dof);
  EXPECT_LT(std::abs(f.quad), 3.0 * f.quad_err);
  // and the straight line fits: χ² within 4σ of its dof (σ = √(2 dof))
  EXPECT_LT(f.chi2, f.dof + 4.0 * std::sqrt(2.0 * f.dof));
}

// the weighted polynomial fit reproduces an exact parabola and its known errors
TEST(Overlap, WeightedPolyfitExact) {
  std::vector<double> x, y, s;
  for (int i = 0; i < 11; ++i) {
    x.push_back(1.2 + 0.001 * i);
    y.push_back(3.0 - 2.0 * x.back() + 0.5 * x.back() * x.back());
    s.push_back(0.1);
  }
  const PolyFit f = weighted_polyfit(x, y, s, 2);
  EXPECT_NEAR(f.coef[2], 0.5, 1e-4);
  EXPECT_NEAR(f.coef[1], -2.0, 1e-3);
  EXPECT_NEAR(f.r2, 1.0, 1e-12);
  // line through equally weighted points: Var(slope) = σ²/Σ(x − x̄)²
  const PolyFit l = weighted_polyfit(x, y, s, 1);
  double sxx = 0.0;
  for (double v : x) sxx += (v - 1.205) * (v - 1.205);
  EXPECT_NEAR(std::sqrt(l.cov[1][1]), 0.1 / std::sqrt(sxx), 1e-9 / std::sqrt(sxx));
}

}  // namespace
}  // namespace gs
