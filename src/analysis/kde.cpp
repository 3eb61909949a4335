// kernel density estimation (paper appendix B, B1–B7)
#include "analysis/kde.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "analysis/stats.hpp"

namespace gs {

std::string kernel_name(Kernel k) {
  switch (k) {
    case Kernel::Normal:
      return "normal";
    case Kernel::Epanechnikov:
      return "epanechnikov";
    case Kernel::Box:
      return "box";
  }
  return "normal";
}

Kernel kernel_from_name(const std::string& name) {
  if (name == "normal" || name == "gauss" || name == "gaussian") return Kernel::Normal;
  if (name == "epanechnikov") return Kernel::Epanechnikov;
  if (name == "box" || name == "rectangular") return Kernel::Box;
  throw std::invalid_argument("unknown kernel '" + name + "' (normal, epanechnikov, box)");
}

double kernel_value(Kernel k, double u) {
  switch (k) {
    // (B3) with the normalisation (2π)^{-1/2} that makes (B2) hold
    case Kernel::Normal:
      return std::exp(-0.5 * u * u) / std::sqrt(2.0 * std::numbers::pi);
    // (B5)
    case Kernel::Epanechnikov:
      return std::abs(u) <= 1.0 ? 0.75 * (1.0 - u * u) : 0.0;
    // (B6)
    case Kernel::Box:
      return std::abs(u) <= 0.5 ? 1.0 : 0.0;
  }
  return 0.0;
}

double kernel_roughness(Kernel k) {
  switch (k) {
    case Kernel::Normal:
      return 0.5 / std::sqrt(std::numbers::pi);
    case Kernel::Epanechnikov:
      return 0.6;
    case Kernel::Box:
      return 1.0;
  }
  return 1.0;
}

double kernel_reach(Kernel k) {
  switch (k) {
    // exp(−u²/2) < 1e-16 beyond |u| ≈ 8.6
    case Kernel::Normal:
      return 8.6;
    case Kernel::Epanechnikov:
      return 1.0;
    case Kernel::Box:
      return 0.5;
  }
  return 1.0;
}

double equivalent_bandwidth(Kernel k, double h_normal) {
  // μ₂(K) = ∫u²K: 1, 1/5, 1/12
  auto delta = [](Kernel kk) {
    const double mu2 = kk == Kernel::Normal ? 1.0 : (kk == Kernel::Epanechnikov ? 0.2 : 1.0 / 12.0);
    return std::pow(kernel_roughness(kk) / (mu2 * mu2), 0.2);
  };
  return h_normal * delta(k) / delta(Kernel::Normal);
}

double silverman_bandwidth(const std::vector<double>& x) {
  // (B7): (4σ⁵/(3n))^{1/5} ≈ 1.06 σ n^{−1/5}
  return 1.06 * stddev(x) * std::pow(static_cast<double>(x.size()), -0.2);
}

std::vector<double> linspace(double a, double b, int n) {
  if (n < 2) throw std::invalid_argument("linspace: needs at least 2 points");
  std::vector<double> g(n);
  for (int i = 0; i < n; ++i) g[i] = a + (b - a) * static_cast<double>(i) / (n - 1);
  return g;
}

std::vector<double> kde(const std::vector<double>& x, const std::vector<double>& grid, double h,
                        Kernel k) {
  if (x.empty()) throw std::invalid_argument("kde: empty sample");
  if (!(h > 0.0)) throw std::invalid_argument("kde: bandwidth must be positive");
  // sort once so each grid point only visits the samples within the kernel's reach
  std::vector<double> s = x;
  std::sort(s.begin(), s.end());
  const double reach = kernel_reach(k) * h;
  const double norm = 1.0 / (static_cast<double>(s.size()) * h);
  std::vector<double> p(grid.size(), 0.0);
  for (std::size_t g = 0; g < grid.size(); ++g) {
    // (B1): P(x) = 1/(n h) Σ K((x − x_i)/h)
    auto it = std::lower_bound(s.begin(), s.end(), grid[g] - reach);
    double sum = 0.0;
    for (; it != s.end() && *it <= grid[g] + reach; ++it)
      sum += kernel_value(k, (grid[g] - *it) / h);
    p[g] = sum * norm;
  }
  return p;
}

KdeCurve kde_auto(const std::vector<double>& x, int points, Kernel k, double h, double pad) {
  KdeCurve c;
  c.bandwidth = h > 0.0 ? h : silverman_bandwidth(x);
  if (!(c.bandwidth > 0.0)) throw std::invalid_argument("kde_auto: sample has zero spread");
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  c.x = linspace(*lo - pad * c.bandwidth, *hi + pad * c.bandwidth, points);
  c.density = kde(x, c.x, c.bandwidth, k);
  return c;
}

}  // namespace gs
