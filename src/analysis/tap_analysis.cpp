// the tapping study's analysis: statistics, KDEs, overlapping histograms, quadron fits
#include "analysis/tap_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "core/error.hpp"

namespace gs {

namespace {

// the values after the first `discard` taps
std::vector<double> tail(const std::vector<double>& x, int discard) {
  if (static_cast<int>(x.size()) <= discard) return {};
  return {x.begin() + discard, x.end()};
}

std::string format_control(double c) {
  std::ostringstream s;
  s << c;
  return s.str();
}

// per-run statistics (docs/physics.md §2.6): φ̄, σ_φ with CIs, τ_int, normality, the halves
TapRunSummary summarize(const TapRunInput& run, const std::vector<double>& phi, int discard,
                        const TapAnalysisOptions& opts) {
  TapRunSummary s;
  s.discard = discard;
  s.label = tap_run_label(run);
  s.protocol = run.protocol;
  s.control = run.control;
  s.n_total = static_cast<int>(run.series.phi.size());
  s.n_used = static_cast<int>(phi.size());
  s.phi_mean = mean(phi);
  s.sigma = stddev(phi);
  s.tau = autocorr_time(phi);
  const double tau = s.tau.tau_int;
  s.phi_err = s.sigma * std::sqrt(2.0 * tau / s.n_used);
  s.phi_mean_ci = mean_ci(phi, opts.level);
  s.phi_mean_ci_tau = mean_ci(phi, opts.level, tau);
  s.sigma_ci = stddev_ci(phi, opts.level);
  s.sigma_ci_tau = stddev_ci(phi, opts.level, tau);
  s.normality = normality_chi2(phi, opts.alpha);
  // the halves of the test rectangle: σ ratio to the whole ≈ √2 for a large enough region
  const auto left = tail(run.series.phi_left, discard);
  const auto right = tail(run.series.phi_right, discard);
  if (left.size() == phi.size() && right.size() == phi.size() && phi.size() >= 2) {
    s.has_halves = true;
    s.mean_left = mean(left);
    s.mean_right = mean(right);
    s.sigma_left = stddev(left);
    s.sigma_right = stddev(right);
  }
  return s;
}

int find_label(const std::vector<TapRunSummary>& runs, const std::string& label) {
  for (std::size_t i = 0; i < runs.size(); ++i)
    if (runs[i].label == label) return static_cast<int>(i);
  return -1;
}

// quadron fit (P.26) over the runs whose index passes `use`, with β̂ against the reference
QuadronFit fit_runs(const TapAnalysisResult& r, const TapAnalysisOptions& opts,
                    const std::vector<int>& use, bool joint = false) {
  std::vector<double> b, be, p, pe;
  for (int i : use) {
    if (joint) {
      const MultiBeta& m = r.multi.joint[i];
      if (!m.valid || !(m.dbeta_err > 0.0 || i == r.ref)) continue;
      b.push_back(m.dbeta);
      // the reference's own β̂ is 0 by definition; its weight comes from the others' errors
      be.push_back(i == r.ref ? 0.0 : m.dbeta_err);
      p.push_back(r.runs[i].phi_mean);
      pe.push_back(r.runs[i].phi_err);
      continue;
    }
    if (!r.beta[i].valid) continue;
    b.push_back(r.beta[i].dbeta);
    be.push_back(r.beta[i].dbeta_err);
    p.push_back(r.runs[i].phi_mean);
    pe.push_back(r.runs[i].phi_err);
  }
  return fit_quadron(b, p, pe, be, opts.quadron);
}

}  // namespace

std::string tap_run_label(const TapRunInput& run) {
  if (!run.label.empty()) return run.label;
  return (run.protocol.empty() ? std::string("run") : run.protocol) + "_" +
         format_control(run.control);
}

TapAnalysisResult run_tap_analysis(const std::vector<TapRunInput>& runs,
                                   const TapAnalysisOptions& opts) {
  if (runs.empty()) throw InputError("", "runs", "the tapping analysis needs at least one run");
  // the options every caller may get wrong, checked before any series is cut with them
  if (opts.discard < 0)
    throw InputError("", "discard", "must be >= 0 taps (got " + std::to_string(opts.discard) + ")");
  if (!(opts.level > 0.0 && opts.level < 1.0))
    throw InputError("", "level", "must lie strictly between 0 and 1");
  if (!(opts.alpha > 0.0 && opts.alpha < 1.0))
    throw InputError("", "alpha", "must lie strictly between 0 and 1");
  // 0: not given (the φ statistics only, no β̂ and no quadron fit)
  if (!(opts.test_area >= 0.0) || !std::isfinite(opts.test_area))
    throw InputError("", "test_area",
                     "must be a finite area > 0 (m²), or none for the φ statistics only");
  if (opts.bootstrap < 0) throw InputError("", "bootstrap", "must be >= 0");
  if (opts.overlap.bins < 0) throw InputError("", "bins", "must be >= 0");
  TapAnalysisResult r;

  // the pairs to test: runs of one protocol at one control value; series of unknown origin
  // (no protocol) are compared with each other, whatever the control
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < runs.size(); ++i)
    for (std::size_t j = i + 1; j < runs.size(); ++j) {
      const TapRunInput &a = runs[i], &b = runs[j];
      const bool unknown = a.protocol.empty() && b.protocol.empty();
      if (a.protocol == b.protocol &&
          (unknown || std::abs(a.control - b.control) <= 1e-9 * (1 + std::abs(a.control))))
        pairs.emplace_back(i, j);
    }
  // the steps the progress counts, known before the first
  const double n_runs = static_cast<double>(runs.size());
  const bool with_beta = opts.test_area > 0.0;
  const double total = 2.0 * n_runs + static_cast<double>(pairs.size()) +
                       (with_beta ? 2.0 + (runs.size() > 1 ? 1.0 + opts.bootstrap : 0.0) : 0.0);
  double done = 0.0;
  auto step = [&] {
    done += 1.0;
    if (opts.progress) opts.progress(done, total);
  };

