// velocity Verlet's correction as a kick inside the acceleration pass (the Fused executor with
// VerletCorrection::Kick): on for disks with velocity Verlet only, and the same dynamics as
// the correction from the half-step velocity (Simulation::set_verlet_correction) up to
// round-off, in 2D (with noise and contacts), on the 1D ring (its noise's mean removed
// in a second pass) and across a switch in the middle of a run
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "scene/parse.hpp"
#include "sim/step_inspector.hpp"
#include "test_world.hpp"

namespace gs {
namespace {

Simulation make_sim(const SceneSpec& s) {
  World w = make_world(s);
  place_particles(w, s);
  return Simulation(std::move(w), SimSettings::from(s));
}

// a randomly forced periodic gas dense enough that ≈ 1% of the disks touch at any time
SceneSpec gas(IntegratorKind kind = IntegratorKind::VelocityVerlet) {
  SceneSpec s = build::disk_gas(2000, 0.45, 0.6, 0.6, 3);
  s.drive.kind = DriveKind::RandomForce;
  s.drive.D = 1e-7;
  s.integrator.kind = kind;
  return s;
}

// the 1D ring of the thesis, 200 rods (`noise` false: no drive; start velocities up to 5 m/s,
// so that rods 5 mm apart meet within 2000 steps)
SceneSpec ring(bool noise = true) {
  std::vector<std::string> set{"species[0].count=200"};
  if (!noise) {
    set.push_back("drive.kind=none");
    set.push_back("preparation.velocity_amplitude=5.0");
  }
  return parse_scene_file(std::string(GS_SOURCE_DIR) + "/scenes/rfm1d_reference.toml", set);
}

// largest difference of positions (relative to the box) and velocities (relative to the
// largest speed) between two runs of the same particles
double max_difference(const World& a, const World& b) {
  double vmax = 0.0, dx = 0.0, dv = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    vmax = std::max(vmax, std::hypot(a.s.vx[i], a.s.vy[i]));
    dx = std::max({dx, std::abs(a.s.x[i] - b.s.x[i]), std::abs(a.s.y[i] - b.s.y[i])});
    dv = std::max({dv, std::abs(a.s.vx[i] - b.s.vx[i]), std::abs(a.s.vy[i] - b.s.vy[i])});
  }
  return std::max(dx / a.Lx, dv / vmax);
}

// steps both simulations side by side; returns the contacts the first one saw, summed
std::size_t step_both(Simulation& a, Simulation& b, int steps) {
  std::size_t contacts = 0;
  for (int k = 0; k < steps; ++k) {
    a.step();
    b.step();
    contacts += a.contacts().keys.size();
  }
  return contacts;
}

TEST(KickFusion, OnForDisksWithVelocityVerletOnly) {
  EXPECT_TRUE(StepInspector::kicks_in_force_pass(make_sim(gas())));
  EXPECT_TRUE(StepInspector::kicks_in_force_pass(make_sim(ring())));
  EXPECT_FALSE(StepInspector::kicks_in_force_pass(make_sim(gas(IntegratorKind::Gear6))));
  EXPECT_FALSE(StepInspector::kicks_in_force_pass(make_sim(gas(IntegratorKind::PositionVerlet))));
  SceneSpec pile = build::decagon_pile(40, 0.2, 0.4, 1);
  pile.integrator.kind = IntegratorKind::VelocityVerlet;
  EXPECT_FALSE(StepInspector::kicks_in_force_pass(
      make_sim(pile)));  // polygons: the integrator's own correct()
  Simulation s = make_sim(gas());
  StepInspector::set_verlet_correction(s, VerletCorrection::HalfStepVelocity);
  EXPECT_FALSE(StepInspector::kicks_in_force_pass(s));
}

// the fused kick v̂ + (a_{n+1} − a_n)·Δt/2 is v_{n+½} + a_{n+1}·Δt/2 in exact arithmetic; the
// runs differ by round-off (≈ 1e-16 per step), which the contacts amplify over the run: after
// 600 steps, with ≈ 20 contacts at any time, the measured difference is 7e-12; 1e-9
// leaves room for another platform's rounding and still fails for any real error (a kick with
// the wrong a_n, or a missing half kick, changes velocities by a_n·Δt/2: ~1e-4 of the speed)
TEST(KickFusion, FollowsTheIntegratorsOwnCorrection) {
  Simulation fused = make_sim(gas());
  Simulation own = make_sim(gas());
  StepInspector::set_verlet_correction(own, VerletCorrection::HalfStepVelocity);
  ASSERT_TRUE(StepInspector::kicks_in_force_pass(fused));
  // the contacts were there to amplify differences
  EXPECT_GT(step_both(fused, own, 600), 600u * 10);
  const double d = max_difference(fused.world(), own.world());
  std::printf("[ gas ] fused against own correct(): max relative difference %.3e\n", d);
  EXPECT_LT(d, 1e-9);
  EXPECT_GT(d, 0.0);  // round-off differs: the two paths really were different code
}

// the ring: the noise's mean momentum is removed in a second pass, where the kick is applied
TEST(KickFusion, RingWithSymmetrisedNoiseFollowsTheOwnCorrection) {
  Simulation fused = make_sim(ring());
  Simulation own = make_sim(ring());
  StepInspector::set_verlet_correction(own, VerletCorrection::HalfStepVelocity);
  auto momentum = [](const World& w) {
    double p = 0.0;
    for (std::size_t i = 0; i < w.size(); ++i) p += w.mass[i] * w.s.vx[i];
    return p;
  };
  const double p0 = momentum(fused.world());
  step_both(fused, own, 2000);
  const double d = max_difference(fused.world(), own.world());
  std::printf(
      "[ ring ] fused against own correct(): max relative difference %.3e, momentum "
      "change %.3e\n",
      d, momentum(fused.world()) - p0);
  EXPECT_LT(d, 1e-9);
  // the symmetrised noise and the contacts conserve momentum (T.2.18) in the fused path too:
  // the change stays at the round-off of sums of 200 momenta ≲ 4e-6 kg·m/s (≈ 1e-21 per step),
  // where unsymmetrised kicks would have moved it by ≈ 1e-4 kg·m/s
  EXPECT_LT(std::abs(momentum(fused.world()) - p0), 1e-15);
}

// the ring without noise: the kick in the force pass's callback, x alone
TEST(KickFusion, RingWithoutNoiseFollowsTheOwnCorrection) {
  Simulation fused = make_sim(ring(false));
  Simulation own = make_sim(ring(false));
  StepInspector::set_verlet_correction(own, VerletCorrection::HalfStepVelocity);
  ASSERT_TRUE(StepInspector::kicks_in_force_pass(fused));
  EXPECT_GT(step_both(fused, own, 2000), 0u);
  EXPECT_LT(max_difference(fused.world(), own.world()), 1e-9);
}

// switching between steps: on → off (v_{n+½} history allocated) → on, the same dynamics
TEST(KickFusion, SwitchesBetweenSteps) {
  Simulation a = make_sim(gas());
  Simulation b = make_sim(gas());
  a.run(200);
  b.run(200);
  StepInspector::set_verlet_correction(b, VerletCorrection::HalfStepVelocity);
  a.run(200);
  b.run(200);
  StepInspector::set_verlet_correction(b, VerletCorrection::Kick);
  a.run(200);
  b.run(200);
  EXPECT_TRUE(StepInspector::kicks_in_force_pass(b));
  EXPECT_LT(max_difference(a.world(), b.world()), 1e-9);
}

}  // namespace
}  // namespace gs
