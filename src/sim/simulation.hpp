// the simulation: owns the World and the stages of a step, and reads like the pipeline
#pragma once
#include <memory>
#include <utility>
#include <vector>

#include "broadphase/broadphase.hpp"
#include "contact/contact_set.hpp"
#include "core/stage_clock.hpp"
#include "core/team.hpp"
#include "core/trigger.hpp"
#include "force/forces.hpp"
#include "integrate/integrator.hpp"
#include "sim/sim_settings.hpp"
#include "sim/step_executor.hpp"
#include "world/world.hpp"

namespace gs {

/// integrator.sort_every with auto (−1) resolved for w: every kAutoSortEvery steps for a 2D
/// Model S system of at least kAutoSortMinParticles particles, else 0
std::int64_t resolved_sort_every(const World& w, int sort_every);

class Simulation {
 public:
  /// take a World with its particles placed and the settings of its scene
  /// (SimSettings::from); computes the initial forces. `bp` other than Auto overrides the
  /// settings' broad phase
  Simulation(World w, const SimSettings& settings, BroadPhaseKind bp = BroadPhaseKind::Auto);
  /// throws HealthError naming the particle when a position or velocity is not finite (also
  /// part of every periodic health check; the run loop calls it after the first step too,
  /// whatever health.check_every is)
  void check_finite() const;
  /// the periodic health check (non-finite state, overlaps, energy growth without driving
  /// input): HealthError with a diagnosis. The run loop also calls it once at the end, so a
  /// run that blew up between two checks is not reported as completed
  void health_check();

  /// advance one time step: its list of stages (sort → drive → predict → broad phase → pairs
  /// → accelerate → correct → constraints/health; docs/architecture.md, "One step")
  void step() { advance(false); }
  /// advance n steps: bitwise n × step(), but where nothing reads or edits the state between
  /// two of them (no drift removal, health check or sort between), the correction may
  /// predict the next step too (sim/step_executor.hpp): one pass over the state less per step
  void run(std::int64_t n);

  const SimSettings& settings() const { return settings_; }
  World& world() { return w_; }
  const World& world() const { return w_; }
  const ContactSet& contacts() const { return contacts_; }
  const ForceStats& last_forces() const { return stats_; }
  const ContactModel& model() const { return model_; }
  const BroadPhase& broadphase() const { return *broad_; }
  /// how this simulation's passes split among the threads (moved by its own timings only; a
  /// test may feed it measurements)
  const ThreadTeam& team() const { return team_; }
  ThreadTeam& team() { return team_; }
  Integrator& integrator() { return *integ_; }
  const Integrator& integrator() const { return *integ_; }
  /// kinetic damping between steps (drive.quench): every velocity and angular velocity to zero
  /// and the integrator's history restarted from rest at the current positions
  void zero_velocities();
  /// checkpoint restore (sim/simulation_restore.cpp): replace the persistent contact set
  void restore_contacts(ContactSet c);
  /// after the caller set positions, orientations or velocities between steps: start again
  /// from this state as a new Simulation would (contacts and their springs afresh, forces
  /// evaluated here, the integrator's history restarted, the energy yardstick taken anew);
  /// the World's arrays stay where they are
  void restart_from_state();
  /// the spatial sort's interval in steps (integrator.sort_every resolved; 0 = never)
  std::int64_t sort_every() const { return sort_every_; }
  /// move the particles between slots in cell order (rows of cells about one diameter
  /// high, bottom to top; left to right within a row; slot order within a cell), with
  /// everything that is kept per slot: the World, the integrator's history, the contact
  /// keys, the random-force streams (sim/simulation_sort.cpp). step() calls it every
  /// sort_every() steps; the dynamics is the same up to round-off (sums over particles run
  /// in another order).
  void sort_particles();
  /// counts the sorts so far: an observer that keeps per-slot data compares it with the
  /// value it saw last and then applies last_order()
  std::uint64_t order_generation() const { return order_generation_; }
  /// the last sort's permutation: slot k received what slot last_order()[k] held
  const std::vector<std::uint32_t>& last_order() const { return last_order_; }
  double dt() const { return dt_; }
  /// gravity applied during the last step, m/s²
  Vec2 gravity() const { return gravity_; }
  /// the blow-up check's energy yardstick (reference, tolerated growth), J: a checkpoint
  /// keeps the original run's, so a resumed run checks against the same numbers
  std::pair<double, double> energy_yardstick() const { return {energy_ref_, energy_slack_}; }
  void set_energy_yardstick(double ref, double slack) {
    energy_ref_ = ref;
    energy_slack_ = slack;
  }
  /// wall time per stage of the steps so far (or since clear_profile())
  const StepProfile& profile() const { return profile_; }
  void clear_profile() { profile_.clear(); }
  /// does anything drive the system (gravity, pulses, noise)?
  bool driven() const;
  /// can the mechanical energy only decrease (no drive, or constant gravity)?
  bool conservative_drive() const;

