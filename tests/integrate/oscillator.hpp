// shared test harness: damped harmonic oscillators q'' = −ω²q − c·q' on several channels,
// stepped through the predict → force → correct sequence, and their exact solutions
#pragma once
#include <Eigen/Dense>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "integrate/integrator.hpp"

namespace gs::test {

/// exact state of q'' = −ω²q − c·q' (underdamped, c < 2ω) at time t
struct Exact {
  double q = 0.0;  ///< position, m
  double v = 0.0;  ///< velocity, m/s
};
inline Exact exact_oscillator(double w, double c, double q0, double v0, double t) {
  // q = e^{−βt}(A cos ω_d t + B sin ω_d t), β = c/2, ω_d = √(ω² − β²)
  const double b = c / 2.0;
  const double wd = std::sqrt(w * w - b * b);
  const double A = q0;
  const double B = (v0 + b * q0) / wd;
  const double e = std::exp(-b * t);
  const double cs = std::cos(wd * t);
  const double sn = std::sin(wd * t);
  return {e * (A * cs + B * sn), e * (-b * (A * cs + B * sn) + wd * (-A * sn + B * cs))};
}

/// a set of channels, each holding independent oscillators with its own ω (1/s) and c (1/s)
struct OscillatorSystem {
  std::vector<std::vector<double>> q, v, a;
  std::vector<double> w, c;
  std::vector<Channel> ch;

  /// add a channel with initial positions q0 and velocities v0
  void add(double omega, double damping, std::vector<double> q0, std::vector<double> v0) {
    w.push_back(omega);
    c.push_back(damping);
    a.emplace_back(q0.size(), 0.0);
    q.push_back(std::move(q0));
    v.push_back(std::move(v0));
  }
  /// rebuild the spans (after add, or after copying)
  std::span<const Channel> spans() {
    ch.clear();
    for (std::size_t k = 0; k < q.size(); ++k) ch.push_back({q[k], v[k], a[k]});
    return ch;
  }
  /// accelerations at the current q, v (the "force" stage)
  void forces() {
    for (std::size_t k = 0; k < q.size(); ++k)
      for (std::size_t i = 0; i < q[k].size(); ++i)
        a[k][i] = -w[k] * w[k] * q[k][i] - c[k] * v[k][i];
  }
  void init(Integrator& I, double dt) {
    forces();
    I.init(spans(), dt);
  }
  /// one full step: predict → forces at the predicted state → correct
  void step(Integrator& I, double dt) {
    auto s = spans();
    I.predict(s, dt, ThreadTeam{});
    forces();
    I.correct(s, dt, ThreadTeam{});
  }
};

/// one oscillator from (q0, v0) integrated to time T with step dt; returns the phase-space
/// error √(Δq² + (Δv/ω)²) against the exact solution
inline double oscillator_error(Integrator& I, double w, double c, double q0, double v0, double dt,
                               double T) {
  OscillatorSystem s;
  s.add(w, c, {q0}, {v0});
  s.init(I, dt);
  const long n = std::lround(T / dt);
  for (long k = 0; k < n; ++k) s.step(I, dt);
  const Exact e = exact_oscillator(w, c, q0, v0, T);
  return std::hypot(s.q[0][0] - e.q, (s.v[0][0] - e.v) / w);
}

/// least-squares slope of log(err) against log(dt): the observed global order
inline double fitted_order(const std::vector<double>& dts, const std::vector<double>& errs) {
  Eigen::MatrixXd X(dts.size(), 2);
  Eigen::VectorXd y(dts.size());
  for (std::size_t i = 0; i < dts.size(); ++i) {
    X(static_cast<Eigen::Index>(i), 0) = 1.0;
    X(static_cast<Eigen::Index>(i), 1) = std::log(dts[i]);
    y(static_cast<Eigen::Index>(i)) = std::log(errs[i]);
  }
  const Eigen::VectorXd beta = X.colPivHouseholderQr().solve(y);
  return beta(1);
}

}  // namespace gs::test
