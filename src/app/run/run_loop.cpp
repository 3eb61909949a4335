// the run loop of `gransim run` and `gransim resume` (app/run/run_session.hpp)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/progress.hpp"
#include "app/run/run.hpp"
#include "app/run/run_info.hpp"
#include "app/run/run_session.hpp"
#include "app/version.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/trigger.hpp"
#include "output/run_dir.hpp"
#include "scene/names.hpp"
#include "sim/state_file.hpp"

namespace gs {
namespace {

// steps between progress updates and checks for a stop request (and at most one batch)
constexpr std::int64_t kProgressEvery = 64;

}  // namespace

void write_series_row(RunSession& rs) {
  const Simulation& sim = *rs.sim;
  const World& w = sim.world();
  double vmax2 = 0;
  for (std::size_t i = 0; i < w.size(); ++i)
    vmax2 = std::max(vmax2, w.s.vx[i] * w.s.vx[i] + w.s.vy[i] * w.s.vy[i]);
  const ForceStats& f = sim.last_forces();
  rs.series.row({w.s.t, static_cast<double>(w.s.step), w.kinetic_energy(),
                 static_cast<double>(f.contacts), f.max_overlap, f.max_overlap_rel,
                 std::sqrt(vmax2), sim.gravity().x, sim.gravity().y,
                 static_cast<double>(sim.contacts().degenerate)});
}

namespace {

void write_run_json(const RunSession& rs, int code, const std::string& failure, double wall,
                    double rate, long taps_done) {
  const SceneSpec& scene = rs.scene;
  const Simulation& sim = *rs.sim;
  const ProtocolClock& clock = *rs.clock;
  nlohmann::ordered_json j;
  j["program"] = "gransim";
  j["version"] = std::string(program_version());
  j["scene_file"] = rs.scene_file;
  j["status"] = code == kExitOk ? "completed" : code == kExitUnstable ? "unstable" : "interrupted";
  j["particles"] = sim.world().size();
  j["steps"] = sim.world().s.step;
  j["simulated_time_s"] = sim.world().s.t;
  j["wall_time_s"] = wall;
  j["sessions"] = rs.sessions;
  // the cost whatever else ran beside it; covers every session when the two counts agree
  j["cpu_time_s"] = run_cpu_seconds(rs);
  j["cpu_time_sessions"] = rs.cpu_sessions;
  j["particle_steps_per_s"] = rate;
  j["broad_phase"] = sim.broadphase().name();
  j["sort_every"] = sim.sort_every();
  j["omp_threads"] = rs.team.threads;
  j["omp_cpus"] = rs.team.cpus;
  j["contact_time_s"] = sim.model().min_contact_time();
  j["degenerate_contacts"] = sim.contacts().degenerate;
  j["settle_time_s"] = scene.prep.settle_time;
  // tapping: the protocol, its control value and how the taps went
  if (is_tapping(scene.drive)) {
    const bool neg = scene.drive.kind == DriveKind::NegativeG;
    const double settled = std::max(rs.wall_settled, 0.0);
    j["protocol"] = std::string(scene_name(scene.drive.kind));
    j["control"] = neg ? scene.drive.g_p : scene.drive.f;
    j["control_name"] = neg ? "g_p" : "f";
    j["period_s"] = drive_period(scene.drive);
    j["taps_requested"] = scene.drive.taps;
    j["taps_done"] = taps_done;
    j["early_ends"] = clock.early_ends();
    j["time_saved_s"] = clock.time_saved();
    j["quench_events"] = clock.quench_events();
    j["wall_time_settling_s"] = settled;
    j["wall_time_per_tap_s"] =
        taps_done > 0 ? (wall - settled) / static_cast<double>(taps_done) : 0.0;
  }
  if (!failure.empty()) j["failure"] = failure;
  // this session's wall time per stage of the step, and inside the step loop as a whole
  nlohmann::ordered_json& prof = j["profile"];
  for (std::size_t k = 0; k < kStageCount; ++k)
    prof[std::string(stage_name(static_cast<Stage>(k)))] = sim.profile().seconds[k];
  j["step_loop_s"] = rs.step_loop;
  j["profile_timed_steps"] = sim.profile().timed;  // short steps are sampled (docs/architecture.md)
  // the resolved scene, one typed value per dotted key (docs/python.md)
  j["scene"] = scene_json(scene.resolved);
  write_file_atomic(rs.out + "/run.json",
                    j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

// gransim run --profile: the stages' wall times as a table on stderr
void print_profile(const RunSession& rs) {
  const StepProfile& p = rs.sim->profile();
  const double total = p.total();
  std::fprintf(stderr, "\n%-14s %12s %7s\n", "stage", "seconds", "share");
  for (std::size_t k = 0; k < kStageCount; ++k) {
    const std::string name(stage_name(static_cast<Stage>(k)));
    std::fprintf(stderr, "%-14s %12.6f %6.1f%%\n", name.c_str(), p.seconds[k],
                 total > 0.0 ? 100.0 * p.seconds[k] / total : 0.0);
  }
  std::fprintf(stderr, "%-14s %12.6f   (%llu steps, %llu of them timed; step loop %.6f s)\n",
               "total", total, static_cast<unsigned long long>(p.steps),
               static_cast<unsigned long long>(p.timed), rs.step_loop);
}

}  // namespace

std::vector<std::string> series_columns() {
  return {"t",  "step", "kinetic_energy", "contacts", "max_overlap", "max_overlap_rel", "max_speed",
          "gx", "gy",   "degenerate"};
}

int run_session(RunSession& rs) {
  Simulation& sim = *rs.sim;
  ProtocolClock& clock = *rs.clock;
  const SceneSpec& scene = rs.scene;
  const OutputSpec& out = scene.output;
  const double dt = sim.dt();
  // how long: taps of a tapping protocol (the clock says when the last one is measured), or
  // settling plus scene.duration
  const bool by_taps = scene.drive.taps > 0 && is_tapping(scene.drive);
  const double nominal = clock.nominal_duration();
  const auto nsteps = static_cast<std::int64_t>(std::llround(nominal / dt));
  auto finished = [&] {
    if (by_taps) return clock.done(sim.world());
    return sim.world().s.step + std::llround(clock.time_saved() / dt) >= nsteps;
  };
  auto settling = [&] {
    return drive_phase(sim.settings().drive, sim.world().clock_origin, sim.world().s.t + dt)
        .settling;
  };
  auto taps_done = [&]() -> long {
    const DrivePhase p =
        drive_phase(sim.settings().drive, sim.world().clock_origin, sim.world().s.t + dt);
    return is_tapping(scene.drive) && !p.settling ? p.tap : 0;
  };
  install_stop_handlers();
  rs.cpu_start = process_cpu_seconds();
  Progress progress(rs.sessions > 1 ? "resume" : "run", nominal, "s", rs.quiet);
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  auto wall_now = [&] {
    return rs.wall_before + std::chrono::duration<double>(Clock::now() - t0).count();
  };
  if (rs.wall_settled < 0 && !settling()) rs.wall_settled = wall_now();
  // periodic checkpoints: every output.checkpoint_steps steps, every output.checkpoint_taps
  // taps of a counted protocol, every output.checkpoint_minutes of this session's wall clock
  Trigger checkpoints = Trigger::every_steps(out.checkpoint_steps)
                            .or_every_taps(by_taps ? out.checkpoint_taps : 0)
                            .or_every_minutes(out.checkpoint_minutes);
  checkpoints.start(wall_now());
  auto checkpoint = [&] { write_run_checkpoint(rs, wall_now()); };
  // how many steps may run at once before anything outside the simulation looks at its state
  // (Simulation::run: a disk step's kick then predicts the next step): up to the next series
  // row, step checkpoint, observer's look, sort, progress check, the next tap or the end. One
  // step at a time while settling and where the protocol clock looks after each (early rest)
  auto batch = [&]() -> std::int64_t {
    if (clock.watches_steps() || rs.wall_settled < 0) return 1;
    const std::int64_t step = sim.world().s.step;
    std::int64_t m = std::min<std::int64_t>(kProgressEvery,
                                            nsteps - step - std::llround(clock.time_saved() / dt));
    auto to_next = [&](std::int64_t every) {
      if (every > 0) m = std::min(m, every - step % every);
    };
    // taps: the clock's end, the tap checkpoints and the tap measurement are at excitations
    m = std::min(m, 1 + steps_before_excitation(sim.settings().drive, sim.world().clock_origin,
                                                sim.world().s.t, dt));
    to_next(out.series_every);
    m = std::min(m, checkpoints.steps_to_next(step));
    if (sim.sort_every() > 0) m = std::min(m, sim.sort_every());  // observers see each sort
    for (const auto& o : rs.observers) m = std::min(m, 1 + o->quiet_steps(sim));
    return std::max<std::int64_t>(m, 1);
  };
  int code = kExitOk;
  std::string failure;
  try {
    std::int64_t since_check = kProgressEvery;  // progress and stop checks from the first step
    while (!finished()) {
      const std::int64_t m = batch();
      const bool first = sim.world().s.step == 0;
      const auto run_start = Clock::now();
      sim.run(m);
      rs.step_loop += std::chrono::duration<double>(Clock::now() - run_start).count();
      since_check += m;
      // a non-finite first step (a scene that blows up at once) is caught before anything is
      // written of it, whatever health.check_every is
      if (first) sim.check_finite();
      // the first health check has passed: a replaced run's files can go
      if (rs.replaced != nullptr && sim.world().s.step >= scene.health.check_every) {
        rs.replaced->discard();
        rs.replaced = nullptr;
      }
      // may end a relaxation early (moves the clock origin) or ask for a quench's reset
      if (clock.after_step(sim.world()) == ClockEvent::Quench) sim.zero_velocities();
      if (rs.wall_settled < 0 && !settling()) rs.wall_settled = wall_now();
      for (auto& o : rs.observers) o->after_step(sim);
      const std::int64_t step = sim.world().s.step;
      if (step % out.series_every == 0) write_series_row(rs);
      // checkpoints between two steps, after every output of this step is written
      const bool due = checkpoints.fires(
          {step, tap_boundary(sim.settings().drive, sim.world().clock_origin, sim.world().s.t, dt),
           wall_now()});
      if (since_check >= kProgressEvery) {
        since_check = 0;
        progress.update(
            clock.progress(sim.world()),
            by_taps ? "tap " + std::to_string(taps_done()) + "/" + std::to_string(scene.drive.taps)
                    : std::string());
        if (stop_requested()) {
          code = kExitInterrupted;
          break;
        }
      }
      if (due && !finished()) checkpoint();
    }
    // "completed" is never said of a state that blew up since the last periodic check
    if (code == kExitOk) sim.health_check();
  } catch (const HealthError& e) {
    code = kExitUnstable;
    failure = e.what();
  } catch (const OutputError& e) {
    code = kExitOutput;
    failure = e.what();
  }
  // whatever else is written now may fail too (a full disk): try each, report, go on
  auto attempt = [&](const char* what, auto&& f) {
    try {
      f();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "gransim: could not write %s: %s\n", what, e.what());
      if (code == kExitOk || code == kExitInterrupted) {
        code = kExitOutput;
        failure = e.what();
      }
    }
  };
  // a checkpoint on the way out (not of a blown-up state, nor after a failed write: the last
  // periodic one stays and matches the files)
  if (code == kExitOk || code == kExitInterrupted) attempt("the final checkpoint", checkpoint);
  const double wall = wall_now();
  const double n = static_cast<double>(sim.world().size());
  const double rate = wall > 0 ? static_cast<double>(sim.world().s.step) * n / wall : 0.0;

  for (auto& o : rs.observers) attempt(o->name(), [&] { o->finish(sim); });
  rs.series = CsvWriter();
  // final state and run.json, also for interrupted and failed runs (nothing is lost)
  attempt("state.csv", [&] { write_state_file(sim.world(), rs.out + "/state.csv"); });
  attempt("run.json", [&] { write_run_json(rs, code, failure, wall, rate, taps_done()); });

  char head[96];
  std::snprintf(head, sizeof head, "%.3g particle-steps/s, output in ", rate);
  std::string summary = head + rs.out;
  // the pictures a run made, named on its last line
  std::string shown;
  for (const char* f : {"final.png", "movie.mp4"})
    if (std::error_code ec; std::filesystem::exists(rs.out + "/" + f, ec))
      shown += (shown.empty() ? "" : " and ") + rs.out + "/" + f;
  if (!shown.empty()) summary += "; see " + shown;
  if (code == kExitOk) {
    progress.finish(summary.c_str());
  } else if (code == kExitOutput) {
    std::fprintf(stderr,
                 "\ngransim: stopped at t = %g s: cannot write output: %s\nEvery complete row "
                 "is kept in %s. Free space (or fix the location), then continue from the last "
                 "checkpoint with: gransim resume %s\n",
                 sim.world().s.t, failure.c_str(), rs.out.c_str(), rs.out.c_str());
  } else if (code == kExitUnstable) {
    std::fprintf(stderr,
                 "\ngransim: run stopped by a health check: %s\n(output so far kept in %s)\n",
                 failure.c_str(), rs.out.c_str());
  } else {
    std::fprintf(stderr,
                 "\ngransim: interrupted at t = %g s (step %lld); checkpoint, state and series "
                 "kept in %s\n  continue with: gransim resume %s\n",
                 sim.world().s.t, static_cast<long long>(sim.world().s.step), rs.out.c_str(),
                 rs.out.c_str());
  }
  if (rs.profile) print_profile(rs);
  return code;
}

}  // namespace gs
