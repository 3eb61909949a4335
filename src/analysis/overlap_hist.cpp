// overlapping histograms (P.19, P.20, P.39): binomial fits of histogram pairs, or weighted
// least squares on kernel estimates; straight line for β and ln Z, parabola for linearity
#include "analysis/overlap_hist.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis/stats.hpp"
#include "core/numbers.hpp"

namespace gs {

namespace {

double binomial(int n, int k) {
  double r = 1.0;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

// correlation of a kernel estimate at two points a distance d·h apart: (K*K)(d)/(K*K)(0)
double kernel_autocorr(Kernel k, double d) {
  const double reach = kernel_reach(k);
  const int steps = 2000;
  const double du = 2.0 * reach / steps;
  double num = 0.0;
  double den = 0.0;
  for (int i = 0; i <= steps; ++i) {
    const double u = -reach + i * du;
    num += kernel_value(k, u) * kernel_value(k, u + d);
    den += kernel_value(k, u) * kernel_value(k, u);
  }
  return den > 0.0 ? num / den : 0.0;
}

// how many grid points (spacing dx) one kernel estimate is correlated over: Σ_k ρ(k dx/h)
double correlated_points(Kernel k, double h, double dx) {
  double sum = 1.0;
  for (int j = 1; j < 100000; ++j) {
    const double r = kernel_autocorr(k, j * dx / h);
    if (r < 1e-6) break;
    sum += 2.0 * r;
  }
  return std::max(1.0, sum);
}

// centring and scaling of x, u = (x − x̄)/s, that keeps the normal equations well conditioned
struct Scale {
  double xm = 0.0;  ///< x̄, units of x
  double s = 1.0;   ///< half-range, units of x
  explicit Scale(const std::vector<double>& x) {
    for (double v : x) xm += v;
    xm /= static_cast<double>(x.size());
    s = 0.0;
    for (double v : x) s = std::max(s, std::abs(v - xm));
    if (s <= 0.0) s = 1.0;
  }
  double u(double x) const { return (x - xm) / s; }
  // back to powers of x: Σ_j c'_j u^j = Σ_i x^i Σ_j c'_j C(j,i) (−x̄)^{j−i} s^{−j}
  Eigen::MatrixXd to_powers(int m) const {
    Eigen::MatrixXd t = Eigen::MatrixXd::Zero(m, m);
    for (int j = 0; j < m; ++j)
      for (int i = 0; i <= j; ++i)
        t(i, j) = binomial(j, i) * std::pow(-xm, j - i) * std::pow(s, -j);
    return t;
  }
};

// coefficients and covariance of a fit in u, transformed to powers of x
void store(const Scale& sc, const Eigen::VectorXd& cu, const Eigen::MatrixXd& covu,
           std::vector<double>& coef, std::vector<std::vector<double>>& cov) {
  const int m = static_cast<int>(cu.size());
  const Eigen::MatrixXd t = sc.to_powers(m);
  const Eigen::VectorXd c = t * cu;
  const Eigen::MatrixXd cv = t * covu * t.transpose();
  coef.assign(c.data(), c.data() + m);
  cov.assign(m, std::vector<double>(m));
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) cov[i][j] = cv(i, j);
}

// binomial (logistic) regression: given the bin totals t_j = n₀_j + n₁_j, the sample's count
// n₁_j is binomial with logit p_j = ln(n₁/n₀) + Q(x_j) — the exact Poisson likelihood of the
// ratio of two histograms, free of the bias of ln(counts) and of observed-count weights.
// Solved by Newton's method (iteratively reweighted least squares) in u.
struct Logistic {
  Eigen::VectorXd coef;  ///< in powers of u
  Eigen::MatrixXd cov;   ///< inverse Fisher information
  bool ok = false;
};
Logistic logistic_fit(const std::vector<double>& u, const std::vector<double>& c1,
                      const std::vector<double>& t, int degree) {
  const int n = static_cast<int>(u.size());
  const int m = degree + 1;
  Eigen::MatrixXd x(n, m);
  for (int i = 0; i < n; ++i) {
    double p = 1.0;
    for (int j = 0; j < m; ++j, p *= u[i]) x(i, j) = p;
  }
  // start from weighted least squares on the empirical logits (with the ½ correction)
  Eigen::VectorXd z(n), w(n);
  for (int i = 0; i < n; ++i) {
    z(i) = std::log((c1[i] + 0.5) / (t[i] - c1[i] + 0.5));
    w(i) = (c1[i] + 0.5) * (t[i] - c1[i] + 0.5) / (t[i] + 1.0);
  }
  Logistic r;
  r.coef = (x.transpose() * w.asDiagonal() * x).ldlt().solve(x.transpose() * (w.asDiagonal() * z));
  Eigen::MatrixXd info(m, m);
  for (int it = 0; it < 100; ++it) {
    // score and Fisher information at the current coefficients
    const Eigen::VectorXd eta = x * r.coef;
    Eigen::VectorXd score = Eigen::VectorXd::Zero(m);
    info.setZero();
    for (int i = 0; i < n; ++i) {
      const double p = 1.0 / (1.0 + std::exp(-eta(i)));
      score += x.row(i).transpose() * (c1[i] - t[i] * p);
      info += t[i] * p * (1.0 - p) * x.row(i).transpose() * x.row(i);
    }
    const Eigen::VectorXd step = info.ldlt().solve(score);
    if (!step.allFinite()) return r;
    r.coef += step;
    if (step.cwiseAbs().maxCoeff() < 1e-12 * (1.0 + r.coef.cwiseAbs().maxCoeff())) {
      r.ok = true;
      break;
    }
  }
  // the covariance at the solution
  const Eigen::VectorXd eta = x * r.coef;
  info.setZero();
  for (int i = 0; i < n; ++i) {
    const double p = 1.0 / (1.0 + std::exp(-eta(i)));
    info += t[i] * p * (1.0 - p) * x.row(i).transpose() * x.row(i);
  }
  r.cov = info.inverse();
  return r;
}

}  // namespace

PolyFit weighted_polyfit(const std::vector<double>& x, const std::vector<double>& y,
                         const std::vector<double>& sigma, int degree) {
  const int n = static_cast<int>(x.size());
  const int m = degree + 1;
  if (n < m || y.size() != x.size() || sigma.size() != x.size())
    throw std::invalid_argument("weighted_polyfit: needs matching x, y, σ with > degree points");
  const Scale sc(x);
  // weighted design matrix rows (u^j/σ) and right-hand side y/σ
  Eigen::MatrixXd a(n, m);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    const double u = sc.u(x[i]);
    double p = 1.0;
    for (int j = 0; j < m; ++j, p *= u) a(i, j) = p / sigma[i];
    b(i) = y[i] / sigma[i];
  }
  const Eigen::MatrixXd cu = (a.transpose() * a).ldlt().solve(Eigen::MatrixXd::Identity(m, m));
  const Eigen::VectorXd cfu = cu * (a.transpose() * b);
  PolyFit f;
  store(sc, cfu, cu, f.coef, f.cov);
  // χ² and the weighted R² = 1 − Σ w (y − fit)² / Σ w (y − ȳ_w)²
  f.chi2 = (b - a * cfu).squaredNorm();
  f.r2 = weighted_r2(y, sigma, f.chi2);
  return f;
}

