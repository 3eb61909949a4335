// the Simulation's settings are taken from the scene once (SimSettings::from) and are all the
// step reads of it; the World holds what it is (its model kind), not the scene
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "test_world.hpp"

namespace gs {
namespace {

TEST(SimSettings, TakeTheScenesValues) {
  SceneSpec s = build::disk_gas(50, 0.2, 0.9, 0.9, 4);
  s.integrator.kind = IntegratorKind::VelocityVerlet;
  s.integrator.dt = 2e-6;
  s.integrator.sort_every = 0;
  s.drive.kind = DriveKind::RandomForce;
  s.drive.D = 3e-9;
  s.prep.seed = 77;
  s.health.check_every = 7;
  s.health.max_overlap = 0.3;
  s.model.clip_attractive = true;
  const SimSettings t = SimSettings::from(s);
  EXPECT_EQ(t.integrator, IntegratorKind::VelocityVerlet);
  EXPECT_EQ(t.dt, 2e-6);
  EXPECT_EQ(t.sort_every, 0);
  EXPECT_EQ(t.drive.kind, DriveKind::RandomForce);
  EXPECT_EQ(t.drive.D, 3e-9);
  EXPECT_EQ(t.seed, 77u);
  EXPECT_EQ(t.health.check_every, 7);
  EXPECT_EQ(t.health.max_overlap, 0.3);
  EXPECT_TRUE(t.contact.clip_attractive);
}

// a scene made in code has not been through the parser: what the step cannot use is refused
// with the scene's file and key
TEST(SimSettings, RefuseWhatTheStepCannotUse) {
  auto key_of = [](SceneSpec s) {
    s.path = "made.toml";
    try {
      SimSettings::from(s);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  SceneSpec s = build::disk_gas(50, 0.2, 0.9, 0.9, 4);
  EXPECT_EQ(key_of(s), "accepted");
  SceneSpec zero_dt = s;
  zero_dt.integrator.dt = 0.0;
  EXPECT_NE(key_of(zero_dt).find("made.toml"), std::string::npos);
  EXPECT_NE(key_of(zero_dt).find("integrator.dt"), std::string::npos);
  SceneSpec sort = s;
  sort.integrator.sort_every = -2;
  EXPECT_NE(key_of(sort).find("integrator.sort_every"), std::string::npos);
  SceneSpec health = s;
  health.health.max_overlap = 0.0;
  EXPECT_NE(key_of(health).find("health.max_overlap"), std::string::npos);
}

// the step follows the settings it was given, not the scene the World was made from
TEST(SimSettings, TheStepFollowsItsSettings) {
  // one disk, no drive in the scene
  const SceneSpec s = build::two_body(ModelKind::Disk, ShapeKind::Disk, 0.01, 1e-3, 0,
                                      build::disk_material(0.9, 0.9), IntegratorKind::Gear6, 1e-5);
  World w = make_world(s);
  w.add_particle(0, {0.05, 0.05}, 0.0);
  SimSettings settings = SimSettings::from(s);
  settings.dt = 2.5e-6;
  settings.drive.kind = DriveKind::Gravity;
  settings.drive.g = 4.0;
  settings.drive.gx = 1.0;
  settings.drive.gy = 0.0;
  Simulation sim(std::move(w), settings);
  sim.run(4);
  EXPECT_EQ(sim.dt(), 2.5e-6);
  EXPECT_EQ(sim.world().s.t, 4 * 2.5e-6);
  EXPECT_EQ(sim.gravity().x, 4.0);
  EXPECT_EQ(sim.gravity().y, 0.0);
  EXPECT_GT(sim.world().s.vx[0], 0.0);
  EXPECT_TRUE(sim.driven());
}

TEST(World, HoldsItsModelKind) {
  const World disks = make_world(build::disk_gas(10, 0.1, 0.9, 0.9, 1));
  EXPECT_EQ(disks.model, ModelKind::Disk);
  EXPECT_FALSE(disks.polygons());
  const World pile = make_world(build::decagon_pile(10, 0.2, 0.3, 1));
  EXPECT_EQ(pile.model, ModelKind::Polygon);
  EXPECT_TRUE(pile.polygons());
}

}  // namespace
}  // namespace gs
