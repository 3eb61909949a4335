// least-squares fits for the RFM analyses: weighted line, power law on logs, Levenberg–Marquardt
#include "analysis/rfm_fit.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "analysis/least_squares.hpp"
#include "core/error.hpp"

namespace gs::rfm {

LineFit fit_line(std::span<const double> x, std::span<const double> y,
                 std::span<const double> sigma) {
  const std::size_t n = x.size();
  if (y.size() != n || (!sigma.empty() && sigma.size() != n))
    throw InputError("fit_line", "", "x, y and sigma must have the same length");
  if (n < 2) throw InputError("fit_line", "", "need at least two points, got " + std::to_string(n));
  const bool weighted = !sigma.empty();

  // normal equations of the weighted line (T.A.7 with a linear model)
  double s = 0, sx = 0, sy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = weighted ? 1.0 / (sigma[i] * sigma[i]) : 1.0;
    s += w;
    sx += w * x[i];
    sy += w * y[i];
  }
  const double xm = sx / s, ym = sy / s;
  // centred sums keep the solution accurate when x is far from 0
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = weighted ? 1.0 / (sigma[i] * sigma[i]) : 1.0;
    sxx += w * (x[i] - xm) * (x[i] - xm);
    sxy += w * (x[i] - xm) * (y[i] - ym);
  }
  if (!(sxx > 0.0)) throw InputError("fit_line", "", "all x values are equal");

  LineFit f;
  f.points = static_cast<int>(n);
  f.b = sxy / sxx;
  f.a = ym - f.b * xm;
  double var_b = 1.0 / sxx;
  double var_a = 1.0 / s + xm * xm / sxx;
  double cov = -xm / sxx;

  // χ² of the residuals
  for (std::size_t i = 0; i < n; ++i) {
    const double w = weighted ? 1.0 / (sigma[i] * sigma[i]) : 1.0;
    const double r = y[i] - f.a - f.b * x[i];
    f.chi2 += w * r * r;
  }
  // unit weights carry no error scale: take it from the scatter
  if (!weighted && n > 2) {
    const double s2 = f.chi2 / static_cast<double>(n - 2);
    var_a *= s2;
    var_b *= s2;
    cov *= s2;
  }
  f.a_err = std::sqrt(var_a);
  f.b_err = std::sqrt(var_b);
  f.cov_ab = cov;
  return f;
}

PowerLawFit fit_power_law(std::span<const double> x, std::span<const double> y,
                          std::span<const double> y_err) {
  if (y.size() != x.size() || (!y_err.empty() && y_err.size() != x.size()))
    throw InputError("fit_power_law", "", "x, y and y_err must have the same length");
  // logarithms of the usable points, σ_ln y = σ_y / y
  std::vector<double> lx, ly, ls;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0.0) || !(y[i] > 0.0)) continue;
    if (!y_err.empty() && !(y_err[i] > 0.0)) continue;
    lx.push_back(std::log(x[i]));
    ly.push_back(std::log(y[i]));
    if (!y_err.empty()) ls.push_back(y_err[i] / y[i]);
  }
  const LineFit lf = fit_line(lx, ly, ls);
  PowerLawFit p;
  p.exponent = lf.b;
  p.amplitude = std::exp(lf.a);
  p.chi2_r = lf.chi2_r();
  p.points = lf.points;
  // a poor model inflates the quoted error (weighted case only; unweighted is already scaled)
  const double inflate = (!y_err.empty() && p.chi2_r > 1.0) ? std::sqrt(p.chi2_r) : 1.0;
  p.exponent_err = lf.b_err * inflate;
  p.ln_amplitude_err = lf.a_err * inflate;
  return p;
}

LmResult fit_lm(const Model& f, std::span<const double> x, std::span<const double> y,
                std::span<const double> sigma, Eigen::VectorXd p0, const LmOptions& opt) {
  const std::size_t n = x.size();
  if (y.size() != n || sigma.size() != n)
    throw InputError("fit_lm", "", "x, y and sigma must have the same length");
  if (n <= static_cast<std::size_t>(p0.size()))
    throw InputError("fit_lm", "",
                     "need more points (" + std::to_string(n) + ") than parameters (" +
                         std::to_string(p0.size()) + ")");
  const auto rows = static_cast<Eigen::Index>(n);
  // r_i = (y_i − f(x_i))/σ_i; ∂r_i/∂p_k by central differences
  const Residuals residuals = [&](const Eigen::VectorXd& p, Eigen::VectorXd& r,
                                  Eigen::MatrixXd* jac) {
    r.resize(rows);
    for (std::size_t i = 0; i < n; ++i)
      r[static_cast<Eigen::Index>(i)] = (y[i] - f(x[i], p)) / sigma[i];
    if (jac) {
      jac->resize(rows, p.size());
      for (Eigen::Index k = 0; k < p.size(); ++k) {
        const double h = 1e-6 * std::max(std::abs(p[k]), 1e-8);
        Eigen::VectorXd pp = p, pm = p;
        pp[k] += h;
        pm[k] -= h;
        for (std::size_t i = 0; i < n; ++i)
          (*jac)(static_cast<Eigen::Index>(i), k) =
              -(f(x[i], pp) - f(x[i], pm)) / (2.0 * h) / sigma[i];
      }
    }
    return r.squaredNorm();
  };
  LmSettings s;
  s.max_iterations = opt.max_iterations;
  s.rel_tol = opt.rel_tol;
  s.lambda0 = opt.lambda0;
  const LmOutcome o = levenberg_marquardt(residuals, std::move(p0), s);

  LmResult r;
  r.p = o.p;
  r.chi2 = o.chi2;
  r.iterations = o.iterations;
  r.converged = o.converged;
  // covariance from the curvature at the minimum
  r.cov = (o.jac.transpose() * o.jac).completeOrthogonalDecomposition().pseudoInverse();
  r.err = r.cov.diagonal().cwiseMax(0.0).cwiseSqrt();
  r.dof = static_cast<int>(n) - static_cast<int>(r.p.size());
  return r;
}

}  // namespace gs::rfm
