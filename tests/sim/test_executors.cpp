// the two executors of a step's narrow phase → laws → correct (sim/step_executor.hpp): the
// Staged one, each stage a pass of its own, and the Fused one (the kick in the force pass,
// prediction ahead, polygons placed ahead, the thread scheduling) give the same bits for every
// integrator, on a decagon pile, a forced disk gas with drift removal, health checks and sorts,
// and the 1D ring with its symmetrised noise, on one and two threads
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "scene/parse.hpp"
#include "test_world.hpp"

namespace gs {
namespace {

using testing::Threads;

Simulation make_sim(const SceneSpec& s, ExecutorKind k) {
  World w = make_world(s);
  place_particles(w, s);
  Simulation sim(std::move(w), SimSettings::from(s));
  sim.set_executor(k);
  return sim;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void expect_same_state(const Simulation& a, const Simulation& b, const std::string& what) {
  const State& p = a.world().s;
  const State& q = b.world().s;
  EXPECT_EQ(p.step, q.step) << what;
  for (auto m : {&State::x, &State::y, &State::th, &State::vx, &State::vy, &State::omega,
                 &State::ax, &State::ay, &State::alpha})
    EXPECT_TRUE(same_bits(p.*m, q.*m)) << what;
  EXPECT_EQ(a.world().id, b.world().id) << what;
  EXPECT_EQ(a.contacts().keys, b.contacts().keys) << what;
}

// a pile of decagons with over kParallelMin candidate pairs (the pair pass on the team),
// thrown about so that they meet within the test's steps
SceneSpec pile() {
  SceneSpec s = build::decagon_pile(400, 0.2, 0.4, 1);
  s.prep.velocity_amplitude = 2.0;
  return s;
}

// 10⁴ randomly forced disks (the particle loops on the team), with drift removal, health checks
// and sorts inside the runs
SceneSpec gas() {
  SceneSpec s = build::disk_gas(10000, 0.45, 0.6, 0.6, 3);
  s.drive.kind = DriveKind::RandomForce;
  s.drive.D = 1e-7;
  s.prep.velocity_amplitude = 5.0;  // the disks meet within the test's steps
  s.drive.com_removal_every = 7;
  s.health.check_every = 11;
  s.integrator.sort_every = 13;
  return s;
}

// the 1D ring, 200 rods: its noise's mean momentum removed in a pass of its own
SceneSpec ring() {
  return parse_scene_file(std::string(GS_SOURCE_DIR) + "/scenes/rfm1d_reference.toml",
                          {"species[0].count=200"});
}

TEST(Executors, StagedAndFusedGiveTheSameBits) {
  const std::pair<const char*, SceneSpec> scenes[] = {
      {"pile", pile()}, {"gas", gas()}, {"ring", ring()}};
  for (IntegratorKind kind :
       {IntegratorKind::VelocityVerlet, IntegratorKind::Gear6, IntegratorKind::SemiImplicitEuler}) {
    for (const auto& [name, base] : scenes) {
      SceneSpec s = base;
      s.integrator.kind = kind;
      for (int threads : {1, 2}) {
        const std::string what =
            std::string(name) + " " + std::string(to_string(kind)) + " " + std::to_string(threads);
        const Threads team(threads);
        Simulation staged = make_sim(s, ExecutorKind::Staged);
        Simulation fused = make_sim(s, ExecutorKind::Fused);
        std::size_t contacts = 0;  // at the ends of the runs
        const bool is_ring = name == std::string("ring");
        const int steps = is_ring ? 100 : 10;  // the ring's steps are cheap
        for (int part = 0; part < 4; ++part) {
          staged.run(steps);
          fused.run(steps);
          contacts += fused.contacts().keys.size();
        }
        expect_same_state(staged, fused, what);
        if (!is_ring) {  // (the ring's rods touch rarely: its noise path is what it tests)
          EXPECT_GT(contacts, 0u) << what;
        }
        EXPECT_EQ(staged.steps_predicted_ahead(), 0u) << what;
        // the fused executor really took its own ways: velocity Verlet's kick in the pass
        // (disks), predictions ahead from the kick or from Gear 6's ranges (not on the noisy
        // ring, whose noise needs every particle before any correction)
        const bool kicks = kind == IntegratorKind::VelocityVerlet && name != std::string("pile");
        const bool ranges = kind == IntegratorKind::Gear6 && name != std::string("ring");
        EXPECT_EQ(fused.kicks_in_force_pass(), kicks) << what;
        EXPECT_FALSE(staged.kicks_in_force_pass()) << what;
        EXPECT_EQ(fused.steps_predicted_ahead() > 0, kicks || ranges) << what;
      }
    }
  }
}

}  // namespace
}  // namespace gs
