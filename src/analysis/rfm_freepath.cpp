// free-path histogram and the fit of T.4.25
#include "analysis/rfm_freepath.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "analysis/rfm_fit.hpp"
#include "core/error.hpp"

namespace gs::rfm {

Histogram free_path_histogram(double l_min, double l_max, int n_bins) {
  return Histogram(Binning::log(l_min, l_max, n_bins));
}

double free_path_density(double l, double a0, double c, double d_f) {
  return a0 * std::pow(l, d_f - 2.0) * std::exp(-c * std::pow(l, d_f - 1.0));
}

FreePathFit fit_free_paths(const Histogram& h, double l_fit_min, double min_count) {
  // the usable bins
  std::vector<double> l, lo, hi, p, s, lnp, sln;
  for (const HistBin& b : h.bins()) {
    if (b.x < l_fit_min || b.count < min_count || b.count <= 0) continue;
    l.push_back(b.x);
    lo.push_back(b.lo);
    hi.push_back(b.hi);
    p.push_back(b.p);
    s.push_back(b.p_err);
    lnp.push_back(std::log(b.p));
    sln.push_back(1.0 / std::sqrt(b.count));
  }
  if (l.size() < 5)
    throw InputError("fit_free_paths", "min_count",
                     "only " + std::to_string(l.size()) + " bins are usable; need at least 5");

  // start: for each trial D_f, ln P − (D_f−2) ln l = ln A₀ − C l^(D_f−1) is a line
  double best_chi2 = std::numeric_limits<double>::infinity();
  Eigen::VectorXd p0(3);
  std::vector<double> x(l.size()), y(l.size());
  for (double df = 1.02; df <= 2.98; df += 0.02) {
    for (std::size_t i = 0; i < l.size(); ++i) {
      x[i] = std::pow(l[i], df - 1.0);
      y[i] = lnp[i] - (df - 2.0) * std::log(l[i]);
    }
    const LineFit lf = fit_line(x, y, sln);
    if (lf.chi2 < best_chi2 && -lf.b > 0.0) {
      best_chi2 = lf.chi2;
      p0 << df, -lf.b, std::exp(lf.a);
    }
  }
  if (!std::isfinite(best_chi2))
    throw InputError("fit_free_paths", "", "no trial D_f gives a decaying tail (C > 0)");

  // the nonlinear fit on densities with Poisson errors; parameters (D_f, C, A₀). The model is
  // the exact bin average of T.4.25, whose integral is (A₀/(Cβ))(1 − exp(−C l^β)), β = D_f − 1,
  // so wide log bins bring no bias; the model's x is the index of the bin.
  const Model model = [&lo, &hi](double x, const Eigen::VectorXd& q) {
    const auto i = static_cast<std::size_t>(x);
    const double beta = q[0] - 1.0, c = q[1];
    const double ea = std::exp(-c * std::pow(lo[i], beta)),
                 eb = std::exp(-c * std::pow(hi[i], beta));
    return q[2] / (c * beta) * (ea - eb) / (hi[i] - lo[i]);
  };
  std::vector<double> index(l.size());
  for (std::size_t i = 0; i < index.size(); ++i) index[i] = static_cast<double>(i);
  const LmResult r = fit_lm(model, index, p, s, p0);
  FreePathFit f;
  const double inflate = r.chi2_r() > 1.0 ? std::sqrt(r.chi2_r()) : 1.0;
  f.d_f = r.p[0];
  f.d_f_err = r.err[0] * inflate;
  f.c = r.p[1];
  f.c_err = r.err[1] * inflate;
  f.a0 = r.p[2];
  f.a0_err = r.err[2] * inflate;
  f.chi2_r = r.chi2_r();
  f.points = static_cast<int>(l.size());
  f.l_min = l.front();
  return f;
}

double tail_start(const Histogram& h, double p_below) {
  double start = std::numeric_limits<double>::infinity();
  const auto& bins = h.bins();
  for (auto it = bins.rbegin(); it != bins.rend(); ++it) {
    if (it->count <= 0) continue;  // empty bins neither end nor extend the tail
    if (!(it->p < p_below)) break;
    start = it->x;
  }
  return start;
}

void write_freepath_csv(const RecordSink& sink, const std::filesystem::path& path,
                        const Histogram& h, const FreePathFit* fit) {
  RecordMeta meta;
  if (fit) {
    meta = {{"D_f", fit->d_f},       {"D_f_err", fit->d_f_err}, {"C", fit->c},
            {"C_err", fit->c_err},   {"A0", fit->a0},           {"A0_err", fit->a0_err},
            {"chi2_r", fit->chi2_r}, {"l_fit_min", fit->l_min}};
  }
  const auto w = sink.create(path.string(), {"l", "count", "P", "P_err", "P_fit"}, meta);
  for (const HistBin& b : h.bins()) {
    const double pf = fit ? free_path_density(b.x, fit->a0, fit->c, fit->d_f)
                          : std::numeric_limits<double>::quiet_NaN();
    w->row({b.x, b.count, b.p, b.p_err, pf});
  }
}

}  // namespace gs::rfm
