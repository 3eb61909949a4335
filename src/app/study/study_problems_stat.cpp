// the statistical reference problems of `gransim study` (docs/speed-accuracy.md): a short
// negative-g tapping run of a small decagon pile (φ̄ and σ_φ over the taps) and a randomly forced
// periodic disk fluid (steady granular temperature). Their values scatter from run to run, so each
// carries a 95% confidence half-width; study.cpp compares it with the small-Δt reference's
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "analysis/rfm_moments.hpp"
#include "analysis/stats.hpp"
#include "app/study/study_problems.hpp"
#include "core/error.hpp"
#include "drive/protocol.hpp"
#include "drive/schedule.hpp"
#include "geometry/polygon.hpp"
#include "measure/packing.hpp"
#include "measure/tap_measure.hpp"
#include "sim/builders.hpp"
#include "sim/simulation.hpp"
#include "world/prepare.hpp"

namespace gs {

namespace {

using WallClock = std::chrono::steady_clock;

double seconds_since(WallClock::time_point t0) {
  return std::chrono::duration<double>(WallClock::now() - t0).count();
}

std::int64_t steps_of(double t, double dt) {
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(std::llround(t / dt)));
}

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// ---- tapping ------------------------------------------------------------------------------

// the pile of scenes/tap_small_negative_g.toml at study size: bidisperse decagons, pulses of
// negative gravity (P.37), early rest as the switch says
SceneSpec tapping_scene(const StudySizes& z, const StudyCase& c) {
  SceneSpec s = build::decagon_pile(z.tap_n, z.tap_width, 1.0, z.tap_seed);
  s.name = "study_tapping";
  s.prep.settle_time = z.tap_settle;
  s.drive.kind = DriveKind::NegativeG;
  s.drive.g_p = z.tap_g_p;
  s.drive.t1 = z.tap_t1;
  s.drive.period = z.tap_period;
  s.drive.taps = z.tap_taps;
  s.drive.early_rest = c.switches.early_rest;
  s.health.check_every = 10;
  s.integrator.kind = c.integrator;
  s.integrator.broad_phase = c.broad_phase;
  s.model.hdot_finite_difference = c.switches.hdot_fd;
  s.model.rocking_damping = c.switches.rocking;
  // the test rectangle from the grains' area (the same for every Δt): 15 mm (~one big grain)
  // from the walls and the floor, 25 mm below the expected top of a pile at φ ≈ 0.8
  double area = 0;
  for (const SpeciesSpec& sp : s.species) area += sp.count * ngon_area(sp.sides, sp.radius);
  const double m = 0.015, top = area / (0.8 * z.tap_width);
  s.output.test_rect[0] = m;
  s.output.test_rect[1] = m;
  s.output.test_rect[2] = z.tap_width - m;
  s.output.test_rect[3] = std::max(2 * m + 0.005, top - 0.025);
  s.output.discard_taps = z.tap_discard;
  return s;
}

// settle, then tap as `gransim run` does (the protocol clock drives the pulses and early
// rest); φ of the test rectangle just before every excitation (measure_tap, docs/physics.md §2.5)
void run_tapping(const StudySizes& z, const StudyCase& c, StudyOutcome& o) {
  SceneSpec s = tapping_scene(z, c);
  s.integrator.dt = o.dt;
  World w = make_world(s);
  place_particles(w, s);
  ProtocolClock clock(s);
  clock.start(w);
  Simulation sim(std::move(w), SimSettings::from(s), s.integrator.broad_phase);
  o.particles = static_cast<int>(sim.world().size());
  std::vector<double> phis;
  const auto w0 = WallClock::now();
  double wall_settled = -1;
  long measured = 0;
  while (!clock.done(sim.world())) {
    sim.step();
    ++o.steps;
    if (clock.after_step(sim.world()) == ClockEvent::Quench) sim.zero_velocities();
    const World& cw = sim.world();
    if (!excitation_starts_next(sim.settings().drive, cw.clock_origin, cw.s.t, o.dt)) continue;
    // the row of tap k: the pile after k pulses (k = 0: settled); the first `discard` dropped
    const long k = drive_phase(sim.settings().drive, cw.clock_origin, cw.s.t + o.dt).tap;
    if (k == 0) wall_settled = seconds_since(w0);
    ++measured;
    if (k > z.tap_discard) phis.push_back(measure_tap(cw, sim.contacts(), s.output.test_rect).phi);
  }
  o.wall_s = seconds_since(w0);
  o.sim_time = sim.world().s.t;
  o.final_ke = sim.world().kinetic_energy();
  if (wall_settled >= 0 && measured > 1)
    o.wall_per_tap = (o.wall_s - wall_settled) / static_cast<double>(z.tap_taps);
  o.samples = static_cast<int>(phis.size());
  if (phis.size() < 3) {
    o.value = NAN;
    o.note = "fewer than 3 taps after the discarded ones";
    return;
  }
  // φ̄ with the autocorrelation-aware interval, σ_φ with its chi-square interval
  // (docs/physics.md §2.6)
  const AutocorrTime ac = autocorr_time(phis);
  o.tau_int = std::max(0.5, ac.tau_int);
  o.value = mean(phis);
  const Interval ci = mean_ci(phis, 0.95, o.tau_int);
  o.stat_error = 0.5 * (ci.hi - ci.lo);
  o.sd = stddev(phis);
  const Interval sci = stddev_ci(phis, 0.95, o.tau_int);
  o.sd_stat = 0.5 * (sci.hi - sci.lo);
  o.note = std::to_string(phis.size()) + " taps, tau_int " + fmt("%.2g", o.tau_int) +
           ", early ends " + std::to_string(clock.early_ends()) +
           (clock.early_ends() > 0
                ? " (at " + fmt("%.2g", z.tap_period - clock.time_saved() / clock.early_ends()) +
                      " s of T)"
                : std::string()) +
           ", final max speed " + fmt("%.2g", max_speed(sim.world())) + " m/s";
}

// ---- random force model ---------------------------------------------------------------------

// the thesis' 2D reference fluid (scenes/rfm2d_reference.toml) at study size
SceneSpec rfm_scene(const StudySizes& z, const StudyCase& c) {
  SceneSpec s = build::disk_gas(z.rfm_n, z.rfm_phi, z.rfm_eps, z.rfm_eps, z.rfm_seed);
  s.name = "study_rfm";
  s.drive.kind = DriveKind::RandomForce;
  s.drive.D = z.rfm_D;
  s.drive.com_removal_every = 100;
  s.health.check_every = 10;
  s.integrator.kind = c.integrator;
  s.model.clip_attractive = c.switches.clip;
  return s;
}

// drive the fluid past the transient, then sample T = (1/N) Σ|v − ⟨v⟩|² (T.2.19, as the RFM
// observer) every rfm_sample seconds; ⟨T⟩ and its error from rfm_blocks block means (T.2.20)
void run_rfm(const StudySizes& z, const StudyCase& c, StudyOutcome& o) {
  SceneSpec s = rfm_scene(z, c);
  s.integrator.dt = o.dt;
  World w = make_world(s);
  place_particles(w, s);
  Simulation sim(std::move(w), SimSettings::from(s), s.integrator.broad_phase);
  const World& cw = sim.world();
  o.particles = static_cast<int>(cw.size());
  const std::int64_t discard = steps_of(z.rfm_discard, o.dt), every = steps_of(z.rfm_sample, o.dt);
  // a whole number of blocks of at least two samples each
  const double per_block = z.rfm_duration / (z.rfm_sample * z.rfm_blocks);
  const std::int64_t block_len = std::max<std::int64_t>(2, std::llround(per_block));
  const std::int64_t samples = block_len * z.rfm_blocks;
  std::vector<double> temps;
  std::vector<Vec2> v(cw.size());
  const auto w0 = WallClock::now();
  sim.run(discard);
  o.steps += discard;
  for (std::int64_t k = 0; k < samples; ++k) {
    sim.run(every);
    o.steps += every;
    for (std::size_t i = 0; i < cw.size(); ++i) v[i] = Vec2{cw.s.vx[i], cw.s.vy[i]};
    temps.push_back(rfm::granular_temperature(v));
  }
  o.wall_s = seconds_since(w0);
  o.sim_time = cw.s.t;
  o.final_ke = cw.kinetic_energy();
  o.samples = static_cast<int>(temps.size());
  const rfm::BlockAverage b = rfm::block_average(temps, static_cast<std::size_t>(block_len));
  o.value = b.mean;
  const double nb = static_cast<double>(b.block_means.size());
  o.stat_error = student_t_quantile(0.975, nb - 1) * b.error;
  o.sd = stddev(temps);
  const AutocorrTime ac = autocorr_time(temps);
  o.tau_int = std::max(0.5, ac.tau_int);
  const Interval sci = stddev_ci(temps, 0.95, o.tau_int);
  o.sd_stat = 0.5 * (sci.hi - sci.lo);
  o.note = std::to_string(temps.size()) + " samples in " + std::to_string(b.block_means.size()) +
           " blocks, tau_int " + fmt("%.2g", o.tau_int) + " samples";
}

}  // namespace

double stat_problem_contact_time(const StudySizes& z, StudyProblem p) {
  StudyCase c;
  c.problem = p;
  SceneSpec s;
  if (p == StudyProblem::Tapping) {
    c.broad_phase = BroadPhaseKind::Box2DTree;
    s = tapping_scene(z, c);
  } else {
    s = rfm_scene(z, c);
  }
  World w = make_world(s);
  place_particles(w, s);
  return Simulation(std::move(w), SimSettings::from(s), s.integrator.broad_phase)
      .model()
      .min_contact_time();
}

void run_stat_problem(const StudySizes& z, const StudyCase& c, StudyOutcome& o) {
  if (c.problem == StudyProblem::Tapping)
    run_tapping(z, c, o);
  else
    run_rfm(z, c, o);
  // a value left NaN with a note is a measurement gap, not a blow-up
  if (!std::isfinite(o.final_ke) || (!std::isfinite(o.value) && o.note.empty())) {
    o.stable = false;
    if (o.note.empty()) o.note = "non-finite result";
  }
}

}  // namespace gs
