// Model S: the thesis's linear spring–dashpot for soft disks (docs/physics.md §3; T.2.4–T.2.12)
#pragma once
#include <algorithm>
#include <cmath>
#include <numbers>

namespace gs::law {

/// normal dashpot coefficient for a target restitution ε (T.2.6), kg/s:
/// γ_n² = (ln ε/π)²·4 m₁₂ k_s / (1 + (ln ε/π)²); ε = 0 gives the limit, critical damping
/// 2√(m₁₂ k_s) (the formula itself would be ∞/∞ = NaN there)
inline double gamma_normal(double eps, double m12, double ks) {
  if (eps <= 0.0) return 2.0 * std::sqrt(m12 * ks);
  const double a = std::log(eps) / std::numbers::pi;
  return std::sqrt(a * a * 4.0 * m12 * ks / (1.0 + a * a));
}
/// tangential dashpot coefficient (T.2.12), kg/s: γ_t = −(√(k_s m₁₂)/π)·ln ε_t
inline double gamma_tangential(double eps_t, double m12, double ks) {
  return -std::sqrt(ks * m12) / std::numbers::pi * std::log(eps_t);
}
/// binary contact time of the damped linear spring, s: π/√(k_s/m₁₂ − (γ_n/2m₁₂)²)
inline double contact_time(double ks, double m12, double gn) {
  const double w0sq = ks / m12;
  const double b = gn / (2.0 * m12);
  return std::numbers::pi / std::sqrt(w0sq - b * b);
}

/// parameters of the linear law for one pair of species
struct DiskLawParams {
  double ks = 5e5;    ///< normal spring stiffness, N/m
  double gn = 0.0;    ///< normal dashpot, kg/s (from gamma_normal)
  double gt = 0.0;    ///< tangential dashpot, kg/s (from gamma_tangential)
  double mu = 0.0;    ///< sliding friction coefficient (T.2.7); 0 = off
  bool clip = false;  ///< clip the attractive normal force to zero (off: T.2.6 exact)
};

/// normal and tangential force magnitudes on j along n̂ and t̂ (i gets the opposite).
struct DiskForce {
  double fn = 0.0;  ///< normal force on j along n̂ (positive = repulsive), N
  double ft = 0.0;  ///< tangential force on j along t̂, N
};

/// the linear law: δ > 0 overlap (m); vn = (v_i − v_j)·n̂ approach speed (m/s, > 0 approaching);
/// vt = (v_i − v_j)·t̂ relative tangential speed (m/s).
inline DiskForce linear_spring_dashpot(const DiskLawParams& p, double delta, double vn, double vt) {
  DiskForce f;
  f.fn = p.ks * delta + p.gn * vn;  // spring (T.2.4) + dashpot (T.2.5)
  if (p.clip && f.fn < 0.0) f.fn = 0.0;
  f.ft = p.gt * vt;  // tangential dashpot (T.2.9), drags j along i's relative motion
  if (p.mu > 0.0) {  // sliding friction caps it (T.2.7)
    const double cap = p.mu * std::max(f.fn, 0.0);
    f.ft = std::clamp(f.ft, -cap, cap);
  }
  return f;
}

}  // namespace gs::law
