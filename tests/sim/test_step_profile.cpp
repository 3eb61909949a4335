// the step's profile (Simulation::profile): every stage of the step is timed, and the stages'
// times add up to the wall time of the steps — on a decagon pile (Gear 6, the integrator's
// correction by ranges) and a forced disk gas (velocity Verlet's kick in the force pass)
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "test_world.hpp"

namespace gs {
namespace {

Simulation make_sim(const SceneSpec& s) {
  World w = make_world(s);
  place_particles(w, s);
  return Simulation(std::move(w), SimSettings::from(s));
}

// runs `steps` steps in runs of 10, every step timed, and checks the profile against the wall
// time around them
void check_profile(Simulation& sim, int steps, const char* what) {
  sim.sample_steps_under(0.0);
  sim.clear_profile();
  double wall = 0.0;
  for (int k = 0; k < steps; k += 10) {
    const auto t0 = std::chrono::steady_clock::now();
    sim.run(10);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  const StepProfile& p = sim.profile();
  EXPECT_EQ(p.steps, static_cast<std::uint64_t>(steps)) << what;
  for (std::size_t k = 0; k < kStageCount; ++k) {
    const Stage s = static_cast<Stage>(k);
    EXPECT_GE(p[s], 0.0) << what << " " << stage_name(s);
    // the stages that run in every step took some time (the fused kick's pass is both laws
    // and correction, and counted as correct)
    if (s != Stage::Drive && s != Stage::Health && s != Stage::Laws) {
      EXPECT_GT(p[s], 0.0) << what << " " << stage_name(s);
    }
  }
  EXPECT_GT(p[Stage::Laws] + p[Stage::Correct], 0.0) << what;
  // laps on one clock: the stages' sum is the steps' time, less the calls between them
  EXPECT_LE(p.total(), wall) << what;
  EXPECT_GT(p.total(), 0.9 * wall) << what;
  EXPECT_EQ(p.timed, p.steps) << what;
}

TEST(StepProfile, EveryStageTimedAndTheSumIsTheStepsWallTime) {
  SceneSpec pile = build::decagon_pile(40, 0.2, 0.4, 1);
  pile.integrator.kind = IntegratorKind::Gear6;
  Simulation a = make_sim(pile);
  check_profile(a, 200, "pile");
  SceneSpec gas = build::disk_gas(2000, 0.45, 0.6, 0.6, 3);
  gas.drive.kind = DriveKind::RandomForce;
  gas.drive.D = 1e-7;
  Simulation b = make_sim(gas);
  check_profile(b, 200, "gas");
}

// short steps are sampled (here every step counts as short): one in 64 timed, each counting
// for 64, the weighted sum an estimate of the steps' wall time (bounds wide enough for a
// preempted timed step; a weight left out would give 1/64 of it)
TEST(StepProfile, ShortStepsAreSampledAndStillAddUpToTheWallTime) {
  SceneSpec pile = build::decagon_pile(40, 0.2, 0.4, 1);
  Simulation a = make_sim(pile);
  a.run(100);
  a.sample_steps_under(1.0);
  a.clear_profile();
  const int steps = 4000;
  const auto t0 = std::chrono::steady_clock::now();
  a.run(steps);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const StepProfile& p = a.profile();
  EXPECT_EQ(p.steps, static_cast<std::uint64_t>(steps));
  EXPECT_LT(p.timed, p.steps / 16);
  EXPECT_GT(p.timed, p.steps / 256);
  EXPECT_GT(p.total(), 0.25 * wall);
  EXPECT_LT(p.total(), 8.0 * wall);
}

TEST(StepProfile, NamesEveryStageOnce) {
  const std::string names[] = {"drive", "predict", "broad_phase", "narrow_phase",
                               "laws",  "correct", "health"};
  for (std::size_t k = 0; k < kStageCount; ++k)
    EXPECT_EQ(stage_name(static_cast<Stage>(k)), names[k]);
}

}  // namespace
}  // namespace gs
