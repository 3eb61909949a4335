// test harness for the force laws: a classical RK4 step for small ODE systems (independent of
// src/integrate, so the laws are checked against a reference integrator), a 1D two-body
// normal collision driven by any law F(h, ḣ), and its analytic linear spring–dashpot solution
#pragma once
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <numbers>

namespace gs::test {

/// one RK4 step of y' = f(y)
template <std::size_t N, class F>
std::array<double, N> rk4(const std::array<double, N>& y, double dt, F&& f) {
  auto axpy = [](const std::array<double, N>& a, double s, const std::array<double, N>& b) {
    std::array<double, N> r{};
    for (std::size_t i = 0; i < N; ++i) r[i] = a[i] + s * b[i];
    return r;
  };
  const auto k1 = f(y);
  const auto k2 = f(axpy(y, dt / 2.0, k1));
  const auto k3 = f(axpy(y, dt / 2.0, k2));
  const auto k4 = f(axpy(y, dt, k3));
  std::array<double, N> r{};
  for (std::size_t i = 0; i < N; ++i)
    r[i] = y[i] + dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  return r;
}

/// outcome of a 1D normal collision
struct Collision {
  double restitution = 0.0;  ///< −ḣ(end)/ḣ(0), dimensionless
  double duration = 0.0;     ///< time from touching to separating (h back to 0), s
};

/// the overlap h (m) of two bodies with reduced mass m (kg) that touch at t = 0 approaching at
/// v0 (m/s): m·ḧ = −F(h, ḣ) until h returns to 0. The end is located by linear interpolation
/// inside the last step (error O(Δt²), far below the tolerances at Δt = t_c/1000).
inline Collision collide(const std::function<double(double, double)>& force, double m, double v0,
                         double dt) {
  std::array<double, 2> y{0.0, v0};
  auto f = [&](const std::array<double, 2>& s) {
    return std::array<double, 2>{s[1], -force(s[0], s[1]) / m};
  };
  double t = 0.0;
  for (long k = 0; k < 100000000L; ++k) {
    const auto n = rk4<2>(y, dt, f);
    if (n[0] < 0.0 && k > 0) {
      const double s = y[0] / (y[0] - n[0]);  // fraction of the step where h = 0
      return {-(y[1] + s * (n[1] - y[1])) / v0, t + s * dt};
    }
    y = n;
    t += dt;
  }
  return {};
}

/// analytic linear spring–dashpot m·ḧ + c·ḣ + k·h = 0 from h = 0, ḣ = v0 (underdamped)
struct LinearContact {
  double beta;  ///< c/(2m), 1/s
  double w0;    ///< √(k/m), rad/s
  double wd;    ///< √(ω0² − β²), rad/s
  LinearContact(double k, double c, double m)
      : beta(c / (2.0 * m)), w0(std::sqrt(k / m)), wd(std::sqrt(k / m - beta * beta)) {}
  /// ḣ(t)/v0
  double hdot(double t) const {
    return std::exp(-beta * t) * (std::cos(wd * t) - beta / wd * std::sin(wd * t));
  }
  /// h(t)/v0, s
  double h(double t) const { return std::exp(-beta * t) * std::sin(wd * t) / wd; }
  /// restitution and duration without clipping: e^{−βπ/ω_d}, π/ω_d
  double restitution() const { return std::exp(-beta * std::numbers::pi / wd); }
  double duration() const { return std::numbers::pi / wd; }
  /// restitution with the force clipped at zero: the force k·h + c·ḣ ∝ ω0²h + 2βḣ first
  /// vanishes at t* < π/ω_d; from then on the bodies fly apart at ḣ(t*) (bisection for t*)
  double clipped_restitution() const {
    auto F = [&](double t) { return w0 * w0 * h(t) + 2.0 * beta * hdot(t); };
    double lo = 0.0, hi = duration();
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (F(mid) > 0.0 ? lo : hi) = mid;
    }
    return -hdot(0.5 * (lo + hi));
  }
};

}  // namespace gs::test
