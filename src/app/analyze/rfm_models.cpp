// `gransim model …`: the auxiliary models of the thesis as commands (docs/physics.md §5.4)
#include "app/analyze/rfm_models.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>
#include <sstream>

#include "analysis/rfm_csv.hpp"
#include "app/analyze/rfm_analyze.hpp"
#include "core/error.hpp"
#include "models/bisection.hpp"
#include "models/cascade.hpp"
#include "models/interval_theory.hpp"
#include "models/walks.hpp"
#include "output/csv.hpp"
#include "output/json_text.hpp"
#include "output/run_dir.hpp"

namespace gs {

namespace fs = std::filesystem;

namespace {

/// options every model shares
struct Common {
  std::string out;
  std::uint64_t seed = 1;
  bool charts = true;
  bool quiet = false;
  bool force = false;
};

struct BisectionOpt {
  models::BisectionParams p;
};
struct WalkOpt {
  models::WalkParams p;
  std::vector<double> radii{1e-3, 8e-3};  ///< disc radii l, m
  std::string paths;                      ///< a freepath.csv (l, P): the Single Particle Model
  bool heating = true;                    ///< also free_heating → heating.csv
};
struct IntervalOpt {
  models::WalkParams p;
  double length = 1e-2;  ///< L, m
  std::string start = "uniform";
};
struct CascadeOpt {
  models::CascadeParams p;
  std::vector<std::string> kinds{"ucp"};
  double fit_lo = 4.0, fit_hi = 32.0;  ///< D_f fit window in |n| = kL/2π
};

std::string as_text(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return std::isfinite(v) ? s.str() : "null";
}

// the output folder, once every argument is checked: refused when it holds files (unless
// --force: they are then overwritten) or when it is a run or sweep; locked while written
std::unique_ptr<DirLock> open_out(const Common& c) {
  const fs::path out(c.out);
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec))
    throw InputError(c.out, "--out", "exists and is not a folder; choose another --out");
  if (fs::exists(out / "run.json", ec) || fs::exists(out / "sweep.json", ec) ||
      fs::exists(out / "scene.toml", ec))
    throw InputError(c.out, "--out", "holds a run or a sweep; choose another --out");
  bool empty = true;
  for (const auto& e : fs::directory_iterator(out, ec))
    if (e.path().filename() != ".lock") empty = false;
  if (!empty && !c.force)
    throw InputError(c.out, "--out",
                     "is not empty; pass --force to overwrite its files, or choose another --out");
  fs::create_directories(out, ec);
  if (ec) throw OutputError(c.out + ": cannot create the folder: " + ec.message());
  return std::make_unique<DirLock>(c.out, "model");
}

// model.json: a flat list of headline numbers
void write_model_json(const fs::path& out, const std::string& model,
                      const std::vector<std::pair<std::string, double>>& f) {
  nlohmann::ordered_json j;
  j["model"] = model;
  for (const auto& [k, v] : f) j[k] = json_number(v, 10);
  write_file_atomic((out / "model.json").string(), json_text(j));
}

void finish(const Common& c, const fs::path& out) {
  if (!c.charts) return;
  const std::string err = draw_rfm_charts(out.string());
  if (!err.empty())
    std::fprintf(stderr, "gransim model: charts skipped: %s; the CSV files are in %s\n",
                 err.c_str(), out.c_str());
}

// the segment lengths of the multiplicative bisection against (−ln x)^(n−1)/(n−1)! (T.3.36)
void run_bisection(const Common& c, BisectionOpt o) {
  const fs::path out(c.out);
  o.p.seed = c.seed;
  o.p.validate();
  const auto lock = open_out(c);
  const models::BisectionResult r = models::run_bisection(o.p);
  models::write_bisection_csv(csv_records(), out / "bisection.csv", r);
  std::vector<std::pair<std::string, double>> f{
      {"levels", o.p.levels}, {"realisations", static_cast<double>(o.p.realisations)}};
  for (std::size_t m = 0; m < r.moments.size(); ++m) {
    f.emplace_back("moment_" + std::to_string(m + 1), r.moments[m]);
    f.emplace_back("moment_" + std::to_string(m + 1) + "_err", r.moment_err[m]);
    f.emplace_back("moment_" + std::to_string(m + 1) + "_exact", r.moment_exact[m]);
  }
  write_model_json(out, "bisection", f);
  if (!c.quiet) {
    std::printf("bisection, n = %d levels, %ld realisations: <x^m> against (1+m)^(-n) (T.3.37)\n",
                o.p.levels, o.p.realisations);
    for (std::size_t m = 0; m < r.moments.size(); ++m)
      std::printf("  m = %zu: %.6g ± %.2g (exact %.6g)\n", m + 1, r.moments[m], r.moment_err[m],
                  r.moment_exact[m]);
  }
  finish(c, out);
}

