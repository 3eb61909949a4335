// descriptive statistics, intervals, autocorrelation time and the normality test
// (docs/physics.md §2.6)
#include "analysis/stats.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace gs {

namespace {

constexpr double kEps = 1e-16;
constexpr double kTiny = 1e-300;

// series of γ(a,x): converges fast for x < a + 1 (Numerical Recipes §6.2)
double gamma_p_series(double a, double x) {
  double term = 1.0 / a;
  double sum = term;
  for (int n = 1; n < 100000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * kEps) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// continued fraction of Γ(a,x) (modified Lentz): converges fast for x ≥ a + 1
double gamma_q_fraction(double a, double x) {
  double b = x + 1.0 - a;
  double c = 1.0 / kTiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < kEps) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

// continued fraction of the incomplete beta (modified Lentz, Numerical Recipes §6.4)
double beta_fraction(double a, double b, double x) {
  const double qab = a + b;
  const double qap = a + 1.0;
  const double qam = a - 1.0;
  double c = 1.0;
  double d = 1.0 - qab * x / qap;
  if (std::abs(d) < kTiny) d = kTiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m < 100000; ++m) {
    const int m2 = 2 * m;
    double aa = m * (b - m) * x / ((qam + m2) * (a + m2));
    d = 1.0 + aa * d;
    if (std::abs(d) < kTiny) d = kTiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    h *= d * c;
    aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
    d = 1.0 + aa * d;
    if (std::abs(d) < kTiny) d = kTiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < kEps) break;
  }
  return h;
}

void require_probability(double p, const char* who) {
  if (!(p > 0.0 && p < 1.0))
    throw std::invalid_argument(std::string(who) + ": probability must lie in (0, 1), got " +
                                std::to_string(p));
}

