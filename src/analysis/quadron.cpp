// the ideal quadron solution (P.21–P.26), its fluctuations (P.17) and the fit of (P.26)
//
// notation: a = N z̄/V_g (1/m²), Δφ⁻¹ = φ_rlp⁻¹ − φ_rcp⁻¹, x = β Δφ⁻¹/a.
// from (P.24) and (P.25) the per-cell limits are V₀ = V_g φ_rlp⁻¹/(N z̄) = 1/(a φ_rlp) and
// Δ = V_g Δφ⁻¹/(N z̄) = Δφ⁻¹/a, so βΔ = x and (P.26) reads φ̄⁻¹ = φ_rlp⁻¹ − Δφ⁻¹ L(x), with
// L(x) = coth x − 1/x the Langevin function (a/β = Δφ⁻¹/x).
//
// σ_φ from (P.17) with (P.26):
//   (P.12) σ_V² = −∂⟨V⟩/∂β, and ⟨V⟩ = V_g/φ̄ (P.15) gives ∂⟨V⟩/∂β = −(V_g/φ̄²) ∂φ̄/∂β;
//   (P.16) σ_φ² = (φ̄⁴/V_g²) σ_V² = (φ̄²/V_g) ∂φ̄/∂β, which is (P.17).
//   From (P.26): ∂φ̄⁻¹/∂β = −Δφ⁻¹ L'(x) ∂x/∂β = −(Δφ⁻¹)² L'(x)/a, and ∂φ̄/∂β = −φ̄² ∂φ̄⁻¹/∂β,
//   so  σ_φ² = φ̄⁴ (Δφ⁻¹)² L'(x) / (a V_g) = φ̄⁴ (Δφ⁻¹)² L'(x) / (N z̄).
//   L'(x) = 1/x² − 1/sinh² x > 0: σ_φ falls from φ̄² Δφ⁻¹/√(3 N z̄) at β → 0 to
//   φ̄² √(a/V_g)/β at large β (each cell then fluctuates like an exponential of mean 1/β).
//
// ln Z from (P.21) with the same substitutions:
//   ln Z = N z̄ [ln(sinh(βΔ)/(βΔ)) − β V₀] = a V_g ln(sinh x/x) − β V_g/φ_rlp.
//   check: −∂ ln Z/∂β = −V_g L(x) Δφ⁻¹ + V_g/φ_rlp = V_g φ̄⁻¹ = ⟨V⟩ (P.10, P.15).
#include "analysis/quadron.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis/least_squares.hpp"