  // per-run statistics after dropping the transient
  std::vector<std::vector<double>> phis;
  std::set<std::string> labels;
  for (const auto& run : runs) {
    const std::string label = tap_run_label(run);
    if (!labels.insert(label).second)
      throw InputError(run.series.source, "label", "duplicate run label '" + label + "'");
    int discard = opts.discard;
    Truncation cut;
    if (opts.discard_auto) {
      // the cut keeps the 20 taps the statistics need (a short run: its transient stays in part)
      cut = mser_truncation(run.series.phi);
      const int n = static_cast<int>(run.series.phi.size());
      discard = std::max(discard, std::min(cut.drop, n - 20));
    }
    phis.push_back(tail(run.series.phi, discard));
    if (phis.back().size() < 20)
      throw InputError(run.series.source, "phi",
                       "run '" + label + "' has " + std::to_string(phis.back().size()) +
                           " taps after discarding " + std::to_string(discard) +
                           " (needs at least 20)");
    // a constant φ has no distribution: no bandwidth, no test, no fit
    const auto [lo, hi] = std::minmax_element(phis.back().begin(), phis.back().end());
    if (*lo == *hi)
      throw InputError(run.series.source, "phi",
                       "run '" + label + "': φ is the same (" + std::to_string(*lo) + ") at all " +
                           std::to_string(phis.back().size()) +
                           " taps after the transient; there is no distribution to analyse");
    r.runs.push_back(summarize(run, phis.back(), discard, opts));
    r.runs.back().steady = cut.steady;
    if (!cut.steady)
      r.notes.push_back("run '" + label + "': no steady part found (MSER cuts at half the run); " +
                        "its statistics are those of a series still drifting");
    if (!r.runs.back().tau.converged)
      r.notes.push_back("run '" + label + "': no autocorrelation window M ≥ 5τ below n/2; " +
                        "τ_int and the τ-corrected intervals are unreliable (series too short)");
    step();
  }

