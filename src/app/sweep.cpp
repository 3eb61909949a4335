#include "app/sweep.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "app/progress.hpp"
#include "app/run.hpp"
#include "app/run_info.hpp"
#include "app/version.hpp"
#include "core/error.hpp"
#include "drive/schedule.hpp"
#include "output/run_dir.hpp"
#include "scene/parse.hpp"

extern char** environ;

namespace gs {

namespace fs = std::filesystem;

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

std::string json_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    o += static_cast<unsigned char>(c) < 0x20 ? ' ' : c;
  }
  return o;
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

// the simulated time of a run's last series.csv row, s (0 when none yet, or when the file is
// older than `since`: a redone run's previous output before the child clears it)
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

// one run as the sweep tracks it
struct Job {
  SweepRun run;
  std::string dir;
  double nominal = 0.0;           // simulated time it needs, s
  std::string expected;           // the scene.toml the run writes (scene_to_toml)
  std::string state = "pending";  // pending, skipped, running, completed, failed
  int exit_code = -1;
  pid_t pid = -1;
  std::chrono::steady_clock::time_point started;
  fs::file_time_type spawned;  // for telling its own series.csv from an older one
  double wall = 0.0;           // s
};

// the children's environment: ours, plus OMP_NUM_THREADS = cores / parallel runs unless it is
// set already, so parallel runs do not oversubscribe the cores with force-loop threads
std::vector<std::string> child_environment(int width) {
  std::vector<std::string> env;
  bool has_omp = false;
  for (char** e = environ; e && *e; ++e) {
    env.emplace_back(*e);
    has_omp = has_omp || env.back().rfind("OMP_NUM_THREADS=", 0) == 0;
  }
  if (!has_omp) {
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    env.push_back("OMP_NUM_THREADS=" + std::to_string(std::max(1, cores / std::max(1, width))));
  }
  return env;
}

// start `gransim run` for a job: output to DIR/logs/<name>.log
pid_t spawn_run(const SweepOptions& opt, const Job& j, const std::string& log,
                std::vector<std::string>& env) {
  std::vector<std::string> args{self_executable(), "run",    opt.scene, "--out", j.dir,
                                "--quiet",         "--force"};
  if (opt.allow_unstable) args.push_back("--allow-unstable");
  for (const auto& s : opt.sets) args.insert(args.end(), {"--set", s});
  for (const auto& s : j.run.overrides) args.insert(args.end(), {"--set", s});
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  std::vector<char*> envp;
  for (auto& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) throw std::runtime_error("cannot start " + args[0] + ": " + std::strerror(rc));
  return pid;
}

// sweep.json: the scene, the parameters and every run directory of the sweep
void write_manifest(const SweepOptions& opt, const std::string& out,
                    const std::vector<SweepParam>& params, const std::string& base_hash,
                    const std::vector<Job>& jobs, bool finished) {
  std::ostringstream js;
  js << "{\n  \"program\": \"gransim\",\n  \"version\": \"" << program_version() << "\",\n"
     << "  \"kind\": \"sweep\",\n"
     << "  \"scene_file\": \"" << json_escape(opt.scene) << "\",\n"
     << "  \"base_scene_hash\": \"" << base_hash << "\",\n"
     << "  \"status\": \"" << (finished ? "finished" : "running") << "\",\n  \"sets\": [";
  for (std::size_t i = 0; i < opt.sets.size(); ++i)
    js << (i ? ", " : "") << '"' << json_escape(opt.sets[i]) << '"';
  js << "],\n  \"params\": [";
  for (std::size_t i = 0; i < params.size(); ++i) {
    js << (i ? ",\n" : "\n") << "    {\"key\": \"" << json_escape(params[i].key)
       << "\", \"values\": [";
    for (std::size_t k = 0; k < params[i].values.size(); ++k)
      js << (k ? ", " : "") << '"' << json_escape(params[i].values[k]) << '"';
    js << "]}";
  }
  js << "\n  ],\n  \"runs\": [";
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const Job& j = jobs[i];
    js << (i ? ",\n" : "\n") << "    {\"name\": \"" << json_escape(j.run.name) << "\", \"dir\": \""
       << json_escape(j.run.name) << "\", \"overrides\": [";
    for (std::size_t k = 0; k < j.run.overrides.size(); ++k)
      js << (k ? ", " : "") << '"' << json_escape(j.run.overrides[k]) << '"';
    js << "], \"state\": \"" << j.state << "\", \"run_status\": \"" << run_status(j.dir)
       << "\", \"exit_code\": " << j.exit_code << ", \"wall_time_s\": " << j.wall << "}";
  }
  js << "\n  ]\n}\n";
  write_file_atomic(out + "/sweep.json", js.str());
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