namespace gs {

double langevin(double x) {
  // series below 0.05 (next term x⁹/93555·2 < 1e-16 there), closed form above
  if (std::abs(x) < 0.05) {
    const double x2 = x * x;
    return x * (1.0 / 3.0 - x2 * (1.0 / 45.0 - x2 * (2.0 / 945.0 - x2 / 4725.0)));
  }
  return 1.0 / std::tanh(x) - 1.0 / x;
}

double langevin_deriv(double x) {
  if (std::abs(x) < 0.05) {
    const double x2 = x * x;
    return 1.0 / 3.0 - x2 * (1.0 / 15.0 - x2 * (2.0 / 189.0 - x2 / 675.0));
  }
  const double s = std::sinh(x);
  return 1.0 / (x * x) - (std::isinf(s) ? 0.0 : 1.0 / (s * s));
}

double langevin_inverse(double u) {
  if (!(u > -1.0 && u < 1.0)) throw std::invalid_argument("langevin_inverse: |u| must be < 1");
  if (u < 0.0) return -langevin_inverse(-u);
  // L(x) < 1 − 1/x for x > 0, so the root lies below 1/(1 − u); bisection to round-off
  double lo = 0.0;
  double hi = 1.0 / (1.0 - u) + 1.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (langevin(mid) < u ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double quadron_inv_phi(double beta, double a, const QuadronParams& p) {
  // (P.26) in the Langevin form (exact, and finite at β = 0)
  const double d = p.delta_inv();
  return 1.0 / p.phi_rlp - d * langevin(beta * d / a);
}

double quadron_phi(double beta, double a, const QuadronParams& p) {
  return 1.0 / quadron_inv_phi(beta, a, p);
}

double quadron_dphi_dbeta(double beta, double a, const QuadronParams& p) {
  // ∂φ̄/∂β = φ̄² (Δφ⁻¹)² L'(x)/a
  const double d = p.delta_inv();
  const double phi = quadron_phi(beta, a, p);
  return phi * phi * d * d * langevin_deriv(beta * d / a) / a;
}

double quadron_beta_of_phi(double phi, double a, const QuadronParams& p) {
  const double d = p.delta_inv();
  return a / d * langevin_inverse((1.0 / p.phi_rlp - 1.0 / phi) / d);
}

double quadron_sigma_phi(double beta, double a, double v_g, const QuadronParams& p) {
  // (P.17): σ_φ² = (φ̄²/V_g) ∂φ̄/∂β (derivation at the top of this file)
  const double phi = quadron_phi(beta, a, p);
  return std::sqrt(phi * phi / v_g * quadron_dphi_dbeta(beta, a, p));
}

double quadron_lnz(double beta, double a, double v_g, const QuadronParams& p) {
  // (P.21): ln Z = a V_g ln(sinh x/x) − β V_g/φ_rlp, ln(sinh x/x) even and evaluated stably
  const double x = std::abs(beta * p.delta_inv() / a);
  double lsx;
  if (x < 1e-4) {
    lsx = x * x / 6.0;
  } else if (x > 20.0) {
    lsx = x - std::log(2.0) - std::log(x) + std::log1p(-std::exp(-2.0 * x));
  } else {
    lsx = std::log(std::sinh(x) / x);
  }
  return a * v_g * lsx - beta * v_g / p.phi_rlp;
}

QuadronFit fit_quadron(const std::vector<double>& beta_hat, const std::vector<double>& phi,
                       const std::vector<double>& phi_err, const std::vector<double>& beta_err,
                       const QuadronParams& p) {
  const std::size_t n = beta_hat.size();
  if (phi.size() != n || (!phi_err.empty() && phi_err.size() != n) ||
      (!beta_err.empty() && beta_err.size() != n))
    throw std::invalid_argument("fit_quadron: β̂, φ̄ and error lists must have equal lengths");
  QuadronFit f;
  f.points = static_cast<int>(n);
  f.dof = static_cast<int>(n) - 2;
  if (n < 3) {
    f.note = "needs at least 3 points";
    return f;
  }
  const double d = p.delta_inv();
  const bool weighted = !phi_err.empty() || !beta_err.empty();
  auto sphi = [&](std::size_t i) { return phi_err.empty() ? 0.0 : phi_err[i]; };
  auto sbeta = [&](std::size_t i) { return beta_err.empty() ? 0.0 : beta_err[i]; };

  // start: for fixed a, β_i = a g_i exactly, so β̂_i = a g_i − β₀ is a straight line in g
  {
    double sg = 0.0, sb = 0.0, sgg = 0.0, sgb = 0.0;
    int m = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double u = std::clamp((1.0 / p.phi_rlp - 1.0 / phi[i]) / d, -0.99, 0.99);
      const double g = langevin_inverse(u) / d;
      sg += g;
      sb += beta_hat[i];
      sgg += g * g;
      sgb += g * beta_hat[i];
      ++m;
    }
    const double den = m * sgg - sg * sg;
    f.a = den != 0.0 ? (m * sgb - sg * sb) / den : 0.0;
    if (!(f.a > 0.0)) {
      // no usable slope (noise or φ̄ outside the limits): a scale from the β̂ spread
      const auto [lo, hi] = std::minmax_element(beta_hat.begin(), beta_hat.end());
      f.a = std::max(1.0, (*hi - *lo) * d);
    }
    f.beta0 = (f.a * sg - sb) / m;
  }

  // residuals r_i = (φ̄_i − φ̄(β̂_i + β₀; a))/σ_i and their Jacobian J = ∂r/∂(a, β₀)
  const Residuals residuals = [&](const Eigen::VectorXd& q, Eigen::VectorXd& r,
                                  Eigen::MatrixXd* jac) {
    const double a = q(0), b0 = q(1);
    if (!(a > 0.0) || !std::isfinite(a) || !std::isfinite(b0))
      return std::numeric_limits<double>::quiet_NaN();
    r.resize(static_cast<Eigen::Index>(n));
    if (jac) jac->resize(static_cast<Eigen::Index>(n), 2);
    for (std::size_t i = 0; i < n; ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      const double beta = beta_hat[i] + b0;
      const double x = beta * d / a;
      const double ph = quadron_phi(beta, a, p);
      const double lp = langevin_deriv(x);
      const double dphi_db = ph * ph * d * d * lp / a;  // ∂φ̄/∂β = ∂φ̄/∂β₀
      const double dphi_da = -ph * ph * d * lp * x / a;  // ∂φ̄/∂a = −φ̄² ∂φ̄⁻¹/∂a
      // effective variance: the β̂ error moves the point along the curve's slope
      double s = 1.0;
      if (weighted) {
        s = std::sqrt(sphi(i) * sphi(i) + dphi_db * dphi_db * sbeta(i) * sbeta(i));
        if (!(s > 0.0)) s = 1e-300;
      }
      r(row) = (phi[i] - ph) / s;
      if (jac) {
        (*jac)(row, 0) = -dphi_da / s;
        (*jac)(row, 1) = -dphi_db / s;
      }
    }
    return r.squaredNorm();
  };
  LmSettings s;
  s.grow = 4.0;
  s.lambda_max = 1e20;
  s.rel_tol = 1e-13;
  s.stall_below_lambda = 1.0;  // a stall counts only under nearly Gauss–Newton steps
  s.small_step = [d](const Eigen::VectorXd& q, const Eigen::VectorXd& step) {
    return std::abs(step(0)) <= 1e-10 * std::abs(q(0)) &&
           std::abs(step(1)) <= 1e-10 * (std::abs(q(1)) + q(0) / d);
  };
  const LmOutcome o = levenberg_marquardt(residuals, Eigen::Vector2d(f.a, f.beta0), s);
  f.a = o.p(0);
  f.beta0 = o.p(1);
  f.iterations = o.iterations + 1;
  f.converged = o.converged;
  const double chi2 = o.chi2;
  const Eigen::MatrixXd& jac = o.jac;
  if (!f.converged) f.note = "Levenberg-Marquardt did not converge in 500 iterations";

  // covariance (JᵀJ)⁻¹ of the weighted problem; unweighted: scaled by χ²/dof
  Eigen::Matrix2d cov = (jac.transpose() * jac).inverse();
  f.chi2 = chi2;
  if (!weighted && f.dof > 0) {
    cov *= chi2 / f.dof;
    f.errors_scaled = true;
  }
  f.a_err = std::sqrt(cov(0, 0));
  f.beta0_err = std::sqrt(cov(1, 1));
  f.cov_a_beta0 = cov(0, 1);
  return f;
}

}  // namespace gs
