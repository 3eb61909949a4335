// overlapping histograms (P.19, P.20, P.39) with weighted line and parabola fits
#include "analysis/overlap_hist.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis/stats.hpp"

namespace gs {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

}  // namespace

PolyFit weighted_polyfit(const std::vector<double>& x, const std::vector<double>& y,
                         const std::vector<double>& sigma, int degree) {
  const int n = static_cast<int>(x.size());
  const int m = degree + 1;
  if (n < m || y.size() != x.size() || sigma.size() != x.size())
    throw std::invalid_argument("weighted_polyfit: needs matching x, y, σ with > degree points");
  // centre and scale x: u = (x − x̄)/s keeps the normal equations well conditioned
  double xm = 0.0;
  for (double v : x) xm += v;
  xm /= n;
  double s = 0.0;
  for (double v : x) s = std::max(s, std::abs(v - xm));
  if (s <= 0.0) s = 1.0;
  // weighted design matrix rows (u^j/σ) and right-hand side y/σ
  Eigen::MatrixXd a(n, m);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    const double u = (x[i] - xm) / s;
    double p = 1.0;
    for (int j = 0; j < m; ++j, p *= u) a(i, j) = p / sigma[i];
    b(i) = y[i] / sigma[i];
  }
  const Eigen::MatrixXd ata = a.transpose() * a;
  const Eigen::MatrixXd cu = ata.ldlt().solve(Eigen::MatrixXd::Identity(m, m));
  const Eigen::VectorXd cfu = cu * (a.transpose() * b);
  // back to powers of x: Σ_j c'_j ((x − x̄)/s)^j = Σ_i x^i Σ_j c'_j C(j,i) (−x̄)^{j−i} s^{−j}
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(m, m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i <= j; ++i) t(i, j) = binomial(j, i) * std::pow(-xm, j - i) * std::pow(s, -j);
  const Eigen::VectorXd cf = t * cfu;
  const Eigen::MatrixXd cov = t * cu * t.transpose();
  PolyFit f;
  f.coef.assign(cf.data(), cf.data() + m);
  f.cov.assign(m, std::vector<double>(m));
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) f.cov[i][j] = cov(i, j);
  // χ² and the weighted R² = 1 − Σ w (y − fit)² / Σ w (y − ȳ_w)²
  const Eigen::VectorXd res = b - a * cfu;
  f.chi2 = res.squaredNorm();
  double sw = 0.0;
  double swy = 0.0;
  for (int i = 0; i < n; ++i) {
    const double w = 1.0 / (sigma[i] * sigma[i]);
    sw += w;
    swy += w * y[i];
  }
  double sst = 0.0;
  for (int i = 0; i < n; ++i) sst += (y[i] - swy / sw) * (y[i] - swy / sw) / (sigma[i] * sigma[i]);
  f.r2 = sst > 0.0 ? 1.0 - f.chi2 / sst : (f.chi2 == 0.0 ? 1.0 : kNaN);
  return f;
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

  // common binning over the pair's range; Scott's width from the narrower-resolved sample
  const auto [lo0, hi0] = std::minmax_element(ref.begin(), ref.end());
  const auto [lo1, hi1] = std::minmax_element(sample.begin(), sample.end());
  const double lo = std::min(*lo0, *lo1);
  const double hi = std::max(*hi0, *hi1);
  int nb = opts.bins;
  if (nb <= 0) {
    const double w = 3.49 * std::min(s0 * std::cbrt(1.0 / n0), s1 * std::cbrt(1.0 / n1));
    nb = w > 0.0 ? static_cast<int>(std::ceil((hi - lo) / w)) : 1;
  }
  nb = std::clamp(nb, 1, 100000);
  const double width = hi > lo ? (hi - lo) / nb : 1.0;
  f.bin_width = width;
  auto centre = [&](int j) { return lo + (j + 0.5) * width; };

  // densities P₀, P₁ and the variance of ln P at every bin centre
  std::vector<double> p0(nb), p1(nb), v0(nb), v1(nb), c0(nb, 0.0), c1(nb, 0.0);
  auto count = [&](const std::vector<double>& x, std::vector<double>& c) {
    for (double v : x) c[std::clamp(static_cast<int>((v - lo) / width), 0, nb - 1)] += 1.0;
  };
  count(ref, c0);
  count(sample, c1);
  double inflate = 1.0;
  if (opts.method == DensityMethod::Histogram) {
    // histogram: P = n_j/(n w); Poisson counts give Var ln P = 1/n_j
    for (int j = 0; j < nb; ++j) {
      p0[j] = c0[j] / (n0 * width);
      p1[j] = c1[j] / (n1 * width);
      v0[j] = c0[j] > 0.0 ? 1.0 / c0[j] : kNaN;
      v1[j] = c1[j] > 0.0 ? 1.0 / c1[j] : kNaN;
    }
  } else {
    // kernel estimate at the bin centres: Var P̂ ≈ P R(K)/(n h), so Var ln P̂ = R(K)/(n h P)
    const double h0 = opts.bandwidth > 0.0 ? opts.bandwidth : silverman_bandwidth(ref);
    const double h1 = opts.bandwidth > 0.0 ? opts.bandwidth : silverman_bandwidth(sample);
    std::vector<double> grid(nb);
    for (int j = 0; j < nb; ++j) grid[j] = centre(j);
    p0 = kde(ref, grid, h0, opts.kernel);
    p1 = kde(sample, grid, h1, opts.kernel);
    const double rk = kernel_roughness(opts.kernel);
    for (int j = 0; j < nb; ++j) {
      v0[j] = p0[j] > 0.0 ? rk / (n0 * h0 * p0[j]) : kNaN;
      v1[j] = p1[j] > 0.0 ? rk / (n1 * h1 * p1[j]) : kNaN;
    }
    inflate = correlated_points(opts.kernel, 0.5 * (h0 + h1), width);
    f.note = "kde: neighbouring points correlated; parameter errors inflated by " +
             std::to_string(std::sqrt(inflate));
  }

  // keep bins where both densities exceed min_fraction of their maxima (paper section V)
  const double m0 = *std::max_element(p0.begin(), p0.end());
  const double m1 = *std::max_element(p1.begin(), p1.end());
  std::vector<double> xs, qs, es;
  for (int j = 0; j < nb; ++j) {
    if (!(p0[j] > opts.min_fraction * m0 && p1[j] > opts.min_fraction * m1)) continue;
    if (opts.method == DensityMethod::Histogram &&
        (c0[j] < std::max(1, opts.min_count) || c1[j] < std::max(1, opts.min_count)))
      continue;
    // (P.19): Q = ln(P₁/P₀), σ_Q² = Var ln P₁ + Var ln P₀ (independent samples)
    const QPoint p{centre(j), std::log(p1[j] / p0[j]), std::sqrt(v0[j] + v1[j])};
    f.points.push_back(p);
    xs.push_back(p.x);
    qs.push_back(p.q);
    es.push_back(p.q_err);
  }
  if (f.points.size() < 3) {
    f.note = "fewer than 3 overlapping bins above " + std::to_string(opts.min_fraction) +
             " of the maxima";
    return f;
  }

  // weighted straight line (P.20): Q = intercept + slope·x
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
  // weighted parabola: its curvature tests linearity (appendix A)
  if (xs.size() >= 4) {
    const PolyFit par = weighted_polyfit(xs, qs, es, 2);
    f.quad = par.coef[2];
    f.quad_err = std::sqrt(par.cov[2][2] * inflate);
  } else {
    f.quad = kNaN;
    f.quad_err = kNaN;
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

std::vector<BetaEstimate> betas_from_phi(const std::vector<double>& phi_ref,
                                         const std::vector<std::vector<double>>& samples,
                                         double v_g, const OverlapOptions& opts) {
  std::vector<BetaEstimate> r;
  r.reserve(samples.size());
  for (const auto& s : samples) r.push_back(beta_from_phi(phi_ref, s, v_g, opts));
  return r;
}

}  // namespace gs
