// the step's profile (Simulation::profile): every stage of the step is timed, and the stages'
// times add up to the wall time of the steps — on a decagon pile (Gear 6, the integrator's
// correction by ranges) and a forced disk gas (velocity Verlet's kick in the force pass)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

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

// runs `steps` steps in runs of 10, every step timed on the counting clock: a step of L laps
// reads the clock 1 + L times and is charged L ticks, so the stages' sum is the steps' time
// (their reads) less one tick per step; and every stage that runs in each step is charged
void check_profile(Simulation& sim, int steps, const char* what) {
  g_tick = std::ldexp(1.0, -10);
  sim.time_profile_on(counting_clock);
  sim.sample_steps_under(0.0);
  sim.clear_profile();
  const std::uint64_t reads0 = g_reads;
  for (int k = 0; k < steps; k += 10) sim.run(10);
  const double reads = static_cast<double>(g_reads - reads0);
  const StepProfile& p = sim.profile();
  EXPECT_EQ(p.steps, static_cast<std::uint64_t>(steps)) << what;
  EXPECT_EQ(p.timed, p.steps) << what;
  for (std::size_t k = 0; k < kStageCount; ++k) {
    const Stage s = static_cast<Stage>(k);
    EXPECT_GE(p[s], 0.0) << what << " " << stage_name(s);
    // the fused kick's pass is both laws and correction, and counted as correct
    if (s != Stage::Drive && s != Stage::Health && s != Stage::Laws) {
      EXPECT_GE(p[s], steps * g_tick) << what << " " << stage_name(s);
    }
  }
  EXPECT_GT(p[Stage::Laws] + p[Stage::Correct], 0.0) << what;
  EXPECT_EQ(p.total(), (reads - static_cast<double>(steps)) * g_tick) << what;
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

// on the real clock the stages' laps lie inside the span of the calls around them, however
// busy the machine (one monotonic clock)
TEST(StepProfile, OnTheSteadyClockTheLapsLieInsideTheRun) {
  SceneSpec pile = build::decagon_pile(40, 0.2, 0.4, 1);
  Simulation a = make_sim(pile);
  a.sample_steps_under(0.0);
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
  a.time_profile_on(counting_clock);
  // the charge of one step when every step is timed
  a.sample_steps_under(0.0);
  a.clear_profile();
  a.run(100);
  const double per_step = a.profile().total() / 100.0;
  ASSERT_GT(per_step, 0.0);
  ASSERT_LT(64.0 * per_step, StepProfile::kTimedStepMin);
  a.sample_steps_under(StepProfile::kTimedStepMin);
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
  const std::string names[] = {"drive", "predict", "broad_phase", "narrow_phase",
                               "laws",  "correct", "health"};
  for (std::size_t k = 0; k < kStageCount; ++k)
    EXPECT_EQ(stage_name(static_cast<Stage>(k)), names[k]);
}

}  // namespace
}  // namespace gs