  // runs of one protocol at one control value, pairwise: same φ distribution?
  // (each run sorted once: the tests need only its values, and the KS walk wants them sorted)
  std::vector<std::vector<double>> sorted;
  if (!pairs.empty())
    for (const auto& phi : phis) {
      sorted.push_back(phi);
      std::sort(sorted.back().begin(), sorted.back().end());
    }
  for (const auto& [i, j] : pairs) {
    r.pairs.push_back(
        {static_cast<int>(i), static_cast<int>(j),
         two_sample_test(sorted[i], r.runs[i].tau.tau_int, sorted[j], r.runs[j].tau.tau_int)});
    step();
  }

  // KDEs (B1–B7): Silverman h for the normal kernel; the compact kernels on the same grid with
  // the equivalent (canonical) bandwidth, so that the three smooth alike (paper Fig. 13)
  for (const auto& phi : phis) {
    r.kde_normal.push_back(kde_auto(phi, opts.kde_points, Kernel::Normal));
    const auto& c = r.kde_normal.back();
    r.kde_epanechnikov.push_back(kde(
        phi, c.x, equivalent_bandwidth(Kernel::Epanechnikov, c.bandwidth), Kernel::Epanechnikov));
    r.kde_box.push_back(kde(phi, c.x, equivalent_bandwidth(Kernel::Box, c.bandwidth), Kernel::Box));
    step();
  }

  // the references: by label, else the paper's (negative g with g_p nearest 6), else the
  // first run; the second one defaults to the next run of the same protocol
  if (opts.reference.empty()) {
    r.ref = 0;
    double best = 1e300;
    for (std::size_t i = 0; i < runs.size(); ++i)
      if (runs[i].protocol == "negative_g" && std::abs(runs[i].control - 6.0) < best) {
        best = std::abs(runs[i].control - 6.0);
        r.ref = static_cast<int>(i);
      }
  } else {
    r.ref = find_label(r.runs, opts.reference);
  }
  if (r.ref < 0) throw InputError("", "reference", "no run labelled '" + opts.reference + "'");
  if (!opts.reference2.empty()) {
    r.ref2 = find_label(r.runs, opts.reference2);
    if (r.ref2 < 0) throw InputError("", "reference2", "no run labelled '" + opts.reference2 + "'");
  } else {
    for (std::size_t k = 1; k < runs.size() && r.ref2 < 0; ++k) {
      const int i = static_cast<int>((r.ref + k) % runs.size());
      if (runs[i].protocol == runs[r.ref].protocol) r.ref2 = i;
    }
  }

  // β̂ needs V_g = V_T φ̄_ref, so without the test area the φ statistics are the analysis
  if (!std::isfinite(opts.test_area))
    throw InputError("", "test_area", "not a finite area (m²); 0 leaves β̂ out");
  if (!(opts.test_area > 0.0)) {
    r.notes.push_back(
        "no test area: φ statistics only; β̂ (overlapping histograms) and the quadron fit "
        "need the area of the test region, m²");
    return r;
  }
  if (r.ref2 < 0) {
    r.notes.push_back("no second reference run: beta against two references skipped");
    step();  // the second reference's fits, counted in the total
  }

