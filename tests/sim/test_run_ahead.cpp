// Simulation::run(n): where nothing reads or edits the state between two steps (no drift
// removal, health check or sort between them), each step's correction also makes the next
// step's prediction (velocity Verlet's fused kick on disks, Gear 6 by ranges). The run is bit
// for bit n × step(): in 2D with noise and contacts, on the 1D ring with and without noise, on
// a decagon pile, on two threads, and across runs of any length, whose state between them is
// the plain one
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "scene/parse.hpp"
#include "sim/state_file.hpp"
#include "sim/step_inspector.hpp"
#include "test_world.hpp"

namespace gs {
namespace {

using testing::Threads;

Simulation make_sim(const SceneSpec& s) {
  World w = make_world(s);
  place_particles(w, s);
  return Simulation(std::move(w), SimSettings::from(s));
}

// a randomly forced periodic gas with contacts, its drift removal, health check and sort at
// intervals that fall inside the runs (7, 11, 13 steps)
SceneSpec gas(int n = 2000) {
  SceneSpec s = build::disk_gas(n, 0.45, 0.6, 0.6, 3);
  s.drive.kind = DriveKind::RandomForce;
  s.drive.D = 1e-7;
  s.drive.com_removal_every = 7;
  s.health.check_every = 11;
  s.integrator.sort_every = 13;
  return s;
}

// the thesis's 1D ring, 200 rods (`noise` false: no drive, rods up to 5 m/s that meet)
SceneSpec ring(bool noise) {
  std::vector<std::string> set{"species[0].count=200", "health.check_every=11"};
  if (!noise) {
    set.push_back("drive.kind=none");
    set.push_back("preparation.velocity_amplitude=5.0");
  }
  return parse_scene_file(std::string(GS_SOURCE_DIR) + "/scenes/rfm1d_reference.toml", set);
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// the clock, every position, velocity and acceleration, the slots' labels and the contacts
void expect_same_state(const Simulation& a, const Simulation& b) {
  const State& p = a.world().s;
  const State& q = b.world().s;
  EXPECT_EQ(p.step, q.step);
  EXPECT_EQ(p.t, q.t);
  EXPECT_TRUE(same_bits(p.x, q.x));
  EXPECT_TRUE(same_bits(p.y, q.y));
  EXPECT_TRUE(same_bits(p.vx, q.vx));
  EXPECT_TRUE(same_bits(p.vy, q.vy));
  EXPECT_TRUE(same_bits(p.ax, q.ax));
  EXPECT_TRUE(same_bits(p.ay, q.ay));
  EXPECT_EQ(a.world().id, b.world().id);
  EXPECT_EQ(a.contacts().keys, b.contacts().keys);
  // the last step's records, which a run keeps for its last step only (keep_records)
  const std::vector<ContactRecord>& ra = a.contacts().records;
  const std::vector<ContactRecord>& rb = b.contacts().records;
  ASSERT_EQ(ra.size(), a.contacts().keys.size());
  ASSERT_EQ(rb.size(), b.contacts().keys.size());
  for (std::size_t k = 0; k < ra.size(); ++k) {
    EXPECT_EQ(ra[k].key, rb[k].key);
    EXPECT_EQ(std::memcmp(&ra[k].s, &rb[k].s, sizeof(Vec2)), 0) << k;
    EXPECT_EQ(std::memcmp(&ra[k].n, &rb[k].n, sizeof(Vec2)), 0) << k;
    EXPECT_TRUE(same_bits({ra[k].fn, ra[k].ft, ra[k].overlap}, {rb[k].fn, rb[k].ft, rb[k].overlap}))
        << k;
  }
}

void steps(Simulation& s, int n) {
  for (int k = 0; k < n; ++k) s.step();
}

// the steps of a run(n) from step 0 whose prediction the previous kick made: those whose
// predecessor was neither followed by drift removal or a health check nor by a sort
std::uint64_t expected_ahead(int n, int com, int check, int sort) {
  std::uint64_t k = 0;
  for (int s = 1; s < n; ++s)
    k += (com == 0 || s % com != 0) && (check == 0 || s % check != 0) &&
         (sort == 0 || s % sort != 0);
  return k;
}

TEST(RunAhead, GasRunIsBitwiseItsSteps) {
  Simulation a = make_sim(gas());
  Simulation b = make_sim(gas());
  a.run(150);
  steps(b, 150);
  expect_same_state(a, b);
  EXPECT_GT(a.contacts().keys.size(), 0u);  // contacts and their history took part
  // the prediction came from the kick on every step but those after an event
  EXPECT_EQ(StepInspector::steps_predicted_ahead(a), expected_ahead(150, 7, 11, 13));
  EXPECT_EQ(StepInspector::steps_predicted_ahead(b), 0u);
}

// the kick's pass also makes the cell grid's displacement test of the positions it predicts
// (BroadPhase::set_moved): the list is made anew on the same steps as by update()'s own test.
// A test that said "still" too often would leave pairs unseen, one that said "moved" too often
// would only rebuild more: both show in the count
TEST(RunAhead, GasListMadeAnewOnTheSameSteps) {
  // 2000 disks (serial), and 10⁴ on two threads (each thread tests its own particles) against
  // single steps on one
  for (int n : {2000, 10000}) {
    SceneSpec s = gas(n);
    s.drive.com_removal_every = 0;  // no events: every step but the first predicted ahead
    s.health.check_every = 0;
    s.integrator.sort_every = 0;
    s.drive.D = 1e-6;  // a hotter gas: the list is made anew about every 80 steps
    Simulation a = make_sim(s);
    Simulation b = make_sim(s);
    const int parts = n == 2000 ? 4 : 2;
    for (int k = 0; k < parts; ++k) {
      {
        const Threads team(n == 2000 ? 1 : 2);
        a.run(100);
      }
      {
        const Threads one(1);
        steps(b, 100);
      }
      EXPECT_EQ(a.broadphase().builds(), b.broadphase().builds()) << n << " part " << k;
    }
    expect_same_state(a, b);
    EXPECT_EQ(StepInspector::steps_predicted_ahead(a), static_cast<std::uint64_t>(parts) * 99u);
    EXPECT_GE(b.broadphase().builds(), static_cast<std::uint64_t>(parts));  // 2000: 5 in 400
  }
}

// a run ends in the plain state: runs of any length, and steps between them, chain
TEST(RunAhead, RunsOfAnyLengthChain) {
  Simulation a = make_sim(gas());
  Simulation b = make_sim(gas());
  for (int n : {37, 1, 2, 0, 60}) {
    a.run(n);
    steps(b, n);
    expect_same_state(a, b);
  }
  a.step();
  a.run(25);
  steps(b, 26);
  expect_same_state(a, b);
}

TEST(RunAhead, RingWithAndWithoutNoise) {
  for (bool noise : {true, false}) {
    Simulation a = make_sim(ring(noise));
    Simulation b = make_sim(ring(noise));
    a.run(700);
    steps(b, 700);
    expect_same_state(a, b);
    EXPECT_EQ(StepInspector::steps_predicted_ahead(a), expected_ahead(700, 0, 11, 0))
        << "noise " << noise;
  }
}

// 10⁴ disks: the kick and its prediction run on the team, inside the force pass
TEST(RunAhead, TwoThreadsGiveOneThreadsSteps) {
  Simulation a = make_sim(gas(10000));
  Simulation b = make_sim(gas(10000));
  {
    const Threads two(2);
    a.run(40);
  }
  {
    const Threads one(1);
    steps(b, 40);
  }
  expect_same_state(a, b);
  EXPECT_GT(StepInspector::steps_predicted_ahead(a), 0u);
}

// velocity Verlet corrected from the half-step velocity predicts through predict() only
TEST(RunAhead, NotWithTheIntegratorsOwnKick) {
  Simulation own = make_sim(gas());
  StepInspector::set_verlet_correction(own, VerletCorrection::HalfStepVelocity);
  Simulation own_steps = make_sim(gas());
  StepInspector::set_verlet_correction(own_steps, VerletCorrection::HalfStepVelocity);
  own.run(50);
  steps(own_steps, 50);
  EXPECT_EQ(StepInspector::steps_predicted_ahead(own), 0u);
  expect_same_state(own, own_steps);
}

// Gear 6 on a decagon pile predicts each particle after correcting it, inside the force pass:
// a falling column of 40 grains (serial), and the paper's settled 1184-grain pile on two
// threads (its polygon pairs run on the team) against one; angles, angular velocities and the
// integrator's six derivatives agree too
TEST(RunAhead, GearSixPredictsByRange) {
  const std::string src = GS_SOURCE_DIR;
  auto settled = [&] {
    const SceneSpec s = parse_scene_file(src + "/scenes/paper_pile.toml");
    World w = make_world(s);
    read_state_file(w, src + "/scenes/data/paper_pile_settled.csv");
    return Simulation(std::move(w), SimSettings::from(s));
  };
  auto column = [] { return make_sim(build::decagon_pile(40, 0.2, 0.4, 1)); };
  for (bool paper : {false, true}) {
    Simulation a = paper ? settled() : column();
    Simulation b = paper ? settled() : column();
    {
      const Threads two(paper ? 2 : 1);
      a.run(30);
    }
    {
      const Threads one(1);
      steps(b, 30);
    }
    expect_same_state(a, b);
    EXPECT_TRUE(same_bits(a.world().s.th, b.world().s.th));
    EXPECT_TRUE(same_bits(a.world().s.omega, b.world().s.omega));
    EXPECT_EQ(a.integrator().save(), b.integrator().save());
    EXPECT_EQ(StepInspector::steps_predicted_ahead(a), 29u) << paper;
    if (paper) {
      EXPECT_GT(a.contacts().keys.size(), 2000u);
    }
  }
}

}  // namespace
}  // namespace gs
