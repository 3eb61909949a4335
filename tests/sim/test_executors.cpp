// the two executors of a step's narrow phase → laws → correct (sim/step_executor.hpp): the
// Staged one, each stage a pass of its own, and the Fused one (the kick in the force pass,
// prediction ahead, polygons placed ahead, the thread scheduling) give the same bits for every
// integrator, on a decagon pile, a forced disk gas with drift removal, health checks and sorts,
// and the 1D ring with its symmetrised noise, on one and two threads, compared after every stage
// (StepInspector::first_difference names the first stage, particle and field that differ)
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "scene/parse.hpp"
#include "sim/step_inspector.hpp"
#include "test_world.hpp"

namespace gs {
namespace {

using testing::Threads;

Simulation make_sim(const SceneSpec& s, ExecutorKind k) {
  World w = make_world(s);
  place_particles(w, s);
  Simulation sim(std::move(w), SimSettings::from(s));
  StepInspector::set_executor(sim, k);
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
        const int steps = is_ring ? 100 : 10;   // the ring's steps are cheap
        for (int part = 0; part < 4; ++part) {  // each part as run(steps) takes it
          EXPECT_EQ(StepInspector::first_difference(staged, fused, steps), "") << what;
          contacts += fused.contacts().keys.size();
        }
        expect_same_state(staged, fused, what);
        if (!is_ring) {  // (the ring's rods touch rarely: its noise path is what it tests)
          EXPECT_GT(contacts, 0u) << what;
        }
        EXPECT_EQ(StepInspector::steps_predicted_ahead(staged), 0u) << what;
        // the fused executor really took its own ways: velocity Verlet's kick in the pass
        // (disks), predictions ahead from the kick or from Gear 6's ranges (not on the noisy
        // ring, whose noise needs every particle before any correction)
        const bool kicks = kind == IntegratorKind::VelocityVerlet && name != std::string("pile");
        const bool ranges = kind == IntegratorKind::Gear6 && name != std::string("ring");
        EXPECT_EQ(StepInspector::kicks_in_force_pass(fused), kicks) << what;
        EXPECT_FALSE(StepInspector::kicks_in_force_pass(staged)) << what;
        EXPECT_EQ(StepInspector::steps_predicted_ahead(fused) > 0, kicks || ranges) << what;
      }
    }
  }
}

// a double of a stage: the stage itself, then at step `step` one particle's field moved by one
// unit in the last place (in the whole pass and in the range that holds the particle)
class Nudged final : public StepStage {
 public:
  Nudged(std::unique_ptr<StepStage> inner, std::int64_t step, std::size_t particle,
         std::vector<double> State::*field)
      : inner_(std::move(inner)), step_(step), particle_(particle), field_(field) {}
  Stage id() const override { return inner_->id(); }
  bool runs(const StepContext& c) const override { return inner_->runs(c); }
  bool by_range(const StepContext& c) const override { return inner_->by_range(c); }
  bool hosts_ranges() const override { return inner_->hosts_ranges(); }
  void prepare(StepContext& c) override { inner_->prepare(c); }
  void pass(StepContext& c) override {
    inner_->pass(c);
    nudge(c, 0, c.p().w.size());
  }
  void pass_with(StepContext& c, ParticlePhase& then) override { inner_->pass_with(c, then); }
  void range(StepContext& c, std::size_t b, std::size_t e) override {
    inner_->range(c, b, e);
    nudge(c, b, e);
  }
  void finish(StepContext& c) override { inner_->finish(c); }

 private:
  void nudge(StepContext& c, std::size_t b, std::size_t e) {
    State& s = c.p().w.s;
    if (s.step != step_ || particle_ < b || particle_ >= e) return;
    double& v = (s.*field_)[particle_];
    v = std::nextafter(v, 1e300);
  }
  std::unique_ptr<StepStage> inner_;
  std::int64_t step_;
  std::size_t particle_;
  std::vector<double> State::*field_;
};

// the fused simulation of `s` with stage `stage` nudged, against the staged one: the name of
// the first difference over `steps` steps run back to back
std::string nudged_difference(const SceneSpec& s, Stage stage, std::int64_t step,
                              std::size_t particle, std::vector<double> State::*field, int steps) {
  Simulation staged = make_sim(s, ExecutorKind::Staged);
  Simulation fused = make_sim(s, ExecutorKind::Fused);
  for (auto& st : StepInspector::stages(fused))
    if (st->id() == stage) st = std::make_unique<Nudged>(std::move(st), step, particle, field);
  return StepInspector::first_difference(staged, fused, steps);
}

// the comparison names the stage, step, particle and field of a difference put there: in a
// whole pass before the pair loop, in the by-range stages of its particle phase (Gear 6 on
// disks, polygons), and in the next step's prediction made ahead, which it sets against the
// staged step's own prediction
TEST(Executors, TheFirstDifferenceIsNamedByStageParticleAndField) {
  SceneSpec gear = gas();
  gear.integrator.kind = IntegratorKind::Gear6;
  SceneSpec verlet = gas();
  SceneSpec polys = pile();
  polys.integrator.kind = IntegratorKind::Gear6;
  struct Case {
    const SceneSpec* scene;
    Stage stage;
    std::int64_t step;
    std::size_t particle;
    std::vector<double> State::*field;
    std::string expected;
  };
  const Case cases[] = {
      {&verlet, Stage::Predict, 0, 5, &State::x, "step 0, stage predict, particle 5, field x: "},
      {&gear, Stage::Correct, 3, 1717, &State::vx,
       "step 3, stage correct, particle 1717, field vx: "},
      {&polys, Stage::Accelerate, 2, 9, &State::alpha,
       "step 2, stage accelerate, particle 9, field alpha: "},
      {&polys, Stage::PredictNext, 4, 3, &State::y,
       "step 5, stage predict (predict vs predict_next), particle 3, field y: "},
  };
  for (int threads : {1, 2}) {
    const Threads team(threads);
    for (const Case& k : cases) {
      const std::string d = nudged_difference(*k.scene, k.stage, k.step, k.particle, k.field, 8);
      EXPECT_EQ(d.substr(0, k.expected.size()), k.expected) << d << " (" << threads << " threads)";
    }
  }
}

}  // namespace
}  // namespace gs