  // overlapping histograms (P.39) with V_g = V_T φ̄_ref held constant
  r.v_g = opts.test_area * r.runs[r.ref].phi_mean;
  r.beta = betas_from_phi(phis[r.ref], phis, r.v_g, opts.overlap);
  step();
  // consecutive taps are correlated: the counts' variance grows by ≈ τ_ref + τ_run
  auto correlate = [&](std::vector<BetaEstimate>& b, int refi) {
    for (std::size_t i = 0; i < b.size(); ++i)
      b[i] = with_variance_factor(b[i], r.runs[refi].tau.tau_int + r.runs[i].tau.tau_int);
  };
  correlate(r.beta, r.ref);
  // the reference against itself is β̂ = 0, ln Z ratio 0 by definition (no error)
  r.beta[r.ref].dbeta = r.beta[r.ref].dbeta_err = 0.0;
  r.beta[r.ref].dlnz = r.beta[r.ref].dlnz_err = r.beta[r.ref].cov = 0.0;
  for (std::size_t i = 0; i < r.beta.size(); ++i)
    if (!r.beta[i].valid)
      r.notes.push_back("run '" + r.runs[i].label + "': no overlap with the reference (" +
                        r.beta[i].fit.note + ")");
  if (r.ref2 >= 0) {
    r.beta2 = betas_from_phi(phis[r.ref2], phis, r.v_g, opts.overlap);
    step();
    correlate(r.beta2, r.ref2);
    r.beta2[r.ref2].dbeta = r.beta2[r.ref2].dbeta_err = 0.0;
    r.beta2[r.ref2].dlnz = r.beta2[r.ref2].dlnz_err = r.beta2[r.ref2].cov = 0.0;
    // (P.39): β̂ from two references differ by a constant; weighted mean and χ² of that
    double sw = 0.0, swd = 0.0;
    std::vector<std::pair<double, double>> d;
    for (std::size_t i = 0; i < r.beta.size(); ++i) {
      if (!r.beta[i].valid || !r.beta2[i].valid) continue;
      const double e2 =
          r.beta[i].dbeta_err * r.beta[i].dbeta_err + r.beta2[i].dbeta_err * r.beta2[i].dbeta_err;
      if (!(e2 > 0.0)) continue;
      d.emplace_back(r.beta[i].dbeta - r.beta2[i].dbeta, e2);
      sw += 1.0 / e2;
      swd += d.back().first / e2;
    }
    if (sw > 0.0) {
      r.ref_offset = swd / sw;
      r.ref_offset_err = 1.0 / std::sqrt(sw);
      for (const auto& [v, e2] : d)
        r.ref_offset_chi2 += (v - r.ref_offset) * (v - r.ref_offset) / e2;
      r.ref_offset_dof = static_cast<int>(d.size()) - 1;
    }
  }

  // β̂ through neighbours, for the runs the reference does not overlap
  if (runs.size() > 1) {
    MultiHistOptions mo;
    mo.overlap = opts.overlap;
    mo.bootstrap = opts.bootstrap;
    for (const auto& s : r.runs) mo.tau_int.push_back(s.tau.tau_int);
    mo.step = step;
    // the direct β̂ too, for the covariance of the two references' β̂ (beta_cov.csv)
    mo.direct_refs = {r.ref};
    if (r.ref2 >= 0) mo.direct_refs.push_back(r.ref2);
    r.multi = multi_histogram_beta(phis, r.ref, r.v_g, mo);
    for (const auto& n : r.multi.notes) r.notes.push_back("multiple histograms: " + n);
  }

  // ideal quadron fit (P.26) over all runs and per protocol
  std::vector<int> all(runs.size());
  for (std::size_t i = 0; i < runs.size(); ++i) all[i] = static_cast<int>(i);
  r.quadron["all"] = fit_runs(r, opts, all);
  if (runs.size() > 1) r.quadron["joint"] = fit_runs(r, opts, all, true);
  std::set<std::string> protocols;
  for (const auto& run : runs) protocols.insert(run.protocol);
  if (protocols.size() > 1) {
    for (const auto& pr : protocols) {
      std::vector<int> use;
      for (std::size_t i = 0; i < runs.size(); ++i)
        if (runs[i].protocol == pr) use.push_back(static_cast<int>(i));
      r.quadron[pr] = fit_runs(r, opts, use);
    }
  }
  for (const auto& [name, f] : r.quadron)
    if (!f.converged) r.notes.push_back("quadron fit '" + name + "': " + f.note);
  return r;
}

void analyze_tapping(const std::vector<TapRunInput>& runs, const TapAnalysisOptions& opts,
                     const std::string& out_dir) {
  write_tap_analysis(run_tap_analysis(runs, opts), runs, opts, out_dir);
}

}  // namespace gs
