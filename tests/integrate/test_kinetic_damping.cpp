// kinetic damping (Cundall's dynamic relaxation, drive.quench) through
// Integrator::zero_velocities: a column of masses on springs with a stiffness-proportional
// dashpot, the pile's slow-mode problem in miniature (its slowest mode has ζ ≈ 0.01), comes to
// rest far sooner when every velocity is zeroed at each kinetic-energy peak, and at the same
// equilibrium; zero_velocities leaves every scheme as init() would from rest
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "integrate/integrator.hpp"

namespace gs {
namespace {

// n unit masses stacked on unit springs (the first on the floor) under gravity g; the
// dashpots act on the springs' rates (c = β·k), so mode j has ζ_j = β·ω_j/2, as the paper's
// normal dashpot γ√(E m⊥)·ḣ does in a pile
struct Column {
  static constexpr int kN = 20;
  static constexpr double kG = 1.0;      // gravity, per unit mass and stiffness
  static constexpr double kBeta = 0.25;  // ζ = 0.25 in the fastest mode (ω ≈ 2)
  std::vector<double> q = std::vector<double>(kN, 0.0), v = q, a = q;
  std::vector<Channel> ch;

  std::span<const Channel> spans() {
    ch = {{q, v, a}};
    return ch;
  }
  // spring i sits below mass i: its extension and rate
  void forces() {
    for (int i = 0; i < kN; ++i) a[i] = -kG;
    for (int i = 0; i < kN; ++i) {
      const double ext = q[i] - (i > 0 ? q[i - 1] : 0.0);
      const double rate = v[i] - (i > 0 ? v[i - 1] : 0.0);
      const double f = -ext - kBeta * rate;  // on mass i; the reaction on mass i − 1
      a[i] += f;
      if (i > 0) a[i - 1] -= f;
    }
  }
  double kinetic() const {
    double e = 0.0;
    for (double x : v) e += 0.5 * x * x;
    return e;
  }
  // the static solution: spring i carries the weight of masses i…n−1
  static double equilibrium(int i) {
    double x = 0.0;
    for (int j = 0; j <= i; ++j) x -= (kN - j) * kG;
    return x;
  }
  double error() const {
    double e = 0.0;
    for (int i = 0; i < kN; ++i)
      e = std::max({e, std::abs(q[i] - equilibrium(i)), std::abs(v[i]) / kOmegaMin});
    return e;
  }
  // slowest mode of the fixed–free chain: 2 sin(π/(2(2n + 1)))
  static inline const double kOmegaMin = 2.0 * std::sin(M_PI / (2.0 * (2 * kN + 1)));
};

// steps until every mass is within tol of its equilibrium (and as slow), with or without
// kinetic damping; -1 if not within max_steps
long steps_to_rest(IntegratorKind kind, bool kinetic_damping, double tol, long max_steps,
                   long* resets = nullptr, Column* out = nullptr) {
  const double dt = 0.05;  // ω_max·Δt = 0.1: inside every scheme's stability region
  Column c;
  auto I = make_integrator(kind);
  c.forces();
  I->init(c.spans(), dt);
  double last = 0.0;
  bool rising = false;
  long n = 0, zeroed = 0;
  for (; n < max_steps && c.error() >= tol; ++n) {
    auto s = c.spans();
    I->predict(s, dt, ThreadTeam{});
    c.forces();
    I->correct(s, dt, ThreadTeam{});
    // a kinetic-energy peak: every velocity to zero (what ProtocolClock/Simulation do)
    const double ke = c.kinetic();
    if (kinetic_damping && rising && ke < last) {
      I->zero_velocities(c.spans());
      ++zeroed;
      rising = false;
      last = 0.0;
    } else {
      rising = ke > last;
      last = ke;
    }
  }
  if (resets) *resets = zeroed;
  if (out) *out = c;
  return c.error() < tol ? n : -1;
}

class KineticDamping : public ::testing::TestWithParam<IntegratorKind> {};

// the sag is 210 units; rest within 1e-6 of it. Without kinetic damping the slowest mode
// (ω = 0.077, ζ = 0.0096) needs ≈ 3.6·10⁵ steps; with it, a few thousand
TEST_P(KineticDamping, ReachesTheSameRestFarSooner) {
  const double sag = -Column::equilibrium(Column::kN - 1);
  const double tol = 1e-6 * sag;
  long resets = 0;
  Column damped, free;
  const long n_kd = steps_to_rest(GetParam(), true, tol, 2'000'000, &resets, &damped);
  const long n_free = steps_to_rest(GetParam(), false, tol, 2'000'000, nullptr, &free);
  std::printf(
      "[ %s ] column of %d: rest within 1e-6 of the sag in %ld steps with kinetic "
      "damping (%ld resets), %ld without\n",
      std::string(to_string(GetParam())).c_str(), Column::kN, n_kd, resets, n_free);
  ASSERT_GT(n_kd, 0) << "kinetic damping did not reach rest";
  ASSERT_GT(n_free, 0) << "the lightly damped column did not reach rest";
  EXPECT_LT(n_kd * 20, n_free) << n_kd << " steps with kinetic damping, " << n_free << " without";
  EXPECT_GT(resets, 2);
  // the same equilibrium, the analytic one, within the tolerance
  for (int i = 0; i < Column::kN; ++i) {
    EXPECT_NEAR(damped.q[i], Column::equilibrium(i), tol) << "mass " << i;
    EXPECT_NEAR(damped.q[i], free.q[i], 2 * tol) << "mass " << i;
  }
}

// after zero_velocities the scheme continues exactly as a fresh init() from rest at the same
// positions and accelerations (the history holds nothing of the zeroed motion)
TEST_P(KineticDamping, ZeroVelocitiesIsAFreshStartFromRest) {
  const double dt = 0.05;
  Column a;
  auto I = make_integrator(GetParam());
  a.forces();
  I->init(a.spans(), dt);
  for (int k = 0; k < 37; ++k) {
    auto s = a.spans();
    I->predict(s, dt, ThreadTeam{});
    a.forces();
    I->correct(s, dt, ThreadTeam{});
  }
  I->zero_velocities(a.spans());
  for (double x : a.v) ASSERT_EQ(x, 0.0);
  // the fresh start: same q, v = 0, the same stored accelerations
  Column b = a;
  auto J = make_integrator(GetParam());
  J->init(b.spans(), dt);
  for (int k = 0; k < 50; ++k) {
    for (Column* c : {&a, &b}) {
      auto& S = c == &a ? *I : *J;
      auto s = c->spans();
      S.predict(s, dt, ThreadTeam{});
      c->forces();
      S.correct(s, dt, ThreadTeam{});
    }
  }
  for (int i = 0; i < Column::kN; ++i) {
    EXPECT_NEAR(a.q[i], b.q[i], 1e-12 * std::abs(b.q[i]) + 1e-12) << "mass " << i;
    EXPECT_NEAR(a.v[i], b.v[i], 1e-12 * std::abs(b.q[i]) + 1e-12) << "mass " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Schemes, KineticDamping,
                         ::testing::Values(IntegratorKind::Gear6, IntegratorKind::VelocityVerlet,
                                           IntegratorKind::PositionVerlet,
                                           IntegratorKind::SemiImplicitEuler),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace gs