int sweep_command(const SweepOptions& opt) {
  // the parameters, then every combination parsed up front: a bad key or value stops the
  // sweep before anything runs (exit 2, the message names the --param)
  if (opt.params.empty())
    throw InputError("", "--param", "a sweep needs at least one --param KEY=V1,V2,…");
  std::vector<SweepParam> params;
  std::set<std::string> keys;
  for (const auto& t : opt.params) {
    params.push_back(parse_sweep_param(t));
    if (!keys.insert(params.back().key).second)
      throw InputError("--param " + t, params.back().key, "the key is swept twice");
  }
  const SceneSpec base = parse_scene_file(opt.scene, opt.sets);
  const std::string base_hash = text_hash(scene_to_toml(base));
  std::vector<Job> jobs;
  for (const SweepRun& r : sweep_runs(params)) {
    std::vector<std::string> ov = opt.sets;
    ov.insert(ov.end(), r.overrides.begin(), r.overrides.end());
    SceneSpec s;
    try {
      s = parse_scene_file(opt.scene, ov);
    } catch (const InputError& e) {
      throw InputError("", "", std::string(e.what()) + " (in the sweep run '" + r.name + "')");
    }
    if (opt.allow_unstable) s.health.allow_unstable = true;  // as run_command writes it
    Job j;
    j.run = r;
    const double T = drive_period(s.drive);
    j.nominal = s.prep.settle_time + (s.drive.taps > 0 && T > 0 ? s.drive.taps * T : s.duration);
    j.expected = scene_to_toml(s);  // compared with an existing run's scene.toml below
    jobs.push_back(std::move(j));
  }

  // the sweep directory; an earlier sweep there must come from the same base scene
  std::string out = opt.out;
  if (out.empty()) {
    out = "runs/" + base.name + "-sweep";
    for (const auto& p : params) out += "-" + short_key(p.key);
  }
  std::error_code ec;
  fs::create_directories(out + "/logs", ec);
  if (ec) throw InputError(out, "", "cannot create the sweep directory: " + ec.message());
  if (const auto old = read_text_file(out + "/sweep.json")) {
    const auto h = json_string_field(*old, "base_scene_hash");
    if (h && *h != base_hash)
      throw InputError(out, "",
                       "this sweep directory holds a sweep of a different scene or --set "
                       "overrides (base scene hash " +
                           *h + ", now " + base_hash + "); use another --out");
  }

  // which runs are done: completed with the same scene → skipped; unfinished → --force
  std::vector<std::string> unfinished;
  for (Job& j : jobs) {
    j.dir = out + "/" + j.run.name;
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
    } else if (!opt.force) {
      unfinished.push_back(j.dir + (st.empty() ? " (no run.json)" : " (" + st + ")"));
    }
  }
  if (!unfinished.empty()) {
    std::string m = "unfinished run directories (pass --force to redo them):";
    for (const auto& u : unfinished) m += "\n  " + u;
    throw InputError(out, "", m);
  }

  // run the pending jobs, `jobs` at a time, with one progress display
  const int n_cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  int pending = 0;
  double total = 0.0;
  for (const Job& j : jobs)
    if (j.state == "pending") {
      ++pending;
      total += j.nominal;
    }
  const int width = std::max(1, std::min(opt.jobs > 0 ? opt.jobs : n_cores, std::max(pending, 1)));
  std::fprintf(stderr, "gransim sweep: %zu runs in %s (%zu already completed), %d at a time\n",
               jobs.size(), out.c_str(), jobs.size() - static_cast<std::size_t>(pending), width);
  write_manifest(opt, out, params, base_hash, jobs, false);
  std::vector<std::string> env = child_environment(width);
  install_stop_handlers();
  Progress progress("sweep", std::max(total, 1e-9), "s", opt.quiet);
  int running = 0, worst = kExitOk;
  bool stopping = false;
  double done_work = 0.0;
  auto rank = [](int c) {
    return c == kExitInterrupted ? 4
           : c == kExitUnstable  ? 3
           : c == kExitOk        ? 0
           : c == kExitBadInput  ? 1
                                 : 2;
  };
  for (;;) {
    // a signal: stop the children cleanly (they write their state) and start nothing new
    if (stop_requested() && !stopping) {
      stopping = true;
      for (const Job& j : jobs)
        if (j.state == "running") kill(j.pid, SIGTERM);
    }
    // start what fits
    for (Job& j : jobs) {
      if (stopping || running >= width) break;
      if (j.state != "pending") continue;
      j.pid = spawn_run(opt, j, out + "/logs/" + j.run.name + ".log", env);
      j.state = "running";
      j.started = std::chrono::steady_clock::now();
      j.spawned = fs::file_time_type::clock::now();
      ++running;
    }
    if (running == 0) break;
    // collect finished children
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid > 0) {
      for (Job& j : jobs) {
        if (j.pid != pid || j.state != "running") continue;
        j.wall =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - j.started).count();
        // killed by a stop signal before its handlers were installed: interrupted; a crash: failure
        const bool stopped =
            WIFSIGNALED(status) && (WTERMSIG(status) == SIGINT || WTERMSIG(status) == SIGTERM ||
                                    WTERMSIG(status) == SIGKILL || WTERMSIG(status) == SIGHUP);
        j.exit_code = WIFEXITED(status) ? WEXITSTATUS(status)
                      : stopped         ? kExitInterrupted
                                        : kExitFailure;
        j.state = j.exit_code == kExitOk ? "completed" : "failed";
        done_work += j.nominal;
        --running;
        if (rank(j.exit_code) > rank(worst)) worst = j.exit_code;
        if (!opt.quiet || j.exit_code != kExitOk)
          std::fprintf(
              stderr, "%s%s: %s (exit %d, %s)%s\n", opt.quiet ? "" : "\n", j.run.name.c_str(),
              j.state.c_str(), j.exit_code, format_duration(j.wall).c_str(),
              j.exit_code == kExitOk ? ""
                                     : (", log " + out + "/logs/" + j.run.name + ".log").c_str());
        write_manifest(opt, out, params, base_hash, jobs, false);
      }
      continue;
    }
    double now = done_work;
    int active = 0;
    for (const Job& j : jobs)
      if (j.state == "running") {
        now += std::min(last_series_time(j.dir, j.spawned), j.nominal);
        ++active;
      }
    int finished = 0;
    for (const Job& j : jobs) finished += j.state == "completed" || j.state == "failed";
    progress.update(now, std::to_string(finished) + "/" + std::to_string(pending) + " runs done, " +
                             std::to_string(active) + " running");
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  write_manifest(opt, out, params, base_hash, jobs, true);
  if (stopping && worst == kExitOk) worst = kExitInterrupted;
  int completed = 0;
  for (const Job& j : jobs) completed += j.state == "completed" || j.state == "skipped";
  std::string summary = std::to_string(completed) + "/" + std::to_string(jobs.size()) +
                        " runs completed; manifest " + out + "/sweep.json";
  if (worst == kExitOk)
    progress.finish(summary);
  else
    std::fprintf(stderr, "\ngransim sweep: %s; %s\n", summary.c_str(),
                 stopping ? "interrupted (continue with --force)" : "some runs failed (see logs/)");
  return worst;
}

}  // namespace gs
