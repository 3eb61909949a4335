// the ideal quadron solution (paper section II.E and V; P.21–P.26): mean volume fraction,
// fluctuations and partition function of N z̄ independent cells whose volumes lie uniformly
// (flat density of states) in [V₀ − Δ, V₀ + Δ], and a Levenberg–Marquardt fit of its two
// free parameters a = N z̄/V_g and β₀ to measured (β̂, φ̄) with β = β̂ + β₀.
#pragma once
#include <string>
#include <vector>

namespace gs {

/// the packing limits that fix V₀ and Δ (P.24, P.25)
struct QuadronParams {
  double phi_rlp = 0.81;   ///< random loose packing, φ̄ at β → 0, dimensionless
  double phi_rcp = 0.855;  ///< random close packing, φ̄ at β → ∞, dimensionless
  /// Δφ⁻¹ = φ_rlp⁻¹ − φ_rcp⁻¹, dimensionless
  double delta_inv() const { return 1.0 / phi_rlp - 1.0 / phi_rcp; }
};

/// Langevin function L(x) = coth x − 1/x (odd; series near 0)
double langevin(double x);
/// L'(x) = 1/x² − 1/sinh² x
double langevin_deriv(double x);
/// the x with L(x) = u, −1 < u < 1
double langevin_inverse(double u);

/// φ̄⁻¹ of (P.26) at inverse compactivity β (1/m²) for a = N z̄/V_g (1/m²):
/// φ̄⁻¹ = φ_rlp⁻¹ + a/β − Δφ⁻¹ coth(β Δφ⁻¹/a) = φ_rlp⁻¹ − Δφ⁻¹ L(β Δφ⁻¹/a)
double quadron_inv_phi(double beta, double a, const QuadronParams& p = {});
/// φ̄ of (P.26), dimensionless
double quadron_phi(double beta, double a, const QuadronParams& p = {});
/// ∂φ̄/∂β of (P.26), m²
double quadron_dphi_dbeta(double beta, double a, const QuadronParams& p = {});
/// the β (1/m²) at which (P.26) gives φ̄; needs φ̄⁻¹ within φ_rlp⁻¹ ± Δφ⁻¹
double quadron_beta_of_phi(double phi, double a, const QuadronParams& p = {});
/// σ_φ predicted by (P.17) with (P.26): σ_φ² = φ̄⁴ (Δφ⁻¹)² L'(x)/(a V_g), x = β Δφ⁻¹/a;
/// v_g is the grain volume of the test region, m²
double quadron_sigma_phi(double beta, double a, double v_g, const QuadronParams& p = {});
/// ln Z of the ideal quadron gas (P.21) in terms of a, V_g and the packing limits:
/// ln Z = a V_g ln(sinh x/x) − β V_g/φ_rlp, x = β Δφ⁻¹/a (dimensionless)
double quadron_lnz(double beta, double a, double v_g, const QuadronParams& p = {});

/// result of the fit of (P.26) with β = β̂ + β₀
struct QuadronFit {
  bool converged = false;      ///< the Levenberg–Marquardt iteration met its tolerance
  std::string note;            ///< what went wrong, if anything
  int iterations = 0;          ///< LM iterations used
  int points = 0;              ///< data points used
  double a = 0.0;              ///< N z̄/V_g, 1/m²
  double a_err = 0.0;          ///< standard error of a, 1/m²
  double beta0 = 0.0;          ///< the additive constant β₀ of the relative β̂, 1/m²
  double beta0_err = 0.0;      ///< standard error of β₀, 1/m²
  double cov_a_beta0 = 0.0;    ///< covariance of a and β₀, 1/m⁴
  double chi2 = 0.0;           ///< Σ (residual/σ_eff)², dimensionless
  int dof = 0;                 ///< points − 2
  bool errors_scaled = false;  ///< true when no errors were given: covariance scaled by χ²/dof
};

/// fit a = N z̄/V_g and β₀ by Levenberg–Marquardt to φ̄_i at β̂_i + β₀ (P.26). Residuals are
/// φ̄_i − φ̄(β̂_i + β₀) over the effective-variance error σ_i² = σ_φ,i² + (∂φ̄/∂β)² σ_β̂,i²
/// (either error list may be empty = zero). The starting point comes from the exact
/// linearisation β̂_i = a g_i − β₀ with g_i = L⁻¹((φ_rlp⁻¹ − φ̄_i⁻¹)/Δφ⁻¹)/Δφ⁻¹.
QuadronFit fit_quadron(const std::vector<double>& beta_hat, const std::vector<double>& phi,
                       const std::vector<double>& phi_err, const std::vector<double>& beta_err,
                       const QuadronParams& p = {});

}  // namespace gs