// invert a monotone increasing cdf on [lo, hi) by bracket growth and bisection; the cdfs here
// are smooth, so 200 halvings (or the resolution of doubles) give full precision
template <class Cdf>
double invert_cdf(Cdf cdf, double p, double lo, double hi) {
  while (cdf(hi) < p) {
    lo = hi;
    hi *= 2.0;
    if (hi > 1e300) return std::numeric_limits<double>::infinity();
  }
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (cdf(mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

void require_size(const std::vector<double>& x, std::size_t n, const char* who) {
  if (x.size() < n)
    throw std::invalid_argument(std::string(who) + ": needs at least " + std::to_string(n) +
                                " values, got " + std::to_string(x.size()));
}

}  // namespace

// ---- special functions --------------------------------------------------------------------

double gamma_p(double a, double x) {
  if (x <= 0.0) return 0.0;
  if (std::isinf(x)) return 1.0;
  return x < a + 1.0 ? gamma_p_series(a, x) : 1.0 - gamma_q_fraction(a, x);
}

double gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  if (std::isinf(x)) return 0.0;
  return x < a + 1.0 ? 1.0 - gamma_p_series(a, x) : gamma_q_fraction(a, x);
}

double beta_inc(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  // prefactor x^a (1−x)^b / (a B(a,b)); the fraction converges for x < (a+1)/(a+b+2)
  const double lbt =
      std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  if (x < (a + 1.0) / (a + b + 2.0)) return std::exp(lbt) * beta_fraction(a, b, x) / a;
  return 1.0 - std::exp(lbt) * beta_fraction(b, a, 1.0 - x) / b;
}

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

double normal_quantile(double p) {
  require_probability(p, "normal_quantile");
  // symmetric: invert the upper half on [0, 40) and mirror
  if (p < 0.5) return -normal_quantile(1.0 - p);
  if (p == 0.5) return 0.0;
  return invert_cdf([](double z) { return normal_cdf(z); }, p, 0.0, 8.0);
}

double chi2_cdf(double x, double k) { return gamma_p(0.5 * k, 0.5 * x); }

double chi2_quantile(double p, double k) {
  require_probability(p, "chi2_quantile");
  return invert_cdf([k](double x) { return chi2_cdf(x, k); }, p, 0.0, std::max(1.0, 4.0 * k));
}

double student_t_cdf(double t, double nu) {
  // P(|T| > |t|) = I_{ν/(ν+t²)}(ν/2, 1/2)
  const double tail = 0.5 * beta_inc(0.5 * nu, 0.5, nu / (nu + t * t));
  return t >= 0.0 ? 1.0 - tail : tail;
}

double student_t_quantile(double p, double nu) {
  require_probability(p, "student_t_quantile");
  if (p < 0.5) return -student_t_quantile(1.0 - p, nu);
  if (p == 0.5) return 0.0;
  return invert_cdf([nu](double t) { return student_t_cdf(t, nu); }, p, 0.0, 16.0);
}

// ---- moments and intervals ----------------------------------------------------------------

double mean(const std::vector<double>& x) {
  require_size(x, 1, "mean");
  double s = 0.0;
  for (double v : x) s += v;
  return s / static_cast<double>(x.size());
}

double variance(const std::vector<double>& x) {
  require_size(x, 2, "variance");
  // two-pass: subtract the mean first so that small fluctuations around φ ≈ 0.82 stay exact
  const double m = mean(x);
  double s = 0.0;
  for (double v : x) s += (v - m) * (v - m);
  return s / static_cast<double>(x.size() - 1);
}

double stddev(const std::vector<double>& x) { return std::sqrt(variance(x)); }

Interval mean_ci(const std::vector<double>& x, double level, double tau_int) {
  require_size(x, 2, "mean_ci");
  // effective sample size of a correlated series: n/(2 τ_int); at least 2 samples
  const double n_eff =
      std::max(2.0, static_cast<double>(x.size()) / (2.0 * std::max(tau_int, 0.5)));
  const double m = mean(x);
  const double half =
      student_t_quantile(0.5 + 0.5 * level, n_eff - 1.0) * stddev(x) / std::sqrt(n_eff);
  return {m - half, m + half};
}

Interval stddev_ci(const std::vector<double>& x, double level, double tau_int) {
  require_size(x, 2, "stddev_ci");
  // (ν s²/σ²) ~ χ²(ν): invert at both tails
  const double n_eff =
      std::max(2.0, static_cast<double>(x.size()) / (2.0 * std::max(tau_int, 0.5)));
  const double nu = n_eff - 1.0;
  const double alpha = 1.0 - level;
  const double s2 = variance(x);
  return {std::sqrt(nu * s2 / chi2_quantile(1.0 - 0.5 * alpha, nu)),
          std::sqrt(nu * s2 / chi2_quantile(0.5 * alpha, nu))};
}

// ---- autocorrelation ----------------------------------------------------------------------

namespace {

// in-place iterative radix-2 FFT (size a power of two); inverse without the 1/n
void fft(std::vector<std::complex<double>>& a, bool inverse) {
  const std::size_t n = a.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double ang = 2.0 * std::numbers::pi / static_cast<double>(len) * (inverse ? 1 : -1);
    const std::complex<double> wl(std::cos(ang), std::sin(ang));
    for (std::size_t i = 0; i < n; i += len) {
      std::complex<double> w(1.0);
      for (std::size_t k = 0; k < len / 2; ++k) {
        const auto u = a[i + k], v = a[i + k + len / 2] * w;
        a[i + k] = u + v;
        a[i + k + len / 2] = u - v;
        w *= wl;
      }
    }
  }
}

// Σ_i d_i d_{i+t} for every lag t < n, by the Wiener–Khinchin theorem: O(n log n)
std::vector<double> lag_sums_fft(const std::vector<double>& d) {
  std::size_t size = 1;
  while (size < 2 * d.size()) size <<= 1;
  std::vector<std::complex<double>> a(size);
  for (std::size_t i = 0; i < d.size(); ++i) a[i] = d[i];
  fft(a, false);
  for (auto& z : a) z = std::norm(z);
  fft(a, true);
  std::vector<double> out(d.size());
  for (std::size_t t = 0; t < d.size(); ++t) out[t] = a[t].real() / static_cast<double>(size);
  return out;
}

}  // namespace