// a walk's step is no finer than a millionth of its time scale (M²l²/D)^(1/3) for the region
// of size l: each walk of the default 1000 steps per time scale would otherwise take millions
void check_walk_step(const char* command, const char* size_flag, const models::WalkParams& p,
                     double l) {
  const auto brief = [](double v) {  // six digits: a message, not a result
    std::ostringstream s;
    s.precision(6);
    s << v;
    return s.str();
  };
  const double ts = models::walk_time_scale(p, l), vs = models::walk_velocity_scale(p, l);
  if (!(ts > 0.0) || !std::isfinite(ts) || !(vs > 0.0) || !std::isfinite(vs))
    throw InputError(command, size_flag,
                     brief(l) + " m with --mass " + brief(p.mass) + " and --noise " +
                         brief(p.noise) + " gives the walk no finite time scale (M²l²/D)^(1/3) = " +
                         brief(ts) + " s or velocity scale (Dl/M²)^(1/3) = " + brief(vs) +
                         " m/s: choose sizes and parameters nearer each other's scale");
  if (p.dt > 0.0 && p.dt < 1e-6 * ts)
    throw InputError(command, "--dt",
                     brief(p.dt) + " s is finer than a millionth of the walk's time scale " +
                         brief(ts) + " s (size " + brief(l) +
                         " m): each walk would take over 10^6 steps; give --dt >= " +
                         brief(1e-6 * ts) + " s, or 0 for the time scale/1000");
}

// Q(v, l) of the single-particle walk in discs of fixed radius, optionally with l drawn
// from a measured free-path table (the Single Particle Model), and free heating
void run_walk(const Common& c, WalkOpt o) {
  const fs::path out(c.out);
  o.p.seed = c.seed;
  o.p.validate();
  for (double l : o.radii)
    if (!(l > 0) || !std::isfinite(l))
      throw InputError("gransim model walk", "--radius", "radii must be positive and finite");
  for (double l : o.radii) check_walk_step("gransim model walk", "--radius", o.p, l);
  // the free-path table is read before anything is written
  rfm::CsvTable paths;
  if (!o.paths.empty()) paths = rfm::read_csv(o.paths);
  models::PathTable tab;
  if (!o.paths.empty()) {
    const auto& l = paths.col("l");
    const auto& p = paths.col("P");
    for (std::size_t i = 0; i < l.size(); ++i)
      if (std::isfinite(p[i]) && p[i] >= 0) {
        tab.l.push_back(l[i]);
        tab.p.push_back(p[i]);
      }
    try {
      tab.validate();
    } catch (const InputError& e) {
      throw InputError(o.paths, "", e.what());
    }
    check_walk_step("gransim model walk", "--paths", o.p, tab.l.back());
  }
  const auto lock = open_out(c);
  std::vector<std::pair<std::string, double>> f;
  for (double l : o.radii) {
    models::WalkParams p = o.p;
    if (p.v_max == 0) p.v_max = 8.0 * models::walk_velocity_scale(p, l);
    const models::WalkResult r = models::disc_walk(p, l);
    std::ostringstream name;
    name << "walk_l" << l << ".csv";
    models::write_walk_csv(csv_records(), out / name.str(), r, p, l);
    const std::string k = "l_" + as_text(l);
    double tail_c = 0.0;
    try {
      tail_c = models::gaussian_tail_coefficient(r, p, l);
    } catch (const InputError&) {
      throw InputError("gransim model walk", "--walks",
                       std::to_string(o.p.walks) + " walks fill too few of the " +
                           std::to_string(p.bins) +
                           " velocity bins for the Gaussian tail fit: raise --walks or lower "
                           "--bins");
    }
    f.insert(f.end(), {{k + "_mean_exit_time", r.mean_exit_time},
                       {k + "_time_scale", models::walk_time_scale(p, l)},
                       {k + "_mean_v2", r.mean_v2},
                       {k + "_gaussian_tail_c", tail_c},
                       {k + "_heating_residual", r.heating_residual},
                       {k + "_heating_residual_err", r.heating_residual_err}});
    if (!c.quiet)
      std::printf(
          "disc walk l = %g m: <tau> = %.4g s (time scale %.4g s), <v_x^2> = %.4g m2/s2, "
          "Gaussian tail c = %.3f (thesis 0.98)\n",
          l, r.mean_exit_time, models::walk_time_scale(p, l), r.mean_v2, tail_c);
  }
  // the Single Particle Model with a measured P_l (columns l and P of a freepath.csv)
  if (!o.paths.empty()) {
    models::WalkParams wp = o.p;
    double lmean = 0.0, norm = 0.0;
    for (std::size_t i = 0; i < tab.l.size(); ++i) {
      lmean += tab.l[i] * tab.p[i];
      norm += tab.p[i];
    }
    lmean = norm > 0 ? lmean / norm : 1e-3;
    if (wp.v_max == 0) wp.v_max = 8.0 * models::walk_velocity_scale(wp, lmean);
    const models::WalkResult r = models::disc_walk_spm(wp, tab);
    models::write_walk_csv(csv_records(), out / "walk_spm.csv", r, wp, r.mean_region);
    f.insert(f.end(), {{"spm_mean_exit_time", r.mean_exit_time},
                       {"spm_mean_v2", r.mean_v2},
                       {"spm_mean_l", r.mean_region}});
    if (!c.quiet)
      std::printf("single particle model (P_l from %s): <l> = %.4g m, <v_x^2> = %.4g m2/s2\n",
                  o.paths.c_str(), r.mean_region, r.mean_v2);
  }
  // free particles: <v_x²> = 2 D t/M² and <x²> (the discrete T.5.11 form)
  if (o.heating) {
    models::WalkParams p = o.p;
    p.dt = 1e-4;
    models::write_heating_csv(csv_records(), out / "heating.csv",
                              models::free_heating(p, 2, 2000, 1000, 20), p);
  }
  write_model_json(out, "walk", f);
  finish(c, out);
}

