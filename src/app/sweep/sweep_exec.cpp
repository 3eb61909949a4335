// running a sweep's plan: each run is a child process of this binary (`gransim run … --out
// OUT/<name>`), at most `width` at a time here and, under MPI, more on the worker ranks; one
// progress display and the manifest OUT/sweep.json kept up to date as runs finish
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "app/locations.hpp"
#include "app/openmp_team.hpp"
#include "app/progress.hpp"
#include "app/run/run.hpp"
#include "app/run/run_info.hpp"
#include "app/subprocess.hpp"
#include "app/sweep/sweep_detail.hpp"
#include "app/version.hpp"
#include "core/error.hpp"
#include "output/json_text.hpp"
#include "output/run_dir.hpp"

extern char** environ;

namespace gs::sweep_detail {

namespace fs = std::filesystem;

namespace {

// variables through which an MPI launcher talks to its processes: a child run is no MPI process
bool is_mpi_variable(const std::string& e) {
  for (const char* p : {"OMPI_", "PMIX_", "PMI_", "MPI_LOCALRANKID", "MPI_LOCALNRANKS"})
    if (e.rfind(p, 0) == 0) return true;
  return false;
}

}  // namespace

double last_series_time(const std::string& dir, fs::file_time_type since) {
  std::error_code ec;
  const std::string path = dir + "/series.csv";
  const auto stamp = fs::last_write_time(path, ec);
  if (ec || stamp < since) return 0.0;
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return 0.0;
  const std::streamoff size = in.tellg();
  const std::streamoff from = std::max<std::streamoff>(0, size - 512);
  in.seekg(from);
  std::string tail(static_cast<std::size_t>(size - from), '\0');
  in.read(tail.data(), size - from);
  // the last complete line
  const auto end = tail.find_last_of('\n');
  if (end == std::string::npos || end == 0) return 0.0;
  const auto start = tail.find_last_of('\n', end - 1);
  const std::string line = tail.substr(start == std::string::npos ? 0 : start + 1,
                                       end - (start == std::string::npos ? 0 : start + 1));
  char* e = nullptr;
  const double t = std::strtod(line.c_str(), &e);
  return e == line.c_str() ? 0.0 : t;
}

std::vector<std::string> child_environment(int threads) {
  std::vector<std::string> env;
  bool has_omp = false;
  for (char** e = environ; e && *e; ++e) {
    std::string v(*e);
    if (is_mpi_variable(v)) continue;
    has_omp = has_omp || v.rfind("OMP_NUM_THREADS=", 0) == 0;
    env.push_back(std::move(v));
  }
  if (!has_omp) env.push_back("OMP_NUM_THREADS=" + std::to_string(std::max(1, threads)));
  // the runs stop (checkpointed) when this process ends, however it ends
  const std::string parent = std::string(kParentPidVariable) + "=";
  std::erase_if(env, [&](const std::string& v) { return v.rfind(parent, 0) == 0; });
  env.push_back(parent + std::to_string(::getpid()));
  // a child of several threads waits with a long spin unless the user chose a policy: its
  // runtime reads the choice as it starts, so the parent makes it (docs/threads.md)
  if (threads > 1 && !wait_policy_chosen()) env.push_back(kSpinCount);
  return env;
}

pid_t spawn_run(const SweepPlan& plan, const Job& j, const std::vector<std::string>& env) {
  const SweepOptions& opt = plan.opt;
  const std::string log = plan.out + "/logs/" + j.run.name + ".log";
  std::vector<std::string> args{self_executable(), "run",    opt.scene, "--out", j.dir,
                                "--quiet",         "--force"};
  if (opt.allow_unstable) args.push_back("--allow-unstable");
  for (const auto& s : opt.sets) args.insert(args.end(), {"--set", s});
  for (const auto& s : j.run.overrides) args.insert(args.end(), {"--set", s});
  // an interrupted run continues from its newest checkpoint (bitwise the same result)
  if (j.resume) args = {self_executable(), "resume", j.dir, "--quiet"};
  ChildSetup setup;
  setup.stdin_null = true;
  setup.log = log;
  setup.append_log = j.resume;
  setup.environment = &env;
  return start_process(args, setup);
}

int child_exit_code(int status) {
  // killed by a stop signal before its handlers were installed: interrupted; a crash: failure
  const bool stopped =
      WIFSIGNALED(status) && (WTERMSIG(status) == SIGINT || WTERMSIG(status) == SIGTERM ||
                              WTERMSIG(status) == SIGKILL || WTERMSIG(status) == SIGHUP);
  return WIFEXITED(status) ? WEXITSTATUS(status) : stopped ? kExitInterrupted : kExitFailure;
}

int worse_exit(int a, int b) {
  auto rank = [](int c) {
    return c == kExitInterrupted ? 4
           : c == kExitUnstable  ? 3
           : c == kExitOk        ? 0
           : c == kExitBadInput  ? 1
                                 : 2;
  };
  return rank(b) > rank(a) ? b : a;
}

void write_manifest(const SweepPlan& plan, bool finished) {
  const SweepOptions& opt = plan.opt;
  nlohmann::ordered_json j;
  j["program"] = "gransim";
  j["version"] = program_version();
  j["kind"] = "sweep";
  j["scene_file"] = opt.scene;
  j["base_scene_hash"] = plan.base_hash;
  j["status"] = finished ? "finished" : "running";
  j["replicas"] = opt.replicas;
  j["sets"] = opt.sets;
  j["params"] = nlohmann::ordered_json::array();
  for (const SweepParam& p : plan.params)
    j["params"].push_back({{"key", p.key}, {"values", p.values}});
  j["runs"] = nlohmann::ordered_json::array();
  for (const Job& r : plan.jobs)
    j["runs"].push_back({{"name", r.run.name},
                         {"dir", r.run.name},
                         {"overrides", r.run.overrides},
                         {"state", r.state},
                         {"run_status", run_status(r.dir)},
                         {"exit_code", r.exit_code},
                         {"replica", r.replica},
                         {"wall_time_s", json_number(r.wall, 6)}});
  write_file_atomic(plan.out + "/sweep.json", json_text(j, {"params", "runs"}));
}

int run_jobs(SweepPlan& plan, int width, int threads, RemoteSlots* remote) {
  return run_jobs(std::vector<SweepPlan*>{&plan}, width, threads, remote);
}

int run_jobs(const std::vector<SweepPlan*>& plans, int width, int threads, RemoteSlots* remote) {
  if (remote && plans.size() != 1)
    throw std::logic_error("run_jobs: the MPI ranks share one sweep's plan");
  const bool quiet = plans.front()->opt.quiet;
  // every job of every plan in one list, plan by plan: a job's place in it is its index
  // (under MPI, one plan: the same index as in the plan the workers computed)
  struct Slot {
    SweepPlan* plan;
    Job* job;
  };
  std::vector<Slot> jobs;
  for (SweepPlan* p : plans)
    for (Job& j : p->jobs) jobs.push_back({p, &j});
  int pending = 0;
  double total = 0.0;
  for (const Slot& s : jobs)
    if (s.job->state == "pending") {
      ++pending;
      total += s.job->nominal * s.job->work;
    }
  const int slots = width + (remote ? remote->open() : 0);
  for (SweepPlan* p : plans) {
    int left = 0;
    for (const Job& j : p->jobs) left += j.state == "pending";
    std::fprintf(
        stderr, "gransim sweep: %zu runs in %s (%zu already completed), %d at a time%s%s\n",
        p->jobs.size(), p->out.c_str(), p->jobs.size() - static_cast<std::size_t>(left), slots,
        remote ? " over MPI ranks" : "", plans.size() > 1 ? " with the other sweeps' runs" : "");
    write_manifest(*p, false);
  }
  std::vector<std::string> env = child_environment(threads);
  install_stop_handlers();
  Progress progress("sweep", std::max(total, 1e-9), "particle-steps", quiet);
  int worst = kExitOk;
  bool stopping = false;
  double done_work = 0.0;
  auto last_progress = std::chrono::steady_clock::now() - std::chrono::seconds(1);

  // a run has finished here or on a worker rank
  auto finish = [&](const Slot& s, int code, double wall) {
    Job& j = *s.job;
    j.wall = wall;
    j.exit_code = code;
    j.pid = -1;
    // a run stopped by a signal has checkpointed and resumes: it has not failed
    j.state = code == kExitOk ? "completed" : code == kExitInterrupted ? "interrupted" : "failed";
    done_work += j.nominal * j.work;
    worst = worse_exit(worst, code);
    if (!quiet || code != kExitOk)
      std::fprintf(
          stderr, "%s%s: %s (exit %d, %s)%s\n", quiet ? "" : "\n", j.run.name.c_str(),
          j.state.c_str(), code, format_duration(wall).c_str(),
          code == kExitOk ? "" : (", log " + s.plan->out + "/logs/" + j.run.name + ".log").c_str());
    write_manifest(*s.plan, false);
  };
  // the next pending run, marked running on `rank`; -1 when none (or stopping)
  auto take = [&](int rank) -> int {
    if (stopping) return -1;
    for (std::size_t i = 0; i < jobs.size(); ++i)
      if (jobs[i].job->state == "pending") {
        Job& j = *jobs[i].job;
        // a resumed run's simulated time so far was done in earlier sittings
        if (j.resume)
          progress.carried(std::min(last_series_time(j.dir, fs::file_time_type::min()), j.nominal) *
                           j.work);
        j.state = "running";
        j.rank = rank;
        j.started = std::chrono::steady_clock::now();
        j.spawned = fs::file_time_type::clock::now();
        return static_cast<int>(i);
      }
    return -1;
  };
  auto remote_done = [&](int index, int code, double wall) {
    if (index < 0 || index >= static_cast<int>(jobs.size())) return;
    const Slot& s = jobs[static_cast<std::size_t>(index)];
    if (code < 0)
      s.job->state = "pending";  // a stopping worker refused it
    else
      finish(s, code, wall);
  };

  for (;;) {
    // a signal: stop the children here cleanly (they write their state), start nothing new
    if (stop_requested() && !stopping) {
      stopping = true;
      for (const Slot& s : jobs)
        if (s.job->state == "running" && s.job->pid > 0) kill(s.job->pid, SIGTERM);
    }
    // start what fits here
    int here = 0;
    for (const Slot& s : jobs) here += s.job->state == "running" && s.job->pid > 0;
    while (here < width) {
      const int i = take(0);
      if (i < 0) break;
      const Slot& s = jobs[static_cast<std::size_t>(i)];
      s.job->pid = spawn_run(*s.plan, *s.job, env);
      ++here;
    }
    // the worker ranks: collect their results, hand them the next runs
    if (remote) remote->poll(remote_done, take);
    if (here == 0 && (!remote || remote->open() == 0)) break;
    // collect finished children
    bool reaped = false;
    for (const Slot& s : jobs) {
      Job& j = *s.job;
      if (j.state != "running" || j.pid <= 0) continue;
      int status = 0;
      if (waitpid(j.pid, &status, WNOHANG) != j.pid) continue;
      finish(s, child_exit_code(status),
             std::chrono::duration<double>(std::chrono::steady_clock::now() - j.started).count());
      reaped = true;
    }
    if (reaped) continue;
    std::this_thread::sleep_for(std::chrono::milliseconds(remote ? 20 : 200));
    // the progress from the runs' series.csv, at most every 200 ms (they may be on a shared
    // file system, and rank 0 turns every 20 ms to answer the workers quickly)
    const auto tick = std::chrono::steady_clock::now();
    if (tick - last_progress < std::chrono::milliseconds(200)) continue;
    last_progress = tick;
    double now = done_work;
    int active = 0, finished = 0;
    for (const Slot& s : jobs) {
      const Job& j = *s.job;
      if (j.state == "running") {
        now += std::min(last_series_time(j.dir, j.spawned), j.nominal) * j.work;
        ++active;
      }
      finished += j.state == "completed" || j.state == "failed" || j.state == "interrupted";
    }
    progress.update(now, std::to_string(finished) + "/" + std::to_string(pending) + " runs done, " +
                             std::to_string(active) + " running");
  }
  if (stopping && worst == kExitOk) worst = kExitInterrupted;
  std::string summary;
  for (SweepPlan* p : plans) {
    write_manifest(*p, true);
    int completed = 0;
    for (const Job& j : p->jobs) completed += j.state == "completed" || j.state == "skipped";
    summary += (summary.empty() ? "" : "; ") + std::to_string(completed) + "/" +
               std::to_string(p->jobs.size()) + " runs completed; manifest " + p->out +
               "/sweep.json";
  }
  if (worst == kExitOk)
    progress.finish(summary);
  else
    std::fprintf(stderr, "\ngransim sweep: %s; %s\n", summary.c_str(),
                 stopping ? "interrupted (run the same command again: interrupted runs resume from "
                            "their checkpoints)"
                          : "some runs failed (see logs/)");
  return worst;
}

}  // namespace gs::sweep_detail