AutocorrTime autocorr_time(const std::vector<double>& x, double c) {
  require_size(x, 2, "autocorr_time");
  const std::size_t n = x.size();
  const double m = mean(x);
  std::vector<double> d(n);
  for (std::size_t i = 0; i < n; ++i) d[i] = x[i] - m;

  // biased autocovariance C(t) = (1/n) Σ d_i d_{i+t}, lag by lag until the window closes. The
  // first lags are summed directly; once the window has cost about 5·10⁷ products (a long or
  // slowly decorrelating series, where lag-by-lag would be quadratic in n) every remaining
  // lag comes from one FFT
  std::vector<double> by_fft;
  const std::size_t direct_lags = std::max<std::size_t>(64, 50'000'000 / n);
  auto cov = [&](std::size_t t) {
    if (t > direct_lags) {
      if (by_fft.empty()) by_fft = lag_sums_fft(d);
      return by_fft[t] / static_cast<double>(n);
    }
    double s = 0.0;
    for (std::size_t i = 0; i + t < n; ++i) s += d[i] * d[i + t];
    return s / static_cast<double>(n);
  };
  AutocorrTime r;
  const double c0 = cov(0);
  r.rho.push_back(1.0);
  // a constant series has no fluctuations (what is left of the mean's rounding is not one)
  if (c0 <= 1e-28 * m * m) {
    r.converged = true;
    return r;
  }
  double tau = 0.5;
  const std::size_t max_lag = n / 2;
  std::size_t lag = 1;
  for (; lag <= max_lag; ++lag) {
    const double rho = cov(lag) / c0;
    r.rho.push_back(rho);
    tau += rho;
    // Sokal's rule: stop at the first M with M ≥ c τ_int(M)
    if (static_cast<double>(lag) >= c * tau) {
      r.converged = true;
      break;
    }
  }
  r.window = static_cast<int>(std::min(lag, max_lag));
  r.tau_int = std::max(tau, 0.5);
  r.tau_err = r.tau_int * std::sqrt(2.0 * (2.0 * r.window + 1.0) / static_cast<double>(n));
  return r;
}

// ---- normality ----------------------------------------------------------------------------

NormalityTest normality_chi2(const std::vector<double>& x, double alpha, int bins) {
  require_size(x, 20, "normality_chi2");
  const std::size_t n = x.size();
  const double m = mean(x);
  const double s = stddev(x);
  NormalityTest r;
  // the number of bins: ≈ 2 n^{2/5}, keeping every expected count n/k ≥ 5
  int k =
      bins > 0 ? bins : static_cast<int>(std::lround(2.0 * std::pow(static_cast<double>(n), 0.4)));
  k = std::clamp(k, 4, std::max(4, static_cast<int>(n / 5)));
  r.bins = k;
  r.dof = k - 3;
  if (s <= 0.0) {
    // all values equal: certainly not a normal sample with finite σ > 0
    r.statistic = std::numeric_limits<double>::infinity();
    r.p_value = 0.0;
    r.normal = false;
    return r;
  }
  // equiprobable bins under N(m, s): the edges are normal quantiles at j/k
  std::vector<double> edges(k - 1);
  for (int j = 1; j < k; ++j) edges[j - 1] = m + s * normal_quantile(static_cast<double>(j) / k);
  std::vector<double> counts(k, 0.0);
  for (double v : x) {
    const auto b = std::upper_bound(edges.begin(), edges.end(), v) - edges.begin();
    counts[b] += 1.0;
  }
  // X² = Σ (O − E)²/E with E = n/k in every bin
  const double e = static_cast<double>(n) / k;
  double x2 = 0.0;
  for (double o : counts) x2 += (o - e) * (o - e) / e;
  r.statistic = x2;
  r.p_value = gamma_q(0.5 * r.dof, 0.5 * x2);
  r.normal = r.p_value >= alpha;
  return r;
}

Truncation mser_truncation(const std::vector<double>& x, int batch) {
  Truncation t;
  const std::size_t b = static_cast<std::size_t>(std::max(batch, 1));
  const std::size_t m = x.size() / b;  // whole batches; a partial last batch is left out
  if (m < 4) return t;
  std::vector<double> z(m);
  for (std::size_t j = 0; j < m; ++j) {
    double sum = 0.0;
    for (std::size_t k = 0; k < b; ++k) sum += x[j * b + k];
    z[j] = sum / static_cast<double>(b);
  }
  // centred first, so that the sums of squares below lose no digits to a large mean
  double centre = 0.0;
  for (double v : z) centre += v;
  centre /= static_cast<double>(m);
  for (double& v : z) v -= centre;
  // suffix sums give every candidate's mean and sum of squares in one pass
  std::vector<double> s1(m + 1, 0.0), s2(m + 1, 0.0);
  for (std::size_t j = m; j-- > 0;) {
    s1[j] = s1[j + 1] + z[j];
    s2[j] = s2[j + 1] + z[j] * z[j];
  }
  const std::size_t last = m / 2;
  double best = 0.0;
  std::size_t arg = 0;
  for (std::size_t k = 0; k <= last; ++k) {
    const double n = static_cast<double>(m - k);
    const double ss = std::max(s2[k] - s1[k] * s1[k] / n, 0.0);  // Σ (z − z̄_k)²
    const double stat = ss / (n * n);
    if (k == 0 || stat < best) {
      best = stat;
      arg = k;
    }
  }
  t.drop = static_cast<int>(arg * b);
  t.steady = arg < last;
  return t;
}

}  // namespace gs
