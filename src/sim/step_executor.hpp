// how a step's list of stages (sim/stages.hpp) runs: each stage a pass of its own, in order
// (StagedExecutor, the reference), or the stages after the pair loop by ranges inside its
// particle phase, with the tricks that make it fast (FusedExecutor). Both give the same bits;
// the executor alone laps the step's clock, once after each stage
#pragma once
#include <cstdint>
#include <memory>

#include "core/stage_clock.hpp"
#include "sim/stages.hpp"

namespace gs {

enum class ExecutorKind : std::uint8_t {
  /// every stage one pass over all pairs or particles, in the order of the step
  Staged,
  /// the stages after the pair loop by ranges, each thread's particles right after their
  /// sums; velocity Verlet's accelerate → correct as the kick stage (disks); run back to back,
  /// the next step's prediction there too (with, for disks in a plane, the broad phase's
  /// displacement test; polygons placed for the next step)
  Fused,
};

class StepExecutor {
 public:
  virtual ~StepExecutor() = default;
  virtual ExecutorKind kind() const = 0;
  /// the stages of `list` that run in c, in order; `clock`, if given, lapped after each with
  /// the stage's id (in a particle phase: the first thread's laps)
  virtual void run(const StageList& list, StepContext& c, StageClock* clock) = 0;
  /// can run() make the next step's prediction?
  virtual bool predicts_ahead(const StepParts& p) const = 0;
  /// does the kick stage stand for accelerate → correct?
  virtual bool kicks_in_pass(const StepParts& p) const = 0;
  /// how many steps took their prediction from the step before
  std::uint64_t steps_predicted_ahead() const { return predicted_steps_; }

 protected:
  std::uint64_t predicted_steps_ = 0;
};

std::unique_ptr<StepExecutor> make_executor(ExecutorKind k);

}  // namespace gs
