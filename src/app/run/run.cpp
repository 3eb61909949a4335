// `gransim run` and `gransim resume`: set up a session (new, or from the newest checkpoint)
// and hand it to the run loop (app/run/run_loop.cpp)
#include "app/run/run.hpp"

#ifdef __linux__
#include <sys/prctl.h>
#endif
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <optional>
#include <sstream>

#include "app/openmp_team.hpp"
#include "app/run/observers.hpp"
#include "app/run/run_info.hpp"
#include "app/run/run_session.hpp"
#include "app/version.hpp"
#include "core/error.hpp"
#include "output/run_dir.hpp"
#include "scene/names.hpp"
#include "scene/parse.hpp"
#include "sim/prepare.hpp"

namespace gs {
namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_stop_signal(int) { g_stop = true; }

// the run directory when none is given: runs/NAME-YYYYMMDD-HHMMSS (local time), new each run
std::string default_out(const std::string& name) {
  char buf[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(buf, sizeof buf, "%Y%m%d-%H%M%S", std::localtime(&now));
  return "runs/" + (name.empty() ? std::string("run") : name) + "-" + buf;
}

void print_banner(const SceneSpec& scene, const Simulation& sim, const ProtocolClock& clock) {
  const double dt = sim.dt();  // the step the simulation takes, whatever the scene asked
  const auto nsteps = static_cast<long long>(std::llround(clock.nominal_duration() / dt));
  const std::string sorted =
      sim.sort_every() > 0 ? ", sorted every " + std::to_string(sim.sort_every()) + " steps" : "";
  std::fprintf(
      stderr, "gransim %s: %s, %zu particles, %lld steps of %g s (%s, %s%s), contact time %.3g s\n",
      program_version().data(), scene.name.c_str(), sim.world().size(), nsteps, dt,
      std::string(to_string(scene.integrator.kind)).c_str(), sim.broadphase().name(),
      sorted.c_str(), sim.model().min_contact_time());
  // the runtime read its wait policy as this process started: say how to choose a better one
  if (openmp_team().threads > 1 && !wait_policy_chosen())
    std::fprintf(stderr,
                 "gransim: several threads with the OpenMP runtime's default wait policy; on a "
                 "virtual machine start gransim with %s (docs/threads.md)\n",
                 kSpinCount);
  if (is_tapping(scene.drive))
    std::fprintf(
        stderr, "gransim: %s, settle %g s, then %d taps of T = %g s (excitation %g s)%s%s\n",
        std::string(scene_name(scene.drive.kind)).c_str(), scene.prep.settle_time, scene.drive.taps,
        drive_period(scene.drive), excitation_length(scene.drive),
        scene.drive.early_rest ? ", early rest on" : "", scene.drive.quench ? ", quench on" : "");
}

constexpr const char* kResumeAdvice =
    "a resume continues the run with the scene it was started with: restore scene.toml (or "
    "remove it), or start a new run with `gransim run` on the edited scene";

ByteReader extra(const Checkpoint& c, const std::string& key) {
  const auto it = c.extras.entries.find(key);
  if (it == c.extras.entries.end())
    throw InputError(c.path, "",
                     "checkpoint has no '" + key + "' entry: it was not written by `gransim run`");
  return ByteReader{it->second, 0, c.path + " [" + key + "]"};
}

// a resume continues the run as its checkpoint recorded it: a scene.toml edited since (a key
// changed by hand, hoping the rest of the run would use it) is refused, not silently ignored
void check_scene_unchanged(const std::string& dir, const Checkpoint& c) {
  const std::string path = dir + "/scene.toml";
  const auto text = read_text_file(path);
  if (!text) return;  // removed: the checkpoint holds the scene
  const std::string recorded = scene_to_toml(parse_scene_string(c.scene_toml, c.path));
  std::string now;
  try {
    now = scene_to_toml(parse_scene_string(*text, path));
  } catch (const InputError& e) {
    throw InputError(path, "",
                     std::string("edited since the run started, and no longer a valid "
                                 "scene (") +
                         e.what() + "); " + kResumeAdvice);
  }
  if (now == recorded) return;
  std::istringstream a(recorded), b(now);
  std::string la, lb;
  while (std::getline(a, la) && std::getline(b, lb) && la == lb) {
  }
  throw InputError(path, "",
                   "edited since the run started (the checkpoint's scene has '" + la +
                       "', this file '" + lb + "'); " + kResumeAdvice);
}

}  // namespace

bool stop_requested() { return g_stop.load(); }
void install_stop_handlers() {
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  std::signal(SIGHUP, on_stop_signal);  // the terminal closed: stop as cleanly as for Ctrl-C
  // a sweep's run stops (checkpointed) with the sweep, however the sweep ends (kill -9 too)
  if (const char* parent = std::getenv(kParentPidVariable)) {
#ifdef __linux__
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
#endif
    if (std::to_string(::getppid()) != parent) g_stop = true;  // it is already gone
  }
}

int run_command(const RunOptions& opt) {
  // the scene is read and prepared before the run directory is touched: a bad scene leaves an
  // existing run as it was
  std::vector<std::string> sets = opt.sets;
  if (opt.allow_unstable) sets.emplace_back("health.allow_unstable=true");
  PreparedRun prepared = prepare_run(parse_scene_file(opt.scene, sets));
  const SceneSpec& scene = prepared.scene;
  Simulation& sim = *prepared.sim;
  ProtocolClock& clock = *prepared.clock;
  const std::string out = opt.out.empty() ? default_out(scene.name) : opt.out;
  const DirLock lock(out, "run");
  // a replaced run's files wait aside until this run has passed its first health check
  SetAside replaced = prepare_run_dir(out, opt.force);
  write_file_atomic(out + "/scene.toml", scene_to_toml(scene));

  RunSession rs;
  rs.scene = scene;
  rs.scene_file = scene.path;
  rs.out = out;
  rs.quiet = opt.quiet;
  rs.profile = opt.profile;
  rs.sim = &sim;
  rs.clock = &clock;
  rs.series = CsvWriter(out + "/series.csv", series_columns());
  print_banner(scene, sim, clock);
  if (const auto& from = prepared.from_state; from && !opt.quiet)
    std::fprintf(stderr, "gransim: %zu grains from %s%s\n", from->grains, from->path.c_str(),
                 from->history ? " (with its integrator history and contact springs)"
                 : from->checkpoint
                     ? " (another integrator, time step or model: positions and velocities only)"
                     : "");
  rs.observers = make_observers(scene);
  for (auto& o : rs.observers) o->start(sim, out);
  write_series_row(rs);  // the prepared state is the first row
  rs.replaced = &replaced;
  const int code = run_session(rs);
  if (replaced.holds() && code == kExitUnstable) {
    replaced.restore();
    std::fprintf(stderr,
                 "gransim: the run failed its first health check; %s holds the run it "
                 "was to replace, as it was\n",
                 out.c_str());
  }
  replaced.discard();
  return code;
}

int resume_command(const ResumeOptions& opt) {
  // a completed run has nothing to continue
  if (run_status(opt.dir) == "completed") {
    std::fprintf(stderr, "gransim: %s is a completed run; nothing to resume\n", opt.dir.c_str());
    return kExitOk;
  }
  if (std::error_code ec; !std::filesystem::is_directory(opt.dir, ec))
    throw InputError(opt.dir, "DIR",
                     std::filesystem::exists(opt.dir, ec)
                         ? "is a file, not a run directory: give the folder the run wrote"
                         : "not a run directory (it does not exist)");
  const DirLock lock(opt.dir, "resume");
  const Checkpoint c = newest_valid_checkpoint(opt.dir);
  check_scene_unchanged(opt.dir, c);
  Simulation sim = restore_simulation(c);
  const SceneSpec scene = checkpoint_scene(c);
  ProtocolClock clock(scene);
  ByteReader ck = extra(c, "run/clock");
  clock.load(ck);
  ByteReader run = extra(c, "run/session");
  RunSession rs;
  rs.wall_before = run.f64("wall time");
  rs.wall_settled = run.f64("settling wall time");
  rs.sessions = static_cast<int>(run.i64("sessions")) + 1;
  // the CPU time of the sessions before (a checkpoint without it: this session's alone)
  if (c.extras.entries.count("run/cpu")) {
    ByteReader cpu = extra(c, "run/cpu");
    rs.cpu_before = cpu.f64("CPU time");
    rs.cpu_sessions = static_cast<int>(cpu.i64("sessions with CPU time")) + 1;
  }
  const double ref = run.f64("energy reference"), slack = run.f64("energy slack");
  sim.set_energy_yardstick(ref, slack);
  rs.scene = scene;
  rs.scene_file =
      c.extras.entries.count("run/scene_file") ? c.extras.entries.at("run/scene_file") : c.path;
  rs.out = opt.dir;
  rs.quiet = opt.quiet;
  rs.sim = &sim;
  rs.clock = &clock;
  // rows written after the checkpoint are dropped; the run writes them again, identically
  truncate_outputs(opt.dir, c);
  rs.series = CsvWriter::append(opt.dir + "/series.csv", series_columns().size());
  print_banner(scene, sim, clock);
  std::fprintf(stderr, "gransim: resuming %s from %s (t = %g s, step %lld)\n", opt.dir.c_str(),
               c.path.c_str(), sim.world().s.t, static_cast<long long>(sim.world().s.step));
  rs.observers = make_observers(scene);
  for (auto& o : rs.observers) {
    ByteReader in = extra(c, std::string("observer/") + o->name());
    o->resume(sim, opt.dir, in);
    if (!in.at_end()) in.fail(in.pos, "observer state has trailing bytes");
  }
  return run_session(rs);
}

}  // namespace gs
