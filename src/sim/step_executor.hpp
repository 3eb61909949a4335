// how a step's narrow phase → laws → correct stages run: one after the other, each a pass of
// its own (StagedExecutor, the reference), or fused into one pass over the pairs and the
// particles, with the tricks that make it fast (FusedExecutor). Both give the same bits
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "broadphase/broadphase.hpp"
#include "contact/contact_set.hpp"
#include "core/stage_clock.hpp"
#include "core/team.hpp"
#include "force/forces.hpp"
#include "integrate/integrator.hpp"
#include "world/world.hpp"

namespace gs {

/// what the force stages read and write: the Simulation's parts, and the drive of the moment
struct StepParts {
  World& w;
  BroadPhase& broad;
  ContactModel& model;
  ContactSet& contacts;
  ForceBuffer& forces;
  ForceStats& stats;
  Integrator& integ;
  ThreadTeam& team;  ///< how the stages' passes split the work among the threads
  const std::vector<std::uint64_t>& noise_keys;  ///< the random force's stream per particle
  Vec2 gravity;                                  ///< m/s²
  double dt;                                     ///< s
  const DriveSpec& drive;                        ///< the drive (random force: on, strength D)
};

enum class ExecutorKind : std::uint8_t {
  /// every stage one pass over all pairs or particles, in the order of the step
  Staged,
  /// one pass: each particle's acceleration and correction computed by the thread that summed
  /// its force, right after the sum; velocity Verlet's kick inside the acceleration pass
  /// (disks); run back to back, the next step's prediction there too (with, for disks in a
  /// plane, the broad phase's displacement test; polygons placed for the next step)
  Fused,
};

class StepExecutor {
 public:
  virtual ~StepExecutor() = default;
  virtual ExecutorKind kind() const = 0;
  /// narrow phase → laws → correct at the current (predicted) state over the candidates;
  /// `correct` empty: accelerations only (the start); `index`: the force evaluation's number
  /// (the random force's stream); `ahead`: also the next step's prediction, where
  /// predicts_ahead(); `clock`: the stages' laps. The caller has run check_correct()
  virtual void run(const StepParts& p, const std::vector<PairKey>& candidates,
                   std::span<const Channel> correct, std::int64_t index, bool ahead,
                   StageClock* clock) = 0;
  /// can run() make the next step's prediction?
  virtual bool predicts_ahead(const StepParts& p) const = 0;
  /// is the integrator's correction a kick applied inside the acceleration pass?
  virtual bool kicks_in_pass(const StepParts& p) const = 0;
};

std::unique_ptr<StepExecutor> make_executor(ExecutorKind k);

}  // namespace gs
