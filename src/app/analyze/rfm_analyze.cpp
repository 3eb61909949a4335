// `gransim analyze` for RFM runs: per-run fits, exponents across sizes, summary, charts
#include "app/analyze/rfm_analyze.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

#include "analysis/rfm_csv.hpp"
#include "analysis/rfm_freepath.hpp"
#include "analysis/rfm_moments.hpp"
#include "analysis/rfm_sk.hpp"
#include "analysis/rfm_tails.hpp"
#include "app/locations.hpp"
#include "app/run/run_info.hpp"
#include "app/subprocess.hpp"
#include "core/error.hpp"
#include "measure/rfm_io.hpp"
#include "models/bisection.hpp"
#include "output/run_dir.hpp"

namespace gs {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// one RFM run directory and what its rfm.json says
struct RfmRun {
  fs::path dir;
  std::string label;  // unique name of its analysis folder
  std::map<std::string, double> info;
  double get(const std::string& k) const {
    auto it = info.find(k);
    return it == info.end() ? kNaN : it->second;
  }
};

// every number field of rfm.json (one "key": value per line, written by RfmObserver)
RfmRun read_run(const fs::path& dir) {
  RfmRun r;
  r.dir = dir;
  const auto text = read_text_file((dir / "rfm.json").string());
  if (!text) throw InputError((dir / "rfm.json").string(), "", "cannot be read");
  for (const char* k : {"dimension",
                        "particles",
                        "box",
                        "box_height",
                        "reduced_length",
                        "diameter",
                        "mass",
                        "phi",
                        "eps_n",
                        "eps_t",
                        "ks",
                        "D",
                        "dt",
                        "sample_every",
                        "discard_time",
                        "t_steady",
                        "t_end",
                        "samples",
                        "T_mean",
                        "T_err",
                        "v_max",
                        "velocity_samples",
                        "leave_events",
                        "free_paths",
                        "sk_nmax",
                        "structure"})
    if (auto v = json_number_field(*text, k)) r.info[k] = *v;
  if (!r.info.count("dimension") || !r.info.count("particles"))
    throw InputError((dir / "rfm.json").string(), "dimension", "not an RFM observer file");
  return r;
}

// the runs in a directory: itself, or its subdirectories with rfm.json (sorted by name)
std::vector<fs::path> run_dirs(const fs::path& d) {
  std::error_code ec;
  if (fs::exists(d / "rfm.json", ec)) return {d};
  std::vector<fs::path> out;
  if (fs::is_directory(d, ec))
    for (const auto& e : fs::directory_iterator(d, ec))
      if (e.is_directory() && fs::exists(e.path() / "rfm.json")) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// what one run's analysis found, for the summary and the exponent fits
struct RunResult {
  const RfmRun* run = nullptr;
  std::optional<rfm::TailFit> tail, tail_post;
  std::optional<rfm::CrossoverFit> cross;
  std::optional<rfm::DfFit> df;
  std::optional<rfm::FreePathFit> paths;
  std::vector<double> v_moments, v_errors, r_moments, r_errors;
  std::vector<std::string> notes;
};

// a CSV is written anew in the current form (metadata in its sidecar), whichever form it had
void copy_if_there(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  if (!fs::exists(from, ec)) return;
  if (from.extension() != ".csv") {
    fs::copy_file(from, to, fs::copy_options::overwrite_existing);
    return;
  }
  const rfm::CsvTable t = rfm::read_csv(from);
  rfm::CsvWriter w(to, t.names, rfm::CsvMeta(t.meta.begin(), t.meta.end()));
  const std::size_t rows = t.names.empty() ? 0 : t.column.at(t.names.front()).size();
  std::vector<double> row(t.names.size());
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t c = 0; c < t.names.size(); ++c) row[c] = t.column.at(t.names[c])[i];
    w.row(row);
  }
}

// a moments.csv (m, moment, error) as two vectors
void read_moments(const fs::path& p, std::vector<double>& m, std::vector<double>& e) {
  std::error_code ec;
  if (!fs::exists(p, ec)) return;
  const rfm::CsvTable t = rfm::read_csv(p);
  m = t.col("moment");
  e = t.col("error");
}