double weighted_r2(const std::vector<double>& y, const std::vector<double>& sigma, double chi2) {
  double sw = 0.0, swy = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double w = 1.0 / (sigma[i] * sigma[i]);
    sw += w;
    swy += w * y[i];
  }
  double sst = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i)
    sst += (y[i] - swy / sw) * (y[i] - swy / sw) / (sigma[i] * sigma[i]);
  return sst > 0.0 ? 1.0 - chi2 / sst : (chi2 == 0.0 ? 1.0 : kNaN);
}

QFit q_fit(const std::vector<double>& ref, const std::vector<double>& sample,
           const OverlapOptions& opts) {
  QFit f;
  if (ref.size() < 2 || sample.size() < 2) {
    f.note = "samples too small";
    return f;
  }
  const double n0 = static_cast<double>(ref.size());
  const double n1 = static_cast<double>(sample.size());
  const double s0 = stddev(ref);
  const double s1 = stddev(sample);
  if (!(s0 > 0.0 && s1 > 0.0)) {
    f.note = "a sample without spread";
    return f;
  }

  // common binning over the pair's range; Scott's width from the better-resolved sample
  const auto [lo0, hi0] = std::minmax_element(ref.begin(), ref.end());
  const auto [lo1, hi1] = std::minmax_element(sample.begin(), sample.end());
  const double lo = std::min(*lo0, *lo1);
  const double hi = std::max(*hi0, *hi1);
  int nb = opts.bins;
  if (nb <= 0) {
    const double w = 3.49 * std::min(s0 * std::cbrt(1.0 / n0), s1 * std::cbrt(1.0 / n1));
    nb = static_cast<int>(std::ceil((hi - lo) / w));
  }
  nb = std::clamp(nb, 1, 100000);
  const double width = hi > lo ? (hi - lo) / nb : 1.0;
  f.bin_width = width;
  std::vector<double> grid(nb), c0(nb, 0.0), c1(nb, 0.0);
  for (int j = 0; j < nb; ++j) grid[j] = lo + (j + 0.5) * width;
  auto count = [&](const std::vector<double>& x, std::vector<double>& c) {
    for (double v : x) c[std::clamp(static_cast<int>((v - lo) / width), 0, nb - 1)] += 1.0;
  };
  count(ref, c0);
  count(sample, c1);

  // the kernel estimates at the bin centres: they define the region where both densities
  // exceed min_fraction of their maxima (paper section V). Being smooth, they keep the
  // region from following the noise of the very counts that are fitted (a selection bias).
  const double h0 = opts.bandwidth > 0.0 ? opts.bandwidth : silverman_bandwidth(ref);
  const double h1 = opts.bandwidth > 0.0 ? opts.bandwidth : silverman_bandwidth(sample);
  const auto k0 = kde_on_bins(ref, lo, width, nb, h0, opts.kernel);
  const auto k1 = kde_on_bins(sample, lo, width, nb, h1, opts.kernel);
  const double m0 = *std::max_element(k0.begin(), k0.end());
  const double m1 = *std::max_element(k1.begin(), k1.end());
  std::vector<int> region;
  for (int j = 0; j < nb; ++j)
    if (k0[j] > opts.min_fraction * m0 && k1[j] > opts.min_fraction * m1) region.push_back(j);
  if (region.size() < 3) {
    f.note = "fewer than 3 overlapping bins above " + std::to_string(opts.min_fraction) +
             " of the maxima";
    return f;
  }

  if (opts.method == DensityMethod::Histogram) {
    // histogram: the binomial fit of the counts (P.19, P.20) — line, then parabola.
    // A bin's count ratio is C⟨e^{Q}⟩ over P₀ within the bin, not e^{Q} at its centre: to first
    // order the bin acts at x_c + (w²/12)(ln P₀)'(x_c), the P₀-weighted mean of the bin. Without
    // this shift the slope shrinks by w²/(12σ₀²) (0.5 % at n = 3000), which is ≈ 0.25 of
    // its statistical error; (ln P₀)' comes from the smooth kernel estimate.
    auto x_eff = [&](int j) {
      if (j == 0 || j == nb - 1 || !(k0[j - 1] > 0.0 && k0[j + 1] > 0.0)) return grid[j];
      const double dlog = (std::log(k0[j + 1]) - std::log(k0[j - 1])) / (2.0 * width);
      return grid[j] + width * width / 12.0 * dlog;
    };
    std::vector<double> xs, us, cs, ts;
    for (int j : region) {
      if (c0[j] + c1[j] <= 0.0) continue;
      xs.push_back(x_eff(j));
      cs.push_back(c1[j]);
      ts.push_back(c0[j] + c1[j]);
    }
    if (xs.size() < 3) {
      f.note = "fewer than 3 occupied bins in the overlap";
      return f;
    }
    const Scale sc(xs);
    for (double x : xs) us.push_back(sc.u(x));
    const Logistic line = logistic_fit(us, cs, ts, 1);
    if (!line.ok) {
      f.note = "binomial fit did not converge";
      return f;
    }
    std::vector<double> coef;
    std::vector<std::vector<double>> cov;
    store(sc, line.coef, line.cov, coef, cov);
    // logit p = ln(n₁/n₀) + Q: the intercept of Q drops the sample-size ratio
    f.valid = true;
    f.intercept = coef[0] - std::log(n1 / n0);
    f.slope = coef[1];
    f.intercept_err = std::sqrt(cov[0][0]);
    f.slope_err = std::sqrt(cov[1][1]);
    f.cov_slope_intercept = cov[0][1];
    // the points: Q = ln(P₁/P₀) where both bins are occupied; σ_Q² = 1/(t p (1 − p)) from
    // the fitted expectation (Poisson propagation, 1/n₁ + 1/n₀ at the expected counts)
    std::vector<double> qs, es;
    for (std::size_t i = 0; i < xs.size(); ++i) {
      const double eta = line.coef(0) + line.coef(1) * us[i];
      const double p = 1.0 / (1.0 + std::exp(-eta));
      const double var = 1.0 / (ts[i] * p * (1.0 - p));
      // Pearson χ² of the binomial fit
      f.chi2 += (cs[i] - ts[i] * p) * (cs[i] - ts[i] * p) / (ts[i] * p * (1.0 - p));
      if (cs[i] <= 0.0 || cs[i] >= ts[i]) continue;
      const QPoint q{xs[i], std::log((cs[i] / n1) / ((ts[i] - cs[i]) / n0)), std::sqrt(var)};
      f.points.push_back(q);
      qs.push_back(q.q);
      es.push_back(q.q_err);
    }
    f.dof = static_cast<int>(xs.size()) - 2;
    double res = 0.0;
    for (std::size_t i = 0; i < f.points.size(); ++i) {
      const double d = (f.points[i].q - f.intercept - f.slope * f.points[i].x) / es[i];
      res += d * d;
    }
    f.r2 = f.points.size() >= 2 ? weighted_r2(qs, es, res) : kNaN;
    // the parabola's curvature tests linearity (appendix A)
    f.quad = f.quad_err = kNaN;
    if (xs.size() >= 4) {
      const Logistic par = logistic_fit(us, cs, ts, 2);
      if (par.ok) {
        store(sc, par.coef, par.cov, coef, cov);
        f.quad = coef[2];
        f.quad_err = std::sqrt(cov[2][2]);
      }
    }
    return f;
  }

  // kernel estimates: Q = ln(P̂₁/P̂₀), Var ln P̂ ≈ R(K)/(n h P̂), weighted least squares
  const double rk = kernel_roughness(opts.kernel);
  std::vector<double> xs, qs, es;
  for (int j : region) {
    const QPoint p{grid[j], std::log(k1[j] / k0[j]),
                   std::sqrt(rk / (n0 * h0 * k0[j]) + rk / (n1 * h1 * k1[j]))};
    f.points.push_back(p);
    xs.push_back(p.x);
    qs.push_back(p.q);
    es.push_back(p.q_err);
  }
  // neighbouring estimates are correlated over ≈ 2h: inflate the parameter covariance
  const double inflate = correlated_points(opts.kernel, 0.5 * (h0 + h1), width);
  f.note = "kde: neighbouring points correlated; parameter errors inflated by " +
           std::to_string(std::sqrt(inflate));
  const PolyFit line = weighted_polyfit(xs, qs, es, 1);
  f.valid = true;
  f.intercept = line.coef[0];
  f.slope = line.coef[1];
  f.intercept_err = std::sqrt(line.cov[0][0] * inflate);
  f.slope_err = std::sqrt(line.cov[1][1] * inflate);
  f.cov_slope_intercept = line.cov[0][1] * inflate;
  f.chi2 = line.chi2;
  f.dof = static_cast<int>(xs.size()) - 2;
  f.r2 = line.r2;
  f.quad = f.quad_err = kNaN;
  if (xs.size() >= 4) {
    const PolyFit par = weighted_polyfit(xs, qs, es, 2);
    f.quad = par.coef[2];
    f.quad_err = std::sqrt(par.cov[2][2] * inflate);
  }
  return f;
}

