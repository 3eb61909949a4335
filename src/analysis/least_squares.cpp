#include "analysis/least_squares.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs {

LmOutcome levenberg_marquardt(const Residuals& residuals, Eigen::VectorXd p0, const LmSettings& s) {
  LmOutcome o;
  o.p = std::move(p0);
  o.chi2 = residuals(o.p, o.r, &o.jac);
  double lambda = s.lambda0;
  for (o.iterations = 0; o.iterations < s.max_iterations; ++o.iterations) {
    const Eigen::MatrixXd jtj = o.jac.transpose() * o.jac;
    const Eigen::VectorXd g = o.jac.transpose() * o.r;
    bool accepted = false;
    // raise λ until a step lowers χ²
    while (lambda < s.lambda_max) {
      Eigen::MatrixXd a = jtj;
      for (Eigen::Index k = 0; k < a.rows(); ++k) a(k, k) += lambda * std::max(jtj(k, k), 1e-300);
      const Eigen::VectorXd step = -a.ldlt().solve(g);
      const Eigen::VectorXd trial = o.p + step;
      Eigen::VectorXd r;
      const double c = step.allFinite() ? residuals(trial, r, nullptr)
                                        : std::numeric_limits<double>::quiet_NaN();
      if (std::isfinite(c) && c <= o.chi2) {
        const double drop = o.chi2 - c, old = o.chi2;
        const bool stalled =
            lambda < s.stall_below_lambda && drop <= s.rel_tol * std::max(old, 1e-300);
        o.p = trial;
        o.chi2 = residuals(o.p, o.r, &o.jac);
        o.converged = stalled || (s.small_step && s.small_step(o.p, step));
        lambda = std::max(lambda * s.shrink, 1e-12);
        accepted = true;
        break;
      }
      lambda *= s.grow;
    }
    if (!accepted) {
      o.converged = true;  // no step lowers χ² at any damping: at the minimum within round-off
      break;
    }
    if (o.converged) break;
  }
  return o;
}

}  // namespace gs