// P(v) at v = 0: the bin holding 0, or the mean of the two bins meeting there
double density_at_zero(const rfm::Histogram& h) {
  const auto bins = h.bins();
  for (std::size_t i = 0; i < bins.size(); ++i) {
    if (bins[i].lo < 0.0 && bins[i].hi > 0.0) return bins[i].p;
    if (bins[i].lo == 0.0 && i > 0) return 0.5 * (bins[i].p + bins[i - 1].p);
  }
  return kNaN;
}

// the velocity histogram: tail scan, crossover, ln–ln views (appendix A, §5.3)
void analyze_velocities(const fs::path& in, const fs::path& out, RunResult& res) {
  const rfm::Histogram h = rfm::read_histogram_raw(in / "hist_velocity.csv");
  try {
    res.tail = rfm::fit_tail(h);  // counts 50…5000, accept α while χ²_r < 1.2
  } catch (const InputError& e) {
    res.notes.push_back(std::string("velocity tail fit skipped: ") + e.what());
  }
  // T.5.32 with α free; α = 1 (the thesis' asymptote) when the free fit does not converge
  try {
    rfm::CrossoverFit c = rfm::fit_crossover(h, 1.0, true);
    if (!std::isfinite(c.alpha) || c.alpha <= 0.0 || c.alpha >= 2.0)
      c = rfm::fit_crossover(h, 1.0, false);
    res.cross = c;
  } catch (const std::exception& e) {
    res.notes.push_back(std::string("crossover fit skipped: ") + e.what());
  }
  rfm::write_velocity_csv(out / "velocity.csv", h, res.tail ? &*res.tail : nullptr,
                          res.cross ? &*res.cross : nullptr);
  if (res.tail) rfm::write_tail_scan_csv(out / "tail_scan.csv", *res.tail);
  // ln–ln tail plots with the asymptotic amplitude A₀ and with P(0) (§5.3.3)
  double c2 = 0.0, cn = 0.0;
  for (const auto& b : h.bins()) {
    c2 += b.count * b.x * b.x;
    cn += b.count;
  }
  const double vrms = cn > 0 ? std::sqrt(c2 / cn) : kNaN;
  if (res.tail && vrms > 0) {
    const double a0 = res.tail->best.a;
    rfm::write_lnln_csv(out / "lnln_A0.csv", rfm::lnln_tail(h, a0, vrms, 50.0), a0, vrms);
    const double p0 = density_at_zero(h);
    rfm::write_lnln_csv(out / "lnln_P0.csv", rfm::lnln_tail(h, p0, vrms, 50.0), p0, vrms);
  }
  // velocities just after collisions: the same tail scan
  std::error_code ec;
  if (fs::exists(in / "hist_postcollision.csv", ec)) {
    const rfm::Histogram hp = rfm::read_histogram_raw(in / "hist_postcollision.csv");
    try {
      res.tail_post = rfm::fit_tail(hp);
    } catch (const InputError&) {
    }
    rfm::write_velocity_csv(out / "velocity_post.csv", hp,
                            res.tail_post ? &*res.tail_post : nullptr);
  }
}

// 2D structure: D_f from S(k) below k′ (T.4.5–4.9) and free paths (T.4.25)
void analyze_structure(const RfmRun& r, const fs::path& out, RunResult& res) {
  std::error_code ec;
  if (fs::exists(r.dir / "sk.csv", ec)) {
    const rfm::CsvTable t = rfm::read_csv(r.dir / "sk.csv");
    std::vector<rfm::SkShell> shells;
    const auto& k = t.col("k");
    for (std::size_t i = 0; i < k.size(); ++i) {
      rfm::SkShell s;
      s.k = k[i];
      s.n = t.col("n")[i];
      s.s = t.col("S")[i];
      s.s_err = t.col("S_err")[i];
      s.modes = static_cast<long>(t.col("modes")[i]);
      shells.push_back(s);
    }
    rfm::RfmSystem sys;
    sys.box = r.get("box");
    sys.n = static_cast<long>(r.get("particles"));
    sys.diameter = r.get("diameter");
    sys.eps_n = r.get("eps_n");
    sys.eps_t = r.get("eps_t");
    try {
      res.df = rfm::fit_df_rfm(shells, sys);
    } catch (const InputError& e) {
      res.notes.push_back(std::string("D_f fit skipped: ") + e.what());
    }
    rfm::write_sk_csv(out / "sk.csv", shells, res.df ? &*res.df : nullptr);
  }
}

