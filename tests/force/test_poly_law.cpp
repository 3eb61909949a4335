// Model P: the overlap-area normal force (P.34, docs/physics.md §2.2) and Cundall–Strack friction
// (P.35–P.36)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "collision.hpp"
#include "force/laws/polygon_law.hpp"

namespace gs {
namespace {

using law::PolyLawParams;
using law::TangentialSpring;

// paper parameters (section IV): E = 1000 N/m, γ = 0.5, μ = 0.6; m⊥ of two big decagons
// (r = 9 mm, ρ = 1 kg/m²: m = 5r²sin 36° = 2.38e-4 kg)
const PolyLawParams kPaper{1000.0, 0.5, 0.6};
const double kMass = 5.0 * 0.009 * 0.009 * std::sin(std::numbers::pi / 5.0);
const double kMperp = kMass / 2.0;

// no overlap and no motion: no force
TEST(PolyNormal, ZeroAtZeroOverlap) {
  EXPECT_EQ(law::poly_normal_force(kPaper, 0.0, 0.0, kMperp), 0.0);
}

// without motion the force is E·h_eff exactly (slope E, through the origin)
TEST(PolyNormal, LinearInPenetrationWithSlopeE) {
  for (double h : {1e-7, 1e-5, 1e-4, 3e-3}) {
    EXPECT_DOUBLE_EQ(law::poly_normal_force(kPaper, h, 0.0, kMperp), kPaper.E * h) << h;
  }
  // and for another modulus, to catch a hard-wired constant
  const PolyLawParams p{2.5e4, 0.5, 0.6};
  EXPECT_DOUBLE_EQ(law::poly_normal_force(p, 2e-4, 0.0, kMperp), 2.5e4 * 2e-4);
}

// the dashpot γ√(E m⊥)·ḣ adds repulsion while the overlap grows and removes it while it
// shrinks (the corrected sign of docs/physics.md §8.2)
TEST(PolyNormal, DashpotAddsWhileApproachingSubtractsWhileSeparating) {
  const double h = 1e-4, hd = 0.01;
  const double f0 = law::poly_normal_force(kPaper, h, 0.0, kMperp);
  const double fin = law::poly_normal_force(kPaper, h, hd, kMperp);
  const double fout = law::poly_normal_force(kPaper, h, -hd, kMperp);
  const double dash = kPaper.gamma * std::sqrt(kPaper.E * kMperp) * hd;
  EXPECT_GT(fin, f0);
  EXPECT_LT(fout, f0);
  // the differences carry the rounding of f ≈ 0.1 N (ulp 1.4e-17): 1e-16 N is a few ulps
  EXPECT_NEAR(fin - f0, dash, 1e-16);
  EXPECT_NEAR(f0 - fout, dash, 1e-16);
}

// clipped at zero: never attractive, whatever the separation speed
TEST(PolyNormal, NeverAttractive) {
  EXPECT_EQ(law::poly_normal_force(kPaper, 1e-4, -10.0, kMperp), 0.0);
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> uh(0.0, 1e-3), uv(-5.0, 5.0);
  for (int k = 0; k < 10000; ++k)
    ASSERT_GE(law::poly_normal_force(kPaper, uh(rng), uv(rng), kMperp), 0.0);
}

// the spring F*∥ grows by (2/7)·E·v∥(t−Δt)·Δt per step, using the previous step's velocity
TEST(CundallStrack, SpringGrowsWithPreviousVelocity) {
  TangentialSpring s;
  const double dt = 5e-5, fn = 1.0, mpar = 1e-4;
  // first step: no previous velocity, so no spring; the force is the dashpot alone
  const double v1 = 0.02;
  const double f1 = law::cundall_strack(kPaper, s, v1, fn, mpar, dt);
  EXPECT_EQ(s.spring, 0.0);
  EXPECT_DOUBLE_EQ(f1, std::sqrt(2.0 / 7.0 * kPaper.E * mpar) * v1);
  // second step with another velocity: spring = (2/7)E·v1·Δt, force adds the new dashpot
  const double v2 = -0.01;
  const double f2 = law::cundall_strack(kPaper, s, v2, fn, mpar, dt);
  EXPECT_DOUBLE_EQ(s.spring, 2.0 / 7.0 * kPaper.E * v1 * dt);
  EXPECT_DOUBLE_EQ(f2, s.spring + std::sqrt(2.0 / 7.0 * kPaper.E * mpar) * v2);
  EXPECT_EQ(s.v_prev, v2);
}

// steady sliding: the spring rises linearly, step by step, until the Coulomb cap μF⊥ holds it
TEST(CundallStrack, SpringIsCappedAtCoulomb) {
  TangentialSpring s;
  const double dt = 5e-5, fn = 0.01, mpar = 1e-4, v = 0.05;
  const double kt = 2.0 / 7.0 * kPaper.E;
  const double cap = kPaper.mu * fn;
  for (int n = 1; n <= 200; ++n) {
    law::cundall_strack(kPaper, s, v, fn, mpar, dt);
    // n calls: n − 1 increments (the first call has no previous velocity)
    const double linear = (n - 1) * kt * v * dt;
    EXPECT_NEAR(s.spring, std::min(linear, cap), 1e-15) << "step " << n;
  }
  EXPECT_EQ(s.spring, cap);  // 200 steps would give 0.143 N unclamped, the cap is 0.006 N
  // and a vanishing normal force releases the contact completely
  EXPECT_EQ(law::cundall_strack(kPaper, s, v, 0.0, mpar, dt), 0.0);
  EXPECT_EQ(s.spring, 0.0);
}

// the force opposes sliding: F∥ has the sign of v∥ (the force on i is −F∥·t̂), so the
// friction power −F∥·v∥ on the relative motion is never positive; |F∥| ≤ μF⊥ always
TEST(CundallStrack, OpposesSlidingAndRespectsCoulomb) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> uv(-0.5, 0.5), uf(0.0, 0.05), us(-0.03, 0.03);
  const double dt = 5e-5, mpar = 1e-4;
  for (int k = 0; k < 20000; ++k) {
    // steady sliding one way from a fresh spring: spring and dashpot both follow v∥
    const double fn = uf(rng);
    const double v = uv(rng);
    TangentialSpring s{0.0, v};
    const double f = law::cundall_strack(kPaper, s, v, fn, mpar, dt);
    ASSERT_LE(std::abs(f), kPaper.mu * fn + 1e-18);
    ASSERT_GE(f * v, 0.0) << "v = " << v << " f = " << f;
    // any history: the Coulomb bound holds
    TangentialSpring r{us(rng), uv(rng)};
    const double g = law::cundall_strack(kPaper, r, uv(rng), fn, mpar, dt);
    ASSERT_LE(std::abs(g), kPaper.mu * fn + 1e-18);
    ASSERT_LE(std::abs(r.spring), kPaper.mu * fn + 1e-18);
  }
}

// a 1D head-on collision under (P.34): m⊥·ḧ = −F⊥(h, ḣ). Energy is never created; with the
// clipped law the restitution equals the analytic clipped linear spring–dashpot value
// (force k h + c ḣ with k = E, c = γ√(E m⊥), i.e. damping ratio ζ = γ/2) within 1e-3
TEST(PolyNormal, CollisionLosesEnergyAndMatchesClippedLinearTheory) {
  const double v0 = 0.1;  // m/s, a tap-like impact speed
  std::printf("  gamma   e_measured  e_clipped_theory  e_unclipped(exp(-pi z/sqrt(1-z^2)))\n");
  for (double gamma : {0.0, 0.1, 0.25, 0.5, 1.0, 1.5}) {
    const PolyLawParams p{kPaper.E, gamma, kPaper.mu};
    const test::LinearContact lin(p.E, gamma * std::sqrt(p.E * kMperp), kMperp);
    const double dt = lin.duration() / 2000.0;
    const auto c =
        test::collide([&](double h, double hd) { return law::poly_normal_force(p, h, hd, kMperp); },
                      kMperp, v0, dt);
    std::printf("  %5.2f   %.5f     %.5f           %.5f\n", gamma, c.restitution,
                lin.clipped_restitution(), lin.restitution());
    // kinetic energy after ≤ before (equal for γ = 0: RK4 at Δt = t_c/2000 keeps 1e-9)
    if (gamma == 0.0)
      EXPECT_NEAR(c.restitution, 1.0, 1e-6);
    else
      EXPECT_LT(c.restitution, 1.0);
    EXPECT_NEAR(c.restitution, lin.clipped_restitution(), 1e-3) << "gamma " << gamma;
    // clipping only ever removes attraction, so it raises the restitution
    EXPECT_GE(c.restitution, lin.restitution() - 1e-6);
  }
}

}  // namespace
}  // namespace gs
