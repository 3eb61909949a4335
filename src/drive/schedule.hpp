// driving schedules: pure functions of time (what applies them lives in the simulation step)
#pragma once
#include <cmath>

#include "core/vec.hpp"
#include "scene/spec.hpp"

namespace gs {

/// where a periodic protocol is: tap number (from 0), time within the period, phase
struct DrivePhase {
  long tap = 0;           ///< completed periods before this one
  double t_in = 0.0;      ///< t̃ = t mod T, s
  bool exciting = false;  ///< inside the excitation window (pulse or rotation)
};

/// the period T of a tapping protocol (negative g: T; rotating g: 2π/ω + relax), s; 0 if none
inline double drive_period(const DriveSpec& d) {
  if (d.kind == DriveKind::NegativeG) return d.period;
  if (d.kind == DriveKind::RotatingG) return 1.0 / d.f + d.relax;
  return 0.0;
}

/// the length of the excitation window of a period, s
inline double excitation_length(const DriveSpec& d) {
  if (d.kind == DriveKind::NegativeG) return d.t1;
  if (d.kind == DriveKind::RotatingG) return 1.0 / d.f;
  return 0.0;
}

inline DrivePhase drive_phase(const DriveSpec& d, double t) {
  DrivePhase p;
  const double T = drive_period(d);
  if (T <= 0.0) return p;
  p.tap = static_cast<long>(std::floor(t / T));
  p.t_in = t - p.tap * T;
  p.exciting = p.t_in < excitation_length(d);
  return p;
}

/// gravitational acceleration at time t, m/s²:
/// negative g (P.37): g·e_y·(g_p if t̃ < t1 else −1);
/// rotating g (P.38, window t̃ < 2π/ω per SPEC 9.3): g·(sin ωt̃, −cos ωt̃), else (0, −g)
inline Vec2 gravity_at(const DriveSpec& d, double t) {
  switch (d.kind) {
    case DriveKind::Gravity: {
      const double n = std::hypot(d.gx, d.gy);
      return n > 0 ? Vec2{d.g * d.gx / n, d.g * d.gy / n} : Vec2{};
    }
    case DriveKind::NegativeG: {
      const DrivePhase p = drive_phase(d, t);
      return {0.0, d.g * (p.exciting ? d.g_p : -1.0)};
    }
    case DriveKind::RotatingG: {
      const DrivePhase p = drive_phase(d, t);
      if (!p.exciting) return {0.0, -d.g};
      const double wt = 2.0 * M_PI * d.f * p.t_in;
      return {d.g * std::sin(wt), -d.g * std::cos(wt)};
    }
    default:
      return {};
  }
}

}  // namespace gs
