// the ideal quadron solution (P.21–P.26, P.17): identities, an exact Monte Carlo of the
// quadron gas against the formulas, and the Levenberg–Marquardt fit of (a = N z̄/V_g, β₀)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "analysis/quadron.hpp"
#include "analysis/stats.hpp"
#include "analysis/tap_synthetic.hpp"
#include "core/rng.hpp"

namespace gs {
namespace {

const QuadronParams kP{};  // φ_rlp = 0.81, φ_rcp = 0.855 (paper section V)
const double kA = 556.51;  // N z̄/V_g of the paper's fit, 1/m²

TEST(Quadron, LangevinSeriesAndInverse) {
  // the series branch (|x| < 0.05) joins the closed form smoothly
  for (double x : {0.0499999, 0.0500001}) {
    const double closed = 1.0 / std::tanh(x) - 1.0 / x;
    EXPECT_NEAR(langevin(x), closed, 1e-12);
    EXPECT_NEAR(langevin_deriv(x), 1.0 / (x * x) - 1.0 / std::pow(std::sinh(x), 2), 1e-10);
  }
  EXPECT_NEAR(langevin(1e-6), 1e-6 / 3.0 - 1e-18 / 45.0, 1e-21);
  for (double u : {-0.9, -0.2, 0.0, 0.01, 0.5, 0.97})
    EXPECT_NEAR(langevin(langevin_inverse(u)), u, 1e-13) << u;
}

// (P.26) as printed, against the Langevin form we evaluate, and its limits (P.24, P.25)
TEST(Quadron, MeanVolumeFractionMatchesP26) {
  const double d = kP.delta_inv();
  for (double beta : {500.0, 3000.0, 9000.0, 30000.0}) {
    const double printed = 1.0 / kP.phi_rlp + kA / beta - d / std::tanh(beta * d / kA);
    EXPECT_NEAR(quadron_inv_phi(beta, kA, kP), printed, 1e-12) << beta;
    // φ̄ lies between rlp and rcp for β > 0 and round-trips through the inverse
    const double phi = quadron_phi(beta, kA, kP);
    EXPECT_GT(phi, kP.phi_rlp);
    EXPECT_LT(phi, kP.phi_rcp);
    EXPECT_NEAR(quadron_beta_of_phi(phi, kA, kP), beta, 1e-6 * beta);
  }
  EXPECT_NEAR(quadron_phi(0.0, kA, kP), kP.phi_rlp, 1e-15);
  EXPECT_NEAR(quadron_phi(1e9, kA, kP), kP.phi_rcp, 1e-6);
}

// thermodynamic consistency of (P.21) with (P.26) and (P.17):
// −∂ln Z/∂β = ⟨V⟩ = V_g/φ̄ (P.10, P.15) and ∂²ln Z/∂β² = σ_V² with σ_φ = φ̄² σ_V/V_g (P.16)
TEST(Quadron, PartitionFunctionIsConsistent) {
  const double v_g = 0.13;
  for (double beta : {800.0, 5000.0, 12000.0, 40000.0}) {
    const double h = 1e-3 * beta;
    const double lp = quadron_lnz(beta + h, kA, v_g, kP);
    const double l0 = quadron_lnz(beta, kA, v_g, kP);
    const double lm = quadron_lnz(beta - h, kA, v_g, kP);
    const double mean_v = -(lp - lm) / (2.0 * h);
    const double var_v = (lp - 2.0 * l0 + lm) / (h * h);
    const double phi = quadron_phi(beta, kA, kP);
    // central differences: truncation O(h²) ≈ 1e-6 relative, round-off ≈ 1e-16·lnZ/h² for var
    EXPECT_NEAR(mean_v, v_g / phi, 1e-7 * v_g / phi) << beta;
    const double sigma_phi = phi * phi * std::sqrt(var_v) / v_g;
    EXPECT_NEAR(sigma_phi, quadron_sigma_phi(beta, kA, v_g, kP), 1e-4 * sigma_phi) << beta;
    // and ∂φ̄/∂β against a difference of φ̄
    const double dphi = (quadron_phi(beta + h, kA, kP) - quadron_phi(beta - h, kA, kP)) / (2 * h);
    EXPECT_NEAR(quadron_dphi_dbeta(beta, kA, kP), dphi, 1e-6 * dphi) << beta;
  }
}

// an exact Monte Carlo of the ideal quadron gas (N z̄ = 72 cells, 20000 independent taps)
// against the formulas: ⟨V⟩ = V_g/φ̄(P.26) to 3 standard errors, σ_φ to 3 standard errors
// of a standard deviation (σ/√(2n) ≈ 0.5 %; the linearisation φ ≈ V_g/V adds O(σ_V²/V²) ≈ 1e-5)
TEST(Quadron, GasSamplerMatchesFormulas) {
  QuadronGasSpec g;
  const double a = quadron_gas_a(g);
  EXPECT_EQ(quadron_gas_cells(g), 72);
  for (double beta : {2000.0, 9000.0, 25000.0}) {
    const auto phi = quadron_gas_phi(beta, 20000, g, 77, static_cast<std::uint64_t>(beta));
    std::vector<double> vol(phi.size());
    for (std::size_t i = 0; i < phi.size(); ++i) vol[i] = g.v_g / phi[i];
    const double se_v = stddev(vol) / std::sqrt(vol.size());
    EXPECT_NEAR(mean(vol), g.v_g / quadron_phi(beta, a, g.limits), 3.0 * se_v) << beta;
    const double s_pred = quadron_sigma_phi(beta, a, g.v_g, g.limits);
    EXPECT_NEAR(stddev(phi), s_pred, 3.0 * s_pred / std::sqrt(2.0 * phi.size())) << beta;
  }
}

// synthetic φ̄(β) from (P.26) with β̂ = β − β₀: noise-free data are fitted to round-off
TEST(Quadron, FitRecoversExactParameters) {
  const double beta0 = 9000.0;
  std::vector<double> bh, ph;
  for (double x = 0.3; x <= 3.0; x += 0.3) {
    const double beta = x * kA / kP.delta_inv();
    bh.push_back(beta - beta0);
    ph.push_back(quadron_phi(beta, kA, kP));
  }
  const QuadronFit f = fit_quadron(bh, ph, {}, {}, kP);
  EXPECT_TRUE(f.converged) << f.note;
  EXPECT_NEAR(f.a, kA, 1e-6 * kA);
  EXPECT_NEAR(f.beta0, beta0, 1e-6 * beta0);
}

// with noise on both φ̄ (σ = 1e-4, the paper's CI scale) and β̂ (σ = 150 m⁻²): the fit is
// within 3σ of the truth in each of 5 seeded data sets, and over 400 data sets the ±1σ
// interval covers a and β₀ 68 % of the time (binomial σ ≈ 2.3 %; we allow ±7 %)
TEST(Quadron, NoisyFitWithinErrors) {
  const double beta0 = 9000.0;
  const double sphi = 1e-4, sbeta = 150.0;
  int cover_a = 0, cover_b = 0;
  const int reps = 400;
  for (int r = 0; r < reps; ++r) {
    RngStream rng(3000 + r, 9);
    std::vector<double> bh, ph, eph, ebh;
    for (double x = 0.3; x <= 3.0; x += 0.2) {
      const double beta = x * kA / kP.delta_inv();
      bh.push_back(beta - beta0 + sbeta * rng.normal());
      ph.push_back(quadron_phi(beta, kA, kP) + sphi * rng.normal());
      eph.push_back(sphi);
      ebh.push_back(sbeta);
    }
    const QuadronFit f = fit_quadron(bh, ph, eph, ebh, kP);
    ASSERT_TRUE(f.converged) << f.note;
    if (r < 5) {
      if (r == 0)
        std::printf(
            "quadron fit: a = %.1f +- %.1f (true %.2f), beta0 = %.0f +- %.0f (true %.0f), "
            "chi2/dof = %.1f/%d\n",
            f.a, f.a_err, kA, f.beta0, f.beta0_err, beta0, f.chi2, f.dof);
      EXPECT_NEAR(f.a, kA, 3.0 * f.a_err) << "set " << r;
      EXPECT_NEAR(f.beta0, beta0, 3.0 * f.beta0_err) << "set " << r;
    }
    cover_a += std::abs(f.a - kA) < f.a_err;
    cover_b += std::abs(f.beta0 - beta0) < f.beta0_err;
  }
  std::printf("quadron fit: 1-sigma coverage a %.3f, beta0 %.3f\n", cover_a / double(reps),
              cover_b / double(reps));
  EXPECT_NEAR(cover_a / double(reps), 0.683, 0.07);
  EXPECT_NEAR(cover_b / double(reps), 0.683, 0.07);
}

}  // namespace
}  // namespace gs