// appendix B: the 1D interval with absorbing ends, arrivals at x = L against B.32
void run_interval(const Common& c, IntervalOpt o) {
  const fs::path out(c.out);
  o.p.seed = c.seed;
  if (!(o.length > 0) || !std::isfinite(o.length))
    throw InputError("gransim model interval", "--length", "must be positive");
  o.p.validate();
  check_walk_step("gransim model interval", "--length", o.p, o.length);
  if (o.p.v_max == 0) o.p.v_max = 5.0 * models::walk_velocity_scale(o.p, o.length);
  models::IntervalStart st;
  if (o.start == "uniform")
    st = models::IntervalStart::uniform;
  else if (o.start == "centre" || o.start == "center")
    st = models::IntervalStart::centre;
  else
    throw InputError("gransim model interval", "--start",
                     "must be uniform or centre (got '" + o.start + "')");
  const auto lock = open_out(c);
  const models::WalkResult r = models::interval_walk(o.p, o.length, st);
  const double theory =
      models::appendix_b_mean_exit_time_coefficient() * models::walk_time_scale(o.p, o.length);
  // a result is written only when it is a number
  if (!std::isfinite(r.mean_exit_time) || !std::isfinite(theory))
    throw InputError("gransim model interval", "--length",
                     as_text(o.length) + " m gives no finite mean exit time (walks " +
                         as_text(r.mean_exit_time) + " s, appendix B " + as_text(theory) +
                         " s): choose a length nearer the scale of --noise and --mass");
  models::write_interval_csv(csv_records(), out / "interval.csv", r, o.p, o.length);
  write_model_json(out, "interval",
                   {{"length", o.length},
                    {"mean_exit_time", r.mean_exit_time},
                    {"mean_exit_time_err", r.exit_time_err},
                    {"mean_exit_time_theory", theory}});
  if (!c.quiet)
    std::printf(
        "interval L = %g m, %s start: <tau> = %.5g ± %.2g s (appendix B, uniform start: %.5g s)\n",
        o.length, o.start.c_str(), r.mean_exit_time, r.exit_time_err, theory);
  finish(c, out);
}

