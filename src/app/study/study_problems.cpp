#include "app/study/study_problems.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include "analysis/rfm_fit.hpp"
#include "core/error.hpp"
#include "geometry/polygon.hpp"
#include "measure/packing.hpp"
#include "sim/builders.hpp"
#include "sim/simulation.hpp"
#include "world/prepare.hpp"

namespace gs {

namespace {

constexpr double kDiskR = 0.5, kDiskM = 1.0, kDiskKs = 5e5;  // thesis Table 2.1 (M = 1 kg)
constexpr double kDecR = 0.009;                              // big paper grain, m
constexpr double kDiskGap = 1e-3, kDecGap = 1e-4;            // start separation, m

// the scene of a problem with the combination's integrator and switches; dt set later
SceneSpec problem_scene(const StudySizes& z, const StudyCase& c) {
  SceneSpec s;
  switch (c.problem) {
    case StudyProblem::TwoDisk:
      s = build::two_body(ModelKind::Disk, ShapeKind::Disk, kDiskR, kDiskM, 0,
                          build::disk_material(z.disk_eps, 1.0, kDiskKs), c.integrator, 1e-6);
      s.prep.particles = {{"a", 0, 0, 0, z.disk_speed, 0, 0},
                          {"a", 2 * kDiskR + kDiskGap, 0, 0, 0, 0, 0}};
      s.health.check_every = 1;
      break;
    case StudyProblem::TwoDecagon:
      s = build::two_body(ModelKind::Polygon, ShapeKind::Polygon, kDecR, ngon_area(10, kDecR), 10,
                          build::paper_material(), c.integrator, 1e-6);
      // faces meeting flat: a vertex sits at θ, so π/10 presents a face
      s.prep.particles = {{"a", 0, 0, M_PI / 10, z.decagon_speed / 2, 0, 0},
                          {"a", 2 * kDecR + kDecGap, 0, M_PI / 10, -z.decagon_speed / 2, 0, 0}};
      s.health.check_every = 1;
      break;
    case StudyProblem::GasEnergy:
      s = build::disk_gas(z.gas_n, z.gas_phi, 1.0, 1.0, z.seed);
      s.prep.velocity_amplitude = z.gas_speed;
      s.health.check_every = 10;
      break;
    case StudyProblem::Haff:
      s = build::disk_gas(z.haff_n, 0.1, 0.9, 1.0, z.seed);
      s.prep.velocity_amplitude = std::sqrt(24.0);  // ⟨|v|²⟩ = 4 m²/s² (tests/sim/test_gas.cpp)
      s.health.check_every = 10;
      break;
    case StudyProblem::Pile:
      s = build::decagon_pile(z.pile_n, z.pile_width, 1.0, z.seed);
      s.health.check_every = 10;
      break;
    case StudyProblem::Tapping:
    case StudyProblem::RfmTemperature:
      throw std::logic_error("problem_scene: a statistical problem (study_problems_stat.cpp)");
  }
  s.integrator.kind = c.integrator;
  if (study_problem_walled(c.problem)) s.integrator.broad_phase = c.broad_phase;
  s.model.hdot_finite_difference = c.switches.hdot_fd;
  s.model.rocking_damping = c.switches.rocking;
  s.model.clip_attractive = c.switches.clip;
  return s;
}

std::unique_ptr<Simulation> start(const SceneSpec& s) {
  World w = make_world(s);
  place_particles(w, s);
  return std::make_unique<Simulation>(std::move(w), SimSettings::from(s), s.integrator.broad_phase);
}

// ⟨|v − v_cm|²⟩, m²/s² (T.2.19)
double temperature(const World& w) {
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    mx += w.s.vx[i];
    my += w.s.vy[i];
  }
  mx /= w.size();
  my /= w.size();
  double t = 0;
  for (std::size_t i = 0; i < w.size(); ++i)
    t += (w.s.vx[i] - mx) * (w.s.vx[i] - mx) + (w.s.vy[i] - my) * (w.s.vy[i] - my);
  return t / w.size();
}

// kinetic + ½k_sδ² of a disk gas (no gravity, no walls), J
double gas_energy(const Simulation& sim) {
  const World& w = sim.world();
  double e = w.kinetic_energy();
  for (const ContactRecord& r : sim.contacts().records) {
    const MaterialSpec& m = w.materials[w.species[w.sp[key_i(r.key)]].material];
    e += 0.5 * m.ks * r.overlap * r.overlap;
  }
  return e;
}

// steps for a simulated time (at least one)
std::int64_t steps_for(double t, double dt) {
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(std::llround(t / dt)));
}

// two bodies approach head-on along x: step until the contact has come and gone; the realised
// restitution −Δv_after/Δv_before
void run_two_body(Simulation& sim, double speed, double flight, StudyOutcome& o) {
  const std::int64_t max_steps = steps_for(flight + 20 * o.tc, o.dt) + 10;
  bool touched = false, separated = false;
  for (std::int64_t k = 0; k < max_steps; ++k) {
    sim.step();
    ++o.steps;
    const bool now = !sim.contacts().keys.empty();
    touched |= now;
    if (touched && !now) {
      separated = true;
      break;
    }
  }
  const World& w = sim.world();
  o.value = -(w.s.vx[0] - w.s.vx[1]) / speed;
  if (!touched)
    o.note = "the bodies never touched (Δt skips the contact)";
  else if (!separated)
    o.note = "the bodies did not separate within 20 contact times";
  if (!touched || !separated) o.stable = false;
}

