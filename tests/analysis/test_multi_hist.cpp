// β and ln Z through neighbours: the joint multiple-histogram fit on exact expected counts,
// and both estimators (chain, joint) on exactly sampled ideal quadron gases whose far runs do
// not overlap the reference
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "analysis/multi_hist.hpp"
#include "analysis/quadron.hpp"
#include "analysis/stats.hpp"
#include "analysis/tap_synthetic.hpp"
#include "core/error.hpp"

namespace gs {
namespace {

// noise-free counts N_k g_j e^{−b_k x_j}/Z_k: the fit must return the b_k and ln Z_k exactly
TEST(JointHistogramFit, RecoversExactTiltsFromExpectedCounts) {
  const int B = 60;
  std::vector<double> x(B), lng(B);
  for (int j = 0; j < B; ++j) {
    x[j] = 1.15 + 0.002 * j;
    lng[j] = 3.0 * std::log(1.0 + j) - 0.01 * j * j;  // any density of states
  }
  const std::vector<double> b = {0.0, 150.0, -120.0, 300.0};  // run 0 is the reference
  const std::vector<double> n = {1000, 2000, 500, 800};
  std::vector<std::vector<double>> counts(b.size(), std::vector<double>(B));
  std::vector<double> lnz(b.size());
  for (std::size_t k = 0; k < b.size(); ++k) {
    double z = 0.0;
    for (int j = 0; j < B; ++j) z += std::exp(lng[j] - b[k] * x[j]);
    lnz[k] = std::log(z);
    for (int j = 0; j < B; ++j) counts[k][j] = n[k] * std::exp(lng[j] - b[k] * x[j]) / z;
  }
  const JointFit f = joint_histogram_fit(counts, x, 0, {}, 100000, 1e-12);
  ASSERT_TRUE(f.converged);
  for (std::size_t k = 0; k < b.size(); ++k) {
    EXPECT_TRUE(f.connected[k]);
    EXPECT_NEAR(f.b[k], b[k], 1e-6) << k;
    EXPECT_NEAR(f.dlnz[k], lnz[k] - lnz[0], 1e-6) << k;
  }
}

// a run that shares no bin with the others cannot be placed
TEST(JointHistogramFit, ARunWithoutSharedBinsIsNotConnected) {
  const std::vector<double> x = {1.0, 1.1, 1.2, 1.3, 1.4, 1.5};
  const std::vector<std::vector<double>> counts = {
      {5, 9, 4, 0, 0, 0}, {1, 6, 8, 2, 0, 0}, {0, 0, 0, 0, 3, 7}};
  const JointFit f = joint_histogram_fit(counts, x, 0, {}, 10000, 1e-10);
  EXPECT_TRUE(f.connected[0]);
  EXPECT_TRUE(f.connected[1]);
  EXPECT_FALSE(f.connected[2]);
  EXPECT_TRUE(std::isnan(f.b[2]));
}

// five synthetic runs with a few hundred correlated taps each, spaced so that neighbours
// overlap and the ends do not: the direct fit against the middle run cannot reach the ends,
// the chain and the joint fit must (within 3 bootstrap standard errors of the true Δβ, Δln Z)
TEST(MultiHistogramBeta, ReachesRunsThatDoNotOverlapTheReference) {
  QuadronGasSpec gas;
  gas.refresh = 0.5;      // τ_int = 1.5 taps
  gas.start_fill = -2.0;  // start in equilibrium: no transient
  const double a = quadron_gas_a(gas);
  const double scale = a / gas.limits.delta_inv();  // β per unit of βΔφ⁻¹/a
  const std::vector<double> xs = {0.35, 0.75, 1.3, 2.0, 3.0};
  const int ref = 2;
  std::vector<std::vector<double>> phi;
  std::vector<double> beta, tau;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    beta.push_back(xs[k] * scale);
    phi.push_back(quadron_gas_phi(beta.back(), 400, gas, 99, 10 + k));
    tau.push_back(autocorr_time(phi.back()).tau_int);
  }
  // V_g as the analysis takes it: the gas' grain volume
  const double v_g = gas.v_g;
  MultiHistOptions opts;
  opts.tau_int = tau;
  opts.bootstrap = 200;
  const MultiHistResult r = multi_histogram_beta(phi, ref, v_g, opts);

  // the premise: the ends do not overlap the reference directly
  int direct_invalid = 0;
  for (std::size_t k : {0u, 4u}) direct_invalid += !beta_from_phi(phi[ref], phi[k], v_g).valid;
  EXPECT_GE(direct_invalid, 1);