// multiplicative cascades: S(k) of the mass field, its exact expectation, the D_f fit
void run_cascade(const Common& c, CascadeOpt o) {
  const fs::path out(c.out);
  std::vector<std::string> kinds = o.kinds;
  if (kinds.size() == 1 && kinds[0] == "all")
    kinds = {"ucp", "unoncp", "symmetrised", "meakin1", "meakin2", "meakin3", "meakin4"};
  for (const std::string& k : kinds) {
    models::CascadeParams p = o.p;
    p.kind = models::cascade_from_name(k);
    p.validate();
  }
  if (!(o.fit_lo > 0.0) || !std::isfinite(o.fit_lo) || !(o.fit_hi > o.fit_lo) ||
      !std::isfinite(o.fit_hi))
    throw InputError("gransim model cascade", "--fit-hi",
                     "the D_f fit window needs 0 < --fit-lo < --fit-hi, finite (got " +
                         as_text(o.fit_lo) + " and " + as_text(o.fit_hi) + ")");
  const auto lock = open_out(c);
  std::vector<std::pair<std::string, double>> f;
  for (const std::string& k : kinds) {
    models::CascadeParams p = o.p;
    p.kind = models::cascade_from_name(k);
    p.seed = c.seed;
    p.validate();
    const int nmax = p.n_max > 0 ? p.n_max : 1 << (p.levels - 1);
    const models::CascadeResult r = models::cascade_structure_factor(p);
    const auto exact = models::cascade_expected_sk(p.kind, p.levels, nmax, p.box);
    const double two_pi_l = 2.0 * std::numbers::pi / p.box;
    rfm::DfFit fit;
    try {
      fit =
          rfm::fit_df(r.shells, two_pi_l * o.fit_lo * (1 - 1e-9), two_pi_l * o.fit_hi * (1 + 1e-9));
    } catch (const InputError&) {
      throw InputError("gransim model cascade", "--fit-hi",
                       "fewer than two shells with S(k) > 0 in |n| from --fit-lo " +
                           as_text(o.fit_lo) + " to --fit-hi " + as_text(o.fit_hi) + " (" + k +
                           ", the grid reaches |n| = " + std::to_string(nmax) +
                           "): widen the window or raise --levels");
    }
    models::write_cascade_csv(csv_records(), out / ("cascade_" + k + ".csv"), r, exact, p.kind,
                              &fit);
    const double d2 = models::correlation_dimension(p.kind);
    // a mass fractal in the plane has 0 < D_f ≤ 2; a fit outside, or with an error above half
    // its value, found no power law to report
    std::string why = models::cascade_no_power_law_reason(p.kind);
    if (why.empty() && !(fit.d_f > 0.0 && fit.d_f <= 2.0 && fit.d_f_err < 0.5 * fit.d_f))
      why = "no power law A k^−D_f fits S(k) in this range";
    f.insert(f.end(), {{k + "_D_f", fit.d_f},
                       {k + "_D_f_err", fit.d_f_err},
                       {k + "_power_law", why.empty() ? 1.0 : 0.0},
                       {k + "_D2", d2}});
    if (!c.quiet && why.empty())
      std::printf(
          "cascade %-12s %d levels, %ld realisations: D_f = %.3f ± %.3f (fit |n| in [%g, %g]), "
          "correlation dimension D2 = %.4f\n",
          k.c_str(), p.levels, p.realisations, fit.d_f, fit.d_f_err, o.fit_lo, o.fit_hi, d2);
    else if (!c.quiet)
      std::printf(
          "cascade %-12s %d levels, %ld realisations: no D_f: %s (a fit over |n| in [%g, %g] "
          "gives %.3f ± %.3f, chi2_r = %.3g); correlation dimension D2 = %.4f\n",
          k.c_str(), p.levels, p.realisations, why.c_str(), o.fit_lo, o.fit_hi, fit.d_f,
          fit.d_f_err, fit.chi2_r, d2);
  }
  write_model_json(out, "cascade", f);
  finish(c, out);
}

// run a model, mapping errors to exit codes the way the rest of gransim does
template <class F>
void guarded(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    // a model's own check names its parameter ("walks: key 'noise'"): name the flag instead
    std::string flag = "--" + e.key();
    std::replace(flag.begin(), flag.end(), '_', '-');
    const bool internal = !e.key().empty() && e.key().rfind("--", 0) != 0 &&
                          e.where().find('/') == std::string::npos &&
                          e.where().rfind("gransim", 0) != 0;
    const std::string text = e.what();
    const std::string::size_type colon = text.find("': ");
    if (internal && colon != std::string::npos)
      std::fprintf(stderr, "gransim: error: %s: %s\n", flag.c_str(), text.c_str() + colon + 3);
    else
      std::fprintf(stderr, "gransim: error: %s\n", e.what());
    throw CLI::RuntimeError(kExitBadInput);
  } catch (const OutputError& e) {
    std::fprintf(stderr, "gransim: cannot write output: %s\n", e.what());
    throw CLI::RuntimeError(kExitOutput);
  } catch (const fs::filesystem_error& e) {
    std::fprintf(stderr, "gransim: cannot write output: %s\n", e.what());
    throw CLI::RuntimeError(kExitOutput);
  } catch (const CLI::Error&) {
    throw;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gransim: internal error: %s\n", e.what());
    throw CLI::RuntimeError(kExitFailure);
  }
}