void analyze_free_paths(const RfmRun& r, const fs::path& out, RunResult& res) {
  std::error_code ec;
  if (!fs::exists(r.dir / "hist_freepath.csv", ec)) return;
  const rfm::Histogram h = rfm::read_histogram_raw(r.dir / "hist_freepath.csv");
  // T.4.25 describes flights between collisions; paths shorter than d/10 are mostly re-contacts
  // within a few overlap depths of soft disks pressed together (they make P_l flat below
  // ~1e-5 m), so the fit starts at d/10 (docs/rfm.md: D_f moves by ~0.02 between d/30 and d/10)
  try {
    res.paths = rfm::fit_free_paths(h, 0.1 * r.get("diameter"), 10.0);
  } catch (const std::exception& e) {
    res.notes.push_back(std::string("free-path fit skipped: ") + e.what());
  }
  rfm::write_freepath_csv(out / "freepath.csv", h, res.paths ? &*res.paths : nullptr);
}

// 1D: G₁(R) against the bisection density of n = round(log₂ N) levels (thesis Fig. 3.16) and
// the gaps of N uniform points, (N−1)(1−R)^(N−2) (R in units of L′)
void write_gh_bisection(const RfmRun& r, const fs::path& out) {
  std::error_code ec;
  if (!fs::exists(r.dir / "gh.csv", ec)) return;
  const rfm::CsvTable t = rfm::read_csv(r.dir / "gh.csv");
  const double n = r.get("particles");
  const int levels = std::max(1, static_cast<int>(std::lround(std::log2(n))));
  rfm::CsvWriter w(out / "gh_bisection.csv", {"R", "G1", "G1_err", "P_bisection", "P_uniform"},
                   {{"levels", static_cast<double>(levels)}, {"N", n}});
  const auto& R = t.col("R");
  for (std::size_t i = 0; i < R.size(); ++i)
    w.row({R[i], t.col("G1")[i], t.col("G1_err")[i], models::bisection_density(R[i], levels),
           R[i] < 1.0 ? (n - 1.0) * std::pow(1.0 - R[i], n - 2.0) : 0.0});
}

RunResult analyze_run(const RfmRun& r, const fs::path& out) {
  RunResult res;
  res.run = &r;
  fs::create_directories(out);
  for (const char* f : {"temperature.csv", "moments.csv", "moments_components.csv", "gr.csv",
                        "gh.csv", "gap_moments.csv", "rfm.json"})
    copy_if_there(r.dir / f, out / f);
  read_moments(r.dir / "moments.csv", res.v_moments, res.v_errors);
  read_moments(r.dir / "gap_moments.csv", res.r_moments, res.r_errors);
  std::error_code ec;
  if (fs::exists(r.dir / "hist_velocity.csv", ec)) analyze_velocities(r.dir, out, res);
  if (r.get("dimension") == 2.0) analyze_structure(r, out, res);
  analyze_free_paths(r, out, res);
  if (r.get("dimension") == 1.0) write_gh_bisection(r, out);
  return res;
}

// runs of one dimension and restitution pair at several N: ξ_m and ζ_m (T.3.13, T.3.20)
struct Group {
  int dim;
  double eps_n, eps_t;
  bool operator<(const Group& o) const {
    return std::tie(dim, eps_n, eps_t) < std::tie(o.dim, o.eps_n, o.eps_t);
  }
};

