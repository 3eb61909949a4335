#include "app/analyze/analyze.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "analysis/tap_analysis.hpp"
#include "app/analyze/rfm_analyze.hpp"
#include "app/progress.hpp"
#include "app/run/run_info.hpp"
#include "app/subprocess.hpp"
#include "core/error.hpp"
#include "drive/schedule.hpp"
#include "output/run_dir.hpp"
#include "scene/names.hpp"
#include "scene/parse.hpp"

namespace gs {

namespace fs = std::filesystem;

namespace {

// a run directory with taps.csv, described by its scene.toml and run.json
FoundTapRun describe_run(const fs::path& dir) {
  const std::string scene_path = (dir / "scene.toml").string();
  if (!fs::exists(scene_path))
    throw InputError(dir.string(), "",
                     "has taps.csv but no scene.toml (not a gransim run directory?)");
  const SceneSpec s = parse_scene_file(scene_path);
  if (!is_tapping(s.drive))
    throw InputError(scene_path, "drive.kind", "not a tapping protocol (negative_g, rotating_g)");
  FoundTapRun r;
  r.dir = dir.string();
  r.protocol = std::string(scene_name(s.drive.kind));
  r.control = s.drive.kind == DriveKind::NegativeG ? s.drive.g_p : s.drive.f;
  r.status = run_status(r.dir);
  return r;
}

// drop the tap-0 row (the prepared pile before the first excitation): it is not a tapped state
void drop_prepared_state(TapSeries& s) {
  std::size_t k = 0;
  while (k < s.tap.size() && s.tap[k] == 0.0) ++k;
  if (k == 0) return;
  for (auto* v : {&s.tap, &s.t, &s.phi, &s.phi_left, &s.phi_right})
    if (v->size() >= k) v->erase(v->begin(), v->begin() + static_cast<long>(k));
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string o = "\"";
  for (char c : s) o += c == '"' ? std::string("\"\"") : std::string(1, c);
  return o + "\"";
}

// where a run's series came from, for runs.csv and the per-run charts
struct RunSource {
  std::string dir, file, protocol;
  double control = 0.0;
  std::string status;
};

}  // namespace

std::vector<FoundTapRun> find_tap_runs(const std::string& dir) {
  const fs::path d(dir);
  std::error_code ec;
  if (!fs::is_directory(d, ec)) throw InputError(dir, "", "not a directory");
  if (fs::exists(d / "taps.csv", ec)) return {describe_run(d)};
  // a sweep (or any folder of runs): the subdirectories with taps.csv
  std::vector<FoundTapRun> runs;
  for (const auto& e : fs::directory_iterator(d, ec))
    if (e.is_directory() && fs::exists(e.path() / "taps.csv"))
      runs.push_back(describe_run(e.path()));
  if (runs.empty())
    throw InputError(dir, "",
                     "no tapping runs here: neither DIR/taps.csv nor DIR/*/taps.csv "
                     "(a run of a negative_g or rotating_g scene writes taps.csv)");
  std::sort(runs.begin(), runs.end(), [](const FoundTapRun& a, const FoundTapRun& b) {
    if (a.protocol != b.protocol) return a.protocol < b.protocol;
    if (a.control != b.control) return a.control < b.control;
    return a.dir < b.dir;
  });
  return runs;
}

// the statistics, their files, the table and the charts of runs however they were found
int finish_analysis(const std::vector<TapRunInput>& runs, const std::vector<RunSource>& src,
                    const TapAnalysisOptions& ao, const AnalyzeOptions& opt,
                    const std::string& out) {
  // the statistics (with progress when they take a while) and their files
  TapAnalysisOptions with_progress = ao;
  double total_taps = 0.0;
  for (const auto& r : runs) total_taps += static_cast<double>(r.series.phi.size());
  std::optional<Progress> progress;  // made at the first step, which knows the total
  with_progress.progress = [&](double done, double total) {
    if (!progress) progress.emplace("analyze", total, "steps", opt.quiet, opt.progress);
    progress->update(done);
  };
  const TapAnalysisResult res = run_tap_analysis(runs, with_progress);
  if (progress) {
    char summary[96];
    std::snprintf(summary, sizeof summary, "%zu runs, %.0f taps", runs.size(), total_taps);
    progress->finish(summary);
  }
  write_tap_analysis(res, runs, ao, out);
  {
    // runs.csv: where each run came from, for the per-run charts
    std::ostringstream f;
    f << "label,dir,protocol,control,status,taps,file\n";
    for (std::size_t i = 0; i < runs.size(); ++i)
      f << csv_field(tap_run_label(runs[i])) << ',' << csv_field(src[i].dir) << ','
        << csv_field(src[i].protocol) << ',' << src[i].control << ',' << src[i].status << ','
        << runs[i].series.phi.size() << ',' << csv_field(src[i].file) << '\n';
    write_file_atomic(out + "/runs.csv", f.str());  // a full disk: exit 5 naming it
  }
  if (!opt.quiet) {
    std::printf("%-28s %6s %10s %9s %9s %21s %7s\n", "run", "taps", "phi_mean", "+-(tau)", "sigma",
                "sigma 95% CI (tau)", "tau");
    for (const auto& s : res.runs)
      std::printf("%-28s %6d %10.5f %9.2e %9.2e [%9.2e,%9.2e] %7.2f\n", s.label.c_str(), s.n_used,
                  s.phi_mean, s.phi_err, s.sigma, s.sigma_ci_tau.lo, s.sigma_ci_tau.hi,
                  s.tau.tau_int);
    for (const auto& p : res.pairs) {
      const TwoSampleTest& t = p.test;
      std::printf(
          "same φ? %s vs %s: Δφ̄ = %.2e ± %.1e (p = %.3f), σ ratio %.3f (p = %.3f), "
          "KS D = %.3f (p = %.3f)\n",
          res.runs[static_cast<std::size_t>(p.a)].label.c_str(),
          res.runs[static_cast<std::size_t>(p.b)].label.c_str(), t.mean_diff, t.mean_diff_err,
          t.p_mean, t.sigma_ratio, t.p_sigma, t.ks_d, t.ks_p);
    }
    for (const auto& n : res.notes) std::printf("note: %s\n", n.c_str());
    std::fflush(stdout);  // before the chart modules write to the same terminal
  }
  std::fprintf(stderr, "gransim analyze: %zu runs, analysis in %s\n", runs.size(), out.c_str());

  // the charts (python + matplotlib); without them the CSV and JSON files still stand
  if (!opt.charts) return kExitOk;
  for (const char* module : {"gransim.charts.tapping", "gransim.charts.taprun"}) {
    const std::string err = run_python_module(module, {out});
    if (!err.empty()) {
      std::fprintf(stderr,
                   "gransim analyze: charts skipped: %s. The CSV and JSON files are in %s\n",
                   err.c_str(), out.c_str());
      break;
    }
  }
  return kExitOk;
}

// plain φ series (FILE[:label], --series, --manifest): no scene, so the test area comes from
// the command line or the manifest; without it the φ statistics are the analysis
int analyze_plain(const AnalyzeOptions& opt, const std::vector<PlainSeries>& given, double area,
                  const std::string& out) {
  TapAnalysisOptions ao;
  ao.discard = opt.discard >= 0 ? opt.discard : 10;
  ao.discard_auto = opt.discard_auto;
  ao.test_area = area > 0.0 ? area : 0.0;
  ao.reference = opt.reference;
  ao.reference2 = opt.reference2;
  std::vector<TapRunInput> runs;
  std::vector<RunSource> sources;
  for (const auto& p : given) {
    TapRunInput in = load_tap_run(p.file, p.protocol, p.control, p.label);
    const int n = static_cast<int>(in.series.phi.size());
    if (n < ao.discard + 20)
      throw InputError(p.file, "phi",
                       std::to_string(n) + " values; the statistics need at least " +
                           std::to_string(ao.discard + 20) + " (" + std::to_string(ao.discard) +
                           " discarded + 20; --discard sets the first)");
    for (double v : in.series.phi)
      if (!(v > 0.0 && v <= 1.0))
        throw InputError(p.file, "phi", "a volume fraction outside (0, 1]: " + std::to_string(v));
    const fs::path f = fs::absolute(p.file);
    sources.push_back({f.parent_path().string(), f.string(), p.protocol, p.control, "plain"});
    runs.push_back(std::move(in));
  }
  if (!(area > 0.0) && !opt.quiet)
    std::fprintf(stderr,
                 "gransim analyze: no --test-area (m²): φ statistics only; β̂ and the quadron "
                 "fit need the area of the test region (V_g = area·φ̄ of the reference)\n");
  return finish_analysis(runs, sources, ao, opt, out);
}

int analyze_command(const AnalyzeOptions& given_opt) {
  // positional arguments that name files are plain series (FILE[:label]), the rest run dirs
  AnalyzeOptions opt = given_opt;
  {
    auto files = split_series_arguments(opt.dirs);
    opt.files.insert(opt.files.end(), files.begin(), files.end());
  }
  const bool plain = !opt.files.empty() || !opt.series.empty() || !opt.manifest.empty();
  if (plain && !opt.dirs.empty())
    throw InputError(opt.dirs[0], "DIR",
                     "give run directories or plain series (FILE[:label], --series, --manifest), "
                     "not both");
  if (!plain && opt.dirs.empty())
    throw InputError("", "DIR",
                     "give at least one run or sweep directory, or plain series: FILE[:label] "
                     "(a CSV with a phi column), --series PROTOCOL:CONTROL:FILE, --manifest");
  if (opt.dirs.size() > 1 && opt.out.empty())
    throw InputError("", "--out",
                     "several directories are analysed together into one folder: "
                     "give it with --out");
  std::vector<PlainSeries> series;
  double area = opt.test_area;
  if (plain) series = plain_series(opt, area);
  if (plain && opt.manifest.empty() && opt.out.empty() && series.size() > 1)
    throw InputError("", "--out",
                     "several series are analysed together into one folder: give it with --out");
  // one plain series: its analysis beside it, named after it
  const std::string out = !opt.out.empty() ? opt.out
                          : !plain         ? (fs::path(opt.dirs[0]) / "analysis").string()
                          : !opt.manifest.empty()
                              ? (fs::path(opt.manifest).parent_path() / "analysis").string()
                              : (fs::path(series[0].file).parent_path() /
                                 (fs::path(series[0].file).stem().string() + "_analysis"))
                                    .string();
  // the analysis never writes over a run or an input: its files (series.csv, …) would
  // replace the run's own
  {
    std::error_code ec;
    const fs::path o = fs::weakly_canonical(out, ec);
    for (const auto& d : opt.dirs)
      if (fs::weakly_canonical(d, ec) == o)
        throw InputError(out, "--out", "is one of the directories analysed; choose another --out");
    for (const char* f : {"run.json", "taps.csv", "rfm.json", "scene.toml", "sweep.json"})
      if (fs::exists(o / f, ec))
        throw InputError(out, "--out",
                         std::string("holds a run or sweep (") + f +
                             "); the analysis would overwrite its files: choose another --out");
    // nor over the plain series it reads (its series.csv may be one of them)
    if (plain) {
      std::vector<std::string> inputs;
      for (const PlainSeries& p : series) inputs.push_back(p.file);
      if (!opt.manifest.empty()) inputs.push_back(opt.manifest);
      for (const std::string& f : inputs) {
        const fs::path dir = fs::weakly_canonical(fs::absolute(f, ec).parent_path(), ec);
        const fs::path root = o.has_filename() ? o : o.parent_path();  // "D/" as "D"
        const auto [end, _] = std::mismatch(root.begin(), root.end(), dir.begin(), dir.end());
        if (end == root.end())
          throw InputError(out, "--out",
                           "holds the input " + f +
                               ", which the analysis's own files could replace: choose an "
                               "--out that holds none of the inputs");
      }
    }
  }
  const DirLock lock(out, "analyze");
  if (plain) return analyze_plain(opt, series, area, out);
  // Random Force Model runs (DIR/rfm.json or DIR/*/rfm.json): app/analyze/rfm_analyze.cpp
  if (std::all_of(opt.dirs.begin(), opt.dirs.end(),
                  [](const std::string& d) { return is_rfm_run(d); }))
    return analyze_rfm_runs(opt.dirs, out, opt.charts, opt.quiet), kExitOk;

  // the runs, their scene settings and labels ("<protocol>_<control>", made unique by folder)
  std::vector<FoundTapRun> found;
  for (const auto& d : opt.dirs) {
    auto r = find_tap_runs(d);
    found.insert(found.end(), r.begin(), r.end());
  }
  std::map<std::string, int> uses;
  auto base_label = [](const FoundTapRun& r) {
    TapRunInput t;
    t.protocol = r.protocol;
    t.control = r.control;
    return tap_run_label(t);
  };
  for (const auto& r : found) ++uses[base_label(r)];
  const SceneSpec first = parse_scene_file((fs::path(found[0].dir) / "scene.toml").string());
  TapAnalysisOptions ao;
  ao.discard = opt.discard >= 0 ? opt.discard : first.output.discard_taps;
  ao.discard_auto = opt.discard_auto;
  const double* rect = first.output.test_rect;
  ao.test_area = (rect[2] - rect[0]) * (rect[3] - rect[1]);
  ao.reference = opt.reference;
  ao.reference2 = opt.reference2;

  std::vector<TapRunInput> runs;
  std::vector<const FoundTapRun*> used;
  for (const auto& r : found) {
    const SceneSpec s = parse_scene_file((fs::path(r.dir) / "scene.toml").string());
    const double* q = s.output.test_rect;
    if (std::abs((q[2] - q[0]) * (q[3] - q[1]) - ao.test_area) > 1e-12)
      std::fprintf(stderr,
                   "gransim analyze: warning: %s has a different test rectangle; V_T of "
                   "%s is used for all\n",
                   r.dir.c_str(), found[0].dir.c_str());
    std::string label = base_label(r);
    if (uses[label] > 1) {
      const fs::path p = fs::weakly_canonical(r.dir);
      label += "@" + p.parent_path().filename().string() + "/" + p.filename().string();
    }
    TapRunInput in =
        load_tap_run((fs::path(r.dir) / "taps.csv").string(), r.protocol, r.control, label);
    drop_prepared_state(in.series);
    const int n = static_cast<int>(in.series.phi.size());
    if (r.status != "completed")
      std::fprintf(stderr, "gransim analyze: note: %s is %s; its %d taps so far are used\n",
                   r.dir.c_str(),
                   r.status.empty() ? "still running or lost (no run.json)" : r.status.c_str(), n);
    if (n < ao.discard + 20) {
      std::fprintf(stderr,
                   "gransim analyze: warning: %s skipped: %d taps, needs at least %d "
                   "(%d discarded + 20)\n",
                   r.dir.c_str(), n, ao.discard + 20, ao.discard);
      continue;
    }
    runs.push_back(std::move(in));
    used.push_back(&r);
  }
  if (runs.empty())
    throw InputError(opt.dirs[0], "",
                     "no run has enough taps for the statistics (at least " +
                         std::to_string(ao.discard + 20) + ")");

  std::vector<RunSource> sources;
  for (const FoundTapRun* r : used)
    sources.push_back({fs::absolute(r->dir).string(),
                       fs::absolute(fs::path(r->dir) / "taps.csv").string(), r->protocol,
                       r->control, r->status});
  return finish_analysis(runs, sources, ao, opt, out);
}

}  // namespace gs