void common_options(CLI::App* s, Common& c) {
  s->add_option("-o,--out", c.out, "output folder for the CSV files and charts")->required();
  s->add_option("--seed", c.seed, "random seed (realisation i uses the stream (seed, i))");
  s->add_flag(
      "--no-charts", [&c](std::int64_t) { c.charts = false; }, "write CSV/JSON only");
  s->add_flag("-q,--quiet", c.quiet, "no summary lines");
  s->add_flag("--force", c.force,
              "write into a folder that already holds files (they are overwritten)");
}

}  // namespace

void add_model_command(CLI::App& app) {
  // the option structs live as long as the app (the callbacks run inside app.parse)
  struct All {
    Common c;
    BisectionOpt b;
    WalkOpt w;
    IntervalOpt i;
    CascadeOpt k;
  };
  auto all = std::make_shared<All>();
  auto* model = app.add_subcommand("model",
                                   "the thesis' auxiliary models (docs/physics.md §5.4): "
                                   "bisection, walk, interval, cascade");
  model->require_subcommand(1);

  auto* b = model->add_subcommand("bisection", "uniform multiplicative bisection (T.3.26–3.38)");
  common_options(b, all->c);
  b->add_option("--levels", all->b.p.levels, "n: 2^n segments")->capture_default_str();
  b->add_option("--realisations", all->b.p.realisations, "independent intervals")
      ->capture_default_str();
  b->add_option("--bins", all->b.p.bins, "log bins of x")->capture_default_str();
  b->add_option("--x-min", all->b.p.x_min, "lowest bin edge")->capture_default_str();
  b->callback([all] { guarded([&] { run_bisection(all->c, all->b); }); });

  auto* w = model->add_subcommand(
      "walk", "single-particle walks in a disc of radius l (T.5.2–5.3): Q(v, l)");
  common_options(w, all->c);
  w->add_option("--radius", all->w.radii, "disc radii l, m (repeatable)")->capture_default_str();
  w->add_option("--walks", all->w.p.walks, "absorbed walks per radius")->capture_default_str();
  w->add_option("--dt", all->w.p.dt, "time step, s (0: time scale/1000)")->capture_default_str();
  w->add_option("--noise", all->w.p.noise, "D, N² s")->capture_default_str();
  w->add_option("--mass", all->w.p.mass, "M, kg")->capture_default_str();
  w->add_option("--bins", all->w.p.bins, "velocity bins")->capture_default_str();
  w->add_option("--v-max", all->w.p.v_max,
                "velocity histogram half-range, m/s (0: 8 (D l/M²)^(1/3) of each region)")
      ->capture_default_str();
  w->add_option("--paths", all->w.paths,
                "a freepath.csv (columns l, P): Single Particle Model with l ~ P_l");
  w->add_flag(
      "--no-heating", [all](std::int64_t) { all->w.heating = false; }, "skip heating.csv");
  w->callback([all] { guarded([&] { run_walk(all->c, all->w); }); });

  auto* i = model->add_subcommand("interval", "1D interval with absorbing ends (appendix B)");
  common_options(i, all->c);
  i->add_option("--length", all->i.length, "L, m")->capture_default_str();
  i->add_option("--walks", all->i.p.walks, "absorbed walks")->capture_default_str();
  i->add_option("--start", all->i.start, "uniform or centre")->capture_default_str();
  i->add_option("--dt", all->i.p.dt, "time step, s (0: time scale/1000)")->capture_default_str();
  i->add_option("--noise", all->i.p.noise, "D, N² s")->capture_default_str();
  i->add_option("--mass", all->i.p.mass, "M, kg")->capture_default_str();
  i->add_option("--bins", all->i.p.bins, "velocity bins")->capture_default_str();
  i->callback([all] { guarded([&] { run_interval(all->c, all->i); }); });

  auto* k =
      model->add_subcommand("cascade", "multiplicative cascades on a 2^n×2^n grid (T.6.1–6.5)");
  common_options(k, all->c);
  k->add_option("--kind", all->k.kinds, "ucp, unoncp, symmetrised, meakin1…4, or all (repeatable)")
      ->capture_default_str();
  k->add_option("--levels", all->k.p.levels, "n: a 2^n×2^n grid")->capture_default_str();
  k->add_option("--realisations", all->k.p.realisations, "fields averaged")->capture_default_str();
  k->add_option("--fit-lo", all->k.fit_lo, "D_f fit from |n| = kL/2π")->capture_default_str();
  k->add_option("--fit-hi", all->k.fit_hi, "D_f fit to |n|")->capture_default_str();
  k->callback([all] { guarded([&] { run_cascade(all->c, all->k); }); });
}

}  // namespace gs
