// the uniform multiplicative bisection process (T.3.26–T.3.38)
#include "models/bisection.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace gs::models {

namespace {
constexpr double kMaxBisectionSegments = 1e11;
}  // namespace

void BisectionParams::validate() const {
  if (levels < 1 || levels > 24)
    throw InputError("bisection", "levels", "need 1 ≤ levels ≤ 24, got " + std::to_string(levels));
  if (realisations < 2) throw InputError("bisection", "realisations", "need at least 2");
  // the work is realisations × 2^levels segments: refuse what could not finish in hours
  const double segments = static_cast<double>(realisations) * std::ldexp(1.0, levels);
  if (segments > kMaxBisectionSegments)
    throw InputError("bisection", "realisations",
                     "realisations × 2^levels = " + std::to_string(segments) + " segments (about " +
                         std::to_string(static_cast<long long>(segments / 1e8)) +
                         " s at 10^8 segments per second); the limit is 10^11");
  if (bins < 1) throw InputError("bisection", "bins", "need at least 1");
  if (!(x_min > 0.0 && x_min < 1.0)) throw InputError("bisection", "x_min", "need 0 < x_min < 1");
  if (m_max < 1) throw InputError("bisection", "m_max", "need m_max ≥ 1");
}

std::vector<double> bisect(int levels, RngStream& rng) {
  std::vector<double> seg{1.0}, next;
  // every level splits every segment at a uniform fraction a (T.3.26–3.27)
  for (int lev = 0; lev < levels; ++lev) {
    next.clear();
    next.reserve(2 * seg.size());
    for (double x : seg) {
      const double a = rng.uniform();
      next.push_back(a * x);
      next.push_back((1.0 - a) * x);
    }
    seg.swap(next);
  }
  return seg;
}

double bisection_density(double x, int n) {
  if (!(x > 0.0) || x > 1.0) return 0.0;
  return std::pow(-std::log(x), n - 1) / std::tgamma(static_cast<double>(n));
}

double bisection_cdf(double x, int n) {
  if (!(x > 0.0)) return 0.0;
  if (x >= 1.0) return 1.0;
  // P(Π a_i ≤ x) = P(Gamma(n, 1) ≥ t), t = −ln x: x Σ_{k<n} t^k/k!
  const double t = -std::log(x);
  double term = 1.0, sum = 1.0;
  for (int k = 1; k < n; ++k) {
    term *= t / k;
    sum += term;
  }
  return x * sum;
}

double bisection_moment(int m, int n) { return std::pow(1.0 + m, -n); }

double bisection_density_length_biased(double x, int n) {
  return std::ldexp(x * bisection_density(x, n), n);
}

BisectionResult run_bisection(const BisectionParams& p) {
  p.validate();
  const auto bins = rfm::Binning::log(p.x_min, 1.0, p.bins);
  const auto nb = static_cast<std::size_t>(p.bins);
  const auto mm = static_cast<std::size_t>(p.m_max);
  const double nseg = std::ldexp(1.0, p.levels);
  // per-realisation sums for the between-realisation errors
  std::vector<double> d_sum(nb, 0.0), d_sum2(nb, 0.0), m_sum(mm, 0.0), m_sum2(mm, 0.0);
  rfm::GapStatistics gaps(bins, {1, 2}, 1);
  std::vector<double> counts(nb), boundaries;

  for (long r = 0; r < p.realisations; ++r) {
    RngStream rng(p.seed, static_cast<std::uint64_t>(r));
    const std::vector<double> seg = bisect(p.levels, rng);
    // segment-length histogram and moments of this realisation
    std::fill(counts.begin(), counts.end(), 0.0);
    std::vector<double> mom(mm, 0.0);
    for (double x : seg) {
      const int b = bins.index(x);
      if (b >= 0) counts[static_cast<std::size_t>(b)] += 1.0;
      double q = 1.0;
      for (std::size_t k = 0; k < mm; ++k) {
        q *= x;
        mom[k] += q;
      }
    }
    for (std::size_t b = 0; b < nb; ++b) {
      const double d = counts[b] / (nseg * bins.width(static_cast<int>(b)));
      d_sum[b] += d;
      d_sum2[b] += d * d;
    }
    for (std::size_t k = 0; k < mm; ++k) {
      const double v = mom[k] / nseg;
      m_sum[k] += v;
      m_sum2[k] += v * v;
    }
    // the boundaries as point-particles on a ring of length 1 (reduced coordinates, d = 0)
    boundaries.assign(1, 0.0);
    for (std::size_t i = 0; i + 1 < seg.size(); ++i)
      boundaries.push_back(boundaries.back() + seg[i]);
    gaps.add_snapshot(boundaries, 1.0);
  }

  // means and standard errors over realisations
  const double nr = static_cast<double>(p.realisations);
  auto stderr_of = [nr](double s, double s2) {
    const double m = s / nr;
    return std::sqrt(std::max(0.0, (s2 / nr - m * m) / (nr - 1.0)));
  };
  BisectionResult out;
  out.levels = p.levels;
  const auto g1 = gaps.g(0), g2 = gaps.g(1);
  for (std::size_t b = 0; b < nb; ++b) {
    BisectionBin bb;
    bb.lo = bins.edge(static_cast<int>(b));
    bb.hi = bins.edge(static_cast<int>(b) + 1);
    bb.x = bins.centre(static_cast<int>(b));
    bb.p = d_sum[b] / nr;
    bb.p_err = stderr_of(d_sum[b], d_sum2[b]);
    bb.p_exact =
        (bisection_cdf(bb.hi, p.levels) - bisection_cdf(bb.lo, p.levels)) / (bb.hi - bb.lo);
    bb.p_exact_prev =
        p.levels > 1 ? (bisection_cdf(bb.hi, p.levels - 1) - bisection_cdf(bb.lo, p.levels - 1)) /
                           (bb.hi - bb.lo)
                     : 0.0;
    bb.g1 = g1[b].p;
    bb.g2 = g2[b].p;
    out.bins.push_back(bb);
  }
  for (std::size_t k = 0; k < mm; ++k) {
    out.moments.push_back(m_sum[k] / nr);
    out.moment_err.push_back(stderr_of(m_sum[k], m_sum2[k]));
    out.moment_exact.push_back(bisection_moment(static_cast<int>(k + 1), p.levels));
  }
  return out;
}

void write_bisection_csv(const RecordSink& sink, const std::filesystem::path& path,
                         const BisectionResult& r) {
  const auto w = sink.create(
      path.string(), {"x", "x_lo", "x_hi", "P", "P_err", "P_exact", "G1", "G2", "P_exact_prev"},
      {{"levels", static_cast<double>(r.levels)}});
  for (const BisectionBin& b : r.bins)
    w->row({b.x, b.lo, b.hi, b.p, b.p_err, b.p_exact, b.g1, b.g2, b.p_exact_prev});
}

}  // namespace gs::models