bool usable(const std::vector<double>& m, const std::vector<double>& e) {
  if (m.size() != 12) return false;
  for (std::size_t k = 0; k < m.size(); ++k)
    if (!(m[k] > 0) || !std::isfinite(m[k]) || !(e.size() == m.size())) return false;
  return true;
}
bool errors_ok(const std::vector<std::vector<double>>& e) {
  for (const auto& row : e)
    for (double x : row)
      if (!(x > 0) || !std::isfinite(x)) return false;
  return true;
}

struct ExponentRow {
  Group g;
  int quantity;  // 0: ξ_m of ⟨|v|^m⟩, 1: ζ_m of ⟨R^m⟩
  rfm::ExponentFit fit;
  int sizes;
};

std::vector<ExponentRow> fit_exponents(const std::vector<RunResult>& results, const fs::path& out) {
  std::map<Group, std::vector<const RunResult*>> groups;
  for (const auto& r : results)
    groups[{static_cast<int>(r.run->get("dimension")), r.run->get("eps_n"), r.run->get("eps_t")}]
        .push_back(&r);
  std::vector<ExponentRow> rows;
  rfm::CsvWriter mv(out / "moments_vs_N.csv", {"dimension", "eps_n", "eps_t", "N", "m", "v_moment",
                                               "v_err", "R_moment", "R_err"});
  for (const auto& [g, rs] : groups) {
    for (int q = 0; q < 2; ++q) {
      std::vector<double> n;
      std::vector<std::vector<double>> m, e;
      for (const RunResult* r : rs) {
        const auto& mm = q == 0 ? r->v_moments : r->r_moments;
        const auto& ee = q == 0 ? r->v_errors : r->r_errors;
        if (!usable(mm, ee)) continue;
        n.push_back(r->run->get("particles"));
        m.push_back(mm);
        e.push_back(ee);
      }
      std::vector<double> sorted = n;
      std::sort(sorted.begin(), sorted.end());
      const auto sizes = std::unique(sorted.begin(), sorted.end()) - sorted.begin();
      if (sizes < 2) continue;
      const auto fits =
          rfm::fit_scaling_exponents(n, m, errors_ok(e) ? e : std::vector<std::vector<double>>{});
      for (const auto& f : fits) rows.push_back({g, q, f, static_cast<int>(sizes)});
    }
    for (const RunResult* r : rs)
      for (std::size_t k = 0; k < 12; ++k) {
        auto at = [k](const std::vector<double>& v) { return k < v.size() ? v[k] : kNaN; };
        mv.row({static_cast<double>(g.dim), g.eps_n, g.eps_t, r->run->get("particles"),
                static_cast<double>(k + 1), at(r->v_moments), at(r->v_errors), at(r->r_moments),
                at(r->r_errors)});
      }
  }
  rfm::CsvWriter w(out / "exponents.csv",
                   {"dimension", "eps_n", "eps_t", "quantity", "m", "exponent", "exponent_err",
                    "amplitude", "chi2_r", "sizes"},
                   {{"quantity_0", 0.0}, {"quantity_1", 1.0}});
  for (const auto& r : rows)
    w.row({static_cast<double>(r.g.dim), r.g.eps_n, r.g.eps_t, static_cast<double>(r.quantity),
           static_cast<double>(r.fit.m), r.fit.exponent, r.fit.exponent_err, r.fit.amplitude,
           r.fit.chi2_r, static_cast<double>(r.sizes)});
  return rows;
}

std::string jnum(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}
std::string jstr(const std::string& v) {
  std::string o = "\"";
  for (char c : v) {
    if (c == '"' || c == '\\') o += '\\';
    o += static_cast<unsigned char>(c) < 0x20 ? ' ' : c;
  }
  return o + "\"";
}

