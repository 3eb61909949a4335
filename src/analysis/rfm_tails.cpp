// velocity histograms, stretched-exponential tail scan (appendix A), crossover fit (T.5.32)
#include "analysis/rfm_tails.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "analysis/rfm_fit.hpp"
#include "core/error.hpp"
#include "core/numbers.hpp"

namespace gs::rfm {

namespace {}  // namespace

Histogram velocity_histogram(double v_max, int n_bins) {
  if (!(v_max > 0.0)) throw InputError("velocity_histogram", "v_max", "must be positive");
  return Histogram(Binning::linear(-v_max, v_max, n_bins));
}

void add_components(Histogram& h, std::span<const Vec2> v) {
  for (const Vec2& u : v) {
    h.add(u.x);
    h.add(u.y);
  }
}

void add_values(Histogram& h, std::span<const double> v) {
  for (double u : v) h.add(u);
}

double stretched_exponential(double v, double a, double b, double alpha) {
  return a * std::exp(-b * std::pow(std::abs(v), alpha));
}

TailFit fit_tail(const Histogram& h, const TailFitOptions& opt) {
  // the bins of the window (both sides pooled through |v|)
  std::vector<double> av, lnp, sig;
  for (const HistBin& b : h.bins()) {
    if (b.count < opt.count_lo || b.count > opt.count_hi) continue;
    if (std::abs(b.x) < opt.v_abs_min || b.count <= 0) continue;
    av.push_back(std::abs(b.x));
    lnp.push_back(std::log(b.p));
    sig.push_back(opt.error_scale / std::sqrt(b.count));  // σ_lnP = s√X/X (T.A.4)
  }
  if (av.size() < 3)
    throw InputError("fit_tail", "count_lo",
                     "only " + std::to_string(av.size()) + " bins have counts in the window");
  TailFit f;
  f.points = static_cast<int>(av.size());
  f.v_lo = *std::min_element(av.begin(), av.end());
  f.v_hi = *std::max_element(av.begin(), av.end());
  f.best.chi2_r = std::numeric_limits<double>::infinity();
  // one weighted line of ln P against |v|^α per grid α
  const int steps =
      static_cast<int>(std::floor((opt.alpha_hi - opt.alpha_lo) / opt.alpha_step + 0.5));
  std::vector<double> x(av.size());
  int last_accepted = -2;
  for (int s = 0; s <= steps; ++s) {
    const double alpha = opt.alpha_lo + s * opt.alpha_step;
    for (std::size_t i = 0; i < av.size(); ++i) x[i] = std::pow(av[i], alpha);
    LineFit lf;
    try {
      lf = fit_line(x, lnp, sig);
    } catch (const InputError&) {
      continue;  // degenerate x (all |v| equal): no information at this α
    }
    TailTrial t{alpha, std::exp(lf.a), -lf.b, lf.chi2_r()};
    f.trials.push_back(t);
    if (t.chi2_r < f.best.chi2_r) f.best = t;
    // the accepted range and whether it has holes
    if (t.chi2_r < opt.chi2_accept) {
      if (!f.any_accepted)
        f.alpha_lo = alpha;
      else if (last_accepted != s - 1)
        f.contiguous = false;
      f.any_accepted = true;
      f.alpha_hi = alpha;
      last_accepted = s;
    }
  }
  return f;
}

// ---- crossover (T.5.32) ------------------------------------------------------------------

double crossover_density(double v, double d, double v_r, double v_c, double alpha) {
  const double u = v / v_r;
  return d * std::exp(-u * u / (1.0 + std::pow(std::abs(v / v_c), 2.0 - alpha)));
}

double CrossoverFit::v_a() const {
  // (v/v_r)² (v_c/v)^(2−α) = |v|^α v_c^(2−α)/v_r² = |v/v_A|^α
  return std::pow(v_r * v_r / std::pow(v_c, 2.0 - alpha), 1.0 / alpha);
}

CrossoverFit fit_crossover(const Histogram& h, double alpha, bool fit_alpha, double min_count) {
  // the bins with enough counts, and moments for a starting guess
  std::vector<double> v, lo, hi, p, s;
  double pmax = 0.0, m2 = 0.0, m0 = 0.0;
  for (const HistBin& b : h.bins()) {
    if (b.count < min_count || b.count <= 0) continue;
    v.push_back(b.x);
    lo.push_back(b.lo);
    hi.push_back(b.hi);
    p.push_back(b.p);
    s.push_back(b.p_err);
    pmax = std::max(pmax, b.p);
    m2 += b.count * b.x * b.x;
    m0 += b.count;
  }
  const int npar = fit_alpha ? 4 : 3;
  if (static_cast<int>(v.size()) <= npar + 1)
    throw InputError("fit_crossover", "min_count", "too few bins with enough counts");
  // a Gaussian core of the same variance: v_r = √2 σ; crossover a little further out
  const double vr0 = std::sqrt(2.0 * m2 / m0);
  Eigen::VectorXd p0(npar);
  p0[0] = pmax;
  p0[1] = vr0;
  p0[2] = 2.0 * vr0;
  if (fit_alpha) p0[3] = alpha;
  // the model is the Simpson average of T.5.32 over each bin (x is the bin index), so the
  // curvature of the density across a bin brings no bias
  const Model model = [&, alpha, fit_alpha](double x, const Eigen::VectorXd& q) {
    const auto i = static_cast<std::size_t>(x);
    const double a = fit_alpha ? q[3] : alpha;
    const double vr = std::abs(q[1]), vc = std::abs(q[2]);
    return (crossover_density(lo[i], q[0], vr, vc, a) +
            4.0 * crossover_density(0.5 * (lo[i] + hi[i]), q[0], vr, vc, a) +
            crossover_density(hi[i], q[0], vr, vc, a)) /
           6.0;
  };
  std::vector<double> index(v.size());
  for (std::size_t i = 0; i < index.size(); ++i) index[i] = static_cast<double>(i);
  const LmResult r = fit_lm(model, index, p, s, p0);
  CrossoverFit c;
  c.d = r.p[0];
  c.d_err = r.err[0];
  c.v_r = std::abs(r.p[1]);
  c.v_r_err = r.err[1];
  c.v_c = std::abs(r.p[2]);
  c.v_c_err = r.err[2];
  c.alpha = fit_alpha ? r.p[3] : alpha;
  c.alpha_err = fit_alpha ? r.err[3] : 0.0;
  c.chi2_r = r.chi2_r();
  c.points = static_cast<int>(v.size());
  return c;
}

// ---- ln–ln plot --------------------------------------------------------------------------

std::vector<LnLnPoint> lnln_tail(const Histogram& h, double amplitude, double v_scale,
                                 double min_count) {
  std::vector<LnLnPoint> out;
  for (const HistBin& b : h.bins()) {
    if (b.count < min_count || b.count <= 0 || b.x == 0.0) continue;
    if (!(b.p < amplitude)) continue;
    const double l = -std::log(b.p / amplitude);  // > 0
    out.push_back({std::log(std::abs(b.x) / v_scale), std::log(l), (b.p_err / b.p) / l});
  }
  return out;
}

// ---- CSV ---------------------------------------------------------------------------------

void write_velocity_csv(const RecordSink& sink, const std::filesystem::path& path,
                        const Histogram& h, const TailFit* tail, const CrossoverFit* cross) {
  RecordMeta meta;
  if (tail) {
    meta.insert(meta.end(), {{"alpha_best", tail->best.alpha},
                             {"tail_A", tail->best.a},
                             {"tail_B", tail->best.b},
                             {"tail_chi2_r", tail->best.chi2_r},
                             {"alpha_lo", tail->any_accepted ? tail->alpha_lo : kNaN},
                             {"alpha_hi", tail->any_accepted ? tail->alpha_hi : kNaN},
                             {"tail_v_lo", tail->v_lo},
                             {"tail_v_hi", tail->v_hi}});
  }
  if (cross) {
    meta.insert(meta.end(), {{"cross_D", cross->d},
                             {"cross_v_r", cross->v_r},
                             {"cross_v_c", cross->v_c},
                             {"cross_alpha", cross->alpha},
                             {"cross_chi2_r", cross->chi2_r}});
  }
  const auto w =
      sink.create(path.string(), {"v", "count", "P", "P_err", "P_tail", "P_cross"}, meta);
  for (const HistBin& b : h.bins()) {
    const bool in_window = tail && std::abs(b.x) >= tail->v_lo && std::abs(b.x) <= tail->v_hi;
    const double pt =
        in_window ? stretched_exponential(b.x, tail->best.a, tail->best.b, tail->best.alpha) : kNaN;
    const double pc =
        cross ? crossover_density(b.x, cross->d, cross->v_r, cross->v_c, cross->alpha) : kNaN;
    w->row({b.x, b.count, b.p, b.p_err, pt, pc});
  }
}

void write_tail_scan_csv(const RecordSink& sink, const std::filesystem::path& path,
                         const TailFit& fit) {
  const auto w = sink.create(path.string(), {"alpha", "chi2_r", "A", "B"},
                             {{"alpha_best", fit.best.alpha},
                              {"alpha_lo", fit.any_accepted ? fit.alpha_lo : kNaN},
                              {"alpha_hi", fit.any_accepted ? fit.alpha_hi : kNaN}});
  for (const TailTrial& t : fit.trials) w->row({t.alpha, t.chi2_r, t.a, t.b});
}

void write_lnln_csv(const RecordSink& sink, const std::filesystem::path& path,
                    std::span<const LnLnPoint> pts, double amplitude, double v_scale) {
  const auto w =
      sink.create(path.string(), {"ln_v", "y", "y_err"}, {{"A", amplitude}, {"v_scale", v_scale}});
  for (const LnLnPoint& p : pts) w->row({p.ln_v, p.y, p.y_err});
}

}  // namespace gs::rfm