  ASSERT_TRUE(r.joint_converged);
  const double lz_ref = quadron_lnz(beta[ref], a, v_g, gas.limits);
  double chi2_chain = 0.0, chi2_joint = 0.0;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    const double db = beta[k] - beta[ref];
    const double dz = quadron_lnz(beta[k], a, v_g, gas.limits) - lz_ref;
    for (const auto* m : {&r.chain[k], &r.joint[k]}) {
      ASSERT_TRUE(m->valid) << k;
      if (static_cast<int>(k) == ref) {
        EXPECT_EQ(m->dbeta, 0.0);
        continue;
      }
      ASSERT_GT(m->dbeta_err, 0.0) << k;
      EXPECT_NEAR(m->dbeta, db, 3.0 * m->dbeta_err) << k;
      EXPECT_NEAR(m->dlnz, dz, 3.0 * m->dlnz_err) << k;
      // an error that says something: a quarter of the span it measures at most, so that a
      // factor-two mistake would fail the 3σ test
      EXPECT_LT(m->dbeta_err, 0.25 * std::abs(db)) << k;
    }
    if (static_cast<int>(k) != ref) {
      chi2_chain += std::pow((r.chain[k].dbeta - db) / r.chain[k].dbeta_err, 2);
      chi2_joint += std::pow((r.joint[k].dbeta - db) / r.joint[k].dbeta_err, 2);
    }
    std::printf("multi-hist run %zu: true %.1f  chain %.1f ± %.1f  joint %.1f ± %.1f\n", k, db,
                r.chain[k].dbeta, r.chain[k].dbeta_err, r.joint[k].dbeta, r.joint[k].dbeta_err);
  }
  // four pulls each: χ² with 4 degrees of freedom stays below 16 in > 99.5 % of samples
  EXPECT_LT(chi2_chain, 16.0);
  EXPECT_LT(chi2_joint, 16.0);
}

// where the direct fit exists the three estimates agree within their errors
TEST(MultiHistogramBeta, AgreesWithTheDirectFitWhereItExists) {
  QuadronGasSpec gas;
  gas.refresh = 1.0;
  gas.start_fill = -2.0;
  const double scale = quadron_gas_a(gas) / gas.limits.delta_inv();
  std::vector<std::vector<double>> phi;
  for (int k = 0; k < 3; ++k)
    phi.push_back(quadron_gas_phi((1.0 + 0.3 * k) * scale, 1500, gas, 5, k));
  MultiHistOptions opts;
  opts.bootstrap = 100;
  const MultiHistResult r = multi_histogram_beta(phi, 0, gas.v_g, opts);
  for (int k = 1; k < 3; ++k) {
    const BetaEstimate d = beta_from_phi(phi[0], phi[k], gas.v_g);
    ASSERT_TRUE(d.valid);
    EXPECT_NEAR(r.joint[k].dbeta, d.dbeta, 3.0 * std::hypot(d.dbeta_err, r.joint[k].dbeta_err));
    EXPECT_NEAR(r.chain[k].dbeta, d.dbeta, 3.0 * std::hypot(d.dbeta_err, r.chain[k].dbeta_err));
  }
}

