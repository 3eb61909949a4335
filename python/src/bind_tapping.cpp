// the tapping study's analysis on in-memory φ series (analysis/tap_analysis.hpp): per-run
// statistics, overlapping histograms → β − β_ref and ln Z − ln Z_ref, the quadron fit, and the
// synthetic ideal quadron gas with known answers
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "analysis/tap_analysis.hpp"
#include "analysis/tap_synthetic.hpp"
#include "arguments.hpp"
#include "bindings.hpp"
#include "core/error.hpp"

namespace gs::py_bind {

namespace {

using Series = std::vector<double>;

py::dict interval(const Interval& i) {
  py::dict d;
  d["lo"] = i.lo;
  d["hi"] = i.hi;
  return d;
}

py::dict qfit_dict(const QFit& f) {
  py::dict d;
  d["valid"] = f.valid;
  d["note"] = f.note;
  Series x, q, e;
  for (const QPoint& p : f.points) {
    x.push_back(p.x);
    q.push_back(p.q);
    e.push_back(p.q_err);
  }
  d["x"] = py::array(py::cast(x));
  d["q"] = py::array(py::cast(q));
  d["q_err"] = py::array(py::cast(e));
  d["slope"] = f.slope;
  d["slope_err"] = f.slope_err;
  d["intercept"] = f.intercept;
  d["intercept_err"] = f.intercept_err;
  d["chi2"] = f.chi2;
  d["dof"] = f.dof;
  d["r2"] = f.r2;
  d["quad"] = f.quad;
  d["quad_err"] = f.quad_err;
  d["bin_width"] = f.bin_width;
  return d;
}

py::dict beta_dict(const BetaEstimate& b) {
  py::dict d;
  d["valid"] = b.valid;
  d["dbeta"] = b.dbeta;
  d["dbeta_err"] = b.dbeta_err;
  d["dlnz"] = b.dlnz;
  d["dlnz_err"] = b.dlnz_err;
  d["cov"] = b.cov;
  d["fit"] = qfit_dict(b.fit);
  return d;
}

py::dict quadron_dict(const QuadronFit& f) {
  py::dict d;
  d["converged"] = f.converged;
  d["note"] = f.note;
  d["iterations"] = f.iterations;
  d["points"] = f.points;
  d["a"] = f.a;
  d["a_err"] = f.a_err;
  d["beta0"] = f.beta0;
  d["beta0_err"] = f.beta0_err;
  d["cov_a_beta0"] = f.cov_a_beta0;
  d["chi2"] = f.chi2;
  d["dof"] = f.dof;
  d["errors_scaled"] = f.errors_scaled;
  return d;
}

py::dict summary_dict(const TapRunSummary& s) {
  py::dict d;
  d["label"] = s.label;
  d["protocol"] = s.protocol;
  d["control"] = s.control;
  d["n_total"] = s.n_total;
  d["n_used"] = s.n_used;
  d["discard"] = s.discard;
  d["steady"] = s.steady;
  d["phi_mean"] = s.phi_mean;
  d["phi_err"] = s.phi_err;
  d["phi_mean_ci"] = interval(s.phi_mean_ci);
  d["phi_mean_ci_tau"] = interval(s.phi_mean_ci_tau);
  d["sigma"] = s.sigma;
  d["sigma_ci"] = interval(s.sigma_ci);
  d["sigma_ci_tau"] = interval(s.sigma_ci_tau);
  d["tau_int"] = s.tau.tau_int;
  d["tau_err"] = s.tau.tau_err;
  d["tau_converged"] = s.tau.converged;
  d["normality_p"] = s.normality.p_value;
  d["normal"] = s.normality.normal;
  return d;
}

// more bins than this only cost memory: a histogram of 10⁶ bins already has empty bins
constexpr long long kMaxBins = 1000000;

OverlapOptions overlap_options(const Args& args, const std::string& method, int bins,
                               double min_fraction) {
  OverlapOptions o;
  if (method == "histogram")
    o.method = DensityMethod::Histogram;
  else if (method == "kde")
    o.method = DensityMethod::Kde;
  else
    args.fail("method", "must be \"histogram\" or \"kde\" (got \"" + method + "\")");
  args.count("bins", bins, 0, kMaxBins);
  args.require(
      min_fraction >= 0.0 && min_fraction < 1.0, "min_fraction",
      "must be a share from 0 up to (not including) 1 (got " + Args::text(min_fraction) + ")");
  o.bins = bins;
  o.min_fraction = min_fraction;
  return o;
}

// a run's value under `key` as `T`, or `fallback` when absent; a value of the wrong type is an
// InputError naming the run and the key
template <class T>
T run_value(const Args& args, const py::dict& run, std::size_t k, const char* key, T fallback) {
  if (!run.contains(key) || run[key].is_none()) return fallback;
  try {
    return run[key].cast<T>();
  } catch (const py::cast_error&) {
    args.fail("runs",
              "run " + std::to_string(k) + ": '" + key + "' is a " +
                  std::string(py::str(py::type::of(run[key]).attr("__name__"))) + ", not " +
                  (std::is_same_v<T, Series>
                       ? "a list of numbers"
                       : "a " + std::string(std::is_same_v<T, std::string> ? "string" : "number")));
  }
}

// φ series: finite volume fractions in (0, 1], as `gransim analyze` requires of taps.csv
void check_phi(const Args& args, const char* name, const Series& phi) {
  args.all_finite(name, phi);
  for (std::size_t k = 0; k < phi.size(); ++k)
    args.require(
        phi[k] > 0.0 && phi[k] <= 1.0, name,
        "item " + std::to_string(k) + " is not a volume fraction in (0, 1]: " + Args::text(phi[k]));
}

void check_quadron_params(const Args& args, double phi_rlp, double phi_rcp) {
  args.open("phi_rlp", phi_rlp, 0.0, 1.0).open("phi_rcp", phi_rcp, 0.0, 1.0);
  args.require(
      phi_rlp < phi_rcp, "phi_rcp",
      "must exceed phi_rlp (got " + Args::text(phi_rcp) + " <= " + Args::text(phi_rlp) + ")");
}

}  // namespace

void bind_tapping(py::module_& m) {
  m.def(
      "tap_analysis",
      [](const py::list& runs, int discard, double level, double alpha,
         std::optional<double> test_area, const std::string& reference,
         const std::string& reference2, const std::string& method, int bins, double phi_rlp,
         double phi_rcp, int bootstrap, const std::string& out_dir, bool discard_auto) {
        const Args args("tap_analysis");
        args.count("discard", discard, 0, std::numeric_limits<int>::max())
            .open("level", level, 0.0, 1.0)
            .open("alpha", alpha, 0.0, 1.0)
            .count("bootstrap", bootstrap, 0, 100000);
        // no test area: the φ statistics only (no β̂, no quadron fit), as `gransim analyze`
        if (test_area) args.positive("test_area", *test_area);
        check_quadron_params(args, phi_rlp, phi_rcp);
        std::vector<TapRunInput> in;
        for (const auto& item : runs) {
          const std::size_t k = in.size();
          if (!py::isinstance<py::dict>(item))
            args.fail("runs", "run " + std::to_string(k) +
                                  " is not a dict with 'phi' (and optionally 'label', "
                                  "'protocol', 'control', 'tap', 'phi_left', 'phi_right')");
          const auto run = item.cast<py::dict>();
          if (!run.contains("phi")) args.fail("runs", "run " + std::to_string(k) + " has no 'phi'");
          TapRunInput r;
          r.label = run_value<std::string>(args, run, k, "label", "");
          // a series without protocol or control is of unknown origin, not a negative-g run
          r.protocol = run_value<std::string>(args, run, k, "protocol", "");
          r.control = run_value<double>(args, run, k, "control", std::nan(""));
          if (run.contains("control")) args.finite("runs", r.control);
          r.series.source = r.label.empty() ? "run " + std::to_string(k) : r.label;
          r.series.phi = run_value<Series>(args, run, k, "phi", {});
          r.series.phi_left = run_value<Series>(args, run, k, "phi_left", {});
          r.series.phi_right = run_value<Series>(args, run, k, "phi_right", {});
          r.series.tap = run_value<Series>(args, run, k, "tap", {});
          check_phi(args, "runs", r.series.phi);
          check_phi(args, "runs", r.series.phi_left);
          check_phi(args, "runs", r.series.phi_right);
          args.all_finite("runs", r.series.tap);
          for (const Series* side : {&r.series.phi_left, &r.series.phi_right, &r.series.tap})
            args.require(side->empty() || side->size() == r.series.phi.size(), "runs",
                         "run " + std::to_string(k) +
                             ": 'tap', 'phi_left' and 'phi_right' must have as many values as "
                             "'phi' (" +
                             std::to_string(r.series.phi.size()) + "), got " +
                             std::to_string(side->size()));
          if (r.series.tap.empty())
            for (std::size_t t = 0; t < r.series.phi.size(); ++t)
              r.series.tap.push_back(static_cast<double>(t + 1));
          in.push_back(std::move(r));
        }
        TapAnalysisOptions o;
        o.discard = discard;
        o.discard_auto = discard_auto;
        o.level = level;
        o.alpha = alpha;
        // no test area: the φ statistics only (no β̂, no quadron fit), as `gransim analyze`
        if (test_area && !(*test_area > 0.0))
          throw InputError("tap_analysis", "test_area",
                           "must be > 0 (m²), or None for the φ statistics only");
        o.test_area = test_area.value_or(0.0);
        o.reference = reference;
        o.reference2 = reference2;
        o.overlap = overlap_options(args, method, bins, o.overlap.min_fraction);
        o.quadron.phi_rlp = phi_rlp;
        o.quadron.phi_rcp = phi_rcp;
        o.bootstrap = bootstrap;
        const TapAnalysisResult r = run_tap_analysis(in, o);
        if (!out_dir.empty()) write_tap_analysis(r, in, o, out_dir);
        py::dict d;
        py::list summaries, beta, beta2, kde, pairs;
        for (const auto& s : r.runs) summaries.append(summary_dict(s));
        for (const auto& b : r.beta) beta.append(beta_dict(b));
        for (const auto& b : r.beta2) beta2.append(beta_dict(b));
        for (const auto& k : r.kde_normal) {
          py::dict c;
          c["x"] = py::array(py::cast(k.x));
          c["density"] = py::array(py::cast(k.density));
          c["bandwidth"] = k.bandwidth;
          kde.append(c);
        }
        for (const auto& p : r.pairs) {
          py::dict c;
          c["a"] = p.a;
          c["b"] = p.b;
          c["mean_diff"] = p.test.mean_diff;
          c["mean_diff_err"] = p.test.mean_diff_err;
          c["p_mean"] = p.test.p_mean;
          c["p_sigma"] = p.test.p_sigma;
          c["ks_p"] = p.test.ks_p;
          pairs.append(c);
        }
        py::dict quad;
        for (const auto& [k, f] : r.quadron) quad[py::str(k)] = quadron_dict(f);
        d["runs"] = summaries;
        d["ref"] = r.ref;
        d["ref2"] = r.ref2;
        d["v_g"] = r.beta.empty() ? py::object(py::none()) : py::object(py::float_(r.v_g));
        d["beta"] = beta;
        d["beta2"] = beta2;
        d["kde"] = kde;
        d["pairs"] = pairs;
        d["quadron"] = quad;
        d["notes"] = r.notes;
        return d;
      },
      py::arg("runs"), py::arg("discard") = 10, py::arg("level") = 0.95, py::arg("alpha") = 0.05,
      py::arg("test_area") = py::none(), py::arg("reference") = "", py::arg("reference2") = "",
      py::arg("method") = "histogram", py::arg("bins") = 0, py::arg("phi_rlp") = 0.81,
      py::arg("phi_rcp") = 0.855, py::arg("bootstrap") = 100, py::arg("out_dir") = "",
      py::arg("discard_auto") = false,
      "the tapping analysis (as `gransim analyze`) of runs given as dicts with 'phi' (per tap) "
      "and optionally 'label', 'protocol', 'control', 'tap', 'phi_left', 'phi_right'. "
      "test_area is the test region's area in m² (V_g = test_area·φ̄_ref); None: the φ "
      "statistics only, with a note in 'notes' (β̂ and the quadron fit need it)");

  m.def(
      "beta_from_phi",
      [](const Series& ref, const Series& phi, double v_g, const std::string& method, int bins,
         double min_fraction) {
        const Args args("beta_from_phi");
        check_phi(args, "phi_ref", ref);
        check_phi(args, "phi", phi);
        args.positive("v_g", v_g);
        const OverlapOptions o = overlap_options(args, method, bins, min_fraction);
        return beta_dict(beta_from_phi(ref, phi, v_g, o));
      },
      py::arg("phi_ref"), py::arg("phi"), py::arg("v_g"), py::arg("method") = "histogram",
      py::arg("bins") = 0, py::arg("min_fraction") = 0.05,
      "β − β_ref (1/m²) and ln Z − ln Z_ref by overlapping histograms of φ (Q against 1/φ)");
  m.def(
      "beta_from_volume",
      [](const Series& ref, const Series& v, const std::string& method, int bins,
         double min_fraction) {
        const Args args("beta_from_volume");
        args.all_finite("v_ref", ref).all_finite("v", v);
        const OverlapOptions o = overlap_options(args, method, bins, min_fraction);
        return beta_dict(beta_from_volume(ref, v, o));
      },
      py::arg("v_ref"), py::arg("v"), py::arg("method") = "histogram", py::arg("bins") = 0,
      py::arg("min_fraction") = 0.05, "the same from volumes (Q against V)");
  m.def(
      "fit_quadron",
      [](const Series& beta_hat, const Series& phi, const Series& phi_err, const Series& beta_err,
         double phi_rlp, double phi_rcp) {
        const Args args("fit_quadron");
        args.all_finite("beta_hat", beta_hat).all_finite("phi", phi);
        args.all_finite("phi_err", phi_err).all_finite("beta_err", beta_err);
        args.require(phi.size() == beta_hat.size(), "phi",
                     "must have as many values as beta_hat (" + std::to_string(beta_hat.size()) +
                         "), got " + std::to_string(phi.size()));
        for (const auto& [name, e] : {std::pair{"phi_err", &phi_err}, {"beta_err", &beta_err}}) {
          args.require(e->empty() || e->size() == beta_hat.size(), name,
                       "must be empty or have as many values as beta_hat (" +
                           std::to_string(beta_hat.size()) + "), got " + std::to_string(e->size()));
          for (double x : *e) args.require(x >= 0.0, name, "errors must be >= 0");
        }
        check_quadron_params(args, phi_rlp, phi_rcp);
        QuadronParams p;
        p.phi_rlp = phi_rlp;
        p.phi_rcp = phi_rcp;
        return quadron_dict(fit_quadron(beta_hat, phi, phi_err, beta_err, p));
      },
      py::arg("beta_hat"), py::arg("phi"), py::arg("phi_err") = Series{},
      py::arg("beta_err") = Series{}, py::arg("phi_rlp") = 0.81, py::arg("phi_rcp") = 0.855,
      "fit a = N z̄/V_g and β₀ of the ideal quadron solution to (β̂, φ̄)");
  // (the vectorised forms broadcast their arguments; shapes that do not broadcast are an
  // argument error, not pybind's RuntimeError)
  using Arr = py::array_t<double, py::array::forcecast>;
  auto broadcast = [](const char* fn, auto&& call) -> py::object {
    try {
      return call();
    } catch (const InputError&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw ArgumentError(fn, "beta",
                          std::string("the arguments' shapes do not broadcast (") + e.what() + ")");
    }
  };
  auto phi_v = py::vectorize([](double beta, double a, double phi_rlp, double phi_rcp) {
    const Args args("quadron_phi");
    args.finite("beta", beta).positive("a", a);
    check_quadron_params(args, phi_rlp, phi_rcp);
    QuadronParams p;
    p.phi_rlp = phi_rlp;
    p.phi_rcp = phi_rcp;
    return quadron_phi(beta, a, p);
  });
  m.def(
      "quadron_phi",
      [phi_v, broadcast](const Arr& beta, const Arr& a, const Arr& rlp, const Arr& rcp) mutable {
        return broadcast("quadron_phi", [&] { return phi_v(beta, a, rlp, rcp); });
      },
      py::arg("beta"), py::arg("a"), py::arg("phi_rlp") = 0.81, py::arg("phi_rcp") = 0.855,
      "φ̄ of the ideal quadron solution at inverse compactivity β (1/m²)");
  auto lnz_v = py::vectorize([](double beta, double a, double v_g, double phi_rlp, double phi_rcp) {
    const Args args("quadron_lnz");
    args.finite("beta", beta).positive("a", a).positive("v_g", v_g);
    check_quadron_params(args, phi_rlp, phi_rcp);
    QuadronParams p;
    p.phi_rlp = phi_rlp;
    p.phi_rcp = phi_rcp;
    return quadron_lnz(beta, a, v_g, p);
  });
  m.def(
      "quadron_lnz",
      [lnz_v, broadcast](const Arr& beta, const Arr& a, const Arr& v_g, const Arr& rlp,
                         const Arr& rcp) mutable {
        return broadcast("quadron_lnz", [&] { return lnz_v(beta, a, v_g, rlp, rcp); });
      },
      py::arg("beta"), py::arg("a"), py::arg("v_g"), py::arg("phi_rlp") = 0.81,
      py::arg("phi_rcp") = 0.855, "ln Z of the ideal quadron gas");
  m.def(
      "quadron_gas_phi",
      [](double beta, int taps, double a, double v_g, double refresh, std::uint64_t seed,
         std::uint64_t stream) {
        const Args args("quadron_gas_phi");
        args.finite("beta", beta)
            .count("taps", taps, 0, 100000000)
            .positive("a", a)
            .positive("v_g", v_g)
            .require(refresh > 0.0 && refresh <= 1.0, "refresh",
                     "must be a share in (0, 1] (got " + Args::text(refresh) + ")");
        QuadronGasSpec g;
        g.a = a;
        g.v_g = v_g;
        g.refresh = refresh;
        return py::array(py::cast(quadron_gas_phi(beta, taps, g, seed, stream)));
      },
      py::arg("beta"), py::arg("taps"), py::arg("a") = 556.5, py::arg("v_g") = 0.13,
      py::arg("refresh") = 1.0, py::arg("seed") = 1, py::arg("stream") = 0,
      "a synthetic φ series of an ideal quadron gas at β (1/m²): known φ̄, ln Z and τ_int");
  m.def(
      "autocorr_time",
      [](const Series& x, double c) {
        Args("autocorr_time").all_finite("x", x).positive("c", c);
        const AutocorrTime t = autocorr_time(x, c);
        py::dict d;
        d["tau_int"] = t.tau_int;
        d["tau_err"] = t.tau_err;
        d["window"] = t.window;
        d["converged"] = t.converged;
        d["rho"] = py::array(py::cast(t.rho));
        return d;
      },
      py::arg("x"), py::arg("c") = 5.0, "integrated autocorrelation time (Sokal's window)");
  m.def(
      "mser_truncation",
      [](const Series& x, int batch) {
        Args("mser_truncation").all_finite("x", x).count("batch", batch, 1, 1000000);
        const Truncation t = mser_truncation(x, batch);
        return py::dict(py::arg("drop") = t.drop, py::arg("steady") = t.steady);
      },
      py::arg("x"), py::arg("batch") = 5,
      "the start of a series' steady part by the marginal standard error rule (MSER-batch)");
  m.def(
      "normality_chi2",
      [](const Series& x, double alpha, int bins) {
        Args("normality_chi2")
            .all_finite("x", x)
            .open("alpha", alpha, 0.0, 1.0)
            .count("bins", bins, 0, kMaxBins);
        const NormalityTest t = normality_chi2(x, alpha, bins);
        py::dict d;
        d["statistic"] = t.statistic;
        d["bins"] = t.bins;
        d["dof"] = t.dof;
        d["p_value"] = t.p_value;
        d["normal"] = t.normal;
        return d;
      },
      py::arg("x"), py::arg("alpha") = 0.05, py::arg("bins") = 0);
}

}  // namespace gs::py_bind