BetaEstimate beta_from_volume(const std::vector<double>& v_ref, const std::vector<double>& v,
                              const OverlapOptions& opts) {
  BetaEstimate b;
  b.fit = q_fit(v_ref, v, opts);
  b.valid = b.fit.valid;
  if (!b.valid) return b;
  // (P.20): slope = −(β − β_ref), intercept = −ln(Z/Z_ref)
  b.dbeta = -b.fit.slope;
  b.dbeta_err = b.fit.slope_err;
  b.dlnz = -b.fit.intercept;
  b.dlnz_err = b.fit.intercept_err;
  b.cov = b.fit.cov_slope_intercept;
  return b;
}

BetaEstimate beta_from_phi(const std::vector<double>& phi_ref, const std::vector<double>& phi,
                           double v_g, const OverlapOptions& opts) {
  if (!(v_g > 0.0)) throw std::invalid_argument("beta_from_phi: grain volume V_g must be > 0");
  // Q against 1/φ: the volume V = V_g/φ is 1/φ up to the constant factor V_g
  auto inv = [](const std::vector<double>& x) {
    std::vector<double> y(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) y[i] = 1.0 / x[i];
    return y;
  };
  BetaEstimate b;
  b.fit = q_fit(inv(phi_ref), inv(phi), opts);
  b.valid = b.fit.valid;
  if (!b.valid) return b;
  // (P.39): slope = −(β − β_ref) V_g, intercept = −ln(Z/Z_ref)
  b.dbeta = -b.fit.slope / v_g;
  b.dbeta_err = b.fit.slope_err / v_g;
  b.dlnz = -b.fit.intercept;
  b.dlnz_err = b.fit.intercept_err;
  b.cov = b.fit.cov_slope_intercept / v_g;
  return b;
}

BetaEstimate with_variance_factor(BetaEstimate b, double factor) {
  const double f = std::max(factor, 0.0);
  const double r = std::sqrt(f);
  b.dbeta_err *= r;
  b.dlnz_err *= r;
  b.cov *= f;
  b.fit.slope_err *= r;
  b.fit.intercept_err *= r;
  b.fit.cov_slope_intercept *= f;
  b.fit.quad_err *= r;
  if (f > 0.0) b.fit.chi2 /= f;
  for (auto& p : b.fit.points) p.q_err *= r;
  return b;
}

std::vector<BetaEstimate> betas_from_phi(const std::vector<double>& phi_ref,
                                         const std::vector<std::vector<double>>& samples,
                                         double v_g, const OverlapOptions& opts) {
  std::vector<BetaEstimate> r;
  r.reserve(samples.size());
  for (const auto& s : samples) r.push_back(beta_from_phi(phi_ref, s, v_g, opts));
  return r;
}

}  // namespace gs
