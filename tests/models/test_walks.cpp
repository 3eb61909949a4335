// single-particle walks: noise heating, exact stopping identities, l^(1/3) scaling, T.5.12
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/error.hpp"
#include "models/walks.hpp"

namespace gs::models {
namespace {

// reduced units: D = M = 1, so D_v = D/M² = 1 and the scales are l^(1/3) and l^(2/3)
WalkParams unit_params(long walks, double dt, std::uint64_t seed) {
  WalkParams p;
  p.noise = 1.0;
  p.mass = 1.0;
  p.dt = dt;
  p.walks = walks;
  p.seed = seed;
  return p;
}

TEST(Walks, FreeParticleHeating) {
  // ⟨v_x²⟩ = 2 D t/M² (docs/physics.md §7) and ⟨x²⟩ = 2 D_v Δt³ (n−1) n (2n−1)/6 for the
  // first-order update T.5.11, both exact in expectation; 5000 particles × 2 components give
  // ≈ 1.4 % errors; 5σ. The same time reached with a 4× larger step must give the same ⟨v²⟩
  // (Δt independence).
  WalkParams p = unit_params(2, 1e-3, 7);
  p.noise = 2e-9;
  p.mass = 3.53e-5;
  const double dv = p.noise / (p.mass * p.mass);
  const HeatingCurve h = free_heating(p, 2, 5000, 2000, 500);
  ASSERT_EQ(h.t.size(), 4u);
  for (std::size_t k = 0; k < h.t.size(); ++k) {
    const double n = std::round(h.t[k] / p.dt);
    EXPECT_NEAR(h.v2[k], 2.0 * dv * h.t[k], 5.0 * h.v2_err[k]) << "t = " << h.t[k];
    const double x2 = 2.0 * dv * std::pow(p.dt, 3) * (n - 1) * n * (2 * n - 1) / 6.0;
    EXPECT_NEAR(h.x2[k], x2, 5.0 * h.x2_err[k]) << "t = " << h.t[k];
  }
  WalkParams q = p;
  q.dt = 4e-3;
  q.seed = 8;
  const HeatingCurve h4 = free_heating(q, 2, 5000, 500, 500);
  EXPECT_NEAR(h4.v2[0], h.v2.back(), 5.0 * std::hypot(h4.v2_err[0], h.v2_err.back()));
}

TEST(Walks, DiscWalkStoppingIdentities) {
  // optional stopping: E[|v_τ|² − 4 D_v τ] = 0 and E[r_τ·v_τ − Σ|v_n|²Δt] = 0 hold exactly for the
  // discrete walk, whatever Δt; 5σ of their own scatter. ⟨v_x²⟩ over time samples is then
  // E[r_τ·v_τ]/(2E[τ]) as well — a check of the uniform-in-time sampling.
  const WalkResult r = disc_walk(unit_params(20000, 1e-3, 11), 1.0);
  EXPECT_EQ(r.capped, 0);
  EXPECT_EQ(r.walks, 20000);
  EXPECT_NEAR(r.heating_residual, 0.0, 5.0 * r.heating_residual_err);
  EXPECT_NEAR(r.virial_residual, 0.0, 5.0 * r.virial_residual_err);
  EXPECT_NEAR(r.q.total(), static_cast<double>(r.samples), 0.5);
  std::printf(
      "[ measured ] disc l=1 (D_v=1): <tau> = %.4f ± %.4f, <v_x^2>_Q = %.4f, steps/walk %.0f\n",
      r.mean_exit_time, r.exit_time_err, r.mean_v2, r.mean_exit_time / r.dt);
}

TEST(Walks, DiscWalkScalesAsLToTheOneThird) {
  // the only scales are v ~ (D l/M²)^(1/3) and t ~ (l²M²/D)^(1/3): l → 8l multiplies ⟨τ⟩ and
  // ⟨v²⟩_Q by 8^(2/3) = 4 (Q collapses in v/l^(1/3), §5.3.1). Same Δt for both, ≥ 1000 steps per
  // walk, so discretisation is < 0.1 %; statistics ≈ 1 % per ratio: 5σ.
  const WalkResult a = disc_walk(unit_params(6000, 1e-3, 21), 1.0);
  const WalkResult b = disc_walk(unit_params(6000, 1e-3, 22), 8.0);
  const double rt = b.mean_exit_time / a.mean_exit_time;
  const double rt_err =
      rt * std::hypot(a.exit_time_err / a.mean_exit_time, b.exit_time_err / b.mean_exit_time);
  EXPECT_NEAR(rt, 4.0, 5.0 * rt_err);
  // ⟨v²⟩_Q = E[Σv²Δt]/E[τ]: its scatter follows that of τ (≈ the same relative error)
  EXPECT_NEAR(b.mean_v2 / a.mean_v2, 4.0, 4.0 * 5.0 * rt_err / rt);
  std::printf("[ measured ] tau(8)/tau(1) = %.4f ± %.4f, v2(8)/v2(1) = %.4f (exact 4)\n", rt,
              rt_err, b.mean_v2 / a.mean_v2);
}

TEST(Walks, GaussianTailCoefficientNearThesisValue) {
  // thesis T.5.12 / Fig. 5.11: for large v, Q(v, l) ≈ A exp(−0.98 (M²/(2Dl))^(2/3) v²). That 0.98
  // is itself a fit to simulation data; fitted here on the same kind of window (10⁻² to 10⁻⁴ of
  // the peak) the coefficient depends on the window by ±0.1, so the bound is 0.98 ± 0.15
  WalkParams p = unit_params(20000, 1e-3, 31);
  p.v_max = 8.0;
  const WalkResult r = disc_walk(p, 1.0);
  const double c = gaussian_tail_coefficient(r, p, 1.0);
  EXPECT_NEAR(c, 0.98, 0.15);
  std::printf("[ measured ] Gaussian tail coefficient of Q(v,l): %.3f (thesis 0.98)\n", c);
}

TEST(Walks, IntervalWalkOfAppendixB) {
  // appendix B: the 1D interval with absorbing ends. Identities as in 2D (with dim = 1); from
  // the centre the two ends are equally likely (arrivals at x = L are half the walks, ±5σ of a
  // binomial); a uniform start exits sooner on average than a central one
  const WalkResult c = interval_walk(unit_params(20000, 1e-3, 41), 1.0, IntervalStart::centre);
  const WalkResult u = interval_walk(unit_params(20000, 1e-3, 42), 1.0, IntervalStart::uniform);
  for (const WalkResult* r : {&c, &u}) {
    EXPECT_EQ(r->capped, 0);
    EXPECT_NEAR(r->heating_residual, 0.0, 5.0 * r->heating_residual_err);
    EXPECT_NEAR(r->virial_residual, 0.0, 5.0 * r->virial_residual_err);
  }
  EXPECT_NEAR(c.arrival.total(), 10000.0, 5.0 * std::sqrt(20000 * 0.25));
  EXPECT_LT(u.mean_exit_time,
            c.mean_exit_time - 5.0 * std::hypot(u.exit_time_err, c.exit_time_err));
  // arrivals at the right end move right
  for (const auto& b : c.arrival.bins())
    if (b.x < -c.arrival.binning().width(0)) {
      EXPECT_EQ(b.count, 0.0);
    }
  std::printf("[ measured ] interval L=1 (D_v=1): <tau> centre %.4f ± %.4f, uniform %.4f ± %.4f\n",
              c.mean_exit_time, c.exit_time_err, u.mean_exit_time, u.exit_time_err);
}

TEST(Walks, SpmDrawsFreePathsFromTheTable) {
  // a linear density P_l ∝ l on [0.01, 1]: mean l = (2/3)(1 − 10⁻⁶)/(1 − 10⁻⁴); a flat one on
  // [0.5, 2]: mean 1.25. The inverse distribution function must reproduce them (5σ with
  // σ = sd/√walks) and the stopping identities must still hold
  WalkParams p = unit_params(6000, 2e-3, 51);
  PathTable lin{{0.01, 1.0}, {0.01, 1.0}};
  const WalkResult a = disc_walk_spm(p, lin);
  const double mean_lin = (2.0 / 3.0) * (1.0 - 1e-6) / (1.0 - 1e-4);
  const double sd_lin = std::sqrt(0.5 - mean_lin * mean_lin);  // ⟨l²⟩ ≈ 1/2
  EXPECT_NEAR(a.mean_region, mean_lin, 5.0 * sd_lin / std::sqrt(6000.0));
  EXPECT_NEAR(a.heating_residual, 0.0, 5.0 * a.heating_residual_err);
  EXPECT_NEAR(a.virial_residual, 0.0, 5.0 * a.virial_residual_err);
  PathTable flat{{0.5, 1.0, 2.0}, {3.0, 3.0, 3.0}};
  const WalkResult b = disc_walk_spm(p, flat);
  EXPECT_NEAR(b.mean_region, 1.25, 5.0 * (1.5 / std::sqrt(12.0)) / std::sqrt(6000.0));
  EXPECT_THROW(disc_walk_spm(p, PathTable{{1.0, 0.5}, {1.0, 1.0}}), InputError);
}

}  // namespace
}  // namespace gs::models
