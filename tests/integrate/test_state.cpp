// bookkeeping of the integrators: checkpoints, independent channels, caller edits between
// steps, Δt changes, names and layout checks
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "integrate/schemes.hpp"
#include "oscillator.hpp"

namespace gs {
namespace {

class State : public ::testing::TestWithParam<IntegratorKind> {};

// x, y and θ channels with different stiffness and damping, two bodies each
test::OscillatorSystem three_channels() {
  test::OscillatorSystem s;
  s.add(1.0, 0.3, {1.0, -0.4}, {0.5, 0.2});   // x
  s.add(2.5, 0.0, {0.2, 0.7}, {-1.0, 0.0});   // y
  s.add(0.7, 0.1, {3.0, -1.5}, {0.0, 0.25});  // θ
  return s;
}

// save mid-run, continue; a fresh integrator loaded from the history with the saved q, v
// continues bitwise identically
TEST_P(State, SaveLoadContinuesBitwise) {
  const double dt = 0.01;
  auto I = make_integrator(GetParam());
  auto s = three_channels();
  s.init(*I, dt);
  for (int k = 0; k < 137; ++k) s.step(*I, dt);
  const std::vector<double> hist = I->save();
  auto copy = s;  // the caller's own checkpoint of q and v
  for (int k = 0; k < 200; ++k) s.step(*I, dt);

  auto J = make_integrator(GetParam());
  J->load(hist);
  for (int k = 0; k < 200; ++k) copy.step(*J, dt);
  for (std::size_t c = 0; c < s.q.size(); ++c) {
    for (std::size_t i = 0; i < s.q[c].size(); ++i) {
      EXPECT_EQ(s.q[c][i], copy.q[c][i]) << "channel " << c << " dof " << i;
      EXPECT_EQ(s.v[c][i], copy.v[c][i]) << "channel " << c << " dof " << i;
    }
  }
  EXPECT_EQ(I->save(), J->save());
}

// channels and degrees of freedom advance independently: the three-channel run equals, bit
// for bit, each oscillator integrated on its own, and each is close to its exact solution
TEST_P(State, ChannelsAdvanceIndependently) {
  const double dt = 0.005;
  const int n = 1000;
  auto I = make_integrator(GetParam());
  auto s = three_channels();
  const auto s0 = s;
  s.init(*I, dt);
  for (int k = 0; k < n; ++k) s.step(*I, dt);
  for (std::size_t c = 0; c < s.q.size(); ++c) {
    for (std::size_t i = 0; i < s.q[c].size(); ++i) {
      auto J = make_integrator(GetParam());
      test::OscillatorSystem one;
      one.add(s0.w[c], s0.c[c], {s0.q[c][i]}, {s0.v[c][i]});
      one.init(*J, dt);
      for (int k = 0; k < n; ++k) one.step(*J, dt);
      EXPECT_EQ(one.q[0][0], s.q[c][i]);
      EXPECT_EQ(one.v[0][0], s.v[c][i]);
      // global error ≲ C·(ωΔt)^p·ωT with C ≈ 0.1 measured; 1.0 leaves margin for ω = 2.5
      const auto e = test::exact_oscillator(s0.w[c], s0.c[c], s0.q[c][i], s0.v[c][i], n * dt);
      const double tol = std::pow(s0.w[c] * dt, integrator_order(GetParam())) * s0.w[c] * n * dt;
      EXPECT_NEAR(s.q[c][i], e.q, tol) << "channel " << c << " dof " << i;
    }
  }
}

// between steps the caller may wrap q (periodic box) and kick v (noise, drift removal):
// a body in constant gravity, wrapped by L and kicked by Δv after step k, ends where the
// exact motion puts it. Constant acceleration is integrated exactly by Gear6 and both
// Verlets (quadratic in t); semi-implicit Euler follows its own closed form
// q_N = q0 + v0·NΔt + g·Δt²·N(N+1)/2 + Δv·(N − k)Δt − L.
TEST_P(State, CallerEditsBetweenStepsArePickedUp) {
  const double dt = 1e-3, g = -9.81, L = 1.0, dv = 0.7, q0 = 0.3, v0 = 1.5;
  const long N = 1000, kick = 400;
  std::vector<double> q{q0}, v{v0}, a{g};
  std::vector<Channel> ch{{q, v, a}};
  auto I = make_integrator(GetParam());
  I->init(ch, dt);
  for (long k = 0; k < N; ++k) {
    if (k == kick) {
      q[0] -= L;
      v[0] += dv;
    }
    I->predict(ch, dt, ThreadTeam{});
    a[0] = g;
    I->correct(ch, dt, ThreadTeam{});
  }
  const double T = N * dt;
  double qe = q0 + v0 * T + g * T * T / 2.0 + dv * (T - kick * dt) - L;
  if (GetParam() == IntegratorKind::SemiImplicitEuler)
    qe = q0 + v0 * T + g * dt * dt * N * (N + 1) / 2.0 + dv * (N - kick) * dt - L;
  // 1000 steps of O(1e-16·|q|) round-off: 1e-10 is a wide margin, and any mishandled edit
  // would be off by ≳ Δv·Δt = 7e-4
  EXPECT_NEAR(q[0], qe, 1e-10);
  EXPECT_NEAR(v[0], v0 + g * T + dv, 1e-10);
}

// Δt may change between steps: half the run at Δt, half at Δt/2, the error stays at the
// level of a constant-Δt run (a history not rescaled would be off by O(1) at once)
TEST_P(State, TimeStepChangeIsConsistent) {
  const double w = 1.0, c = 0.3, dt = 0.01, T = 10.0;
  auto I = make_integrator(GetParam());
  test::OscillatorSystem s;
  s.add(w, c, {1.0}, {0.5});
  s.init(*I, dt);
  for (int k = 0; k < 500; ++k) s.step(*I, dt);
  for (int k = 0; k < 1000; ++k) s.step(*I, dt / 2.0);
  const auto e = test::exact_oscillator(w, c, 1.0, 0.5, T);
  const double err = std::hypot(s.q[0][0] - e.q, s.v[0][0] - e.v);
  auto J = make_integrator(GetParam());
  const double err_const = test::oscillator_error(*J, w, c, 1.0, 0.5, dt, T);
  std::printf("[ %s ] dt switch: error %.3e, constant dt %.3e\n",
              std::string(to_string(GetParam())).c_str(), err, err_const);
  EXPECT_LT(err, 1.5 * err_const);
}

// velocity Verlet's history is its header (a_n is the channels' acceleration); the history of
// earlier versions, the header followed by a copy of a_n, still loads and continues the same
TEST(VelocityVerletHistory, OldLayoutWithAccelerationsLoads) {
  const double dt = 0.01;
  auto I = make_integrator(IntegratorKind::VelocityVerlet);
  auto s = three_channels();
  s.init(*I, dt);
  for (int k = 0; k < 50; ++k) s.step(*I, dt);
  const std::vector<double> hist = I->save();
  std::vector<double> old = hist;
  for (const auto& a : s.a) old.insert(old.end(), a.begin(), a.end());
  ASSERT_EQ(old.size(), hist.size() + 6);
  auto copy = s;
  auto J = make_integrator(IntegratorKind::VelocityVerlet);
  J->load(old);
  for (int k = 0; k < 100; ++k) {
    s.step(*I, dt);
    copy.step(*J, dt);
  }
  EXPECT_EQ(s.q, copy.q);
  EXPECT_EQ(s.v, copy.v);
  old.pop_back();
  EXPECT_THROW(make_integrator(IntegratorKind::VelocityVerlet)->load(old), InputError);
}

// a history never silently applies to another layout or another scheme
TEST_P(State, LayoutAndHistoryAreChecked) {
  auto I = make_integrator(GetParam());
  auto s = three_channels();
  s.init(*I, 0.01);
  std::vector<double> q{1.0}, v{0.0}, a{0.0};
  std::vector<Channel> other{{q, v, a}};
  EXPECT_THROW(I->predict(other, 0.01, ThreadTeam{}), std::invalid_argument);
  auto hist = I->save();
  for (auto k : {IntegratorKind::Gear6, IntegratorKind::VelocityVerlet,
                 IntegratorKind::PositionVerlet, IntegratorKind::SemiImplicitEuler}) {
    if (k == GetParam()) continue;
    EXPECT_THROW(make_integrator(k)->load(hist), InputError) << to_string(k);
  }
  hist.push_back(0.0);
  EXPECT_THROW(make_integrator(GetParam())->load(hist), InputError);
  EXPECT_THROW(make_integrator(GetParam())->load({}), InputError);
}

// names round-trip, kinds match
TEST_P(State, NamesRoundTrip) {
  IntegratorKind k{};
  ASSERT_TRUE(parse_integrator(to_string(GetParam()), k));
  EXPECT_EQ(k, GetParam());
  EXPECT_EQ(make_integrator(GetParam())->kind(), GetParam());
}

// correct() split into check_correct() and correct_range() over uneven, out-of-order ranges
// that cover every particle once (what the force pass does, a range per thread) gives the same
// bits; channels of different lengths are clipped; a wrong Δt throws from check_correct()
TEST_P(State, CorrectByRangesIsCorrect) {
  const double dt = 0.01;
  auto make = [] {
    test::OscillatorSystem s;
    s.add(1.0, 0.3, {1.0, -0.4, 0.3, 0.9, -0.2}, {0.5, 0.2, -0.1, 0.0, 0.4});
    s.add(2.5, 0.0, {0.2, 0.7, -0.6}, {-1.0, 0.0, 0.3});
    s.add(0.7, 0.1, {3.0, -1.5, 0.1, 0.2, 0.5}, {0.0, 0.25, 0.1, -0.3, 0.0});
    return s;
  };
  auto I = make_integrator(GetParam()), J = make_integrator(GetParam());
  auto s = make(), r = make();
  s.init(*I, dt);
  r.init(*J, dt);
  for (int k = 0; k < 150; ++k) {
    s.step(*I, dt);
    auto sp = r.spans();
    J->predict(sp, dt, ThreadTeam{});
    r.forces();
    J->ranges().check_correct(sp, dt);
    J->ranges().correct_range(sp, 4, 99);  // past every channel's end
    J->ranges().correct_range(sp, 0, 1);
    J->ranges().correct_range(sp, 1, 4);
  }
  for (std::size_t c = 0; c < s.q.size(); ++c)
    for (std::size_t i = 0; i < s.q[c].size(); ++i) {
      EXPECT_EQ(r.q[c][i], s.q[c][i]) << c << " " << i;
      EXPECT_EQ(r.v[c][i], s.v[c][i]) << c << " " << i;
    }
  auto sp = r.spans();
  J->predict(sp, dt, ThreadTeam{});
  EXPECT_THROW(J->ranges().check_correct(sp, 2.0 * dt), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, State,
                         ::testing::Values(IntegratorKind::Gear6, IntegratorKind::VelocityVerlet,
                                           IntegratorKind::PositionVerlet,
                                           IntegratorKind::SemiImplicitEuler),
                         [](const auto& info) { return std::string(to_string(info.param)); });

TEST(IntegratorNames, UnknownNameIsRejected) {
  IntegratorKind k = IntegratorKind::Gear6;
  EXPECT_FALSE(parse_integrator("rk4", k));
  EXPECT_FALSE(parse_integrator("Gear6", k));  // names are lower case as in scene files
  EXPECT_EQ(k, IntegratorKind::Gear6);
}

}  // namespace
}  // namespace gs
