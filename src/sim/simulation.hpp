// the simulation: owns the World and the stages of a step, and reads like the pipeline
#pragma once
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "broadphase/broadphase.hpp"
#include "contact/contact_set.hpp"
#include "core/stage_clock.hpp"
#include "force/forces.hpp"
#include "integrate/integrator.hpp"
#include "world/world.hpp"

namespace gs {

/// integrator.sort_every of w's scene with auto (−1) resolved for w: every kAutoSortEvery
/// steps for a 2D Model S system of at least kAutoSortMinParticles particles, else 0
std::int64_t resolved_sort_every(const World& w);

class Simulation {
 public:
  /// take a World with its particles placed; computes the initial forces
  explicit Simulation(World w);
  /// throws HealthError naming the particle when a position or velocity is not finite (also
  /// part of every periodic health check; the run loop calls it after the first step too,
  /// whatever health.check_every is)
  void check_finite() const;
  /// the periodic health check (non-finite state, overlaps, energy growth without driving
  /// input): HealthError with a diagnosis. The run loop also calls it once at the end, so a
  /// run that blew up between two checks is not reported as completed
  void health_check();
  Simulation(World w, BroadPhaseKind bp);

  /// advance one time step: drive → predict → broad phase → contacts → forces → correct →
  /// health check
  void step() { advance(false); }
  /// advance n steps: bitwise n × step(), but where nothing reads or edits the state between
  /// two of them (no drift removal, health check or sort between), each step's correction
  /// predicts the next step too, particle by particle inside the force pass (the fused kick
  /// of velocity Verlet on disks; Gear 6): one pass over the state less per step
  void run(std::int64_t n);

  World& world() { return w_; }
  const World& world() const { return w_; }
  const ContactSet& contacts() const { return contacts_; }
  const ForceStats& last_forces() const { return stats_; }
  const ContactModel& model() const { return model_; }
  const BroadPhase& broadphase() const { return *broad_; }
  Integrator& integrator() { return *integ_; }
  const Integrator& integrator() const { return *integ_; }
  /// kinetic damping between steps (drive.quench): every velocity and angular velocity to zero
  /// and the integrator's history restarted from rest at the current positions
  void zero_velocities();
  /// checkpoint restore (sim/simulation_restore.cpp): replace the persistent contact set
  void restore_contacts(ContactSet c);
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
  /// the integrator's correction as a velocity kick inside the acceleration pass (one pass
  /// over the velocities less): on by default where the scheme has one (velocity Verlet)
  /// and the particles are disks; off: the integrator's own correct() (for comparisons)
  void set_kick_fusion(bool on);
  bool kick_fused() const { return fused_; }
  /// how many steps so far took their prediction from the previous step's kick (run())
  std::uint64_t steps_predicted_ahead() const { return ahead_steps_; }
  /// wall time per stage of the steps so far (or since clear_profile())
  const StepProfile& profile() const { return profile_; }
  void clear_profile() { profile_ = {}; }
  /// does anything drive the system (gravity, pulses, noise)?
  bool driven() const;
  /// can the mechanical energy only decrease (no drive, or constant gravity)?
  bool conservative_drive() const;

 private:
  /// accelerations at the current state; `index` counts force evaluations (noise stream)
  // forces and accelerations at the current (predicted) state; with `correct`, the
  // integrator's corrector too, each particle right after its acceleration, on the thread
  // that computed it (Integrator::correct_range; check_correct() done by the caller)
  // (`ahead`: and, after the kick, the next step's prediction: may_predict_ahead())
  void compute_accelerations(std::int64_t index, const std::vector<PairKey>& candidates,
                             std::span<const Channel> correct = {}, bool ahead = false,
                             StageClock* clock = nullptr);
  /// the drive stage at the current time: gravity_, the random force's stream keys
  void drive();
  /// one step; `then_predict`: the next step follows at once (run())
  void advance(bool then_predict);
  bool may_predict_ahead(std::int64_t from) const;
  /// does this scene's force pass predict the next step where asked (may_predict_ahead)?
  bool predicts_in_pass() const;
  /// what step() does around step `step` (the step count after it): the drift removal and the
  /// health check after it, the spatial sort before the next
  bool removes_drift_after(std::int64_t step) const;
  bool checks_health_after(std::int64_t step) const;
  bool sorts_before(std::int64_t step) const;
  /// kinetic + contact elastic + gravitational energy (J); elastic ½k_sδ² (Model S), not
  /// counted for Model P (a lower bound)
  double mechanical_energy() const;
  std::vector<Channel> channels();

  World w_;
  double dt_;
  BroadPhaseKind broad_kind_;
  std::unique_ptr<BroadPhase> broad_;
  ContactModel model_;
  std::unique_ptr<Integrator> integ_;
  ContactSet contacts_;
  ForceBuffer forces_;
  ForceStats stats_;
  std::vector<std::uint64_t> noise_keys_;  ///< random force: stream keys per particle (cached)
  std::vector<double> kick_;      ///< the ring's momentum kicks summed per block, kg·m/s²
  std::vector<double> ring_pre_;  ///< the ring's accelerations before the mean kick, m/s²
  bool fused_ = false;            ///< the integrator's kick inside the acceleration pass
  bool ahead_ = false;  ///< inside run(): the state already holds the next step's prediction
  std::uint64_t ahead_steps_ = 0;  ///< steps that took their prediction from the last kick
  KickForm kick_form_;
  Vec2 gravity_;
  std::int64_t sort_every_ = 0;
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
