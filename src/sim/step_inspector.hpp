// a test's hold on a Simulation's step: which executor runs it, its list of stages, the
// profile's clock, and the stage-by-stage comparison of two simulations. Not part of what a
// run needs: the fast path's switches stay off Simulation's own surface
#pragma once
#include <cstdint>
#include <string>

#include "sim/simulation.hpp"

namespace gs {

class StepInspector {
 public:
  /// how the step's stages run (Fused unless set; the same bits either way). Between steps
  static void set_executor(Simulation& sim, ExecutorKind k) { sim.exec_ = make_executor(k); }
  static ExecutorKind executor(const Simulation& sim) { return sim.exec_->kind(); }
  /// does the kick stage stand for accelerate → correct (Fused, disks, velocity Verlet)?
  static bool kicks_in_force_pass(const Simulation& sim) {
    return sim.exec_->kicks_in_pass(sim.parts());
  }
  /// how many steps took their prediction from the step before (run() back to back)
  static std::uint64_t steps_predicted_ahead(const Simulation& sim) {
    return sim.exec_->steps_predicted_ahead();
  }
  /// velocity Verlet's correction (disks: the kick, polygons: from the half-step velocity, by
  /// default); the two differ by round-off. Between steps; other schemes have one form only
  static void set_verlet_correction(Simulation& sim, VerletCorrection c);
  /// time the stages on `clock` (steady_seconds by default)
  static void time_profile_on(Simulation& sim, ClockSeconds clock) { sim.profile_.now = clock; }
  /// steps shorter than `seconds` are sampled (StepProfile; by default 50 µs); 0: every step
  static void sample_steps_under(Simulation& sim, double seconds) {
    sim.profile_.timed_step_min = seconds;
    sim.profile_.stride = 1;
  }
  /// the step's stages, in order: a test may put a double in a stage's place
  static StageList& stages(Simulation& sim) { return sim.stages_; }
  /// `steps` steps of a and b side by side (run back to back, as run(steps) takes them), their
  /// states compared after each stage: the first stage (in step order) where they differ, as
  /// "step k, stage s, particle i, field f: a vs b"; empty where every stage agrees
  static std::string first_difference(Simulation& a, Simulation& b, std::int64_t steps);
};

}  // namespace gs
