// `gransim sweep`: the parameters, the runs and their validation (the plan); running the plan is
// in sweep_exec.cpp (child processes on this machine) and sweep_mpi.cpp (over MPI ranks)
#include "app/sweep/sweep.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <thread>

#include "app/run/run_info.hpp"
#include "app/run/run_session.hpp"
#include "app/sweep/sweep_detail.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "drive/schedule.hpp"
#include "output/run_dir.hpp"
#include "scene/parse.hpp"

namespace gs {

namespace fs = std::filesystem;
using sweep_detail::Job;
using sweep_detail::SweepPlan;

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// the value as it appears in a directory name: TOML strings without their quotes
std::string value_for_name(const std::string& v) {
  if (v.size() >= 2 && (v.front() == '"' || v.front() == '\'') && v.back() == v.front())
    return v.substr(1, v.size() - 2);
  return v;
}

// the short name of a key in directory names: its last dotted component
std::string short_key(const std::string& key) {
  const auto p = key.rfind('.');
  return p == std::string::npos ? key : key.substr(p + 1);
}

// FNV-1a of a text, to recognise the base scene of an existing sweep
std::string text_hash(const std::string& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ULL;
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

// the scene of one run: the shared --set overrides, then the run's own
SceneSpec run_scene(const SweepOptions& opt, const SweepRun& r) {
  std::vector<std::string> ov = opt.sets;
  ov.insert(ov.end(), r.overrides.begin(), r.overrides.end());
  try {
    return parse_scene_file(opt.scene, ov);
  } catch (const InputError& e) {
    throw InputError("", "", std::string(e.what()) + " (in the sweep run '" + r.name + "')");
  }
}

}  // namespace

SweepParam parse_sweep_param(const std::string& text) {
  const std::string where = "--param " + text;
  const auto eq = text.find('=');
  if (eq == std::string::npos)
    throw InputError(where, "", "expected KEY=V1,V2,… (e.g. --param drive.g_p=4,6,8)");
  SweepParam p;
  p.key = trim(text.substr(0, eq));
  if (p.key.empty()) throw InputError(where, "", "the key before '=' is empty");
  const std::string list = text.substr(eq + 1);
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ',')) {
    item = trim(item);
    if (item.empty()) throw InputError(where, p.key, "empty value in the list '" + list + "'");
    if (item.find('/') != std::string::npos)
      throw InputError(where, p.key, "value '" + item + "' cannot name a directory (contains '/')");
    p.values.push_back(item);
  }
  if (!list.empty() && list.back() == ',')
    throw InputError(where, p.key, "empty value in the list '" + list + "'");
  if (p.values.empty()) throw InputError(where, p.key, "no values after '='");
  std::set<std::string> seen;
  for (const auto& v : p.values)
    if (!seen.insert(v).second) throw InputError(where, p.key, "value '" + v + "' appears twice");
  return p;
}

std::vector<SweepRun> sweep_runs(const std::vector<SweepParam>& params) {
  // short names unless two keys share their last component
  std::map<std::string, int> uses;
  for (const auto& p : params) ++uses[short_key(p.key)];
  std::vector<SweepRun> runs{SweepRun{}};
  for (const auto& p : params) {
    const std::string label = uses[short_key(p.key)] > 1 ? p.key : short_key(p.key);
    std::vector<SweepRun> next;
    for (const auto& r : runs)
      for (const auto& v : p.values) {
        SweepRun n = r;
        n.name += (n.name.empty() ? "" : "_") + label + "=" + value_for_name(v);
        n.overrides.push_back(p.key + "=" + v);
        next.push_back(n);
      }
    runs = std::move(next);
  }
  return runs;
}

