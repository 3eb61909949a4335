// the Random Force Model analyses (analysis/rfm_*.hpp) on in-memory snapshots: S(k) and its
// fractal dimension, g(R), velocity histograms with tail and crossover fits, moments and their
// scaling exponents, granular temperature, block averages, gaps, free paths, line fits
#include <pybind11/stl.h>

#include <limits>
#include <span>
#include <string>

#include "analysis/rfm_fit.hpp"
#include "analysis/rfm_freepath.hpp"
#include "analysis/rfm_gaps.hpp"
#include "analysis/rfm_gr.hpp"
#include "analysis/rfm_moments.hpp"
#include "analysis/rfm_sk.hpp"
#include "analysis/rfm_tails.hpp"
#include "arguments.hpp"
#include "bindings.hpp"
#include "core/error.hpp"

namespace gs::py_bind {

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::vector<Vec2> to_points(const Doubles& a) {
  if (a.ndim() != 2 || a.shape(1) != 2)
    throw InputError("points", "points", "must be an N×2 array of (x, y)");
  std::vector<Vec2> p(static_cast<std::size_t>(a.shape(0)));
  const double* d = a.data();
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = {d[2 * i], d[2 * i + 1]};
  return p;
}

namespace {

// more wave vectors or bins than these only exhaust memory
constexpr long long kMaxModes = 1024;
constexpr long long kMaxBins = 1000000;

/// N×2 finite points, named as the argument `name` of `args`
std::vector<Vec2> finite_points(const Args& args, const char* name, const Doubles& a) {
  args.require(a.ndim() == 2 && a.shape(1) == 2, name, "must be an N×2 array of (x, y)");
  args.all_finite(name, std::span<const double>(a.data(), static_cast<std::size_t>(a.size())));
  return to_points(a);
}

/// finite 1-D values (any shape, flattened)
std::span<const double> finite_values(const Args& args, const char* name, const Doubles& a) {
  const std::span<const double> v(a.data(), static_cast<std::size_t>(a.size()));
  args.all_finite(name, v);
  return v;
}

py::array arr(const std::vector<double>& v) { return py::array(py::cast(v)); }

py::dict shells_dict(const std::vector<rfm::SkShell>& sh) {
  std::vector<double> k, n, s, e, modes;
  for (const auto& x : sh) {
    k.push_back(x.k);
    n.push_back(x.n);
    s.push_back(x.s);
    e.push_back(x.s_err);
    modes.push_back(static_cast<double>(x.modes));
  }
  py::dict d;
  d["k"] = arr(k);
  d["n"] = arr(n);
  d["s"] = arr(s);
  d["s_err"] = arr(e);
  d["modes"] = arr(modes);
  return d;
}

py::dict df_dict(const rfm::DfFit& f) {
  py::dict d;
  d["d_f"] = f.d_f;
  d["d_f_err"] = f.d_f_err;
  d["amplitude"] = f.amplitude;
  d["chi2_r"] = f.chi2_r;
  d["points"] = f.points;
  d["k_lo"] = f.k_lo;
  d["k_hi"] = f.k_hi;
  d["k_d"] = f.k_d;
  d["l_eff"] = f.l_eff;
  return d;
}

py::dict hist_dict(const rfm::Histogram& h) {
  std::vector<double> lo, hi, x, c, p, e;
  for (const auto& b : h.bins()) {
    lo.push_back(b.lo);
    hi.push_back(b.hi);
    x.push_back(b.x);
    c.push_back(b.count);
    p.push_back(b.p);
    e.push_back(b.p_err);
  }
  py::dict d;
  d["lo"] = arr(lo);
  d["hi"] = arr(hi);
  d["x"] = arr(x);
  d["count"] = arr(c);
  d["p"] = arr(p);
  d["p_err"] = arr(e);
  return d;
}

}  // namespace

void bind_rfm(py::module_& m) {
  py::module_ r = m.def_submodule("rfm", "the Random Force Model analyses (docs/rfm.md)");

  py::class_<rfm::StructureFactor2D>(r, "StructureFactor2D",
                                     "S(k) of point sets in a periodic square box of side `box`")
      .def(py::init([](double box, int n_max, const std::string& grouping) {
             Args("StructureFactor2D").positive("box", box).count("n_max", n_max, 1, kMaxModes);
             if (grouping != "exact" && grouping != "rounded")
               throw InputError("StructureFactor2D", "grouping",
                                "must be \"exact\" or \"rounded\" (got \"" + grouping + "\")");
             return std::make_unique<rfm::StructureFactor2D>(
                 box, n_max,
                 grouping == "exact" ? rfm::ShellGrouping::exact : rfm::ShellGrouping::rounded);
           }),
           py::arg("box"), py::arg("n_max"), py::arg("grouping") = "exact")
      .def(
          "add_snapshot",
          [](rfm::StructureFactor2D& s, const Doubles& pts) {
            s.add_snapshot(finite_points(Args("StructureFactor2D.add_snapshot"), "positions", pts));
          },
          py::arg("positions"), "one snapshot of N×2 positions, m")
      .def("shells", [](const rfm::StructureFactor2D& s) { return shells_dict(s.shells()); })
      .def_property_readonly("snapshots", &rfm::StructureFactor2D::snapshots)
      .def(
          "fit_df",
          [](const rfm::StructureFactor2D& s, double k_lo, double k_hi) {
            const Args args("StructureFactor2D.fit_df");
            args.non_negative("k_lo", k_lo).positive("k_hi", k_hi);
            args.require(k_hi > k_lo, "k_hi", "must exceed k_lo");
            const auto sh = s.shells();
            return df_dict(rfm::fit_df(sh, k_lo, k_hi));
          },
          py::arg("k_lo"), py::arg("k_hi"), "S(k) ∝ k^−D_f fitted on k_lo ≤ k ≤ k_hi (1/m)")
      .def(
          "fit_df_rfm",
          [](const rfm::StructureFactor2D& s, double box, long n, double diameter, double eps_n,
             double eps_t) {
            const Args args("StructureFactor2D.fit_df_rfm");
            args.positive("box", box).count("n", n, 1, std::numeric_limits<long>::max());
            args.positive("diameter", diameter)
                .require(eps_n >= 0.0 && eps_n <= 1.0, "eps_n", "must lie in [0, 1]")
                .require(eps_t >= -1.0 && eps_t <= 1.0, "eps_t", "must lie in [-1, 1]");
            const auto sh = s.shells();
            rfm::RfmSystem sys;
            sys.box = box;
            sys.n = n;
            sys.diameter = diameter;
            sys.eps_n = eps_n;
            sys.eps_t = eps_t;
            return df_dict(rfm::fit_df_rfm(sh, sys));
          },
          py::arg("box"), py::arg("n"), py::arg("diameter"), py::arg("eps_n"), py::arg("eps_t"),
          "the thesis's fit window: 2π/L_Eff ≤ k ≤ k′");

  py::class_<rfm::PairCorrelation2D>(r, "PairCorrelation2D", "g(R) in a periodic square box")
      .def(py::init([](double box, double r_max, int bins) {
             Args("PairCorrelation2D")
                 .positive("box", box)
                 .positive("r_max", r_max)
                 .count("bins", bins, 1, kMaxBins);
             return std::make_unique<rfm::PairCorrelation2D>(box, r_max, bins);
           }),
           py::arg("box"), py::arg("r_max"), py::arg("bins"))
      .def(
          "add_snapshot",
          [](rfm::PairCorrelation2D& g, const Doubles& pts) {
            g.add_snapshot(finite_points(Args("PairCorrelation2D.add_snapshot"), "positions", pts));
          },
          py::arg("positions"))
      .def("bins", [](const rfm::PairCorrelation2D& g) {
        std::vector<double> rr, gg, ee;
        for (const auto& b : g.bins()) {
          rr.push_back(b.r);
          gg.push_back(b.g);
          ee.push_back(b.g_err);
        }
        py::dict d;
        d["r"] = arr(rr);
        d["g"] = arr(gg);
        d["g_err"] = arr(ee);
        return d;
      });

  py::class_<rfm::Histogram>(r, "Histogram", "counts in bins, normalised by every sample added")
      .def(
          "add",
          [](rfm::Histogram& h, const Doubles& v) {
            const Args args("Histogram.add");
            if (v.ndim() == 2)
              rfm::add_components(h, finite_points(args, "values", v));
            else
              rfm::add_values(h, finite_values(args, "values", v));
          },
          py::arg("values"), "1-D values, or N×2 velocities (both components)")
      .def("bins", &hist_dict)
      .def_property_readonly("total", &rfm::Histogram::total);
  r.def(
      "velocity_histogram",
      [](double v_max, int bins) {
        Args("velocity_histogram").positive("v_max", v_max).count("bins", bins, 1, kMaxBins);
        return rfm::velocity_histogram(v_max, bins);
      },
      py::arg("v_max"), py::arg("bins"), "bins on [−v_max, v_max) for one velocity component, m/s");
  r.def(
      "free_path_histogram",
      [](double l_min, double l_max, int bins) {
        const Args args("free_path_histogram");
        args.positive("l_min", l_min).positive("l_max", l_max).count("bins", bins, 1, kMaxBins);
        args.require(l_max > l_min, "l_max", "must exceed l_min");
        return rfm::free_path_histogram(l_min, l_max, bins);
      },
      py::arg("l_min"), py::arg("l_max"), py::arg("bins"),
      "logarithmic bins of free path lengths, m");
  r.def(
      "fit_tail",
      [](const rfm::Histogram& h, double count_lo, double count_hi, double v_abs_min,
         double error_scale) {
        const Args args("fit_tail");
        args.non_negative("count_lo", count_lo)
            .non_negative("count_hi", count_hi)
            .non_negative("v_abs_min", v_abs_min)
            .positive("error_scale", error_scale)
            .require(count_hi >= count_lo, "count_hi", "must be >= count_lo");
        rfm::TailFitOptions o;
        o.count_lo = count_lo;
        o.count_hi = count_hi;
        o.v_abs_min = v_abs_min;
        o.error_scale = error_scale;
        const rfm::TailFit f = rfm::fit_tail(h, o);
        py::dict d;
        d["alpha"] = f.best.alpha;
        d["a"] = f.best.a;
        d["b"] = f.best.b;
        d["chi2_r"] = f.best.chi2_r;
        d["any_accepted"] = f.any_accepted;
        d["alpha_lo"] = f.alpha_lo;
        d["alpha_hi"] = f.alpha_hi;
        d["points"] = f.points;
        return d;
      },
      py::arg("hist"), py::arg("count_lo") = 50.0, py::arg("count_hi") = 5000.0,
      py::arg("v_abs_min") = 0.0, py::arg("error_scale") = 1.0,
      "stretched-exponential tail P = A exp(−B|v|^α): the α grid scan's best fit");
  r.def(
      "fit_crossover",
      [](const rfm::Histogram& h, double alpha, bool fit_alpha, double min_count) {
        Args("fit_crossover").positive("alpha", alpha).non_negative("min_count", min_count);
        const rfm::CrossoverFit f = rfm::fit_crossover(h, alpha, fit_alpha, min_count);
        py::dict d;
        d["d"] = f.d;
        d["v_r"] = f.v_r;
        d["v_r_err"] = f.v_r_err;
        d["v_c"] = f.v_c;
        d["v_c_err"] = f.v_c_err;
        d["alpha"] = f.alpha;
        d["alpha_err"] = f.alpha_err;
        d["chi2_r"] = f.chi2_r;
        d["v_a"] = f.v_a();
        return d;
      },
      py::arg("hist"), py::arg("alpha") = 1.0, py::arg("fit_alpha") = false,
      py::arg("min_count") = 10.0, "the Gaussian-to-exponential crossover density");
  r.def(
      "fit_free_paths",
      [](const rfm::Histogram& h, double l_fit_min, double min_count) {
        Args("fit_free_paths")
            .non_negative("l_fit_min", l_fit_min)
            .non_negative("min_count", min_count);
        const rfm::FreePathFit f = rfm::fit_free_paths(h, l_fit_min, min_count);
        py::dict d;
        d["d_f"] = f.d_f;
        d["d_f_err"] = f.d_f_err;
        d["c"] = f.c;
        d["a0"] = f.a0;
        d["chi2_r"] = f.chi2_r;
        d["points"] = f.points;
        return d;
      },
      py::arg("hist"), py::arg("l_fit_min") = 0.0, py::arg("min_count") = 10.0);

  r.def(
      "abs_moments",
      [](const Doubles& x, int m_max) {
        const Args args("abs_moments");
        args.count("m_max", m_max, 1, 1000);
        return arr(rfm::abs_moments(finite_values(args, "x", x), m_max));
      },
      py::arg("x"), py::arg("m_max") = 12, "⟨|x|^m⟩ for m = 1 … m_max");
  r.def(
      "fit_scaling_exponent",
      [](const Doubles& n, const Doubles& y, const Doubles& y_err) {
        const Args args("fit_scaling_exponent");
        const auto nn = finite_values(args, "n", n), yy = finite_values(args, "y", y),
                   ee = finite_values(args, "y_err", y_err);
        args.require(yy.size() == nn.size(), "y", "must have as many values as n");
        args.require(ee.empty() || ee.size() == nn.size(), "y_err",
                     "must be empty or have as many values as n");
        const rfm::ExponentFit f = rfm::fit_scaling_exponent(nn, yy, ee);
        py::dict d;
        d["exponent"] = f.exponent;
        d["exponent_err"] = f.exponent_err;
        d["amplitude"] = f.amplitude;
        d["chi2_r"] = f.chi2_r;
        return d;
      },
      py::arg("n"), py::arg("y"), py::arg("y_err") = Doubles(), "y = c N^(−exponent)");
  r.def(
      "granular_temperature",
      [](const Doubles& v) {
        const Args args("granular_temperature");
        return v.ndim() == 2
                   ? rfm::granular_temperature(std::span<const Vec2>(finite_points(args, "v", v)))
                   : rfm::granular_temperature(finite_values(args, "v", v));
      },
      py::arg("v"), "T = ⟨v²⟩ per degree of freedom: N×2 velocities or 1-D values, m²/s²");
  r.def(
      "block_average",
      [](const Doubles& x, long long block_len) {
        const Args args("block_average");
        args.count("block_len", block_len, 1, std::numeric_limits<long long>::max());
        const rfm::BlockAverage b = rfm::block_average(finite_values(args, "series", x),
                                                       static_cast<std::size_t>(block_len));
        py::dict d;
        d["mean"] = b.mean;
        d["error"] = b.error;
        d["block_means"] = arr(b.block_means);
        d["block_len"] = b.block_len;
        return d;
      },
      py::arg("series"), py::arg("block_len"));
  r.def(
      "reduced_length",
      [](double box, long n, double diameter) {
        Args("reduced_length")
            .positive("box", box)
            .count("n", n, 1, std::numeric_limits<long>::max())
            .positive("diameter", diameter);
        return rfm::reduced_length(box, n, diameter);
      },
      py::arg("box"), py::arg("n"), py::arg("diameter"));
  r.def(
      "reduced_coordinates",
      [](const Doubles& x, double box, double diameter) {
        const Args args("reduced_coordinates");
        args.positive("box", box).non_negative("diameter", diameter);
        return arr(rfm::reduced_coordinates(finite_values(args, "x", x), box, diameter));
      },
      py::arg("x"), py::arg("box"), py::arg("diameter"));
  r.def(
      "neighbour_gaps",
      [](const Doubles& x, double l_reduced, int h) {
        const Args args("neighbour_gaps");
        args.positive("l_reduced", l_reduced).count("h", h, 1, std::numeric_limits<int>::max());
        const auto v = finite_values(args, "reduced", x);
        args.require(static_cast<std::size_t>(h) < v.size() || v.empty(), "h",
                     "must be less than the number of particles");
        return arr(rfm::neighbour_gaps(v, l_reduced, h));
      },
      py::arg("reduced"), py::arg("l_reduced"), py::arg("h") = 1);
  r.def(
      "fit_line",
      [](const Doubles& x, const Doubles& y, const Doubles& sigma) {
        const Args args("fit_line");
        const auto xx = finite_values(args, "x", x), yy = finite_values(args, "y", y),
                   ss = finite_values(args, "sigma", sigma);
        args.require(yy.size() == xx.size(), "y", "must have as many values as x");
        args.require(ss.empty() || ss.size() == xx.size(), "sigma",
                     "must be empty or have as many values as x");
        for (double e : ss) args.require(e > 0.0, "sigma", "errors must be > 0");
        const rfm::LineFit f = rfm::fit_line(xx, yy, ss);
        py::dict d;
        d["a"] = f.a;
        d["b"] = f.b;
        d["a_err"] = f.a_err;
        d["b_err"] = f.b_err;
        d["chi2"] = f.chi2;
        d["points"] = f.points;
        return d;
      },
      py::arg("x"), py::arg("y"), py::arg("sigma") = Doubles(), "y = a + b x (weighted)");
  r.def(
      "fit_power_law",
      [](const Doubles& x, const Doubles& y, const Doubles& y_err) {
        const Args args("fit_power_law");
        const auto xx = finite_values(args, "x", x), yy = finite_values(args, "y", y),
                   ee = finite_values(args, "y_err", y_err);
        args.require(yy.size() == xx.size(), "y", "must have as many values as x");
        args.require(ee.empty() || ee.size() == xx.size(), "y_err",
                     "must be empty or have as many values as x");
        for (double e : ee) args.require(e > 0.0, "y_err", "errors must be > 0");
        const rfm::PowerLawFit f = rfm::fit_power_law(xx, yy, ee);
        py::dict d;
        d["exponent"] = f.exponent;
        d["exponent_err"] = f.exponent_err;
        d["amplitude"] = f.amplitude;
        d["chi2_r"] = f.chi2_r;
        d["points"] = f.points;
        return d;
      },
      py::arg("x"), py::arg("y"), py::arg("y_err") = Doubles(), "y = A x^p on logarithms");
  r.def(
      "mean_free_path",
      [](double box, double diameter, long n) {
        Args("mean_free_path")
            .positive("box", box)
            .positive("diameter", diameter)
            .count("n", n, 1, std::numeric_limits<long>::max());
        return rfm::mean_free_path(box, diameter, n);
      },
      py::arg("box"), py::arg("diameter"), py::arg("n"));
}

}  // namespace gs::py_bind
