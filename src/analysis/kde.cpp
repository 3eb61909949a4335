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

std::vector<double> kde_on_bins(const std::vector<double>& x, double lo, double width, int nb,
                                double h, Kernel k) {
  std::vector<double> grid(static_cast<std::size_t>(nb));
  for (int j = 0; j < nb; ++j) grid[static_cast<std::size_t>(j)] = lo + (j + 0.5) * width;
  if (k != Kernel::Normal) return kde(x, grid, h, k);
  if (x.empty()) throw std::invalid_argument("kde_on_bins: empty sample");
  if (!(h > 0.0) || !(width > 0.0)) throw std::invalid_argument("kde_on_bins: bad h or width");
  // r fine cells a bin, odd, so that every bin centre is a fine cell's centre
  const double per_bin = std::ceil(32.0 * width / h);
  if (per_bin * nb > 4e6) return kde(x, grid, h, k);  // h far below the bins: summed exactly
  auto r = static_cast<long>(per_bin);
  if (r % 2 == 0) ++r;
  const long m = r * nb;
  const double d = width / static_cast<double>(r);
  // linear binning: a sample between two fine centres is shared in proportion to its distance
  std::vector<double> c(static_cast<std::size_t>(m), 0.0);
  for (double v : x) {
    const double u = (v - lo) / d - 0.5;
    if (!(u > 0.0)) {
      c.front() += 1.0;
    } else if (u >= static_cast<double>(m - 1)) {
      c.back() += 1.0;
    } else {
      const auto i = static_cast<std::size_t>(u);
      const double f = u - static_cast<double>(i);
      c[i] += 1.0 - f;
      c[i + 1] += f;
    }
  }
  // the kernel at whole fine-cell offsets, out to its reach
  const long reach = static_cast<long>(std::ceil(kernel_reach(k) * h / d));
  std::vector<double> w(static_cast<std::size_t>(reach) + 1);
  for (long t = 0; t <= reach; ++t)
    w[static_cast<std::size_t>(t)] = kernel_value(k, static_cast<double>(t) * d / h);
  const double norm = 1.0 / (static_cast<double>(x.size()) * h);
  std::vector<double> p(static_cast<std::size_t>(nb), 0.0);
  for (long j = 0; j < nb; ++j) {
    const long centre = j * r + (r - 1) / 2;
    const long a = std::max(0L, centre - reach), b = std::min(m - 1, centre + reach);
    double sum = 0.0;
    for (long i = a; i <= b; ++i)
      sum += w[static_cast<std::size_t>(std::abs(i - centre))] * c[static_cast<std::size_t>(i)];
    p[static_cast<std::size_t>(j)] = sum * norm;
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
