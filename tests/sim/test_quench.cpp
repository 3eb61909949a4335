// the quench (drive.quench) in a tapped pile, in process: off, it leaves the trajectory
// bitwise as it was (the quench keys alone change nothing, and a quench that never arms
// changes nothing either: only its velocity resets act); on, relaxations end sooner
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "drive/protocol.hpp"
#include "scene/parse.hpp"
#include "sim/simulation.hpp"
#include "test_world.hpp"
#include "world/prepare.hpp"

namespace gs {
namespace {

using testing::state_hash;

struct Outcome {
  std::uint64_t hash = 0;
  std::int64_t steps = 0;
  std::int64_t early_ends = 0;
  std::int64_t quenches = 0;
  std::vector<double> rest_ke;  ///< kinetic energy at each measurement (before an excitation)
};

// 60 decagons of the small tapping scene, 2 taps of 1.5 s, early rest on; the loop of
// `gransim run` (app/run/run_loop.cpp) without its files
Outcome tap(std::vector<std::string> overrides) {
  overrides.insert(overrides.end(),
                   {"species[0].count=25", "species[1].count=35", "box.width=0.12",
                    "preparation.settle_time=0.6", "drive.period=1.5", "drive.taps=2"});
  const SceneSpec s =
      parse_scene_file(std::string(GS_SOURCE_DIR) + "/scenes/tap_small_negative_g.toml", overrides);
  World w = make_world(s);
  place_particles(w, s);
  ProtocolClock clock(s);
  clock.start(w);
  Simulation sim(std::move(w), SimSettings::from(s));
  Outcome o;
  while (!clock.done(sim.world())) {
    sim.step();
    if (clock.after_step(sim.world()) == ClockEvent::Quench) sim.zero_velocities();
    const World& cw = sim.world();
    if (excitation_starts_next(s.drive, cw.clock_origin, cw.s.t, s.integrator.dt))
      o.rest_ke.push_back(cw.kinetic_energy());
  }
  o.hash = state_hash(sim.world());
  o.steps = sim.world().s.step;
  o.early_ends = clock.early_ends();
  o.quenches = clock.quench_events();
  return o;
}

TEST(Quench, OffOrNeverArmedLeavesTheTrajectoryBitwiseUnchanged) {
  const Outcome base = tap({});
  EXPECT_EQ(base.quenches, 0);
  // the quench's own keys while it is off
  const Outcome keys =
      tap({"drive.quench=false", "drive.quench_speed=1e-9", "drive.quench_hold=0"});
  EXPECT_EQ(keys.hash, base.hash);
  EXPECT_EQ(keys.steps, base.steps);
  // on, but never armed (no grain is ever that slow for that long): its bookkeeping runs
  // every step and must not touch the state
  const Outcome idle = tap({"drive.quench=true", "drive.quench_speed=1e-12"});
  EXPECT_EQ(idle.quenches, 0);
  EXPECT_EQ(idle.hash, base.hash);
  EXPECT_EQ(idle.steps, base.steps);
  EXPECT_EQ(idle.early_ends, base.early_ends);
}

TEST(Quench, OnEndsTheRelaxationsSoonerAndAtRest) {
  const Outcome off = tap({});
  const Outcome on = tap({"drive.quench=true"});
  std::printf(
      "[ measured ] 60 decagons, 2 taps: %lld steps without the quench (%lld early "
      "ends), %lld with it (%lld early ends, %lld resets)\n",
      static_cast<long long>(off.steps), static_cast<long long>(off.early_ends),
      static_cast<long long>(on.steps), static_cast<long long>(on.early_ends),
      static_cast<long long>(on.quenches));
  EXPECT_GT(on.quenches, 0);
  EXPECT_EQ(on.early_ends, 2);
  EXPECT_LT(on.steps, off.steps);
  EXPECT_NE(on.hash, off.hash);
  // every measurement of a tap sees a pile at rest by the early-rest criterion
  ASSERT_EQ(on.rest_ke.size(), 3u);  // the settled pile, then after each tap
  for (std::size_t k = 1; k < on.rest_ke.size(); ++k) EXPECT_LT(on.rest_ke[k], 1e-6) << "tap " << k;
}

}  // namespace
}  // namespace gs
