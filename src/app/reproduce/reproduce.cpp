#include "app/reproduce/reproduce.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "app/analyze/analyze.hpp"
#include "app/cli_checks.hpp"
#include "app/locations.hpp"
#include "app/reproduce/plan.hpp"
#include "app/run/run_info.hpp"
#include "app/subprocess.hpp"
#include "app/sweep/sweep.hpp"
#include "core/error.hpp"
#include "output/run_dir.hpp"

namespace gs {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// steps timed for the tapping projections: ≈ 0.2–0.5 CPU-s of the paper pile
constexpr int kCostSteps = 300;
constexpr int kRingCostSteps = 20000;  // 2·10⁷ particle-steps: a few tenths of a second

// the shipped scenes: $GS_SCENES_DIR, else beside the executable (build tree or install)
// or in the source tree it was built from
std::string find_scenes_dir(const std::string& scene) {
  std::error_code ec;
  if (const char* env = std::getenv("GS_SCENES_DIR"); env && *env) {
    if (fs::exists(fs::path(env) / scene, ec)) return env;
    throw InputError(env, "GS_SCENES_DIR", "has no " + scene);
  }
  if (std::string d = find_data_dir("scenes", scene); !d.empty()) return d;
  throw InputError(scene, "",
                   "the shipped scenes are not beside the executable (set GS_SCENES_DIR)");
}

int mpi_rank() {
  for (const char* v : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"})
    if (const char* s = std::getenv(v); s && *s) return std::atoi(s);
  return 0;
}

void print_plan(const ReproducePlan& p, const std::string& out, int cores, int slots) {
  std::printf("gransim reproduce %s --budget %s: %s\n", p.study.c_str(), budget_name(p.budget),
              p.purpose.c_str());
  for (const auto& s : p.sweeps) {
    std::printf("  %-13s %s", s.name.c_str(), s.scene.c_str());
    for (const auto& x : s.params) std::printf(" --param %s", x.c_str());
    for (const auto& x : s.sets) std::printf(" --set %s", x.c_str());
    std::printf("  (%zu runs, ≈ %.2g core-h)\n", s.run_seconds.size(), s.core_seconds() / 3600.0);
  }
  std::printf(
      "  projected: %d runs, %.3g core-hours, ≈ %.2g h on %d cores (%d runs at a time, the "
      "longest run %.2g h); into %s\n",
      p.runs(), p.core_hours(), p.wall_hours(slots), cores, slots, p.longest_run_hours(),
      out.c_str());
  if (p.study != "tapping") {
    if (p.cost.measured)
      std::printf(
          "  cost measured here: %.3g core-µs per particle-step of the %d-disk ring (%d steps from "
          "its start, CPU time, one thread): ×%.2f the reference core's, which the projections "
          "above include\n",
          p.cost.seconds * 1e6, p.cost.particles, p.cost.steps,
          p.cost.seconds / kRingCostReference);
    return;
  }
  if (p.cost.measured)
    std::printf(
        "  cost measured here: %.3g core-µs per grain-step (%d steps of the settled %d-grain "
        "pile, CPU time, one thread): %.3g core-s a tap at g_p = 6\n",
        p.cost.seconds * 1e6, p.cost.steps, p.cost.particles,
        p.cost.seconds * p.cost.particles * neg_tap_seconds(6.0) / kPaperDt);
  else
    std::printf(
        "  cost not measured here (the settled pile is not among the scenes): %.3g "
        "core-µs per grain-step assumed\n",
        p.cost.seconds * 1e6);
}

// the cluster commands for a budget too large for one machine: one rank per run of the
// widest sweep; under MPI the sweeps run one after the other, and a run's steps follow one
// another, so each sweep takes at least its longest run
void print_cluster_commands(const ReproducePlan& p, const std::string& out) {
  const int ranks = p.widest_sweep();
  const double wall = p.sweep_by_sweep_wall_hours(ranks);
  std::printf(
      "\nThe %s budget is a cluster job: %.0f core-hours (≈ %.1f days on 2 cores). With %d ranks "
      "(one per run of the widest sweep) it takes ≈ %.0f h, its sweeps one after the other: its "
      "longest run alone is ≈ %.0f h, as a run's steps follow one another. Nothing was started. To "
      "run it:\n"
      "  mpirun -np %d gransim reproduce %s --budget %s --run --out %s\n"
      "  sbatch -n %d --wrap 'srun --mpi=pmix gransim reproduce %s --budget %s --run --out %s'\n"
      "Each sweep's runs spread over the ranks (one thread each); started again, the command "
      "resumes where it stopped; rank 0 writes the report at the end.\n",
      budget_name(p.budget), p.core_hours(), p.wall_hours(2) / 24, ranks, wall,
      p.longest_run_hours(), ranks, p.study.c_str(), budget_name(p.budget), out.c_str(), ranks,
      p.study.c_str(), budget_name(p.budget), out.c_str());
}

// wall time spent on this directory over every sitting
double add_wall_time(const fs::path& out, double seconds) {
  json j = json::object();
  const fs::path f = out / "progress.json";
  if (std::ifstream in(f); in) {
    try {
      in >> j;
    } catch (const json::exception&) {
      j = json::object();
    }
  }
  const double total = j.value("wall_seconds", 0.0) + seconds;
  if (seconds <= 0.0) return total;  // a report of what is there changes no tally
  j["wall_seconds"] = total;
  j["sittings"] = j.value("sittings", 0) + 1;
  std::ofstream o(f);
  o << j.dump(2) << '\n';
  if (!o) throw OutputError(f.string() + ": cannot be written");
  return total;
}

void write_plan_json(const ReproducePlan& p, const fs::path& out, const std::string& command,
                     int slots) {
  std::ofstream o(out / "plan.json");
  o << plan_json(p, command, slots) << '\n';
  if (!o) throw OutputError((out / "plan.json").string() + ": cannot be written");
}

// the report's Python package is found, else an input error that says where it was looked for
void check_report_package() {
  if (find_python_dir("gransim.reproduce").empty())
    throw InputError("gransim.reproduce", "",
                     "the report's Python package is not beside the executable, in its install "
                     "or in its source tree (set GS_PYTHON_DIR to the folder that holds gransim/)");
}

// a published report written again from the series it ships: no run, no analysis
int report_from_series(const ReproducePlan& plan, const std::string& out) {
  const fs::path dir(out);
  if (!fs::exists(dir / "report.json"))
    throw InputError((dir / "report.json").string(), "",
                     "missing: --from-series needs a report folder with its series (written by "
                     "gransim reproduce)");
  check_report_package();
  const std::string err = run_python_module(
      "gransim.reproduce",
      {"--study", plan.study, "--budget", budget_name(plan.budget), "--from-series", out});
  if (!err.empty()) {
    std::fprintf(stderr, "reproduce: the report could not be written: %s\n", err.c_str());
    return kExitFailure;
  }
  return kExitOk;
}

// the paper pile's cost per particle-step on this machine (kPileCostReference where the
// settled pile is not among the shipped scenes)
PileCost pile_cost_here() {
  const std::string scene = "paper_negative_g_fast.toml", state = "data/paper_pile_settled.csv";
  std::error_code ec;
  const std::string dir = find_data_dir("scenes", state);
  if (dir.empty() || !fs::exists(fs::path(dir) / scene, ec)) return {};
  return measure_pile_cost(dir + "/" + scene, dir + "/" + state, kCostSteps);
}

// the RFM ring's cost per particle-step on this machine (nothing measured where the scene is not
// among the shipped ones)
PileCost ring_cost_here() {
  const std::string scene = "rfm1d_reference.toml";
  const std::string dir = find_data_dir("scenes", scene);
  if (dir.empty()) return {};
  return measure_pile_cost(dir + "/" + scene, "", kRingCostSteps);
}

}  // namespace

int reproduce_command(const ReproduceOptions& opt) {
  const Budget budget = parse_budget(opt.budget);
  const bool root = mpi_rank() == 0;
  // measured where projections are printed: before a run, not for a report from its series
  const bool measure = root && !opt.from_series && !opt.report_only;
  const ReproducePlan plan = make_plan(opt.study, budget,
                                       !measure                 ? PileCost{}
                                       : opt.study == "tapping" ? pile_cost_here()
                                                                : ring_cost_here());
  const std::string out =
      opt.out.empty() ? "runs/reproduce-" + opt.study + "-" + opt.budget : opt.out;
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (opt.from_series) return root ? report_from_series(plan, out) : kExitOk;
  const int slots = opt.jobs > 0 ? opt.jobs : cores;  // runs at a time, as the pool runs them
  if (root && !opt.quiet) print_plan(plan, out, cores, slots);
  std::fflush(stdout);  // the plan before the runs' progress (stderr) in a log of both
  if (plan.budget == Budget::Full && !opt.run_full && !opt.report_only) {
    if (root) print_cluster_commands(plan, out);
    return kExitOk;
  }

  // every scene is found before anything starts
  std::vector<std::string> scenes;
  for (const auto& s : plan.sweeps) scenes.push_back(find_scenes_dir(s.scene) + "/" + s.scene);
  const fs::path dir(out);
  std::error_code ec;
  // a run or a sweep is no study folder: its files would be mixed with the study's
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw InputError(out, "--out", "is a file, not a folder; choose another --out");
  for (const char* f : {"run.json", "scene.toml", "taps.csv", "rfm.json", "sweep.json"})
    if (fs::exists(dir / f, ec))
      throw InputError(out, "--out",
                       std::string("holds a run or a sweep (") + f +
                           "), not a study of `gransim reproduce`: choose another --out");
  // the runs' writer holds DIR/.lock, whoever analyses and reports DIR/.report.lock: a report
  // of a study still running can be made beside it (--report-only), one report at a time
  std::unique_ptr<DirLock> lock, report_lock;
  if (root && !opt.report_only) lock = std::make_unique<DirLock>(out, "reproduce");
  if (root && opt.report_only)
    report_lock = std::make_unique<DirLock>(out, "reproduce --report-only", ".report.lock");
  fs::create_directories(dir / "sweeps", ec);
  if (ec) throw OutputError(out + ": cannot create the directory: " + ec.message());
  // as a reader would type it: where this machine put the runs is no part of the study
  const std::string command = "gransim reproduce " + opt.study + " --budget " + opt.budget;
  if (root && (!opt.report_only || !fs::exists(dir / "plan.json")))
    write_plan_json(plan, dir, command, slots);

  // the sweeps: completed runs are kept, interrupted ones resume from their checkpoints
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  int code = kExitOk;
  if (!opt.report_only) {
    // the study's runs as one pool: a run of the next sweep starts as soon as a slot is free
    std::vector<SweepOptions> all;
    for (std::size_t i = 0; i < plan.sweeps.size(); ++i) {
      const PlannedSweep& s = plan.sweeps[i];
      SweepOptions so;
      so.scene = scenes[i];
      so.params = s.params;
      so.sets = s.sets;
      so.out = (dir / "sweeps" / s.name).string();
      so.jobs = opt.jobs;
      so.quiet = opt.quiet;
      all.push_back(so);
    }
    code = sweeps_command(all, opt.jobs);
  }
  if (!root) return code;
  const double wall = add_wall_time(dir, opt.report_only ? 0.0 : elapsed());
  if (code == kExitInterrupted) {
    std::fprintf(stderr,
                 "reproduce: interrupted; run the same command again to continue (finished runs "
                 "are kept, interrupted runs resume from their checkpoints)\n");
    return code;
  }
  if (code != kExitOk) {
    std::fprintf(stderr, "reproduce: a run failed (exit %d); see %s/sweeps/*/logs\n", code,
                 out.c_str());
    return code;
  }

  // the analyses: tapping over both protocols at once (the joint quadron fit needs both);
  // each RFM sweep on its own
  if (!report_lock) report_lock = std::make_unique<DirLock>(out, "reproduce", ".report.lock");
  // a report of a study still running covers the sweeps that have begun
  // (a sweep counts once one of its runs has written what the analysis reads)
  const char* data = plan.study == "tapping" ? "taps.csv" : "rfm.json";
  auto has_data = [&](const fs::path& sweep) {
    std::error_code e;
    for (const auto& run : fs::directory_iterator(sweep, e))
      if (run.is_directory(e) && fs::exists(run.path() / data, e)) return true;
    return false;
  };
  std::vector<PlannedSweep> begun;
  for (const auto& s : plan.sweeps) {
    if (has_data(dir / "sweeps" / s.name))
      begun.push_back(s);
    else
      std::fprintf(stderr,
                   "reproduce: sweep %s has not begun (no run with %s yet); the report leaves it "
                   "out\n",
                   s.name.c_str(), data);
  }
  if (begun.empty())
    throw InputError(out, "", "no sweep of the study has begun: nothing to report");
  if (plan.study == "tapping") {
    // the protocols together; the time-step check's runs apart (their labels repeat the
    // study's and they are no part of its fits)
    AnalyzeOptions ao, check;
    for (const auto& s : begun)
      (s.name == "timestep" ? check : ao).dirs.push_back((dir / "sweeps" / s.name).string());
    ao.out = (dir / "analysis").string();
    check.out = (dir / "analysis" / "timestep").string();
    for (AnalyzeOptions* a : {&ao, &check}) {
      a->quiet = opt.quiet;
      a->discard_auto = true;  // a weak pulse compacts the pile over far more than 10 taps
      if (!a->dirs.empty()) code = std::max(code, analyze_command(*a));
    }
  } else {
    for (const auto& s : begun) {
      AnalyzeOptions ao;
      ao.dirs = {(dir / "sweeps" / s.name).string()};
      ao.out = (dir / "analysis" / s.name).string();
      ao.quiet = opt.quiet;
      code = std::max(code, analyze_command(ao));
    }
  }
  if (code != kExitOk) return code;

  // the auxiliary models, each once: a folder with its model.json is done (an interrupted one
  // is written again); one that reads an analysis' output waits until it is there
  if (!opt.report_only) {
    for (const auto& m : plan.models) {
      const fs::path mo = dir / "models" / m.name;
      if (fs::exists(mo / "model.json", ec)) continue;
      if (!m.needs.empty() && !fs::exists(dir / m.needs, ec)) {
        std::fprintf(stderr, "reproduce: model %s waits for %s\n", m.name.c_str(),
                     (dir / m.needs).c_str());
        continue;
      }
      std::vector<std::string> argv = {self_executable()};
      for (const auto& a : m.args)
        argv.push_back(a.rfind("DIR/", 0) == 0 ? (dir / a.substr(4)).string() : a);
      argv.insert(argv.end(), {"--out", mo.string(), "--force", "--no-charts"});
      if (!opt.quiet) std::printf("reproduce: model %s into %s\n", m.name.c_str(), mo.c_str());
      const std::string err = run_process(argv, opt.quiet);
      if (!err.empty()) {
        std::fprintf(stderr, "reproduce: model %s failed: %s\n", m.name.c_str(), err.c_str());
        return kExitFailure;
      }
    }
  }

  // the report
  check_report_package();
  char wall_text[32];
  std::snprintf(wall_text, sizeof wall_text, "%.0f", wall);
  const std::string err = run_python_module(
      "gransim.reproduce", {"--study", plan.study, "--budget", opt.budget, "--wall", wall_text,
                            "--cores", std::to_string(cores), "--command", command, out});
  if (!err.empty()) {
    std::fprintf(stderr, "reproduce: the report could not be written: %s\n", err.c_str());
    return kExitFailure;
  }
  std::printf("reproduce: %s/report.md and %s/report.html (%.0f s of wall time in all)\n",
              out.c_str(), out.c_str(), wall);
  return kExitOk;
}

CLI::App* add_reproduce_command(CLI::App& app, ReproduceOptions& opt) {
  auto* c = app.add_subcommand(
      "reproduce",
      "run a study's sweeps at a budget (resumable), analyse them and write a report of the "
      "sources' claims beside the program's results");
  c->add_option("study", opt.study, "tapping (the paper) or rfm (the thesis)")
      ->required()
      ->check(CLI::IsMember({"tapping", "rfm"}));
  c->add_option("--budget", opt.budget,
                "smoke (minutes: the pipeline), quick (< 1 h on 2 cores), standard (one night), "
                "full (the sources' scale: prints the cluster command)")
      ->check(CLI::IsMember({"smoke", "quick", "standard", "full"}));
  c->add_option("-o,--out", opt.out, "directory (default runs/reproduce-<study>-<budget>)");
  c->add_option("-j,--jobs", opt.jobs, "runs at a time (default: the number of cores)")
      ->check(cli_check::non_negative);
  c->add_flag("--run", opt.run_full, "run the full budget here instead of printing its commands");
  auto* report_only = c->add_flag("--report-only", opt.report_only,
                                  "analyse and report what is there; start no run");
  c->add_flag("--from-series", opt.from_series,
              "write the report in --out again from the series it ships (DIR/series, "
              "DIR/report.json): no run, no analysis")
      ->excludes(report_only);
  c->add_flag("-q,--quiet", opt.quiet, "no progress display");
  return c;
}

}  // namespace gs
