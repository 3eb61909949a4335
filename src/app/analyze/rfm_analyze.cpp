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
#include "app/analyze/rfm_run.hpp"
#include "app/run/run_info.hpp"
#include "app/subprocess.hpp"
#include "core/error.hpp"
#include "measure/rfm_io.hpp"
#include "models/bisection.hpp"
#include "output/csv.hpp"
#include "output/json_text.hpp"
#include "output/run_dir.hpp"

namespace gs {

namespace fs = std::filesystem;
using rfm_detail::RfmRun;
using rfm_detail::run_dirs;
using rfm_detail::RunResult;

namespace {

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
  CsvWriter mv((out / "moments_vs_N.csv").string(),
               {"dimension", "eps_n", "eps_t", "N", "m", "v_moment", "v_err", "R_moment", "R_err"});
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
  CsvWriter w((out / "exponents.csv").string(),
              {"dimension", "eps_n", "eps_t", "quantity", "m", "exponent", "exponent_err",
               "amplitude", "chi2_r", "sizes"},
              {{"quantity_0", 0.0}, {"quantity_1", 1.0}});
  for (const auto& r : rows)
    w.row({static_cast<double>(r.g.dim), r.g.eps_n, r.g.eps_t, static_cast<double>(r.quantity),
           static_cast<double>(r.fit.m), r.fit.exponent, r.fit.exponent_err, r.fit.amplitude,
           r.fit.chi2_r, static_cast<double>(r.sizes)});
  return rows;
}

// fits in rfm_summary.json carry ten significant digits
nlohmann::ordered_json num(double v) { return json_number(v, 10); }

void write_summary(const std::vector<RunResult>& results, const std::vector<ExponentRow>& ex,
                   const fs::path& out) {
  using ojson = nlohmann::ordered_json;
  ojson j;
  j["runs"] = ojson::array();
  for (const RunResult& r : results) {
    const RfmRun& run = *r.run;
    ojson row{{"label", run.label}, {"dir", run.dir.string()}};
    for (const char* k :
         {"dimension", "particles", "phi", "eps_n", "eps_t", "samples", "T_mean", "T_err"})
      row[k] = num(run.get(k));
    if (const auto& f = r.tail)
      row["tail"] = {{"alpha_best", num(f->best.alpha)},
                     {"accepted", f->any_accepted},
                     {"alpha_lo", num(f->any_accepted ? f->alpha_lo : kNaN)},
                     {"alpha_hi", num(f->any_accepted ? f->alpha_hi : kNaN)},
                     {"chi2_r", num(f->best.chi2_r)},
                     {"bins", f->points},
                     {"v_lo", num(f->v_lo)},
                     {"v_hi", num(f->v_hi)}};
    if (const auto& f = r.tail_post)
      row["tail_post"] = {{"alpha_best", num(f->best.alpha)},
                          {"alpha_lo", num(f->any_accepted ? f->alpha_lo : kNaN)},
                          {"alpha_hi", num(f->any_accepted ? f->alpha_hi : kNaN)}};
    if (const auto& f = r.cross)
      row["crossover"] = {{"D", num(f->d)},
                          {"v_r", num(f->v_r)},
                          {"v_c", num(f->v_c)},
                          {"alpha", num(f->alpha)},
                          {"alpha_err", num(f->alpha_err)},
                          {"chi2_r", num(f->chi2_r)}};
    if (const auto& f = r.df)
      row["structure"] = {{"D_f", num(f->d_f)},      {"D_f_err", num(f->d_f_err)},
                          {"k_D", num(f->k_d)},      {"L_eff", num(f->l_eff)},
                          {"k_prime", num(f->k_hi)}, {"shells", f->points},
                          {"chi2_r", num(f->chi2_r)}};
    if (const auto& f = r.paths)
      row["free_paths"] = {
          {"D_f", num(f->d_f)},        {"D_f_err", num(f->d_f_err)}, {"C", num(f->c)},
          {"A0", num(f->a0)},          {"chi2_r", num(f->chi2_r)},   {"bins", f->points},
          {"l_fit_min", num(f->l_min)}};
    row["notes"] = r.notes;
    j["runs"].push_back(std::move(row));
  }
  j["exponents"] = ojson::array();
  for (const ExponentRow& e : ex)
    j["exponents"].push_back({{"dimension", e.g.dim},
                              {"eps_n", num(e.g.eps_n)},
                              {"quantity", e.quantity == 0 ? "xi" : "zeta"},
                              {"m", e.fit.m},
                              {"exponent", num(e.fit.exponent)},
                              {"err", num(e.fit.exponent_err)},
                              {"chi2_r", num(e.fit.chi2_r)},
                              {"sizes", e.sizes}});
  write_file_atomic((out / "rfm_summary.json").string(), json_text(j, {"runs", "exponents"}));
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
  // the charts' "wrote …" lines are not wanted on our stdout
  return run_python_module("gransim.charts.rfm", {dir}, true);
}

void analyze_rfm_runs(const std::vector<std::string>& dirs, const std::string& out_dir, bool charts,
                      bool quiet) {
  // the runs and unique labels (the folder name, numbered when repeated)
  std::vector<RfmRun> runs;
  std::map<std::string, int> uses;
  for (const auto& d : dirs)
    for (const fs::path& p : run_dirs(d)) {
      RfmRun r = rfm_detail::read_run(p);
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
    results.push_back(rfm_detail::analyze_run(r, out / r.label));
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
