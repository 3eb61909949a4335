// least-squares fits shared by the Random Force Model analyses (thesis chapters 3–5 and
// appendix A): a weighted straight line, a power law fitted on logarithms, and a
// Levenberg–Marquardt fit for the nonlinear forms (crossover T.5.32, free paths T.4.25).
// All fits minimise χ² = Σ((y − f)/σ)² (T.A.7) and report χ²_r = χ²/(n − n_par).
#pragma once
#include <Eigen/Dense>
#include <functional>
#include <span>
#include <vector>

namespace gs::rfm {

/// a weighted straight-line fit y = a + b·x
struct LineFit {
  double a = 0.0;       ///< intercept, units of y
  double b = 0.0;       ///< slope, units of y per unit of x
  double a_err = 0.0;   ///< standard error of a from the given σ, units of y
  double b_err = 0.0;   ///< standard error of b from the given σ, units of y/x
  double cov_ab = 0.0;  ///< covariance of a and b, units of y²/x
  double chi2 = 0.0;    ///< Σ((y − a − b·x)/σ)², dimensionless
  int points = 0;       ///< data points used
  /// reduced χ², χ²/(n − 2); 0 when n ≤ 2
  double chi2_r() const { return points > 2 ? chi2 / (points - 2) : 0.0; }
};

/// weighted least-squares line. An empty `sigma` means unit weights, in which case the
/// errors are scaled by the residual scatter (χ²_r) since no error estimate was given.
/// Throws gs::InputError when fewer than two points or the x values are all equal.
LineFit fit_line(std::span<const double> x, std::span<const double> y,
                 std::span<const double> sigma = {});

/// a power law y = A·x^p fitted as a straight line on ln y against ln x
struct PowerLawFit {
  double exponent = 0.0;          ///< p, dimensionless
  double exponent_err = 0.0;      ///< standard error of p (inflated by √χ²_r when χ²_r > 1)
  double amplitude = 0.0;         ///< A, units of y/x^p
  double ln_amplitude_err = 0.0;  ///< standard error of ln A (inflated like exponent_err)
  double chi2_r = 0.0;            ///< reduced χ² of the fit on logarithms, dimensionless
  int points = 0;                 ///< points used (those with x > 0 and y > 0)
};

/// fits y = A·x^p using only points with x > 0 and y > 0; σ_ln y = y_err/y. An empty
/// `y_err` means unit weights on the logarithms.
PowerLawFit fit_power_law(std::span<const double> x, std::span<const double> y,
                          std::span<const double> y_err = {});

/// options of the Levenberg–Marquardt minimiser
struct LmOptions {
  int max_iterations = 500;  ///< iteration cap
  double rel_tol = 1e-12;    ///< stop when χ² improves by less than this fraction
  double lambda0 = 1e-3;     ///< initial damping, dimensionless
};

/// the result of a nonlinear least-squares fit
struct LmResult {
  Eigen::VectorXd p;    ///< best parameters, model units
  Eigen::VectorXd err;  ///< standard errors √diag(cov), model units
  Eigen::MatrixXd cov;  ///< covariance (JᵀWJ)⁻¹ from the given σ (not scaled by χ²_r)
  double chi2 = 0.0;    ///< χ² at the minimum, dimensionless
  int dof = 0;          ///< degrees of freedom n − n_par
  int iterations = 0;   ///< iterations used
  bool converged = false;
  double chi2_r() const { return dof > 0 ? chi2 / dof : 0.0; }
};

/// a model f(x; p)
using Model = std::function<double(double x, const Eigen::VectorXd& p)>;

/// Levenberg–Marquardt fit of f(x; p) to (x, y ± σ) with a central-difference Jacobian.
/// Throws gs::InputError when there are not more points than parameters.
LmResult fit_lm(const Model& f, std::span<const double> x, std::span<const double> y,
                std::span<const double> sigma, Eigen::VectorXd p0, const LmOptions& opt = {});

}  // namespace gs::rfm
