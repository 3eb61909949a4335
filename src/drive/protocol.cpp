#include "drive/protocol.hpp"

#include <cmath>

namespace gs {

ProtocolClock::ProtocolClock(const SceneSpec& scene)
    : drive_(scene.drive),
      settle_(scene.prep.settle_time),
      duration_(scene.duration),
      dt_(scene.integrator.dt) {
  drive_.clock_origin = 0.0;
}

void ProtocolClock::start(World& w) const {
  // half a step past the settling time: phase boundaries fall between steps
  w.scene.drive.clock_origin = settle_ + 0.5 * dt_;
}

// at rest: every grain slower than rest_speed and the total kinetic energy below rest_energy
bool ProtocolClock::at_rest(const World& w) const {
  const double v2max = drive_.rest_speed * drive_.rest_speed;
  for (std::size_t i = 0; i < w.size(); ++i)
    if (w.s.vx[i] * w.s.vx[i] + w.s.vy[i] * w.s.vy[i] >= v2max) return false;
  return w.kinetic_energy() < drive_.rest_energy;
}

ClockEvent ProtocolClock::after_step(World& w) {
  if ((!drive_.early_rest && !drive_.quench) || !is_tapping(drive_)) return ClockEvent::None;
  DriveSpec& d = w.scene.drive;
  const double t = w.s.t;
  const DrivePhase p = drive_phase(d, t);
  // only inside a relaxation, and not when the next step starts an excitation anyway
  if (p.settling || p.exciting || excitation_starts_next(d, t, dt_)) {
    rest_since_ = -1.0;
    quench_reset();
    return ClockEvent::None;
  }
  // the quench looks at the step as the dynamics left it; its reset waits for the caller
  const bool peak = drive_.quench && quench_peak(w, p.tap);
  const ClockEvent quench = peak ? ClockEvent::Quench : ClockEvent::None;
  if (!drive_.early_rest) return quench;
  if (!at_rest(w)) {
    rest_since_ = -1.0;
    return quench;
  }
  if (rest_since_ < 0.0 || rest_tap_ != p.tap) {
    rest_since_ = t;
    rest_tap_ = p.tap;
  }
  if (t - rest_since_ < drive_.rest_hold) return quench;
  // end the relaxation: t becomes half a step before the start of the next period
  const double T = drive_period(d);
  const double origin = t - static_cast<double>(p.tap + 1) * T + 0.5 * dt_;
  saved_ += d.clock_origin - origin;  // the protocol time t − origin jumps forward by this
  d.clock_origin = origin;
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
  const double v2max = drive_.quench_speed * drive_.quench_speed;
  bool slow = true;
  for (std::size_t i = 0; i < w.size() && slow; ++i)
    slow = w.s.vx[i] * w.s.vx[i] + w.s.vy[i] * w.s.vy[i] < v2max;
  if (!slow) {
    slow_since_ = -1.0;
    quenching_ = false;
  } else {
    if (slow_since_ < 0.0) slow_since_ = w.s.t;
    quenching_ = w.s.t - slow_since_ >= drive_.quench_hold;
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
  if (drive_.taps <= 0 || !is_tapping(drive_)) return false;
  const DrivePhase next = drive_phase(w.scene.drive, w.s.t + dt_);
  return !next.settling && next.tap >= drive_.taps;
}

double ProtocolClock::nominal_duration() const {
  if (drive_.taps > 0 && is_tapping(drive_))
    return settle_ + static_cast<double>(drive_.taps) * drive_period(drive_);
  return settle_ + duration_;
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
