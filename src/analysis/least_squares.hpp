// one Levenberg–Marquardt minimiser for every nonlinear fit of the analyses (the RFM fits, the
// ideal-quadron fit): the caller supplies weighted residuals and their Jacobian
#pragma once
#include <Eigen/Dense>
#include <functional>
#include <limits>

namespace gs {

/// weighted residuals r_i(p) = (y_i − f(x_i; p))/σ_i and, when `jac` is not null, the
/// Jacobian ∂r_i/∂p_k; returns χ² = Σ r_i², or NaN when p is outside the model's domain
using Residuals =
    std::function<double(const Eigen::VectorXd& p, Eigen::VectorXd& r, Eigen::MatrixXd* jac)>;

/// when a step counts as the last one
struct LmSettings {
  int max_iterations = 500;  ///< iteration cap
  double lambda0 = 1e-3;     ///< initial damping, dimensionless
  double grow = 10.0;        ///< damping factor after a rejected step
  double shrink = 0.2;       ///< damping factor after an accepted step
  double lambda_max = 1e16;  ///< no step lowers χ² even at this damping: at the minimum
  double rel_tol = 1e-12;  ///< converged when an accepted step lowers χ² by less than this fraction
  /// …counted only while the damping is below this (near Gauss–Newton steps)
  double stall_below_lambda = std::numeric_limits<double>::infinity();
  /// optional: converged when this says the accepted step is negligible against p
  std::function<bool(const Eigen::VectorXd& p, const Eigen::VectorXd& step)> small_step;
};

/// the minimum and the residuals and Jacobian there (for the covariance (JᵀJ)⁻¹)
struct LmOutcome {
  Eigen::VectorXd p;
  Eigen::VectorXd r;
  Eigen::MatrixXd jac;
  double chi2 = 0.0;
  int iterations = 0;
  bool converged = false;
};

/// damped Gauss–Newton steps (JᵀJ + λ diag JᵀJ) δ = −Jᵀr with Marquardt's diagonal scaling, so
/// that parameters of very different size (a ~ 10², β₀ ~ 10⁴) are stepped alike
LmOutcome levenberg_marquardt(const Residuals& residuals, Eigen::VectorXd p0,
                              const LmSettings& s = {});

}  // namespace gs