namespace sweep_detail {

std::uint64_t replica_seed(std::uint64_t base, int replica) {
  if (replica <= 0) return base;
  // a hash of (base seed, replica): independent streams, not base + r (which would make
  // replica 1 of seed 5 the same pile as replica 0 of seed 6); scene seeds are 0 … 2^63 − 1
  const std::uint64_t h =
      mix64(mix64(base ^ 0x7265706c69636173ULL) + static_cast<std::uint64_t>(replica));
  return h & 0x7fffffffffffffffULL;
}

// runs per sweep: each is a directory, a log file and a child process
constexpr double kMaxSweepRuns = 100000;

SweepPlan plan_sweep(const SweepOptions& opt, bool check_dirs) {
  // the parameters, then every combination parsed up front: a bad key or value stops the
  // sweep before anything runs (exit 2, the message names the --param)
  if (opt.params.empty())
    throw InputError("", "--param", "a sweep needs at least one --param KEY=V1,V2,…");
  if (opt.replicas < 1) throw InputError("", "--replicas", "needs at least 1 replica");
  SweepPlan plan;
  plan.opt = opt;
  std::set<std::string> keys;
  for (const auto& t : opt.params) {
    plan.params.push_back(parse_sweep_param(t));
    if (!keys.insert(plan.params.back().key).second)
      throw InputError("--param " + t, plan.params.back().key, "the key is swept twice");
  }
  const SceneSpec base = parse_scene_file(opt.scene, opt.sets);
  plan.base_hash = text_hash(scene_to_toml(base));
  const std::vector<SweepRun> values = sweep_runs(plan.params);
  // every run gets a directory, a log and a scene parse before anything starts
  const double runs = static_cast<double>(values.size()) * opt.replicas;
  if (runs > kMaxSweepRuns)
    throw InputError("", opt.replicas > 1 ? "--replicas" : "--param",
                     "the sweep would hold " + std::to_string(static_cast<long long>(runs)) +
                         " runs (" + std::to_string(values.size()) + " values × " +
                         std::to_string(opt.replicas) + " replicas); at most " +
                         std::to_string(static_cast<long long>(kMaxSweepRuns)) + " runs per sweep");
  // two values that name the same directory would write one run over the other
  std::map<std::string, std::string> names;
  for (const SweepRun& v : values) {
    std::string ov;
    for (const auto& o : v.overrides) ov += (ov.empty() ? "" : ", ") + o;
    const auto [it, fresh] = names.emplace(v.name, ov);
    if (!fresh)
      throw InputError("", "--param",
                       "the values " + it->second + " and " + ov +
                           " give the same run directory name '" + v.name +
                           "'; sweep distinct values");
  }
  for (int rep = 0; rep < opt.replicas; ++rep)
    for (const SweepRun& v : values) {
      Job j;
      j.run = v;
      j.replica = rep;
      SceneSpec s = run_scene(opt, v);
      if (rep > 0) {
        // the run's own seed (the scene's, or a swept or --set one), hashed with the replica
        j.run.name += "_rep=" + std::to_string(rep);
        j.run.overrides.push_back("preparation.seed=" +
                                  std::to_string(replica_seed(s.prep.seed, rep)));
        s = run_scene(opt, j.run);
      }
      if (opt.allow_unstable) s.health.allow_unstable = true;  // as run_command writes it
      const double T = drive_period(s.drive);
      j.nominal = s.prep.settle_time + (s.drive.taps > 0 && T > 0 ? s.drive.taps * T : s.duration);
      // a run's cost goes with its particle-steps: a second of a 27 000-disk fluid is not one
      // of a 512-disk ring
      long grains = 0;
      for (const SpeciesSpec& sp : s.species) grains += std::max(sp.count, 0);
      j.work = static_cast<double>(std::max(grains, 1L)) / s.integrator.dt;
      j.expected = scene_to_toml(s);  // compared with an existing run's scene.toml below
      plan.jobs.push_back(std::move(j));
    }
  // nor may a replica's directory be a value's ("x_rep=1" swept beside x with replicas)
  std::map<std::string, const Job*> dirs;
  for (const Job& j : plan.jobs) {
    const auto [it, fresh] = dirs.emplace(j.run.name, &j);
    if (fresh) continue;
    auto what = [](const Job& k) {
      std::string ov;
      for (std::size_t i = 0; i < k.run.overrides.size(); ++i)
        if (k.run.overrides[i].rfind("preparation.seed=", 0) != 0 || k.replica == 0)
          ov += (ov.empty() ? "" : ", ") + k.run.overrides[i];
      return ov + (k.replica > 0 ? " (replica " + std::to_string(k.replica) + ")" : "");
    };
    throw InputError("", opt.replicas > 1 ? "--replicas" : "--param",
                     "the runs " + what(*it->second) + " and " + what(j) +
                         " would share the run directory '" + j.run.name +
                         "'; sweep values that do not end in _rep=N");
  }

  // the sweep directory; an earlier sweep there must come from the same base scene
  plan.out = opt.out;
  if (plan.out.empty()) {
    plan.out = "runs/" + base.name + "-sweep";
    for (const auto& p : plan.params) plan.out += "-" + short_key(p.key);
  }
  for (Job& j : plan.jobs) j.dir = plan.out + "/" + j.run.name;
  if (!check_dirs) return plan;
  std::error_code ec;
  fs::create_directories(plan.out + "/logs", ec);
  if (ec) throw InputError(plan.out, "", "cannot create the sweep directory: " + ec.message());
  // a run directory is no sweep directory; a folder with other files is refused without --force
  for (const char* f : {"run.json", "scene.toml", "series.csv"})
    if (fs::exists(plan.out + "/" + f, ec))
      throw InputError(plan.out, "--out",
                       std::string("holds a run (") + f + "), not a sweep; choose another --out");
  if (!fs::exists(plan.out + "/sweep.json", ec) && !opt.force) {
    std::set<std::string> known = {".lock", "logs"};
    for (const Job& j : plan.jobs) known.insert(fs::path(j.dir).filename().string());
    for (const auto& e : fs::directory_iterator(plan.out, ec))
      if (!known.count(e.path().filename().string()))
        throw InputError(plan.out, "--out",
                         "is not empty and holds no sweep (" + e.path().filename().string() +
                             "); pass --force to sweep into it anyway, or choose another --out");
  }
  if (const auto old = read_text_file(plan.out + "/sweep.json")) {
    const auto h = json_string_field(*old, "base_scene_hash");
    if (h && *h != plan.base_hash)
      throw InputError(plan.out, "",
                       "this sweep directory holds a sweep of a different scene or --set "
                       "overrides (base scene hash " +
                           *h + ", now " + plan.base_hash + "); use another --out");
  }

  // which runs are done: completed with the same scene → skipped; interrupted with a
  // checkpoint and the same scene → resumed; other unfinished runs → redone with --force
  std::vector<std::string> unfinished;
  for (Job& j : plan.jobs) {
    const bool exists = fs::exists(j.dir, ec) && !fs::is_empty(j.dir, ec);
    if (!exists) continue;
    const std::string st = run_status(j.dir);
    if (st == "completed") {
      const auto have = read_text_file(j.dir + "/scene.toml");
      if (!have || *have != j.expected)
        throw InputError(j.dir, "",
                         "a completed run of a different scene is in the way (its "
                         "scene.toml differs from this sweep's); use another --out");
      j.state = "skipped";
      j.exit_code = 0;
    } else if (const auto have = read_text_file(j.dir + "/scene.toml");
               have && *have == j.expected && !list_checkpoints(j.dir).empty()) {
      j.resume = true;
    } else if (!opt.force) {
      unfinished.push_back(j.dir + (st.empty() ? " (no run.json)" : " (" + st + ")"));
    }
  }
  if (!unfinished.empty()) {
    std::string m = "unfinished run directories (pass --force to redo them):";
    for (const auto& u : unfinished) m += "\n  " + u;
    throw InputError(plan.out, "", m);
  }
  return plan;
}

}  // namespace sweep_detail