void write_summary(const std::vector<RunResult>& results, const std::vector<ExponentRow>& ex,
                   const fs::path& out) {
  std::ostringstream js;
  js << "{\n  \"runs\": [";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const RunResult& r = results[i];
    const RfmRun& run = *r.run;
    js << (i ? ",\n" : "\n") << "    {\"label\": " << jstr(run.label)
       << ", \"dir\": " << jstr(run.dir.string());
    for (const char* k :
         {"dimension", "particles", "phi", "eps_n", "eps_t", "samples", "T_mean", "T_err"})
      js << ", \"" << k << "\": " << jnum(run.get(k));
    if (r.tail)
      js << ", \"tail\": {\"alpha_best\": " << jnum(r.tail->best.alpha)
         << ", \"accepted\": " << (r.tail->any_accepted ? "true" : "false")
         << ", \"alpha_lo\": " << jnum(r.tail->any_accepted ? r.tail->alpha_lo : kNaN)
         << ", \"alpha_hi\": " << jnum(r.tail->any_accepted ? r.tail->alpha_hi : kNaN)
         << ", \"chi2_r\": " << jnum(r.tail->best.chi2_r) << ", \"bins\": " << r.tail->points
         << ", \"v_lo\": " << jnum(r.tail->v_lo) << ", \"v_hi\": " << jnum(r.tail->v_hi) << "}";
    if (r.tail_post)
      js << ", \"tail_post\": {\"alpha_best\": " << jnum(r.tail_post->best.alpha)
         << ", \"alpha_lo\": " << jnum(r.tail_post->any_accepted ? r.tail_post->alpha_lo : kNaN)
         << ", \"alpha_hi\": " << jnum(r.tail_post->any_accepted ? r.tail_post->alpha_hi : kNaN)
         << "}";
    if (r.cross)
      js << ", \"crossover\": {\"D\": " << jnum(r.cross->d) << ", \"v_r\": " << jnum(r.cross->v_r)
         << ", \"v_c\": " << jnum(r.cross->v_c) << ", \"alpha\": " << jnum(r.cross->alpha)
         << ", \"alpha_err\": " << jnum(r.cross->alpha_err)
         << ", \"chi2_r\": " << jnum(r.cross->chi2_r) << "}";
    if (r.df)
      js << ", \"structure\": {\"D_f\": " << jnum(r.df->d_f)
         << ", \"D_f_err\": " << jnum(r.df->d_f_err) << ", \"k_D\": " << jnum(r.df->k_d)
         << ", \"L_eff\": " << jnum(r.df->l_eff) << ", \"k_prime\": " << jnum(r.df->k_hi)
         << ", \"shells\": " << r.df->points << ", \"chi2_r\": " << jnum(r.df->chi2_r) << "}";
    if (r.paths)
      js << ", \"free_paths\": {\"D_f\": " << jnum(r.paths->d_f)
         << ", \"D_f_err\": " << jnum(r.paths->d_f_err) << ", \"C\": " << jnum(r.paths->c)
         << ", \"A0\": " << jnum(r.paths->a0) << ", \"chi2_r\": " << jnum(r.paths->chi2_r)
         << ", \"bins\": " << r.paths->points << "}";
    js << ", \"notes\": [";
    for (std::size_t k = 0; k < r.notes.size(); ++k) js << (k ? ", " : "") << jstr(r.notes[k]);
    js << "]}";
  }
  js << "\n  ],\n  \"exponents\": [";
  for (std::size_t i = 0; i < ex.size(); ++i)
    js << (i ? ",\n" : "\n") << "    {\"dimension\": " << ex[i].g.dim
       << ", \"eps_n\": " << jnum(ex[i].g.eps_n)
       << ", \"quantity\": " << (ex[i].quantity == 0 ? "\"xi\"" : "\"zeta\"")
       << ", \"m\": " << ex[i].fit.m << ", \"exponent\": " << jnum(ex[i].fit.exponent)
       << ", \"err\": " << jnum(ex[i].fit.exponent_err)
       << ", \"chi2_r\": " << jnum(ex[i].fit.chi2_r) << ", \"sizes\": " << ex[i].sizes << "}";
  js << "\n  ]\n}\n";
  write_file_atomic((out / "rfm_summary.json").string(), js.str());
}

