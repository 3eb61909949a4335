// observed global convergence orders of every integrator against exact oscillator solutions
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <vector>

#include "integrate/schemes.hpp"
#include "integrate/vv_kernel.hpp"
#include "oscillator.hpp"

namespace gs {
namespace {

using test::fitted_order;
using test::oscillator_error;

// generic initial conditions: q0 = 1 m, v0 = 0.5 m/s, so that no odd derivative vanishes at
// t = 0 (starting at a turning point hides Gear's start-up error: q''' = −ω²v0 = 0 there)
constexpr double kW = 1.0;   // 1/s
constexpr double kQ0 = 1.0;  // m
constexpr double kV0 = 0.5;  // m/s
constexpr double kT = 10.0;  // s, about 1.6 periods
// Δt·ω from 0.05 to 0.00625: asymptotic for all four (the measured local slopes change by
// < 0.1 over this range) and the smallest error (≈1e-7 for Gear6) stays far above round-off
const std::vector<double> kDts = {0.05, 0.025, 0.0125, 0.00625};

class Orders : public ::testing::TestWithParam<IntegratorKind> {
 protected:
  // the fitted order on the dt ladder for damping c
  double order(double c, std::vector<double>* errs_out = nullptr) {
    std::vector<double> errs;
    for (double dt : kDts) {
      auto I = make_integrator(GetParam());
      errs.push_back(oscillator_error(*I, kW, c, kQ0, kV0, dt, kT));
    }
    if (errs_out) *errs_out = errs;
    return fitted_order(kDts, errs);
  }
};

// undamped q'' = −ω²q: the slope matches integrator_order() within ±0.3
TEST_P(Orders, HarmonicOscillator) {
  std::vector<double> errs;
  const double p = order(0.0, &errs);
  std::printf("[ %s ] undamped: errors %.3e %.3e %.3e %.3e, order %.3f\n",
              std::string(to_string(GetParam())).c_str(), errs[0], errs[1], errs[2], errs[3], p);
  EXPECT_NEAR(p, integrator_order(GetParam()), 0.3);
}

// damped q'' = −ω²q − c q': the force depends on velocity, so the velocity each scheme shows
// the force evaluation matters; the order must not drop
TEST_P(Orders, DampedOscillator) {
  std::vector<double> errs;
  const double p = order(0.3, &errs);
  std::printf("[ %s ] damped c=0.3: errors %.3e %.3e %.3e %.3e, order %.3f\n",
              std::string(to_string(GetParam())).c_str(), errs[0], errs[1], errs[2], errs[3], p);
  EXPECT_NEAR(p, integrator_order(GetParam()), 0.3);
}

// every scheme converges to the exact solution, not just at the right rate: at Δt = 0.00625
// the error is bounded by the leading term C·Δt^p with a generous C = 1 (the measured
// constants are 0.04…0.1)
TEST_P(Orders, ConvergesToExactSolution) {
  for (double c : {0.0, 0.3}) {
    auto I = make_integrator(GetParam());
    const double dt = kDts.back();
    const double err = oscillator_error(*I, kW, c, kQ0, kV0, dt, kT);
    EXPECT_LT(err, std::pow(dt, integrator_order(GetParam()))) << "c = " << c;
  }
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, Orders,
                         ::testing::Values(IntegratorKind::Gear6, IntegratorKind::VelocityVerlet,
                                           IntegratorKind::PositionVerlet,
                                           IntegratorKind::SemiImplicitEuler),
                         [](const auto& info) { return std::string(to_string(info.param)); });

// Gear6 with an exact start (r3…r5 from the known derivatives) shows the corrector's own
// order, 5: this pins the Pascal predictor and the coefficients (3/16, 251/360, 1, 11/18,
// 1/6, 1/60); a wrong coefficient drops it to ≤ 3. With the customary start r3 = r4 = r5 = 0
// the O(Δt³) error in r3 = Δt³q'''/6 is an O(Δt²) error in v = r1/Δt after the first
// correction, which persists: hence integrator_order(Gear6) = 2 (tested above).
TEST(Gear6, ExactStartShowsFifthOrder) {
  for (double c : {0.0, 0.3}) {
    std::vector<double> errs;
    const std::vector<double> dts = {0.1, 0.05, 0.025, 0.0125};
    for (double dt : dts) {
      Gear6 g;
      test::OscillatorSystem s;
      s.add(kW, c, {kQ0}, {kV0});
      s.init(g, dt);
      // d^k q/dt^k = −ω² d^{k−2}q − c d^{k−1}q, from q0, v0, a0
      double d[6] = {kQ0, kV0, s.a[0][0], 0, 0, 0};
      for (int k = 3; k < 6; ++k) {
        d[k] = -kW * kW * d[k - 2] - c * d[k - 1];
        g.set_derivative(0, k, {&d[k], 1});
      }
      const long n = std::lround(kT / dt);
      for (long k = 0; k < n; ++k) s.step(g, dt);
      const auto e = test::exact_oscillator(kW, c, kQ0, kV0, kT);
      errs.push_back(std::hypot(s.q[0][0] - e.q, (s.v[0][0] - e.v) / kW));
    }
    const double p = fitted_order(dts, errs);
    std::printf("[ gear6 exact start ] c=%.1f: errors %.3e %.3e %.3e %.3e, order %.3f\n", c,
                errs[0], errs[1], errs[2], errs[3], p);
    EXPECT_NEAR(p, 5.0, 0.3);
  }
}

// velocity Verlet showing the forces the half-step velocity v_{n+½} (LAMMPS style): the
// dashpot lags by Δt/2, an O(Δt) change of the equation of motion, so it is first order
// with damping (and still second order without). This is why Extrapolated is the default.
TEST(VelocityVerlet, HalfStepForceVelocityIsFirstOrderWithDamping) {
  std::vector<double> undamped, damped;
  for (double dt : kDts) {
    VelocityVerlet a(VerletForceVelocity::HalfStep), b(VerletForceVelocity::HalfStep);
    undamped.push_back(oscillator_error(a, kW, 0.0, kQ0, kV0, dt, kT));
    damped.push_back(oscillator_error(b, kW, 0.3, kQ0, kV0, dt, kT));
  }
  const double p0 = fitted_order(kDts, undamped);
  const double p1 = fitted_order(kDts, damped);
  std::printf("[ velocity_verlet half-step ] order undamped %.3f, damped %.3f\n", p0, p1);
  EXPECT_NEAR(p0, 2.0, 0.3);
  EXPECT_NEAR(p1, 1.0, 0.3);
}

// position Verlet and velocity Verlet (extrapolated force velocity) are the same map in exact
// arithmetic; they agree to round-off over many steps with damping
TEST(PositionVerlet, MatchesVelocityVerletToRoundOff) {
  for (double c : {0.0, 0.3}) {
    PositionVerlet pv;
    VelocityVerlet vv;
    test::OscillatorSystem a, b;
    a.add(kW, c, {kQ0}, {kV0});
    b.add(kW, c, {kQ0}, {kV0});
    a.init(pv, 0.01);
    b.init(vv, 0.01);
    for (int k = 0; k < 5000; ++k) {
      a.step(pv, 0.01);
      b.step(vv, 0.01);
    }
    // states are O(1); 5000 steps of different round-off accumulate to ≲ 1e-12
    EXPECT_NEAR(a.q[0][0], b.q[0][0], 1e-10) << "c = " << c;
    EXPECT_NEAR(a.v[0][0], b.v[0][0], 1e-10) << "c = " << c;
  }
}

// velocity Verlet's two corrections: the kick v̂ + c_new·a_{n+1} − c_old·a_n
// (VerletCorrection::Kick) follows the one from the half-step velocity to round-off, with
// either force velocity and with damping; a caller that applies the kick itself
// (RangeStepping::kick_form, vv_kick_dof: the Fused executor) gets correct()'s bits
TEST(VelocityVerlet, KickCorrectionFollowsTheHalfStepOne) {
  for (auto fv : {VerletForceVelocity::Extrapolated, VerletForceVelocity::HalfStep}) {
    VelocityVerlet own(fv), kick(fv, VerletCorrection::Kick), caller(fv, VerletCorrection::Kick);
    EXPECT_FALSE(own.kick_form().has_value());
    const std::optional<KickForm> form = kick.kick_form();
    ASSERT_TRUE(form.has_value());
    EXPECT_EQ(form->new_frac, 0.5);
    EXPECT_EQ(form->old_frac, fv == VerletForceVelocity::HalfStep ? 0.0 : 0.5);
    const double dt = 0.01;
    test::OscillatorSystem a, b, c;
    for (test::OscillatorSystem* s : {&a, &b, &c}) s->add(kW, 0.3, {kQ0, -0.2}, {kV0, 0.1});
    a.init(own, dt);
    b.init(kick, dt);
    c.init(caller, dt);
    for (int k = 0; k < 5000; ++k) {
      a.step(own, dt);
      b.step(kick, dt);
      auto ch = c.spans();
      caller.predict(ch, dt, ThreadTeam{});
      const std::vector<double> a_old = c.a[0];
      c.forces();
      for (std::size_t i = 0; i < c.q[0].size(); ++i)
        c.v[0][i] =
            vv_kick_dof(c.v[0][i], c.a[0][i], a_old[i], form->new_frac * dt, form->old_frac * dt);
    }
    // O(1) states; 5000 steps of different round-off stay ≲ 1e-13
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_NEAR(a.q[0][i], b.q[0][i], 1e-11);
      EXPECT_NEAR(a.v[0][i], b.v[0][i], 1e-11);
      EXPECT_EQ(b.q[0][i], c.q[0][i]);
      EXPECT_EQ(b.v[0][i], c.v[0][i]);
    }
  }
}

}  // namespace
}  // namespace gs