int sweep_command(const SweepOptions& opt) {
  // started by mpirun/srun: the MPI driver (sweep_mpi.cpp) spreads the runs over the ranks
  if (sweep_detail::mpi_launch_detected()) return sweep_detail::sweep_mpi(opt);
  return sweeps_command({opt}, opt.jobs);
}

int sweeps_command(const std::vector<SweepOptions>& opts, int jobs) {
  if (opts.empty()) return kExitOk;
  // under MPI each sweep spreads over the ranks in turn
  if (sweep_detail::mpi_launch_detected()) {
    int code = kExitOk;
    for (const SweepOptions& o : opts) {
      code = sweep_detail::sweep_mpi(o);
      if (code != kExitOk) return code;
    }
    return code;
  }
  // one sweep at a time in a directory: each lock is taken before its plan looks at the runs
  std::vector<std::unique_ptr<DirLock>> locks;
  std::vector<SweepPlan> plans;
  for (const SweepOptions& o : opts) {
    locks.push_back(std::make_unique<DirLock>(sweep_detail::plan_sweep(o, false).out, "sweep"));
    plans.push_back(sweep_detail::plan_sweep(o, true));
  }
  std::vector<SweepPlan*> all;
  int pending = 0;
  for (SweepPlan& p : plans) {
    all.push_back(&p);
    for (const Job& j : p.jobs) pending += j.state == "pending";
  }
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int width = std::max(1, std::min(jobs > 0 ? jobs : cores, std::max(pending, 1)));
  return sweep_detail::run_jobs(all, width, std::max(1, cores / width), nullptr);
}

}  // namespace gs