void print_table(const std::vector<RunResult>& results) {
  std::printf("%-28s %3s %6s %6s %7s %10s %16s %8s %8s\n", "run", "dim", "N", "eps_n", "samples",
              "T (m2/s2)", "tail alpha", "D_f S(k)", "D_f P_l");
  for (const RunResult& r : results) {
    char tail[40] = "-", df[16] = "-", dp[16] = "-";
    if (r.tail && r.tail->any_accepted)
      std::snprintf(tail, sizeof tail, "%.2f [%.2f,%.2f]", r.tail->best.alpha, r.tail->alpha_lo,
                    r.tail->alpha_hi);
    else if (r.tail)
      std::snprintf(tail, sizeof tail, "%.2f (none<1.2)", r.tail->best.alpha);
    if (r.df) std::snprintf(df, sizeof df, "%.3f", r.df->d_f);
    if (r.paths) std::snprintf(dp, sizeof dp, "%.3f", r.paths->d_f);
    std::printf("%-28s %3.0f %6.0f %6.3g %7.0f %10.4g %16s %8s %8s\n", r.run->label.c_str(),
                r.run->get("dimension"), r.run->get("particles"), r.run->get("eps_n"),
                r.run->get("samples"), r.run->get("T_mean"), tail, df, dp);
  }
}

}  // namespace

bool is_rfm_run(const std::string& dir) { return !run_dirs(dir).empty(); }

std::string draw_rfm_charts(const std::string& dir) {
  const std::string tools = find_tools_dir("charts_rfm.py");
  if (tools.empty()) return "tools/charts_rfm.py not found (set GS_TOOLS_DIR)";
  // the script's "wrote …" lines are not wanted on our stdout
  return run_python_script((fs::path(tools) / "charts_rfm.py").string(), {dir}, true);
}

void analyze_rfm_runs(const std::vector<std::string>& dirs, const std::string& out_dir, bool charts,
                      bool quiet) {
  // the runs and unique labels (the folder name, numbered when repeated)
  std::vector<RfmRun> runs;
  std::map<std::string, int> uses;
  for (const auto& d : dirs)
    for (const fs::path& p : run_dirs(d)) {
      RfmRun r = read_run(p);
      std::string base = p.filename().string();
      if (base.empty() || base == ".") base = fs::absolute(p).parent_path().filename().string();
      r.label = ++uses[base] > 1 ? base + "_" + std::to_string(uses[base]) : base;
      runs.push_back(std::move(r));
    }
  if (runs.empty())
    throw InputError(dirs.empty() ? "" : dirs.front(), "",
                     "no RFM runs here: neither DIR/rfm.json nor DIR/*/rfm.json (a run of a "
                     "random_force scene, or one with [rfm] enabled, writes rfm.json)");
  const fs::path out(out_dir);
  fs::create_directories(out);

  std::vector<RunResult> results;
  for (const RfmRun& r : runs) {
    if (!(r.get("samples") > 0)) {
      std::fprintf(stderr, "gransim analyze: %s has no samples after the discarded %g s; skipped\n",
                   r.dir.c_str(), r.get("discard_time"));
      continue;
    }
    results.push_back(analyze_run(r, out / r.label));
  }
  if (results.empty())
    throw InputError(dirs.front(), "rfm.discard_time",
                     "no run has steady-state samples (runs shorter than the discarded transient)");
  const auto ex = fit_exponents(results, out);
  write_summary(results, ex, out);
  if (!quiet) {
    print_table(results);
    for (const auto& r : results)
      for (const auto& n : r.notes) std::printf("  %s: %s\n", r.run->label.c_str(), n.c_str());
    std::printf("analysis in %s\n", out.c_str());
  }
  if (!charts) return;
  for (const RunResult& r : results) {
    const std::string err = draw_rfm_charts((out / r.run->label).string());
    if (!err.empty()) {
      std::fprintf(stderr,
                   "gransim analyze: charts skipped: %s; the CSV and JSON files are in %s\n",
                   err.c_str(), out.c_str());
      return;
    }
  }
}

}  // namespace gs
