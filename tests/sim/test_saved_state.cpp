// preparation.from_state in the library: a state file gives grains only (the contact springs
// start at zero), a checkpoint gives the springs and the integrator's history as they were
#include <gtest/gtest.h>

#include <filesystem>

#include "scene/parse.hpp"
#include "sim/checkpoint.hpp"
#include "sim/saved_state.hpp"
#include "sim/state_file.hpp"
#include "world/prepare.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

const char* kPile = R"(
[[species]]
name = "g"
radius = 0.009
count = 20
[box]
width = 0.1
[preparation]
seed = 3
)";

double spring_sum(const Simulation& sim) {
  double s = 0.0;
  for (const ContactState& c : sim.contacts().state) s += std::abs(c.spring.spring);
  return s;
}

// the saved state's Simulation, as `gransim run` builds it
Simulation start(const std::string& from) {
  SceneSpec scene =
      parse_scene_string(std::string(kPile) + "from_state = \"" + from + "\"\n", "fork.toml");
  const SavedState st = read_saved_state(scene);
  fit_scene_to_state(scene, st);
  World w = make_world(scene);
  place_saved_state(w, st);
  Simulation sim(std::move(w), SimSettings::from(scene));
  take_saved_history(sim, st);
  return sim;
}

TEST(SavedState, StateFileSpringsStartAtZeroCheckpointKeepsThem) {
  const fs::path dir = fs::temp_directory_path() / "gs_saved_state";
  fs::create_directories(dir);
  const SceneSpec scene = parse_scene_string(kPile, "pile.toml");
  World w = make_world(scene);
  place_particles(w, scene);
  Simulation sim(std::move(w), SimSettings::from(scene));
  sim.run(6000);  // a settled pile with stretched springs
  ASSERT_GT(sim.contacts().keys.size(), 10u);
  ASSERT_GT(spring_sum(sim), 0.0);
  write_state_file(sim.world(), (dir / "state.csv").string());
  write_checkpoint(sim, scene, {}, (dir / "ck.gsck").string());

  const Simulation a = start((dir / "state.csv").string());
  EXPECT_EQ(a.world().size(), 20u);
  EXPECT_EQ(a.world().s.step, 0);
  EXPECT_EQ(spring_sum(a), 0.0);

  Simulation b = start((dir / "ck.gsck").string());
  EXPECT_EQ(b.contacts().keys, sim.contacts().keys);
  EXPECT_EQ(spring_sum(b), spring_sum(sim));
  EXPECT_EQ(b.integrator().save(), sim.integrator().save());
  // and it goes on as the original does
  sim.run(200);
  b.run(200);
  EXPECT_EQ(b.world().s.x, sim.world().s.x);
  EXPECT_EQ(b.world().s.omega, sim.world().s.omega);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gs
