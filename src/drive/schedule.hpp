// driving schedules: pure functions of the scene's drive, the protocol clock's origin (run
// state, World::clock_origin) and the time (what moves the origin — the protocol clock, early
// rest — lives in drive/protocol.hpp; the simulation step calls gravity_at once per force
// evaluation)
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/vec.hpp"
#include "scene/spec.hpp"

namespace gs {

/// where a periodic protocol is at one instant
struct DrivePhase {
  bool settling = false;  ///< before the protocol clock starts (t < origin)
  long tap = 0;           ///< completed periods before this one
  double t_in = 0.0;      ///< t̃ = (t − origin) mod T, s
  bool exciting = false;  ///< inside the excitation window (pulse or rotation)
};

/// is this one of the tapping protocols (negative g P.37, rotating g P.38)?
inline bool is_tapping(const DriveSpec& d) {
  return d.kind == DriveKind::NegativeG || d.kind == DriveKind::RotatingG;
}

/// the period T of a tapping protocol (negative g: T; rotating g: 2π/ω + relax), s; 0 if none
inline double drive_period(const DriveSpec& d) {
  if (d.kind == DriveKind::NegativeG) return d.period;
  if (d.kind == DriveKind::RotatingG) return 1.0 / d.f + d.relax;
  return 0.0;
}

/// the length of the excitation window of a period (t1, or one rotation 2π/ω = 1/f), s
inline double excitation_length(const DriveSpec& d) {
  if (d.kind == DriveKind::NegativeG) return d.t1;
  if (d.kind == DriveKind::RotatingG) return 1.0 / d.f;
  return 0.0;
}

/// the protocol time t − origin, s (negative while settling)
inline double protocol_time(double origin, double t) { return t - origin; }

/// the phase of the protocol at simulated time t, the protocol clock started at `origin`
inline DrivePhase drive_phase(const DriveSpec& d, double origin, double t) {
  DrivePhase p;
  const double T = drive_period(d);
  if (T <= 0.0) return p;
  const double tau = protocol_time(origin, t);
  if (tau < 0.0) {
    p.settling = true;
    return p;
  }
  p.tap = static_cast<long>(std::floor(tau / T));
  p.t_in = tau - static_cast<double>(p.tap) * T;
  // round-off can put t̃ a hair outside [0, T)
  if (p.t_in >= T) {
    ++p.tap;
    p.t_in -= T;
  }
  if (p.t_in < 0.0) p.t_in = 0.0;
  p.exciting = p.t_in < excitation_length(d);
  return p;
}

/// does the step from t to t + dt enter a new excitation window? (the per-tap measurement is
/// taken at t, "just before the next excitation", docs/physics.md §2.5)
inline bool excitation_starts_next(const DriveSpec& d, double origin, double t, double dt) {
  if (!is_tapping(d)) return false;
  const DrivePhase now = drive_phase(d, origin, t), next = drive_phase(d, origin, t + dt);
  if (next.settling || !next.exciting) return false;
  return now.settling || !now.exciting || now.tap != next.tap;
}

/// the tap boundary the step from t to t + dt crosses (where a Trigger's tap condition looks):
/// the taps done before the excitation it enters, or −1 when it enters none
inline std::int64_t tap_boundary(const DriveSpec& d, double origin, double t, double dt) {
  if (!excitation_starts_next(d, origin, t, dt)) return -1;
  return drive_phase(d, origin, t + dt).tap;
}

/// how many of the steps after t certainly end before the step after which
/// excitation_starts_next() holds (the start of the protocol or of the next period), three
/// fewer than the time left allows (round-off); 0 close to it. No tapping: a large number
inline std::int64_t steps_before_excitation(const DriveSpec& d, double origin, double t,
                                            double dt) {
  if (!is_tapping(d) || drive_period(d) <= 0.0) return std::int64_t{1} << 40;
  const double tau = protocol_time(origin, t);
  const double left = tau < 0.0 ? -tau : drive_period(d) - drive_phase(d, origin, t).t_in;
  const double steps = std::floor(left / dt) - 3.0;
  return steps > 0.0 ? static_cast<std::int64_t>(steps) : 0;
}

/// gravitational acceleration at time t (protocol clock started at `origin`), m/s²:
/// negative g (P.37): g·e_y·(g_p if t̃ < t1 else −1);
/// rotating g (P.38, window t̃ < 2π/ω per docs/physics.md §8.3): g·(sin ωt̃, −cos ωt̃), else (0,
/// −g); before the protocol clock starts (settling): (0, −g) for the tapping protocols; none and
/// random force have no gravity
inline Vec2 gravity_at(const DriveSpec& d, double origin, double t) {
  if (d.kind == DriveKind::Gravity) {
    const double n = std::hypot(d.gx, d.gy);
    if (n > 0 && std::isfinite(n)) return Vec2{d.g * d.gx / n, d.g * d.gy / n};
    // a direction too long for its norm (|g| near the largest double): scaled first
    const double s = std::max(std::abs(d.gx), std::abs(d.gy));
    if (!(s > 0)) return Vec2{};
    const double ux = d.gx / s, uy = d.gy / s, m = std::hypot(ux, uy);
    return Vec2{d.g * ux / m, d.g * uy / m};
  }
  if (!is_tapping(d)) return {};  // none, random force: no gravity at all
  if (protocol_time(origin, t) < 0.0) return {0.0, -d.g};
  switch (d.kind) {
    case DriveKind::NegativeG: {
      const DrivePhase p = drive_phase(d, origin, t);
      return {0.0, d.g * (p.exciting ? d.g_p : -1.0)};
    }
    case DriveKind::RotatingG: {
      const DrivePhase p = drive_phase(d, origin, t);
      if (!p.exciting) return {0.0, -d.g};
      const double wt = 2.0 * M_PI * d.f * p.t_in;
      return {d.g * std::sin(wt), -d.g * std::cos(wt)};
    }
    default:
      return {};
  }
}

}  // namespace gs
