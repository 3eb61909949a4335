// the stages of a time step as objects: each has a whole pass over all particles or pairs and,
// where each particle's result depends on that particle alone, a form by ranges of particles.
// Simulation::advance is the list of them; an executor (sim/step_executor.hpp) runs the list
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
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

class Simulation;
class StageTrace;

/// what the stages read and write: the Simulation's parts, and the drive of the moment
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
  const Vec2& gravity;                           ///< m/s², set by the drive
  double dt;                                     ///< s
  const DriveSpec& drive;                        ///< the drive (random force: on, strength D)
};

/// one step (or the start's force evaluation) as the stages see it
struct StepContext {
  Simulation& sim;
  std::optional<StepParts> parts{};  ///< made anew where a stage rebuilds them (the sort)
  std::vector<Channel> ch{};         ///< the integrator's channels over the state
  std::int64_t index = 0;            ///< the force evaluation's number (the random force's stream)
  bool start = false;                ///< the start: forces and accelerations only
  bool may_ahead = false;            ///< nothing reads or edits the state before the next step
  bool ahead = false;                ///< the executor's choice: this step predicts the next one
  bool predicted = false;            ///< the last step predicted this one
  const std::vector<PairKey>* candidates = nullptr;  ///< the broad phase's list
  StageTrace* trace = nullptr;                       ///< a test's record of each stage
  const StepParts& p() const { return *parts; }
};

class StepStage {
 public:
  virtual ~StepStage() = default;
  /// the profile slot its time is charged to, and its name
  virtual Stage id() const = 0;
  /// does it run in this step?
  virtual bool runs(const StepContext& c) const = 0;
  /// can it run by ranges of particles, each particle's result from that particle alone?
  virtual bool by_range(const StepContext&) const { return false; }
  /// does its pass host by-range stages in its particle phase (the pair loop)?
  virtual bool hosts_ranges() const { return false; }
  /// before the pass or the ranges, outside any parallel region (the only place to throw)
  virtual void prepare(StepContext&) {}
  /// the whole pass
  virtual void pass(StepContext& c) = 0;
  /// where hosts_ranges(): the pass with `then` run in its particle phase
  virtual void pass_with(StepContext& c, ParticlePhase& then);
  /// where by_range(): the pass over particles [b, e); ranges that cover every particle once
  /// give the whole pass's bits, and disjoint ones may run at once
  virtual void range(StepContext& c, std::size_t b, std::size_t e);
  /// after the pass or every range, outside any parallel region
  virtual void finish(StepContext&) {}
};

/// a step's list of stages, in order
using StageList = std::vector<std::unique_ptr<StepStage>>;

/// the physics stages of a step: predict, broad phase, pairs, accelerate, correct, and (run
/// back to back) predict-next and place-next
std::unique_ptr<StepStage> make_predict_stage();
std::unique_ptr<StepStage> make_broad_phase_stage();
std::unique_ptr<StepStage> make_pairs_stage();
std::unique_ptr<StepStage> make_accelerate_stage();
std::unique_ptr<StepStage> make_correct_stage();
std::unique_ptr<StepStage> make_predict_next_stage();
std::unique_ptr<StepStage> make_place_next_stage();
/// accelerate → correct → predict-next as one pass over each block of disks, velocity Verlet's
/// correction a kick applied while a_n is still at hand (runs where kicks(c))
std::unique_ptr<StepStage> make_kick_stage();
/// can velocity Verlet's correction be the kick stage? (disks; the kick form)
bool kick_possible(const StepParts& p);

/// the 1D ring with the random force: its noise's mean needs every particle's kick first, so
/// its accelerations are a whole pass
bool ring_noise(const StepParts& p);

}  // namespace gs
