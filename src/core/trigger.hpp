// when a periodic action runs, apart from what it does (HOOMD-blue's Trigger): every N steps, at
// every N-th tap boundary (the drive says where they are), every N wall-clock minutes, or the
// first of these. Steps and taps are pure functions of the run's position, so a resumed run
// fires where an uninterrupted one does; only the wall clock has state, saved with save().
#pragma once
#include <cstdint>

#include "core/bytes.hpp"

namespace gs {

/// where a run is when a trigger is asked
struct TriggerTime {
  std::int64_t step = 0;  ///< steps taken
  /// at a tap boundary (the next step starts an excitation): the taps done before it; −1 when
  /// this step is no tap boundary
  std::int64_t tap = -1;
  /// the run's wall-clock time so far (all sessions), s; negative when the clock was not read
  /// (the wall-clock condition is then not looked at)
  double wall_s = -1.0;
};

class Trigger {
 public:
  /// never fires
  Trigger() = default;
  static Trigger every_steps(std::int64_t n) { return Trigger{}.or_every_steps(n); }
  static Trigger every_taps(std::int64_t n) { return Trigger{}.or_every_taps(n); }
  static Trigger every_minutes(double m) { return Trigger{}.or_every_minutes(m); }
  /// also fire after every step that is a multiple of n (n ≤ 0: no such condition)
  Trigger& or_every_steps(std::int64_t n) {
    steps_ = n > 0 ? n : 0;
    return *this;
  }
  /// also fire at every tap boundary whose count of taps done is a multiple of n (n = 1: every
  /// tap boundary, the first after settling included)
  Trigger& or_every_taps(std::int64_t n) {
    taps_ = n > 0 ? n : 0;
    return *this;
  }
  /// also fire once m wall-clock minutes have passed since it last fired (or was started)
  Trigger& or_every_minutes(double m) {
    minutes_ = m > 0.0 ? m : 0.0;
    return *this;
  }

  /// can it fire at all?
  bool active() const { return steps_ > 0 || taps_ > 0 || minutes_ > 0.0; }
  std::int64_t step_period() const { return steps_; }

  /// the step condition alone: is `step` one of its steps? (no state, no wall clock)
  bool at_step(std::int64_t step) const { return steps_ > 0 && step % steps_ == 0; }

  /// how many steps may be taken from `step` before the step condition can next hold: the run
  /// may take that many at once. Without a step condition a large number
  std::int64_t steps_to_next(std::int64_t step) const {
    return steps_ > 0 ? steps_ - step % steps_ : std::int64_t{1} << 40;
  }

  /// does it fire at t? Firing restarts the wall-clock interval
  bool fires(const TriggerTime& t) {
    bool due = at_step(t.step) || (taps_ > 0 && t.tap >= 0 && t.tap % taps_ == 0);
    if (minutes_ > 0.0 && t.wall_s >= 0.0 && t.wall_s - last_wall_ >= 60.0 * minutes_) due = true;
    if (due && t.wall_s >= 0.0) last_wall_ = t.wall_s;
    return due;
  }

  /// the wall-clock interval starts at `wall_s` (a run's start)
  void start(double wall_s) { last_wall_ = wall_s; }
  /// the wall-clock interval's start when it last fired, s of the run's wall time
  double last_wall() const { return last_wall_; }

  /// checkpoint: the wall-clock interval's start (the conditions come from the settings)
  void save(ByteWriter& out) const { out.f64(last_wall_); }
  void load(ByteReader& in) { last_wall_ = in.f64("trigger: last wall-clock firing"); }

 private:
  std::int64_t steps_ = 0, taps_ = 0;
  double minutes_ = 0.0;
  double last_wall_ = 0.0;
};

}  // namespace gs