 private:
  friend class StepInspector;  // tests: the executor, the stages, the profile's clock
  /// what the stages work on
  StepParts parts() const;
  /// the drive stage at the current time: gravity_, the random force's stream keys
  void drive();
  /// one step; `then_predict`: the next step follows at once (run())
  void advance(bool then_predict);
  /// the stages' context of one step (`start`: the forces and accelerations of a new state)
  StepContext context(bool start);
  /// the forces and accelerations at the state as it is (the constructor, a restart)
  void evaluate_start();
  bool may_predict_ahead(std::int64_t from) const;
  /// the step's count, its drift removal and health check (the constraints stage)
  void constrain();
  /// what step() does around step `step` (the step count after it): the drift removal and the
  /// health check after it, the spatial sort before the next
  bool removes_drift_after(std::int64_t step) const;
  bool checks_health_after(std::int64_t step) const;
  bool sorts_before(std::int64_t step) const;
  /// kinetic + contact elastic + gravitational energy (J); elastic ½k_sδ² (Model S), not
  /// counted for Model P (a lower bound)
  double mechanical_energy() const;
  /// the blow-up check's yardstick from the state now (the constructor, restart_from_state)
  void take_energy_yardstick();
  std::vector<Channel> channels();

  SimSettings settings_;
  World w_;
  double dt_;
  BroadPhaseKind broad_kind_;
  std::unique_ptr<BroadPhase> broad_;
  ContactModel model_;
  std::unique_ptr<Integrator> integ_;
  ThreadTeam team_;  ///< which thread runs which pairs and particles, from this run's timings
  ContactSet contacts_;
  ForceBuffer forces_;
  ForceStats stats_;
  std::vector<std::uint64_t> noise_keys_;  ///< random force: stream keys per particle (cached)
  std::unique_ptr<StepExecutor> exec_ = make_executor(ExecutorKind::Fused);
  StageList stages_;             ///< a step, in order (the constructor makes it)
  StageTrace* trace_ = nullptr;  ///< a test's record of each stage
  Vec2 gravity_;
  std::int64_t sort_every_ = 0;
  // when the jobs between steps run: slots re-sorted in cell order before a step, the random
  // force's drift removed and the health checked after one (step counts only: the state stays
  // bitwise independent of wall time and of where a run was resumed)
  Trigger sort_trigger_, drift_trigger_, health_trigger_;
  std::uint64_t order_generation_ = 0;
  std::vector<std::uint32_t> last_order_;
  /// sort_particles()'s buffers, kept between sorts: at 10⁶ particles fresh pages for them
  /// cost as much as the sort itself
  struct SortScratch {
    std::vector<std::uint32_t> start, cell, perm, slot;
    std::vector<std::uint64_t> keys;
    World::PermuteScratch world;
  } sort_scratch_;
  StepProfile profile_;
  double energy_ref_ = 0.0;    ///< mechanical energy at the start, J (undriven/constant g)
  double energy_slack_ = 0.0;  ///< growth tolerated before it counts as a blow-up, J
};

}  // namespace gs
