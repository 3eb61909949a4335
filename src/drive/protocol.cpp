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

bool ProtocolClock::after_step(World& w) {
  if (!drive_.early_rest || !is_tapping(drive_)) return false;
  DriveSpec& d = w.scene.drive;
  const double t = w.s.t;
  const DrivePhase p = drive_phase(d, t);
  // only inside a relaxation, and not when the next step starts an excitation anyway
  if (p.settling || p.exciting || excitation_starts_next(d, t, dt_)) {
    rest_since_ = -1.0;
    return false;
  }
  if (!at_rest(w)) {
    rest_since_ = -1.0;
    return false;
  }
  if (rest_since_ < 0.0 || rest_tap_ != p.tap) {
    rest_since_ = t;
    rest_tap_ = p.tap;
  }
  if (t - rest_since_ < drive_.rest_hold) return false;
  // end the relaxation: t becomes half a step before the start of the next period
  const double T = drive_period(d);
  const double origin = t - static_cast<double>(p.tap + 1) * T + 0.5 * dt_;
  saved_ += d.clock_origin - origin;  // the protocol time t − origin jumps forward by this
  d.clock_origin = origin;
  ++early_ends_;
  rest_since_ = -1.0;
  return true;
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
}

void ProtocolClock::load(ByteReader& in) {
  rest_since_ = in.f64("clock: rest since");
  rest_tap_ = static_cast<long>(in.i64("clock: rest tap"));
  early_ends_ = in.i64("clock: early ends");
  saved_ = in.f64("clock: time saved");
}

double ProtocolClock::progress(const World& w) const { return w.s.t + saved_; }

}  // namespace gs
