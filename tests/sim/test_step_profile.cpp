// the step's profile (Simulation::profile): each stage is charged with its own laps only, and
// the stages' times add up to the wall time of the steps — on a decagon pile (Gear 6, the
// stages by ranges, polygons placed ahead) and a forced disk gas (the kick stage)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "sim/step_inspector.hpp"
#include "test_world.hpp"

namespace gs {
namespace {

Simulation make_sim(const SceneSpec& s) {
  World w = make_world(s);
  place_particles(w, s);
  return Simulation(std::move(w), SimSettings::from(s));
}

// a clock the test owns: each read moves it on by one tick, so that the profile is a count of
// the clock reads and no result depends on how busy the machine is
std::uint64_t g_reads = 0;
double g_tick = 0.0;  // s, a power of 2 (the sums are exact)
double counting_clock() { return static_cast<double>(++g_reads) * g_tick; }

// runs `steps` steps in runs of 10, every step timed on the counting clock: each lap reads the
// clock once and is charged one tick, so a stage's time counts the laps the executor gave it
// and the stages' sum is the steps' time (their reads) less one tick per step. `kick`: the
// kick stage stands for accelerate → correct (velocity Verlet on disks); else the stages run
// one by one and the polygons are placed ahead
void check_profile(Simulation& sim, int steps, bool kick, const char* what) {
  g_tick = std::ldexp(1.0, -10);
  StepInspector::time_profile_on(sim, counting_clock);
  StepInspector::sample_steps_under(sim, 0.0);
  sim.clear_profile();
  const std::uint64_t reads0 = g_reads, ahead0 = StepInspector::steps_predicted_ahead(sim);
  for (int k = 0; k < steps; k += 10) sim.run(10);
  const double reads = static_cast<double>(g_reads - reads0);
  const StepProfile& p = sim.profile();
  EXPECT_EQ(p.steps, static_cast<std::uint64_t>(steps)) << what;
  EXPECT_EQ(p.timed, p.steps) << what;
  const double every = steps * g_tick;  // one lap a step
  EXPECT_EQ(p[Stage::Drive], every) << what;
  EXPECT_EQ(p[Stage::BroadPhase], every) << what;
  EXPECT_EQ(p[Stage::Pairs], 2 * every) << what;  // its pass up to the particle phase, and after
  EXPECT_GE(p[Stage::Health], every) << what;     // the constraints (and any sort)
  // each step predicted once: by its own predict, or by the step before (not the first of a run)
  const auto ahead = static_cast<double>(StepInspector::steps_predicted_ahead(sim) - ahead0);
  EXPECT_EQ(p[Stage::Predict], (steps - ahead) * g_tick) << what;
  EXPECT_GE(p[Stage::Predict], steps / 10 * g_tick) << what;
  if (kick) {
    EXPECT_EQ(p[Stage::Kick], every) << what;
    for (Stage s : {Stage::Accelerate, Stage::Correct, Stage::PredictNext, Stage::PlaceNext})
      EXPECT_EQ(p[s], 0.0) << what << " " << stage_name(s);
  } else {
    EXPECT_EQ(p[Stage::Accelerate], every) << what;
    EXPECT_EQ(p[Stage::Correct], every) << what;
    EXPECT_EQ(p[Stage::Kick], 0.0) << what;
    EXPECT_EQ(p[Stage::PredictNext], ahead * g_tick) << what;
    EXPECT_EQ(p[Stage::PlaceNext], ahead * g_tick) << what;  // polygons
  }
  EXPECT_EQ(p.total(), (reads - static_cast<double>(steps)) * g_tick) << what;
}

TEST(StepProfile, EveryStageChargedWithItsOwnLaps) {
  SceneSpec pile = build::decagon_pile(40, 0.2, 0.4, 1);
  pile.integrator.kind = IntegratorKind::Gear6;
  Simulation a = make_sim(pile);
  check_profile(a, 200, false, "pile");
  SceneSpec gas = build::disk_gas(2000, 0.45, 0.6, 0.6, 3);
  gas.drive.kind = DriveKind::RandomForce;
  gas.drive.D = 1e-7;
  Simulation b = make_sim(gas);
  check_profile(b, 200, true, "gas");
}

// on the real clock the stages' laps lie inside the span of the calls around them, however
// busy the machine (one monotonic clock)
TEST(StepProfile, OnTheSteadyClockTheLapsLieInsideTheRun) {
  SceneSpec pile = build::decagon_pile(40, 0.2, 0.4, 1);
  Simulation a = make_sim(pile);
  StepInspector::sample_steps_under(a, 0.0);
  a.clear_profile();
  const double t0 = steady_seconds();
  a.run(50);
  const double wall = steady_seconds() - t0;
  for (double s : a.profile().seconds) EXPECT_GE(s, 0.0);
  EXPECT_GT(a.profile().total(), 0.0);
  EXPECT_LE(a.profile().total(), wall * (1.0 + 1e-9));
}

// short steps are sampled (on the counting clock every step is short): one in 64 timed, each
// counting for 64, so that the weighted sum estimates the time every step would have been
// charged; the timed steps are a deterministic hash of the step index, about Binomial(n, 1/64)
// of them (4σ bounds; a weight left out would give 1/64 of the estimate)
TEST(StepProfile, ShortStepsAreSampledAndStillAddUpToTheWallTime) {
  SceneSpec pile = build::decagon_pile(40, 0.2, 0.4, 1);
  Simulation a = make_sim(pile);
  a.run(100);
  g_tick = std::ldexp(1.0, -30);
  StepInspector::time_profile_on(a, counting_clock);
  // the charge of one step when every step is timed
  StepInspector::sample_steps_under(a, 0.0);
  a.clear_profile();
  a.run(100);
  const double per_step = a.profile().total() / 100.0;
  ASSERT_GT(per_step, 0.0);
  ASSERT_LT(64.0 * per_step, StepProfile::kTimedStepMin);
  StepInspector::sample_steps_under(a, StepProfile::kTimedStepMin);
  a.clear_profile();
  const int steps = 20000;
  a.run(steps);
  const StepProfile& p = a.profile();
  EXPECT_EQ(p.steps, static_cast<std::uint64_t>(steps));
  EXPECT_EQ(p.stride, StepProfile::kMaxStride);
  const double mean = steps / 64.0, sd = std::sqrt(mean * 63.0 / 64.0);
  EXPECT_NEAR(static_cast<double>(p.timed), mean, 4.0 * sd);
  EXPECT_NEAR(p.total(), steps * per_step, 4.0 * sd / mean * steps * per_step);
}

TEST(StepProfile, NamesEveryStageOnce) {
  const std::string names[] = {"drive", "predict", "broad_phase",  "pairs",      "accelerate",
                               "kick",  "correct", "predict_next", "place_next", "health"};
  for (std::size_t k = 0; k < kStageCount; ++k)
    EXPECT_EQ(stage_name(static_cast<Stage>(k)), names[k]);
}

}  // namespace
}  // namespace gs
