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
#include "output/csv.hpp"
#include "output/run_dir.hpp"
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
  CsvWriter series(out + "/series.csv",
                   {"t", "step", "kinetic_energy", "contacts", "max_overlap", "max_overlap_rel",
                    "max_speed", "gx", "gy", "degenerate"});
  auto write_row = [&] {
    const World& w = sim.world();
    double vmax2 = 0;
    for (std::size_t i = 0; i < w.size(); ++i)
      vmax2 = std::max(vmax2, w.s.vx[i] * w.s.vx[i] + w.s.vy[i] * w.s.vy[i]);
    const ForceStats& f = sim.last_forces();
    series.row({w.s.t, static_cast<double>(w.s.step), w.kinetic_energy(),
                static_cast<double>(f.contacts), f.max_overlap, f.max_overlap_rel,
                std::sqrt(vmax2), sim.gravity().x, sim.gravity().y,
                static_cast<double>(sim.contacts().degenerate)});
  };

  const auto nsteps = static_cast<std::int64_t>(std::llround(scene.duration / dt));
  const std::size_t n = sim.world().size();
  std::fprintf(stderr, "gransim %s: %s, %zu particles, %lld steps of %g s (%s, %s), contact time %.3g s\n",
               program_version().data(), scene.name.c_str(), n, static_cast<long long>(nsteps), dt,
               std::string(to_string(scene.integrator.kind)).c_str(), sim.broadphase().name(), tc);
  Observers observers = make_observers(scene);
  for (auto& o : observers) o->start(sim, out);
  install_stop_handlers();
  Progress progress("run", scene.duration, "s", opt.quiet);
  const auto t0 = std::chrono::steady_clock::now();
  write_row();
  int code = kExitOk;
  std::string failure;
  try {
    for (std::int64_t k = 0; k < nsteps; ++k) {
      sim.step();
      for (auto& o : observers) o->after_step(sim);
      if (sim.world().s.step % scene.output.series_every == 0) write_row();
      if ((k & 63) == 0) {
        progress.update(sim.world().s.t);
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
     << "  \"status\": \"" << (code == kExitOk ? "completed" : code == kExitUnstable ? "unstable" : "interrupted") << "\",\n"
     << "  \"particles\": " << n << ",\n  \"steps\": " << sim.world().s.step << ",\n"
     << "  \"simulated_time_s\": " << sim.world().s.t << ",\n  \"wall_time_s\": " << wall << ",\n"
     << "  \"particle_steps_per_s\": " << rate << ",\n"
     << "  \"broad_phase\": \"" << sim.broadphase().name() << "\",\n"
     << "  \"contact_time_s\": " << tc << ",\n"
     << "  \"degenerate_contacts\": " << sim.contacts().degenerate << ",\n";
  if (!failure.empty()) js << "  \"failure\": \"" << json_escape(failure) << "\",\n";
  js << "  \"scene\": {";
  bool first = true;
  for (const auto& [k, v] : scene.resolved) {
    js << (first ? "\n" : ",\n") << "    \"" << json_escape(k) << "\": \"" << json_escape(v) << "\"";
    first = false;
  }
  js << "\n  }\n}\n";
  write_file_atomic(out + "/run.json", js.str());

  char summary[160];
  std::snprintf(summary, sizeof summary, "%.3g particle-steps/s, output in %s", rate, out.c_str());
  if (code == kExitOk) {
    progress.finish(summary);
  } else if (code == kExitUnstable) {
    std::fprintf(stderr, "\ngransim: run stopped by a health check: %s\n(output so far kept in %s)\n",
                 failure.c_str(), out.c_str());
  } else {
    std::fprintf(stderr, "\ngransim: interrupted at t = %g s; state and series kept in %s\n",
                 sim.world().s.t, out.c_str());
  }
  return code;
}

}  // namespace gs
