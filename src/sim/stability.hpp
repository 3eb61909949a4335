// time-step stability: the largest ω·Δt each integrator survives on the damped linear contact
// (measured by tests/integrate/test_stability.cpp), and the advice derived from it
#pragma once
#include <string>

#include "integrate/integrator.hpp"
#include "scene/spec.hpp"

namespace gs {

class Simulation;

/// largest stable ω·Δt of an integrator on q'' = −ω²q − 2ζωq' (ζ the contact's damping ratio);
/// linear interpolation between the measured values at ζ = 0 and ζ = 0.25
double stable_omega_dt(IntegratorKind kind, double zeta);

struct StepAdvice {
  double omega = 0.0;         ///< angular frequency of the stiffest binary contact, rad/s
  double omega_dt = 0.0;      ///< ω·Δt of the scene
  double limit = 0.0;         ///< the integrator's stable ω·Δt
  double suggested_dt = 0.0;  ///< Δt at half the limit, s
  bool stable = true;         ///< ω·Δt within the limit
  std::string message;        ///< a sentence for the user when not stable
};

/// judge the scene's Δt against its stiffest contact and its integrator
StepAdvice time_step_advice(const Simulation& sim);

/// refuse a scene whose Δt is unstable for its integrator or resolves the stiffest contact
/// with fewer than 5 steps: InputError naming the scene file and integrator.dt (with the Δt
/// to use, and the scene's keys that set the contact time), unless health.allow_unstable.
/// `sim` is built from `scene`
void check_time_step(const Simulation& sim, const SceneSpec& scene);

}  // namespace gs