// Haff: relax 0.015 s, then fit a line to T^{-1/2}(t) every 0.002 s; value = slope/predicted
void run_haff(Simulation& sim, const StudySizes& z, StudyOutcome& o) {
  const World& w = sim.world();
  const double phi = 0.1, eps = 0.9, L = w.Lx, sigma = 3e-3;  // L: the periodic box's side
  const double chi = (1 - 7 * phi / 16) / ((1 - phi) * (1 - phi));
  const double slope = (z.haff_n / (L * L)) * chi * sigma * (1 - eps * eps) * std::sqrt(M_PI / 8);
  const std::int64_t relax = steps_for(0.015, o.dt), every = steps_for(0.002, o.dt);
  sim.run(relax);
  o.steps += relax;
  std::vector<double> ts, ys;
  const double t_end = w.s.t + z.haff_duration;
  while (w.s.t < t_end) {
    ts.push_back(w.s.t);
    ys.push_back(1 / std::sqrt(temperature(w)));
    sim.run(every);
    o.steps += every;
  }
  // the least-squares line through T^{-1/2}(t); unit weights take its error from the scatter
  const rfm::LineFit fit = rfm::fit_line(ts, ys);
  o.value = fit.b / slope;
  // the fit's error, and the ~1/√N fluctuation of T of N disks (samples are correlated, so
  // the fit alone understates it)
  o.stat_error = std::max(fit.b_err / slope, 1.0 / std::sqrt(static_cast<double>(z.haff_n)));
  o.note = "T fell " + std::to_string(ys.back() * ys.back() / (ys.front() * ys.front())) + "x";
}

// pile: settle for the duration, φ in a window ~one grain from the walls and floor and 25 mm
// below the highest grain centre
void run_pile(Simulation& sim, const StudySizes& z, StudyOutcome& o) {
  const std::int64_t n = steps_for(z.pile_duration, o.dt);
  sim.run(n);
  o.steps += n;
  const World& w = sim.world();
  double top = 0;
  for (std::size_t i = 0; i < w.size(); ++i) top = std::max(top, w.s.y[i]);
  const double m = 0.015;  // window margin from the walls and floor, m (~one big grain)
  if (top - 0.025 <= 2 * m) {
    o.note = "pile too low for the φ window";
    o.value = NAN;
    return;
  }
  o.value = phi_in_rect(w, m, m, z.pile_width - m, top - 0.025);
  o.note = "max speed " + std::to_string(max_speed(w)) + " m/s";
}

}  // namespace

bool study_problem_walled(StudyProblem p) {
  return p == StudyProblem::Pile || p == StudyProblem::Tapping;
}

double study_contact_time(const StudySizes& z, StudyProblem p) {
  if (p == StudyProblem::Tapping || p == StudyProblem::RfmTemperature)
    return stat_problem_contact_time(z, p);
  StudyCase c;
  c.problem = p;
  const SceneSpec s = problem_scene(z, c);
  return start(s)->model().min_contact_time();
}

StudyOutcome run_study_case(const StudySizes& z, const StudyCase& c) {
  StudyOutcome o;
  try {
    o.tc = study_contact_time(z, c.problem);
    o.dt = c.dt_over_tc * o.tc;
    if (c.problem == StudyProblem::Tapping || c.problem == StudyProblem::RfmTemperature) {
      run_stat_problem(z, c, o);
      return o;
    }
    SceneSpec s = problem_scene(z, c);
    s.integrator.dt = o.dt;
    auto sim = start(s);
    o.particles = static_cast<int>(sim->world().size());
    const double e0 = gas_energy(*sim);
    const double t0 = sim->world().s.t;
    const auto w0 = std::chrono::steady_clock::now();
    switch (c.problem) {
      case StudyProblem::TwoDisk:
        run_two_body(*sim, z.disk_speed, kDiskGap / z.disk_speed, o);
        break;
      case StudyProblem::TwoDecagon:
        run_two_body(*sim, z.decagon_speed, kDecGap / z.decagon_speed, o);
        break;
      case StudyProblem::GasEnergy: {
        const std::int64_t n = steps_for(z.gas_duration, o.dt);
        sim->run(n);
        o.steps = n;
        const double t = sim->world().s.t - t0;
        o.value = std::abs(gas_energy(*sim) - e0) / (e0 * t);
        break;
      }
      case StudyProblem::Haff:
        run_haff(*sim, z, o);
        break;
      case StudyProblem::Pile:
        run_pile(*sim, z, o);
        break;
      case StudyProblem::Tapping:
      case StudyProblem::RfmTemperature:
        break;  // run_stat_problem above
    }
    o.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
    o.sim_time = sim->world().s.t - t0;
    o.final_ke = sim->world().kinetic_energy();
    // a value left NaN with a note (pile too low) is a measurement gap, not a blow-up
    if (o.stable && (!std::isfinite(o.final_ke) || (!std::isfinite(o.value) && o.note.empty()))) {
      o.stable = false;
      if (o.note.empty()) o.note = "non-finite result";
    }
  } catch (const HealthError& e) {
    o.stable = false;
    o.value = NAN;
    o.note = e.what();
  } catch (const std::exception& e) {
    o.stable = false;
    o.value = NAN;
    o.note = std::string("failed: ") + e.what();
  }
  return o;
}

}  // namespace gs
