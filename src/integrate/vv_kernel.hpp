// velocity Verlet's prediction of one degree of freedom: VelocityVerlet::predict and a caller
// that predicts inside its fused kick (Simulation::run) share it, so both give the same bits
#pragma once

namespace gs {

/// kick half a step with a_n, drift a full step: q_{n+1} = q_n + (v_n + a_n·Δt/2)·Δt; the
/// velocity the forces see is v_{n+½} (kHalf; error O(Δt)) or v_n + a_n·Δt (error O(Δt²)).
/// Returns v_{n+½}
template <bool kHalf>
inline double vv_predict_dof(double dt, double a, double& q, double& v) {
  const double h = v + a * dt / 2.0;
  q += h * dt;
  v = kHalf ? h : v + a * dt;
  return h;
}

/// velocity Verlet's correction as one kick: v_{n+1} = v̂ + c_new·a_{n+1} − c_old·a_n (shared
/// by VelocityVerlet's Kick correction and an executor's kick in its force pass: same bits)
inline double vv_kick_dof(double v, double a_new, double a_old, double c_new, double c_old) {
  return v + a_new * c_new - a_old * c_old;
}

}  // namespace gs
