#include "drive/protocol.hpp"

#include <cmath>

namespace gs {

ProtocolSettings ProtocolSettings::from(const SceneSpec& scene) {
  return {scene.drive, scene.prep.settle_time, scene.duration, scene.integrator.dt};
}

ProtocolClock::ProtocolClock(const ProtocolSettings& settings) : set_(settings) {}

void ProtocolClock::start(World& w) const {
  // half a step past the settling time: phase boundaries fall between steps
  w.clock_origin = set_.settle_time + 0.5 * set_.dt;
}

// at rest: every grain slower than rest_speed and the total kinetic energy below rest_energy
bool ProtocolClock::at_rest(const World& w) const {
  const double v2max = set_.drive.rest_speed * set_.drive.rest_speed;
  for (std::size_t i = 0; i < w.size(); ++i)
    if (w.s.vx[i] * w.s.vx[i] + w.s.vy[i] * w.s.vy[i] >= v2max) return false;
  return w.kinetic_energy() < set_.drive.rest_energy;
}

ClockEvent ProtocolClock::after_step(World& w) {
  if ((!set_.drive.early_rest && !set_.drive.quench) || !is_tapping(set_.drive))
    return ClockEvent::None;
  const DriveSpec& d = set_.drive;
  const double dt = set_.dt, t = w.s.t;
  const DrivePhase p = drive_phase(d, w.clock_origin, t);
  // only inside a relaxation, and not when the next step starts an excitation anyway
  if (p.settling || p.exciting || excitation_starts_next(d, w.clock_origin, t, dt)) {
    rest_since_ = -1.0;
    quench_reset();
    return ClockEvent::None;
  }
  // the quench looks at the step as the dynamics left it; its reset waits for the caller
  const bool peak = set_.drive.quench && quench_peak(w, p.tap);
  const ClockEvent quench = peak ? ClockEvent::Quench : ClockEvent::None;
  if (!set_.drive.early_rest) return quench;
  if (!at_rest(w)) {
    rest_since_ = -1.0;
    return quench;
  }
  if (rest_since_ < 0.0 || rest_tap_ != p.tap) {
    rest_since_ = t;
    rest_tap_ = p.tap;
  }
  if (t - rest_since_ < set_.drive.rest_hold) return quench;
  // end the relaxation: t becomes half a step before the start of the next period
  const double T = drive_period(d);
  const double origin = t - static_cast<double>(p.tap + 1) * T + 0.5 * dt;
  saved_ += w.clock_origin - origin;  // the protocol time t − origin jumps forward by this
  w.clock_origin = origin;
  ++early_ends_;
  rest_since_ = -1.0;
  // the next step is an excitation: no reset of this step's velocities
  if (peak) --quenches_;
  quench_reset();
  return ClockEvent::RestEnded;
}

void ProtocolClock::quench_reset() {
  quench_tap_ = -1;
  slow_since_ = -1.0;
  quenching_ = false;
  ke_rising_ = false;
  last_ke_ = 0.0;
}

// armed while every grain has been slower than quench_speed for quench_hold in this relaxation
// (a grain faster than that, a late slip, disarms it until the hold is met again); armed, a
// peak is a step at which the kinetic energy fell after it had risen
bool ProtocolClock::quench_peak(const World& w, long tap) {
  if (quench_tap_ != tap) {
    quench_reset();
    quench_tap_ = tap;
  }
  const double ke = w.kinetic_energy();
  const double v2max = set_.drive.quench_speed * set_.drive.quench_speed;
  bool slow = true;
  for (std::size_t i = 0; i < w.size() && slow; ++i)
    slow = w.s.vx[i] * w.s.vx[i] + w.s.vy[i] * w.s.vy[i] < v2max;
  if (!slow) {
    slow_since_ = -1.0;
    quenching_ = false;
  } else {
    if (slow_since_ < 0.0) slow_since_ = w.s.t;
    quenching_ = w.s.t - slow_since_ >= set_.drive.quench_hold;
  }
  // kinetic damping (Cundall): at a peak the caller zeroes every velocity, the energy with it
  if (quenching_ && ke_rising_ && ke < last_ke_) {
    ++quenches_;
    ke_rising_ = false;
    last_ke_ = 0.0;
    return true;
  }
  ke_rising_ = ke > last_ke_;
  last_ke_ = ke;
  return false;
}

bool ProtocolClock::done(const World& w) const {
  if (set_.drive.taps <= 0 || !is_tapping(set_.drive)) return false;
  const DrivePhase next = drive_phase(set_.drive, w.clock_origin, w.s.t + set_.dt);
  return !next.settling && next.tap >= set_.drive.taps;
}

double ProtocolClock::nominal_duration() const {
  if (set_.drive.taps > 0 && is_tapping(set_.drive))
    return set_.settle_time + static_cast<double>(set_.drive.taps) * drive_period(set_.drive);
  return set_.settle_time + set_.duration;
}

void ProtocolClock::save(ByteWriter& out) const {
  out.f64(rest_since_);
  out.i64(rest_tap_);
  out.i64(early_ends_);
  out.f64(saved_);
  // the quench (appended: older checkpoints end here)
  out.i64(quench_tap_);
  out.f64(slow_since_);
  out.u8(quenching_ ? 1 : 0);
  out.u8(ke_rising_ ? 1 : 0);
  out.f64(last_ke_);
  out.i64(quenches_);
}

void ProtocolClock::load(ByteReader& in) {
  rest_since_ = in.f64("clock: rest since");
  rest_tap_ = static_cast<long>(in.i64("clock: rest tap"));
  early_ends_ = in.i64("clock: early ends");
  saved_ = in.f64("clock: time saved");
  quench_reset();
  quenches_ = 0;
  if (in.at_end()) return;  // written before the quench existed
  quench_tap_ = static_cast<long>(in.i64("clock: quench tap"));
  slow_since_ = in.f64("clock: quench slow since");
  quenching_ = in.u8("clock: quenching") != 0;
  ke_rising_ = in.u8("clock: kinetic energy rising") != 0;
  last_ke_ = in.f64("clock: last kinetic energy");
  quenches_ = in.i64("clock: quench events");
}

double ProtocolClock::progress(const World& w) const { return w.s.t + saved_; }

}  // namespace gs
