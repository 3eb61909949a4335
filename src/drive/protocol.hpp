// what applies a tapping protocol: the protocol clock. It starts the schedule after the
// settling time and ends a relaxation early once the pile is at rest (docs/physics.md §2.4) by
// moving the clock origin back (the protocol time t − origin jumps to the next excitation), so the
// schedules stay pure functions of (drive, t). With drive.quench it also says when the run
// should zero every velocity (kinetic damping of the ringing pile, so that rest can come).
#pragma once
#include <cstdint>

#include "core/bytes.hpp"
#include "drive/schedule.hpp"
#include "world/world.hpp"

namespace gs {

/// what ProtocolClock::after_step did or asks for
enum class ClockEvent : std::uint8_t {
  None,
  RestEnded,  ///< early rest ended the relaxation: the next step starts the next excitation
  Quench,     ///< a kinetic-energy peak while quenching: the caller zeroes every velocity now
              ///< (Simulation::zero_velocities), before the observers see the step
};

/// what the protocol clock needs of a scene, taken once (Jolt's *Settings): the drive, the
/// settling time, the run's length and the time step
struct ProtocolSettings {
  DriveSpec drive;
  double settle_time = 0.0;  ///< preparation.settle_time, s
  double duration = 0.0;     ///< scene.duration (used when drive.taps = 0), s
  double dt = 0.0;           ///< integrator.dt, s
  static ProtocolSettings from(const SceneSpec& scene);
};

/// the protocol clock of one run; the only writer of World::clock_origin
class ProtocolClock {
 public:
  explicit ProtocolClock(const ProtocolSettings& settings);
  explicit ProtocolClock(const SceneSpec& scene) : ProtocolClock(ProtocolSettings::from(scene)) {}
  const ProtocolSettings& settings() const { return set_; }

  /// start the protocol clock after preparation.settle_time. The origin sits half a step past
  /// the settling time so that no step time falls on a phase boundary: every pulse lasts
  /// exactly round(t1/Δt) force evaluations whatever the round-off in t = step·Δt
  void start(World& w) const;

  /// after a step: early rest (off unless drive.early_rest). While relaxing, once the largest
  /// speed stays below drive.rest_speed and the kinetic energy below drive.rest_energy for
  /// drive.rest_hold, the relaxation ends: the origin moves back so that the next step begins
  /// the next excitation (t itself is continuous); returns RestEnded when it did so now.
  /// Quench (off unless drive.quench): while relaxing, once the largest speed has stayed below
  /// drive.quench_speed for drive.quench_hold (the pile landed and its contact network froze),
  /// every step at which the kinetic energy falls after rising (a peak) returns Quench, and the
  /// caller sets every velocity to zero (Cundall's kinetic damping; docs/tapping.md). Never
  /// on the step before an excitation, so the measured state is one the dynamics produced.
  ClockEvent after_step(World& w);

  /// does after_step() look at every step (early rest or quench in a tapping protocol)? If
  /// not, a run may call it after a batch of steps only
  bool watches_steps() const {
    return (set_.drive.early_rest || set_.drive.quench) && is_tapping(set_.drive);
  }

  /// the number of full taps done: after this step the next one would start tap `taps`
  /// (only when drive.taps > 0)
  bool done(const World& w) const;

  /// simulated time the run needs without early ends (settling plus taps·T, or settling plus
  /// scene.duration when drive.taps = 0), s
  double nominal_duration() const;
  /// settling plus protocol time at t (counts skipped rest as done), s
  double progress(const World& w) const;

  /// relaxations ended early so far
  std::int64_t early_ends() const { return early_ends_; }
  /// simulated time saved by early ends so far, s
  double time_saved() const { return saved_; }
  /// velocity resets of the quench so far
  std::int64_t quench_events() const { return quenches_; }

  /// checkpoint: the early-rest and quench state (the clock origin itself is World state, saved
  /// with it). Checkpoints written before the quench existed load with it idle
  void save(ByteWriter& out) const;
  void load(ByteReader& in);

 private:
  bool at_rest(const World& w) const;
  /// the quench's part of after_step inside a relaxation of tap `tap`: true at a KE peak
  bool quench_peak(const World& w, long tap);
  void quench_reset();

  ProtocolSettings set_;
  double rest_since_ = -1.0;  ///< time from which the pile has been at rest, s (−1: not)
  long rest_tap_ = -1;        ///< the tap whose relaxation rest_since_ belongs to
  std::int64_t early_ends_ = 0;
  double saved_ = 0.0;
  // quench: armed once slow for quench_hold within the relaxation of quench_tap_
  long quench_tap_ = -1;      ///< the tap whose relaxation the quench state belongs to
  double slow_since_ = -1.0;  ///< time from which every grain has been below quench_speed, s
  bool quenching_ = false;    ///< armed: zero the velocities at every KE peak
  bool ke_rising_ = false;    ///< the kinetic energy rose over the last step
  double last_ke_ = 0.0;      ///< kinetic energy after the last step (0 after a reset), J
  std::int64_t quenches_ = 0;
};

}  // namespace gs