// the bootstrap covariance across runs against the covariance over independent realizations:
// runs on the same side of a reference share the noise of its tail, so their β̂ are positively
// correlated, and a run's β̂ against two references shares that run's noise; each element must match
// within the errors of both estimates (var ĉ_ab = (c_ab² + c_aa c_bb)/(R − 1) for R draws), the
// bootstrap's averaged over B realizations (one realization's own scatter, O(n^−½), would
// otherwise dominate), and the joint diagonal must be the marginal errors squared
TEST(MultiHistogramBeta, BootstrapCovarianceMatchesTheSpreadOverRealizations) {
  QuadronGasSpec gas;
  gas.start_fill = -2.0;  // equilibrium, independent taps (refresh 1): blocks of one tap
  const double scale = quadron_gas_a(gas) / gas.limits.delta_inv();
  const std::vector<double> xs = {1.0, 1.15, 1.3, 1.45};
  const int ref = 0, n = 400, M = 300, R = 150, B = 4;
  auto draw = [&](std::uint64_t seed) {
    std::vector<std::vector<double>> phi;
    for (std::size_t k = 0; k < xs.size(); ++k)
      phi.push_back(quadron_gas_phi(xs[k] * scale, n, gas, seed, k));
    return phi;
  };
  MultiHistOptions opts;
  opts.direct_refs = {ref, 1};
  // quantities: joint β̂ of runs 1–3, direct β̂ of runs 1–3 against run 0, of runs 0, 2, 3
  // against run 1 (index b·K + k)
  const std::vector<int> q = {1, 2, 3, 5, 6, 7, 8, 10, 11};
  std::vector<std::vector<double>> mc(q.size());
  opts.bootstrap = 0;
  for (int m = 0; m < M; ++m) {
    const auto phi = draw(1000 + m);
    const MultiHistResult r = multi_histogram_beta(phi, ref, gas.v_g, opts);
    ASSERT_TRUE(r.joint_converged);
    std::vector<double> v = {r.joint[1].dbeta, r.joint[2].dbeta, r.joint[3].dbeta};
    for (int k : {1, 2, 3}) v.push_back(beta_from_phi(phi[0], phi[k], gas.v_g).dbeta);
    for (int k : {0, 2, 3}) v.push_back(beta_from_phi(phi[1], phi[k], gas.v_g).dbeta);
    for (std::size_t i = 0; i < q.size(); ++i) mc[i].push_back(v[i]);
  }
  opts.bootstrap = R;
  std::vector<std::vector<double>> boot(12, std::vector<double>(12, 0.0));
  for (int i = 0; i < B; ++i) {
    const MultiHistResult b = multi_histogram_beta(draw(7 + i), ref, gas.v_g, opts);
    ASSERT_EQ(b.cov.size(), 12u);
    for (int k : {1, 2, 3})
      EXPECT_NEAR(b.cov[k][k], b.joint[k].dbeta_err * b.joint[k].dbeta_err, 1e-9 * b.cov[k][k]);
    EXPECT_EQ(b.cov[ref][ref], 0.0);  // the reference's own β̂ is 0 in every replica
    for (int x = 0; x < 12; ++x)
      for (int y = 0; y < 12; ++y) boot[x][y] += b.cov[x][y] / B;
  }
  auto cov = [](const std::vector<double>& x, const std::vector<double>& y) {
    const double mx = mean(x), my = mean(y);
    double s = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) s += (x[i] - mx) * (y[i] - my);
    return s / static_cast<double>(x.size() - 1);
  };
  for (std::size_t i = 0; i < q.size(); ++i)
    for (std::size_t j = i; j < q.size(); ++j) {
      const double t = cov(mc[i], mc[j]), ti = cov(mc[i], mc[i]), tj = cov(mc[j], mc[j]);
      const double c = boot[q[i]][q[j]];
      const double err = std::sqrt((t * t + ti * tj) * (1.0 / (B * (R - 1)) + 1.0 / (M - 1)));
      EXPECT_NEAR(c, t, 4.0 * err) << q[i] << ' ' << q[j];
      std::printf("cov %d %d: bootstrap %.4g, realizations %.4g ± %.2g (ρ %.2f) pull %.1f\n", q[i],
                  q[j], c, t, err, t / std::sqrt(ti * tj), (c - t) / err);
    }
  // the premise: the correlations tested are far from zero (positive, and a test of a wrong
  // sign or of independence would fail)
  auto rho = [&](int i, int j) {
    return cov(mc[i], mc[j]) / std::sqrt(cov(mc[i], mc[i]) * cov(mc[j], mc[j]));
  };
  const double rho_joint = rho(1, 2), rho_refs = rho(4, 7);  // runs 2, 3; run 2 against 0, 1
  EXPECT_GT(rho_joint, 0.2);
  EXPECT_GT(rho_refs, 0.2);
}

// the joint fit's work is set by the cells of x, not by the taps: ten times the taps (each
// series as long, the same distributions) must not cost ten times the Newton terms, and
// the cells must stay as many (each value its own cell made every Newton step O(taps))
TEST(MultiHistogramBeta, JointFitWorkDoesNotGrowWithTheTaps) {
  auto work = [](int n) {
    std::mt19937_64 rng(7);
    std::normal_distribution<double> noise(0.0, 0.002);
    std::vector<std::vector<double>> phi(3);
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < n; ++i) phi[k].push_back(0.815 + 0.002 * k + noise(rng));
    MultiHistOptions opts;
    opts.bootstrap = 4;
    int steps = 0;
    opts.step = [&] { ++steps; };
    const MultiHistResult r = multi_histogram_beta(phi, 1, 0.01, opts);
    EXPECT_TRUE(r.joint_converged);
    // the answer stays that of the direct fit of the pair, within their errors
    const BetaEstimate d = beta_from_phi(phi[1], phi[0], 0.01);
    EXPECT_NEAR(r.joint[0].dbeta, d.dbeta, 3.0 * std::hypot(d.dbeta_err, r.joint[0].dbeta_err));
    EXPECT_EQ(steps, 1 + opts.bootstrap);  // the fit and each replica report their end
    return r;
  };
  const MultiHistResult small = work(3000), large = work(30000);
  std::printf("joint fit: %d cells, %lld terms at 3·3000 taps; %d cells, %lld terms at 3·30000\n",
              small.values, static_cast<long long>(small.terms), large.values,
              static_cast<long long>(large.terms));
  EXPECT_LT(large.values, 1.5 * small.values);
  EXPECT_LT(static_cast<double>(large.terms), 2.0 * static_cast<double>(small.terms));
}

TEST(MultiHistogramBeta, RefusesBadInput) {
  EXPECT_THROW(multi_histogram_beta({{0.8, 0.81, 0.82}}, 0, 0.1), InputError);
  EXPECT_THROW(multi_histogram_beta({{0.8, 0.81, 0.82}, {0.8, 1.5, 0.82}}, 0, 0.1), InputError);
  EXPECT_THROW(multi_histogram_beta({{0.8, 0.81, 0.82}, {0.8, 0.81}}, 0, 0.1), InputError);
  EXPECT_THROW(multi_histogram_beta({{0.8, 0.81, 0.82}, {0.8, 0.81, 0.83}}, 2, 0.1), InputError);
}

}  // namespace
}  // namespace gs
