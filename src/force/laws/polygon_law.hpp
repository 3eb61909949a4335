// Model P: the tapping paper's overlap-area normal force and Cundall–Strack friction
// (docs/physics.md §2.2)
#pragma once
#include <algorithm>
#include <cmath>

#include "contact/tangential_spring.hpp"

namespace gs::law {

/// material constants of Model P
struct PolyLawParams {
  double E = 1000.0;   ///< 2D modulus, N/m
  double gamma = 0.5;  ///< normal damping coefficient, dimensionless
  double mu = 0.6;     ///< Coulomb friction coefficient
};

/// normal force magnitude (P.34), corrected dashpot sign (docs/physics.md §8.2):
/// F⊥ = max(E·h_eff + γ·√(E m⊥)·ḣ_eff, 0); ḣ_eff > 0 while the overlap grows. N.
inline double poly_normal_force_damped(const PolyLawParams& p, double h_eff, double hdot_eff,
                                       double damp_n) {
  return std::max(p.E * h_eff + damp_n * hdot_eff, 0.0);
}
/// the same with the dashpot coefficient γ·√(E m⊥) (kg/s) computed once per pair type
inline double poly_normal_force(const PolyLawParams& p, double h_eff, double hdot_eff,
                                double m_perp) {
  return poly_normal_force_damped(p, h_eff, hdot_eff, p.gamma * std::sqrt(p.E * m_perp));
}

using gs::TangentialSpring;  // the contact's stored state, updated by the laws below

/// tangential force (P.35–P.36); updates the spring in place, returns F∥ (N), with
/// v_par the relative tangential velocity (P.32) at this step and F_n = F⊥ at this step.
///   F*∥(t) = clamp(F*∥(t−Δt) + (2/7)·E·v∥(t−Δt)·Δt, ±μF⊥(t))
///   F∥(t)  = clamp(F*∥(t) + √((2/7)·E·m∥)·v∥(t), ±μF⊥(t))
/// damp_t = √((2/7)·E·m∥) (kg/s): the dashpot, computed once per pair type
inline double cundall_strack_damped(const PolyLawParams& p, TangentialSpring& s, double v_par,
                                    double F_n, double damp_t, double dt) {
  const double cap = p.mu * F_n;
  const double k_t = (2.0 / 7.0) * p.E;
  s.spring = std::clamp(s.spring + k_t * s.v_prev * dt, -cap, cap);
  s.v_prev = v_par;
  return std::clamp(s.spring + damp_t * v_par, -cap, cap);
}
inline double cundall_strack(const PolyLawParams& p, TangentialSpring& s, double v_par, double F_n,
                             double m_par, double dt) {
  return cundall_strack_damped(p, s, v_par, F_n, std::sqrt((2.0 / 7.0) * p.E * m_par), dt);
}

}  // namespace gs::law
