// the analytic steady state of appendix B (B.31–B.32) and the numerics it needs
#include "models/interval_theory.hpp"

#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace gs::models {

namespace {

// the hypergeometric series, for |z| ≤ ½ (terms fall at least as fast as 2⁻ⁿ)
double series(double a, double b, double c, double z) {
  double term = 1.0, sum = 1.0;
  for (int n = 0; n < 5000; ++n) {
    term *= (a + n) * (b + n) / ((c + n) * (n + 1.0)) * z;
    sum += term;
    if (std::abs(term) < 1e-17 * std::abs(sum)) break;
  }
  return sum;
}

}  // namespace

double hyp2f1(double a, double b, double c, double z) {
  if (z < 0.0 || z > 1.0) throw InputError("hyp2f1", "z", "implemented for 0 ≤ z ≤ 1 only");
  if (z <= 0.5) return series(a, b, c, z);
  // connection to 1 − z (Abramowitz & Stegun 15.3.6)
  const double s = c - a - b;
  if (std::abs(s - std::round(s)) < 1e-12)
    throw InputError("hyp2f1", "c", "c − a − b is an integer: the connection formula is singular");
  const double w = 1.0 - z;
  const double t1 = std::tgamma(c) * std::tgamma(s) / (std::tgamma(c - a) * std::tgamma(c - b));
  const double t2 = std::tgamma(c) * std::tgamma(-s) / (std::tgamma(a) * std::tgamma(b));
  return t1 * series(a, b, 1.0 - s, w) +
         (w > 0.0 ? t2 * std::pow(w, s) * series(c - a, c - b, 1.0 + s, w) : 0.0);
}

double tanh_sinh(const std::function<double(double, double, double)>& f, double a, double b) {
  // y = mid + half·tanh(π/2 sinh t), t = k h for |t| ≤ 4.5: nodes crowd both ends doubly
  // exponentially, so integrable end singularities cost nothing
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b), h = 1.0 / 64.0;
  double sum = 0.0;
  for (int k = -288; k <= 288; ++k) {
    const double t = k * h, s = 0.5 * std::numbers::pi * std::sinh(t);
    const double cs = std::cosh(s);
    const double w = half * 0.5 * std::numbers::pi * std::cosh(t) / (cs * cs);
    // distances to the ends: half(1 ± tanh s) without cancellation
    const double da = half * 2.0 / (std::exp(-2.0 * s) + 1.0);
    const double db = half * 2.0 / (std::exp(2.0 * s) + 1.0);
    if (!(da > 0.0) || !(db > 0.0) || !(w > 0.0)) continue;
    sum += w * f(mid + half * std::tanh(s), da, db);
  }
  return sum * h;
}

double appendix_b_f(double y) {
  return hyp2f1(-1.0 / 3.0, 1.0, 5.0 / 6.0, 1.0 - y) - hyp2f1(-1.0 / 3.0, 1.0, 5.0 / 6.0, y);
}

namespace {
double k_const() {
  return std::tgamma(1.0 / 6.0) /
         (2.0 * std::sqrt(3.0) * std::tgamma(1.0 / 3.0) * std::tgamma(5.0 / 6.0));
}
}  // namespace

double appendix_b_density(double xi, double u) {
  if (!(xi > 0.0) || xi > 1.0 || !(u > 0.0))
    throw InputError("appendix_b_density", "xi", "needs 0 < ξ ≤ 1 and u > 0");
  const double u3 = u * u * u;
  // the hypergeometric term: the singular ends are y → 0, y → 1 (weights) and y → ξ (kernel)
  const double i1 = tanh_sinh(
      [xi, u3](double y, double dy0, double dyx) {
        const double one_minus_y = xi == 1.0 ? dyx : 1.0 - y;
        return std::exp(-u3 / (9.0 * dyx)) * std::pow(dyx, -2.0 / 3.0) *
               std::pow(dy0 * one_minus_y, -1.0 / 6.0) * appendix_b_f(y);
      },
      0.0, xi);
  // the source term
  const double i2 =
      tanh_sinh([u3](double, double y,
                     double) { return std::pow(y, -2.0 / 3.0) * std::exp(-u3 / (9.0 * y)); },
                0.0, xi);
  return -k_const() * i1 + i2;
}

double appendix_b_arrival_density(double u) {
  // ∫₀^∞ u p(1, u) du = Γ(⅔) 3^(1/3): the u-integrals are Γ(⅔)(9s)^(2/3)/3 and F is odd about ½
  return u * appendix_b_density(1.0, u) / (std::tgamma(2.0 / 3.0) * std::cbrt(3.0));
}

double appendix_b_mean_exit_time_coefficient() {
  // ∫₀¹ [y(1−y)]^(−1/6) (1−y)^(2/3) F(y) dy folded onto [0, ½] with F(1−y) = −F(y)
  const double j = tanh_sinh(
      [](double y, double dy0, double) {
        return std::pow(dy0 * (1.0 - y), -1.0 / 6.0) * appendix_b_f(y) *
               (std::pow(1.0 - y, 2.0 / 3.0) - std::pow(y, 2.0 / 3.0));
      },
      0.0, 0.5);
  return std::tgamma(4.0 / 3.0) * std::cbrt(3.0) / std::tgamma(2.0 / 3.0) *
         (0.9 - 1.5 * k_const() * j);
}

}  // namespace gs::models
