// single-particle walks: the SPM disc (§5.2–5.3), the 1D interval (appendix B), free heating
#include "models/walks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "analysis/rfm_fit.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "core/vec.hpp"
#include "models/interval_theory.hpp"

namespace gs::models {

void WalkParams::validate() const {
  if (!(noise > 0.0)) throw InputError("walks", "noise", "D must be positive");
  if (!(mass > 0.0)) throw InputError("walks", "mass", "M must be positive");
  if (dt < 0.0) throw InputError("walks", "dt", "must be ≥ 0 (0 chooses it)");
  if (walks < 2) throw InputError("walks", "walks", "need at least 2 walks");
  if (walks > 1'000'000'000)
    throw InputError("walks", "walks", "at most 10^9 walks (each takes thousands of steps)");
  if (bins < 1) throw InputError("walks", "bins", "need at least 1 bin");
  if (v_max < 0.0) throw InputError("walks", "v_max", "must be ≥ 0 (0 chooses it)");
  if (max_steps < 1) throw InputError("walks", "max_steps", "must be ≥ 1");
}

double walk_velocity_scale(const WalkParams& p, double l) {
  return std::cbrt(p.noise * l / (p.mass * p.mass));
}

double walk_time_scale(const WalkParams& p, double l) {
  return std::cbrt(l * l * p.mass * p.mass / p.noise);
}

namespace {

// running mean and variance of residuals and exit times
struct Moments {
  double s = 0.0, s2 = 0.0;
  long n = 0;
  void add(double x) {
    s += x;
    s2 += x * x;
    ++n;
  }
  double mean() const { return n ? s / static_cast<double>(n) : 0.0; }
  double err() const {
    if (n < 2) return 0.0;
    const double m = mean();
    return std::sqrt(
        std::max(0.0, (s2 / static_cast<double>(n) - m * m) / static_cast<double>(n - 1)));
  }
};

// what the walk loops accumulate
struct Tally {
  Moments tau, heat, virial;
  double v2_sum = 0.0, region_sum = 0.0;
  long samples = 0, capped = 0;
};

// one 2D walk from rest at the centre of a disc of radius l (T.5.11)
void walk_disc(RngStream& rng, double l, double dt, double kick, double dv, long max_steps,
               rfm::Histogram& q, rfm::Histogram& arrival, Tally& t) {
  Vec2 r{}, v{}, moved{};
  double sum_v2 = 0.0;
  long n = 0;
  const double l2 = l * l;
  while (n < max_steps) {
    // sample uniformly in time, then move, then kick
    q.add(v.x);
    q.add(v.y);
    sum_v2 += norm2(v);
    r += v * dt;
    moved = v;
    double z0, z1;
    rng.normal_pair(z0, z1);
    v += Vec2{z0, z1} * kick;
    ++n;
    if (norm2(r) > l2) break;
  }
  if (n >= max_steps && norm2(r) <= l2) ++t.capped;
  // the velocity that carried it across the boundary (the kick of the last step comes after)
  arrival.add(moved.x);
  arrival.add(moved.y);
  const double tau = static_cast<double>(n) * dt;
  t.tau.add(tau);
  t.heat.add(norm2(v) - 2.0 * 2.0 * dv * tau);
  t.virial.add(dot(r, v) - sum_v2 * dt);
  t.v2_sum += sum_v2;
  t.samples += 2 * n;
  t.region_sum += l;
}

// the common result fields
WalkResult finish(const Tally& t, int dim, double dt, rfm::Histogram q, rfm::Histogram arrival) {
  WalkResult r;
  r.dim = dim;
  r.dt = dt;
  r.q = std::move(q);
  r.arrival = std::move(arrival);
  r.walks = t.tau.n;
  r.samples = t.samples;
  r.mean_exit_time = t.tau.mean();
  r.exit_time_err = t.tau.err();
  r.mean_v2 = t.samples ? t.v2_sum / static_cast<double>(t.samples) : 0.0;
  r.mean_region = t.region_sum / static_cast<double>(std::max(1L, t.tau.n));
  r.heating_residual = t.heat.mean();
  r.heating_residual_err = t.heat.err();
  r.virial_residual = t.virial.mean();
  r.virial_residual_err = t.virial.err();
  r.capped = t.capped;
  return r;
}

}  // namespace

WalkResult disc_walk(const WalkParams& p, double radius) {
  p.validate();
  if (!(radius > 0.0)) throw InputError("disc_walk", "radius", "must be positive");
  const double dt = p.dt > 0.0 ? p.dt : walk_time_scale(p, radius) / 1000.0;
  const double vmax = p.v_max > 0.0 ? p.v_max : 8.0 * walk_velocity_scale(p, radius);
  const double dv = p.noise / (p.mass * p.mass);
  const double kick = std::sqrt(2.0 * p.noise * dt) / p.mass;  // σ of Δv per component
  rfm::Histogram q(rfm::Binning::linear(-vmax, vmax, p.bins)), arrival = q;
  Tally t;
  for (long w = 0; w < p.walks; ++w) {
    RngStream rng(p.seed, static_cast<std::uint64_t>(w));
    walk_disc(rng, radius, dt, kick, dv, p.max_steps, q, arrival, t);
  }
  return finish(t, 2, dt, std::move(q), std::move(arrival));
}

void PathTable::validate() const {
  if (l.size() != p.size() || l.size() < 2)
    throw InputError("PathTable", "l", "need at least two (l, P_l) points of equal count");
  for (std::size_t i = 0; i < l.size(); ++i) {
    if (!(l[i] > 0.0) || (i > 0 && !(l[i] > l[i - 1])))
      throw InputError("PathTable", "l", "free paths must be positive and increasing");
    if (!(p[i] >= 0.0)) throw InputError("PathTable", "p", "densities must be ≥ 0");
  }
}

WalkResult disc_walk_spm(const WalkParams& p, const PathTable& table) {
  p.validate();
  table.validate();
  // distribution function of the piecewise-linear density
  std::vector<double> cdf(table.l.size(), 0.0);
  for (std::size_t i = 1; i < cdf.size(); ++i)
    cdf[i] = cdf[i - 1] + 0.5 * (table.p[i - 1] + table.p[i]) * (table.l[i] - table.l[i - 1]);
  if (!(cdf.back() > 0.0)) throw InputError("PathTable", "p", "the density is zero everywhere");
  // the smallest region with weight sets the step; the median sets the histogram range
  double l_small = table.l.front();
  for (std::size_t i = 0; i + 1 < table.l.size(); ++i)
    if (cdf[i + 1] > 0.0) {
      l_small = table.l[i] > 0 ? table.l[i] : table.l[i + 1];
      break;
    }
  const double l_med = table.l[static_cast<std::size_t>(
      std::lower_bound(cdf.begin(), cdf.end(), 0.5 * cdf.back()) - cdf.begin())];
  const double dt = p.dt > 0.0 ? p.dt : walk_time_scale(p, l_small) / 50.0;
  const double vmax = p.v_max > 0.0 ? p.v_max : 20.0 * walk_velocity_scale(p, l_med);
  const double dv = p.noise / (p.mass * p.mass);
  const double kick = std::sqrt(2.0 * p.noise * dt) / p.mass;
  rfm::Histogram q(rfm::Binning::linear(-vmax, vmax, p.bins)), arrival = q;
  Tally t;
  for (long w = 0; w < p.walks; ++w) {
    RngStream rng(p.seed, static_cast<std::uint64_t>(w));
    // l by inverting the distribution function: a linear density within the segment
    const double u = rng.uniform() * cdf.back();
    const auto i =
        static_cast<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin()) - 1;
    const std::size_t j = std::min(i, cdf.size() - 2);
    const double w0 = table.l[j + 1] - table.l[j], p0 = table.p[j], p1 = table.p[j + 1];
    const double need = u - cdf[j], slope = (p1 - p0) / w0;
    // p0 s + slope s²/2 = need, the root in [0, w0]
    double s = std::abs(slope) < 1e-300 * std::max(1.0, p0)
                   ? need / p0
                   : (-p0 + std::sqrt(std::max(0.0, p0 * p0 + 2.0 * slope * need))) / slope;
    s = std::clamp(s, 0.0, w0);
    walk_disc(rng, table.l[j] + s, dt, kick, dv, p.max_steps, q, arrival, t);
  }
  return finish(t, 2, dt, std::move(q), std::move(arrival));
}

WalkResult interval_walk(const WalkParams& p, double length, IntervalStart start) {
  p.validate();
  if (!(length > 0.0)) throw InputError("interval_walk", "length", "must be positive");
  const double dt = p.dt > 0.0 ? p.dt : walk_time_scale(p, length) / 1000.0;
  const double vmax = p.v_max > 0.0 ? p.v_max : 8.0 * walk_velocity_scale(p, length);
  const double dv = p.noise / (p.mass * p.mass);
  const double kick = std::sqrt(2.0 * p.noise * dt) / p.mass;
  rfm::Histogram q(rfm::Binning::linear(-vmax, vmax, p.bins)), arrival = q;
  Tally t;
  for (long w = 0; w < p.walks; ++w) {
    RngStream rng(p.seed, static_cast<std::uint64_t>(w));
    const double x0 = start == IntervalStart::centre ? 0.5 * length : rng.uniform(0.0, length);
    double x = x0, v = 0.0, moved = 0.0, sum_v2 = 0.0, z[2] = {0.0, 0.0};
    long n = 0;
    bool inside = true;
    // the 1D version of T.5.11, one normal per step (both of each Box–Muller pair are used)
    while (n < p.max_steps) {
      q.add(v);
      sum_v2 += v * v;
      x += v * dt;
      moved = v;
      if (n % 2 == 0) rng.normal_pair(z[0], z[1]);
      v += kick * z[n % 2];
      ++n;
      if (x <= 0.0 || x >= length) {
        inside = false;
        break;
      }
    }
    if (inside) ++t.capped;
    if (x >= length) arrival.add(moved);  // arrival velocities at x = L (Fig. B.1)
    const double tau = static_cast<double>(n) * dt;
    t.tau.add(tau);
    t.heat.add(v * v - 2.0 * dv * tau);
    t.virial.add((x - x0) * v - sum_v2 * dt);
    t.v2_sum += sum_v2;
    t.samples += n;
    t.region_sum += length;
  }
  return finish(t, 1, dt, std::move(q), std::move(arrival));
}

HeatingCurve free_heating(const WalkParams& p, int dim, long particles, long steps, long every) {
  p.validate();
  if (!(p.dt > 0.0)) throw InputError("free_heating", "dt", "needs an explicit time step");
  if (dim < 1 || dim > 3) throw InputError("free_heating", "dim", "must be 1, 2 or 3");
  if (particles < 2 || steps < 1 || every < 1)
    throw InputError("free_heating", "particles", "need ≥ 2 particles, ≥ 1 step, every ≥ 1");
  const double kick = std::sqrt(2.0 * p.noise * p.dt) / p.mass;
  const long records = steps / every;
  std::vector<double> v2s(static_cast<std::size_t>(records), 0.0), v4s = v2s, x2s = v2s, x4s = v2s;
  // every component of every particle is an independent walk (T.5.11 without a boundary)
  for (long i = 0; i < particles; ++i) {
    RngStream rng(p.seed, static_cast<std::uint64_t>(i));
    for (int c = 0; c < dim; ++c) {
      double x = 0.0, v = 0.0;
      for (long n = 1; n <= records * every; ++n) {
        x += v * p.dt;
        v += kick * rng.normal();
        if (n % every == 0) {
          const auto k = static_cast<std::size_t>(n / every - 1);
          v2s[k] += v * v;
          v4s[k] += v * v * v * v;
          x2s[k] += x * x;
          x4s[k] += x * x * x * x;
        }
      }
    }
  }
  HeatingCurve h;
  const double m = static_cast<double>(particles) * dim;
  for (long k = 0; k < records; ++k) {
    const auto u = static_cast<std::size_t>(k);
    h.t.push_back(static_cast<double>((k + 1) * every) * p.dt);
    const double a = v2s[u] / m, b = x2s[u] / m;
    h.v2.push_back(a);
    h.v2_err.push_back(std::sqrt(std::max(0.0, v4s[u] / m - a * a) / (m - 1.0)));
    h.x2.push_back(b);
    h.x2_err.push_back(std::sqrt(std::max(0.0, x4s[u] / m - b * b) / (m - 1.0)));
  }
  return h;
}

double gaussian_tail_coefficient(const WalkResult& r, const WalkParams& p, double radius,
                                 double q_hi, double q_lo) {
  // ln Q against v² over the window below the peak, both sides pooled (T.5.12)
  const auto bins = r.q.bins();
  double peak = 0.0;
  for (const auto& b : bins) peak = std::max(peak, b.p);
  std::vector<double> x, y, s;
  for (const auto& b : bins) {
    if (b.count < 10 || b.p > q_hi * peak || b.p < q_lo * peak) continue;
    x.push_back(b.x * b.x);
    y.push_back(std::log(b.p));
    s.push_back(1.0 / std::sqrt(b.count));
  }
  const rfm::LineFit f = rfm::fit_line(x, y, s);
  const double scale = std::pow(p.mass * p.mass / (2.0 * p.noise * radius), 2.0 / 3.0);
  return -f.b / scale;
}

void write_walk_csv(const RecordSink& sink, const std::filesystem::path& path, const WalkResult& r,
                    const WalkParams& p, double radius) {
  const double vs = walk_velocity_scale(p, radius);
  const auto w =
      sink.create(path.string(), {"v", "u", "count", "Q", "Q_err", "Q_scaled", "arrival"},
                  {{"dim", static_cast<double>(r.dim)},
                   {"dt", r.dt},
                   {"radius", radius},
                   {"velocity_scale", vs},
                   {"mean_exit_time", r.mean_exit_time},
                   {"exit_time_err", r.exit_time_err},
                   {"mean_v2", r.mean_v2},
                   {"heating_residual", r.heating_residual},
                   {"heating_residual_err", r.heating_residual_err},
                   {"virial_residual", r.virial_residual},
                   {"virial_residual_err", r.virial_residual_err}});
  const auto qb = r.q.bins(), ab = r.arrival.bins();
  for (std::size_t i = 0; i < qb.size(); ++i)
    w->row({qb[i].x, qb[i].x / vs, qb[i].count, qb[i].p, qb[i].p_err, qb[i].p * vs, ab[i].p});
}

void write_interval_csv(const RecordSink& sink, const std::filesystem::path& path,
                        const WalkResult& r, const WalkParams& p, double length) {
  // arrivals at x = L in u = v/(D_v L)^(1/3), normalised over u > 0, beside B.32
  const double vs = walk_velocity_scale(p, length);
  const double tau_theory = appendix_b_mean_exit_time_coefficient() * walk_time_scale(p, length);
  const auto w = sink.create(path.string(), {"u", "count", "f", "f_err", "f_theory"},
                             {{"mean_exit_time", r.mean_exit_time},
                              {"exit_time_err", r.exit_time_err},
                              {"mean_exit_time_theory", tau_theory},
                              {"length", length}});
  const auto bins = r.arrival.bins();
  double total = 0.0;
  for (const auto& b : bins)
    if (b.x > 0.0) total += b.count;
  for (const auto& b : bins) {
    if (!(b.x > 0.0)) continue;
    const double du = (b.hi - b.lo) / vs;
    w->row({b.x / vs, b.count, b.count / (total * du), std::sqrt(b.count) / (total * du),
            appendix_b_arrival_density(b.x / vs)});
  }
}

void write_heating_csv(const RecordSink& sink, const std::filesystem::path& path,
                       const HeatingCurve& h, const WalkParams& p) {
  const double dv = p.noise / (p.mass * p.mass);
  const auto w =
      sink.create(path.string(), {"t", "v2", "v2_err", "v2_exact", "x2", "x2_err", "x2_exact"},
                  {{"D_v", dv}, {"dt", p.dt}});
  for (std::size_t k = 0; k < h.t.size(); ++k) {
    const double n = std::round(h.t[k] / p.dt);
    const double x2 = 2.0 * dv * p.dt * p.dt * p.dt * (n - 1.0) * n * (2.0 * n - 1.0) / 6.0;
    w->row({h.t[k], h.v2[k], h.v2_err[k], 2.0 * dv * h.t[k], h.x2[k], h.x2_err[k], x2});
  }
}

}  // namespace gs::models
