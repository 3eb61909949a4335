// Model S: the thesis's linear spring–dashpot (T.2.4–T.2.12, docs/physics.md §3)
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "collision.hpp"
#include "force/laws/disk_law.hpp"

namespace gs {
namespace {

using law::DiskLawParams;

// thesis parameters: k_s = 5e5 N/m, two glass beads of M = 3.53e-5 kg
constexpr double kKs = 5e5;
constexpr double kM = 3.53e-5;
constexpr double kM12 = kM / 2.0;
constexpr double kV0 = 1.0;  // m/s

// the force components are the plain sums of (T.2.4), (T.2.5), (T.2.9)
TEST(DiskLaw, ForceComponents) {
  const DiskLawParams p{kKs, 0.3, 0.2, 0.0, false};
  const auto f = law::linear_spring_dashpot(p, 1e-6, 0.5, -0.25);
  EXPECT_DOUBLE_EQ(f.fn, kKs * 1e-6 + 0.3 * 0.5);
  EXPECT_DOUBLE_EQ(f.ft, 0.2 * -0.25);
  // unclipped it may attract (T.2.6 relies on it); clipped it may not
  EXPECT_LT(law::linear_spring_dashpot(p, 1e-7, -1.0, 0.0).fn, 0.0);
  const DiskLawParams pc{kKs, 0.3, 0.2, 0.0, true};
  EXPECT_EQ(law::linear_spring_dashpot(pc, 1e-7, -1.0, 0.0).fn, 0.0);
}

// a head-on collision: m12·δ̈ = −f_n(δ, δ̇) from δ = 0, δ̇ = v0, until δ < 0 again
test::Collision head_on(const DiskLawParams& p, double dt) {
  return test::collide(
      [&](double d, double dd) { return law::linear_spring_dashpot(p, d, dd, 0.0).fn; }, kM12, kV0,
      dt);
}

// (T.2.6) is exact for the unclipped law: the realised restitution equals ε (1e-3 asked; RK4
// at Δt = t_c/1000 and the end interpolation are good to ≈1e-7), the duration equals
// contact_time() (1% asked). With clipping the restitution is larger, as the clipped theory
// says.
TEST(DiskLaw, RestitutionAndContactTime) {
  std::printf("  eps    e_unclipped  t_c/contact_time  e_clipped  (clipped theory)\n");
  for (double eps : {0.1, 0.3, 0.5, 0.7, 0.9, 0.99}) {
    DiskLawParams p{kKs, law::gamma_normal(eps, kM12, kKs), 0.0, 0.0, false};
    const double tc = law::contact_time(kKs, kM12, p.gn);
    const auto c = head_on(p, tc / 1000.0);
    EXPECT_NEAR(c.restitution, eps, 1e-3);
    EXPECT_NEAR(c.duration / tc, 1.0, 1e-2);
    p.clip = true;
    const auto cc = head_on(p, tc / 1000.0);
    const test::LinearContact lin(kKs, p.gn, kM12);
    std::printf("  %.2f   %.6f     %.6f          %.6f   (%.6f)\n", eps, c.restitution,
                c.duration / tc, cc.restitution, lin.clipped_restitution());
    EXPECT_GT(cc.restitution, eps);
    EXPECT_NEAR(cc.restitution, lin.clipped_restitution(), 1e-3);
  }
}

// the edge values of (T.2.6): ε = 1 is undamped; ε → 0 is critical damping γ_n = 2√(m12 k_s)
TEST(DiskLaw, GammaNormalLimits) {
  EXPECT_EQ(law::gamma_normal(1.0, kM12, kKs), 0.0);
  const double crit = 2.0 * std::sqrt(kM12 * kKs);
  // the approach is logarithmic: γ/γ_crit = √(a²/(1+a²)), a = ln ε/π; for ε = 1e-300,
  // a = −220 and the ratio is 1 − 1.0e-5
  EXPECT_NEAR(law::gamma_normal(1e-300, kM12, kKs) / crit, 1.0 - 1.034e-5, 1e-8);
  EXPECT_DOUBLE_EQ(law::gamma_normal(0.0, kM12, kKs), crit);
}

// tangential dashpot on a contact of constant overlap: the relative tangential velocity
// u = (v_i − v_j)·t̂ obeys u̇ = −f_t/m_i − f_t/m_j = −(γ_t/m12)·u, an exponential decay;
// the fitted rate matches γ_t/m12 to 1e-6 and the tangential momentum is conserved
TEST(DiskLaw, TangentialDashpotDecaysExponentially) {
  const double mi = 2e-5, mj = 6e-5, m12 = mi * mj / (mi + mj);
  const double gt = law::gamma_tangential(0.6, m12, kKs);
  const DiskLawParams p{kKs, 0.0, gt, 0.0, false};
  const double delta = 1e-6;  // constant overlap, m
  // y = (v_i, v_j) along t̂; f_t acts on j along t̂ and on i against it
  auto f = [&](const std::array<double, 2>& y) {
    const double ft = law::linear_spring_dashpot(p, delta, 0.0, y[0] - y[1]).ft;
    return std::array<double, 2>{-ft / mi, ft / mj};
  };
  const double rate = gt / m12;
  const double dt = 1e-3 / rate;
  std::array<double, 2> y{0.3, -0.1};
  const double p0 = mi * y[0] + mj * y[1];
  const double u0 = y[0] - y[1];
  const int n = 3000;  // three e-folds
  for (int k = 0; k < n; ++k) y = test::rk4<2>(y, dt, f);
  const double measured = -std::log((y[0] - y[1]) / u0) / (n * dt);
  EXPECT_NEAR(measured / rate, 1.0, 1e-6);
  EXPECT_NEAR(mi * y[0] + mj * y[1], p0, 1e-15 * std::abs(mj * 0.1) + 1e-18);
}

// (T.2.12) over a whole collision: the tangential velocity decays for the whole contact time,
// which damping lengthens, so the realised tangential restitution is ε_t^√(1+(ln ε_n/π)²)
TEST(DiskLaw, RealisedTangentialRestitution) {
  std::printf("  eps_n  eps_t  realised  eps_t^sqrt(1+(ln eps_n/pi)^2)\n");
  for (double en : {0.3, 0.6, 0.9}) {
    for (double et : {0.3, 0.6, 0.9}) {
      const DiskLawParams p{kKs, law::gamma_normal(en, kM12, kKs),
                            law::gamma_tangential(et, kM12, kKs), 0.0, false};
      const double tc = law::contact_time(kKs, kM12, p.gn);
      const double dt = tc / 1000.0;
      // y = (δ, δ̇, u): normal and tangential relative motion of two equal beads
      auto f = [&](const std::array<double, 3>& y) {
        const auto F = law::linear_spring_dashpot(p, y[0], y[1], y[2]);
        return std::array<double, 3>{y[1], -F.fn / kM12, -F.ft / kM12};
      };
      std::array<double, 3> y{0.0, kV0, 0.5};
      for (int k = 0; k < 10000; ++k) {
        const auto nx = test::rk4<3>(y, dt, f);
        if (nx[0] < 0.0 && k > 0) {
          const double s = y[0] / (y[0] - nx[0]);
          y[2] += s * (nx[2] - y[2]);
          break;
        }
        y = nx;
      }
      const double a = std::log(en) / std::numbers::pi;
      const double expect = std::pow(et, std::sqrt(1.0 + a * a));
      std::printf("  %.1f    %.1f    %.6f  %.6f\n", en, et, y[2] / 0.5, expect);
      EXPECT_NEAR(y[2] / 0.5, expect, 1e-3);
    }
  }
}

// sliding friction (T.2.7): |f_t| ≤ μ·f_n. A fast slide first decelerates at the constant
// rate μ f_n/m12 (Coulomb), and once γ_t·u < μ f_n the dashpot takes over exponentially
TEST(DiskLaw, FrictionCap) {
  const double mu = 0.3, delta = 2e-6, gt = law::gamma_tangential(0.6, kM12, kKs);
  const DiskLawParams p{kKs, 0.0, gt, mu, false};
  const double fn = kKs * delta;
  // the cap, in both directions, and never from an attractive normal force
  EXPECT_DOUBLE_EQ(law::linear_spring_dashpot(p, delta, 0.0, 100.0).ft, mu * fn);
  EXPECT_DOUBLE_EQ(law::linear_spring_dashpot(p, delta, 0.0, -100.0).ft, -mu * fn);
  const DiskLawParams pd{kKs, 1.0, gt, mu, false};  // a dashpot strong enough to attract
  ASSERT_LT(law::linear_spring_dashpot(pd, 1e-9, -10.0, 5.0).fn, 0.0);
  EXPECT_EQ(law::linear_spring_dashpot(pd, 1e-9, -10.0, 5.0).ft, 0.0);
  // the two regimes of u̇ = −f_t/m12
  const double u0 = 5.0, uc = mu * fn / gt;  // the crossover speed
  ASSERT_GT(u0, 2.0 * uc);
  const double t1 = kM12 * (u0 - uc) / (mu * fn);  // end of the Coulomb phase
  const double tau = kM12 / gt;                    // dashpot time constant
  auto f = [&](const std::array<double, 1>& y) {
    return std::array<double, 1>{-law::linear_spring_dashpot(p, delta, 0.0, y[0]).ft / kM12};
  };
  const double dt = std::min(t1, tau) / 4000.0;
  std::array<double, 1> y{u0};
  double t = 0.0;
  const double t_end = t1 + 2.0 * tau;
  double u_half = 0.0;
  while (t < t_end - 0.5 * dt) {
    y = test::rk4<1>(y, dt, f);
    t += dt;
    if (u_half == 0.0 && t >= 0.5 * t1) u_half = y[0] + (t - 0.5 * t1) * mu * fn / kM12;
  }
  // Coulomb phase linear to 1e-9 (RK4 is exact on a constant force); the kink at t1 costs
  // O(Δt²) so the exponential tail is checked to 1e-4
  EXPECT_NEAR(u_half, u0 - 0.5 * t1 * mu * fn / kM12, 1e-9 * u0);
  EXPECT_NEAR(y[0] / (uc * std::exp(-(t - t1) / tau)), 1.0, 1e-4);
}

}  // namespace
}  // namespace gs
