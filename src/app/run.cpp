#include "app/run.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <sstream>

#include "app/observers.hpp"
#include "app/progress.hpp"
#include "app/version.hpp"
#include "core/error.hpp"
#include "drive/protocol.hpp"
#include "output/csv.hpp"
#include "output/run_dir.hpp"
#include "scene/names.hpp"
#include "scene/parse.hpp"
#include "sim/simulation.hpp"
#include "sim/state_file.hpp"
#include "world/prepare.hpp"

namespace gs {
namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_stop_signal(int) { g_stop = true; }

std::string json_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      o += ' ';
      continue;
    }
    o += c;
  }
  return o;
}

std::string default_out(const std::string& name) {
  char buf[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(buf, sizeof buf, "%Y%m%d-%H%M%S", std::localtime(&now));
  return "runs/" + (name.empty() ? std::string("run") : name) + "-" + buf;
}

}  // namespace

bool stop_requested() { return g_stop.load(); }
void install_stop_handlers() {
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
}

int run_command(const RunOptions& opt) {
  // scene and run directory are checked before any work is done
  SceneSpec scene = parse_scene_file(opt.scene, opt.sets);
  if (opt.allow_unstable) scene.health.allow_unstable = true;
  World world = make_world(scene);
  place_particles(world);
  // the protocol clock starts after preparation.settle_time (constant gravity until then); it
  // is set before the first force evaluation so the initial accelerations see settling gravity
  ProtocolClock clock(scene);
  clock.start(world);
  Simulation sim(std::move(world));
  const double dt = scene.integrator.dt, tc = sim.model().min_contact_time();
  if (!scene.health.allow_unstable && dt > tc / 5.0) {
    std::ostringstream m;
    m << "dt = " << dt << " s is " << dt / tc << " of the stiffest contact time (" << tc
      << " s); at more than 1/5 the contacts are not resolved and the integration is unstable. "
      << "Use dt <= " << tc / 20.0 << " s, or pass --allow-unstable to run it anyway";
    throw InputError(scene.path, "integrator.dt", m.str());
  }
  const std::string out = opt.out.empty() ? default_out(scene.name) : opt.out;
  prepare_run_dir(out, opt.force);
  write_file_atomic(out + "/scene.toml", scene_to_toml(scene));

  // series: one flushed row every output.series_every steps
  CsvWriter series(out + "/series.csv", {"t", "step", "kinetic_energy", "contacts", "max_overlap",
                                         "max_overlap_rel", "max_speed", "gx", "gy", "degenerate"});
  auto write_row = [&] {
    const World& w = sim.world();
    double vmax2 = 0;
    for (std::size_t i = 0; i < w.size(); ++i)
      vmax2 = std::max(vmax2, w.s.vx[i] * w.s.vx[i] + w.s.vy[i] * w.s.vy[i]);
    const ForceStats& f = sim.last_forces();
    series.row({w.s.t, static_cast<double>(w.s.step), w.kinetic_energy(),
                static_cast<double>(f.contacts), f.max_overlap, f.max_overlap_rel, std::sqrt(vmax2),
                sim.gravity().x, sim.gravity().y, static_cast<double>(sim.contacts().degenerate)});
  };

  // how long: taps of a tapping protocol (the clock says when the last one is measured), or
  // settling plus scene.duration
  const bool by_taps = scene.drive.taps > 0 && is_tapping(scene.drive);
  const double nominal = clock.nominal_duration();
  const auto nsteps = static_cast<std::int64_t>(std::llround(nominal / dt));
  auto finished = [&] {
    if (by_taps) return clock.done(sim.world());
    return sim.world().s.step + std::llround(clock.time_saved() / dt) >= nsteps;
  };
  auto taps_done = [&]() -> long {
    const DrivePhase p = drive_phase(sim.world().scene.drive, sim.world().s.t + dt);
    return is_tapping(scene.drive) && !p.settling ? p.tap : 0;
  };
  const std::size_t n = sim.world().size();
  std::fprintf(stderr,
               "gransim %s: %s, %zu particles, %lld steps of %g s (%s, %s), contact time %.3g s\n",
               program_version().data(), scene.name.c_str(), n, static_cast<long long>(nsteps), dt,
               std::string(to_string(scene.integrator.kind)).c_str(), sim.broadphase().name(), tc);
  if (is_tapping(scene.drive))
    std::fprintf(stderr, "gransim: %s, settle %g s, then %d taps of T = %g s (excitation %g s)%s\n",
                 std::string(scene_name(scene.drive.kind)).c_str(), scene.prep.settle_time,
                 scene.drive.taps, drive_period(scene.drive), excitation_length(scene.drive),
                 scene.drive.early_rest ? ", early rest on" : "");
  Observers observers = make_observers(scene);
  for (auto& o : observers) o->start(sim, out);
  install_stop_handlers();
  Progress progress("run", nominal, "s", opt.quiet);
  const auto t0 = std::chrono::steady_clock::now();
  write_row();
  int code = kExitOk;
  std::string failure;
  // wall time when the protocol clock started (after settling), for the time per tap
  double wall_settled =
      drive_phase(sim.world().scene.drive, sim.world().s.t + dt).settling ? -1.0 : 0.0;
  try {
    for (std::int64_t k = 0; !finished(); ++k) {
      sim.step();
      clock.after_step(sim.world());  // may end a relaxation early (moves the clock origin)
      if (wall_settled < 0 && !drive_phase(sim.world().scene.drive, sim.world().s.t + dt).settling)
        wall_settled = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      for (auto& o : observers) o->after_step(sim);
      if (sim.world().s.step % scene.output.series_every == 0) write_row();
      if ((k & 63) == 0) {
        progress.update(
            clock.progress(sim.world()),
            by_taps ? "tap " + std::to_string(taps_done()) + "/" + std::to_string(scene.drive.taps)
                    : std::string());
        if (stop_requested()) {
          code = kExitInterrupted;
          break;
        }
      }
    }
  } catch (const HealthError& e) {
    code = kExitUnstable;
    failure = e.what();
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double steps_done = static_cast<double>(sim.world().s.step);
  const double rate = wall > 0 ? steps_done * static_cast<double>(n) / wall : 0.0;

  for (auto& o : observers) o->finish(sim);
  // final state and run.json, also for interrupted and failed runs (nothing is lost)
  write_state_file(sim.world(), out + "/state.csv");
  std::ostringstream js;
  js << "{\n  \"program\": \"gransim\",\n  \"version\": \"" << program_version() << "\",\n"
     << "  \"scene_file\": \"" << json_escape(scene.path) << "\",\n"
     << "  \"status\": \""
     << (code == kExitOk         ? "completed"
         : code == kExitUnstable ? "unstable"
                                 : "interrupted")
     << "\",\n"
     << "  \"particles\": " << n << ",\n  \"steps\": " << sim.world().s.step << ",\n"
     << "  \"simulated_time_s\": " << sim.world().s.t << ",\n  \"wall_time_s\": " << wall << ",\n"
     << "  \"particle_steps_per_s\": " << rate << ",\n"
     << "  \"broad_phase\": \"" << sim.broadphase().name() << "\",\n"
     << "  \"contact_time_s\": " << tc << ",\n"
     << "  \"degenerate_contacts\": " << sim.contacts().degenerate << ",\n"
     << "  \"settle_time_s\": " << scene.prep.settle_time << ",\n";
  // tapping: the protocol, its control value and how the taps went
  if (is_tapping(scene.drive)) {
    const bool neg = scene.drive.kind == DriveKind::NegativeG;
    js << "  \"protocol\": \"" << scene_name(scene.drive.kind) << "\",\n"
       << "  \"control\": " << (neg ? scene.drive.g_p : scene.drive.f) << ",\n"
       << "  \"control_name\": \"" << (neg ? "g_p" : "f") << "\",\n"
       << "  \"period_s\": " << drive_period(scene.drive) << ",\n"
       << "  \"taps_requested\": " << scene.drive.taps << ",\n"
       << "  \"taps_done\": " << taps_done() << ",\n"
       << "  \"early_ends\": " << clock.early_ends() << ",\n"
       << "  \"time_saved_s\": " << clock.time_saved() << ",\n"
       << "  \"wall_time_settling_s\": " << std::max(wall_settled, 0.0) << ",\n"
       << "  \"wall_time_per_tap_s\": "
       << (taps_done() > 0 ? (wall - std::max(wall_settled, 0.0)) / static_cast<double>(taps_done())
                           : 0.0)
       << ",\n";
  }
  if (!failure.empty()) js << "  \"failure\": \"" << json_escape(failure) << "\",\n";
  js << "  \"scene\": {";
  bool first = true;
  for (const auto& [k, v] : scene.resolved) {
    js << (first ? "\n" : ",\n") << "    \"" << json_escape(k) << "\": \"" << json_escape(v)
       << "\"";
    first = false;
  }
  js << "\n  }\n}\n";
  write_file_atomic(out + "/run.json", js.str());

  char summary[160];
  std::snprintf(summary, sizeof summary, "%.3g particle-steps/s, output in %s", rate, out.c_str());
  if (code == kExitOk) {
    progress.finish(summary);
  } else if (code == kExitUnstable) {
    std::fprintf(stderr,
                 "\ngransim: run stopped by a health check: %s\n(output so far kept in %s)\n",
                 failure.c_str(), out.c_str());
  } else {
    std::fprintf(stderr, "\ngransim: interrupted at t = %g s; state and series kept in %s\n",
                 sim.world().s.t, out.c_str());
  }
  return code;
}

}  // namespace gs
