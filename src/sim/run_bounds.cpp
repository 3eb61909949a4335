#include "sim/run_bounds.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "drive/schedule.hpp"

namespace gs {

namespace {

// rough memory per particle (state, constants, broad phase, a few contacts) and per species
// pair (the force law's pair table and its caches): an estimate, to refuse the impossible
constexpr double kBytesPerParticle = 1024.0;
constexpr double kBytesPerSpeciesPair = 256.0;
constexpr double kMaxFrames = 1e6;            // hours of drawing at hundreds of frames a second
constexpr double kMaxTrajectoryBytes = 1e12;  // 1 TB

std::string gib(double bytes) {
  std::ostringstream m;
  m.precision(3);
  m << bytes / (1024.0 * 1024.0 * 1024.0) << " GiB";
  return m.str();
}

double physical_memory() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), size = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? static_cast<double>(pages) * static_cast<double>(size) : 64e9;
}

// the number of steps must be one the run can count and finish: a tiny Δt or a huge duration
// (or settle time, or tap count) is refused up front, naming the keys that make it
void check_step_count(const SceneSpec& scene, double nominal, double particles) {
  const double dt = scene.integrator.dt;
  const double steps = nominal / dt;
  const double particle_steps = steps * std::max(particles, 1.0);
  constexpr double kMaxSteps = 1e15;  // far beyond any run; well inside int64 and exact doubles
  constexpr double kMaxParticleSteps = 1e15;  // ≈ 3 years at 10⁷ particle-steps per second
  if (std::isfinite(steps) && steps >= 0.0 && steps <= kMaxSteps &&
      particle_steps <= kMaxParticleSteps)
    return;
  const std::string keys = is_tapping(scene.drive)
                               ? "drive.taps × the period, preparation.settle_time"
                               : "scene.duration, preparation.settle_time";
  std::ostringstream m;
  m << "the run would take " << steps << " steps (" << nominal
    << " s of simulated time at dt = " << dt << " s";
  if (std::isfinite(particle_steps))
    m << ", ≈ " << particle_steps / 1e7 / 3.15e7 << " years on one core at 10⁷ particle-steps/s";
  m << "); lower " << keys << " or raise integrator.dt";
  throw InputError(scene.path, "integrator.dt", m.str());
}

// a tap shorter than a step would fall between two steps: silently no tap at all
void check_tap_length(const SceneSpec& scene) {
  if (!is_tapping(scene.drive) || scene.drive.taps <= 0) return;
  const double dt = scene.integrator.dt;
  const double pulse = excitation_length(scene.drive), period = drive_period(scene.drive);
  const bool neg = scene.drive.kind == DriveKind::NegativeG;
  if (!(pulse >= 2.0 * dt)) {
    std::ostringstream m;
    m << "the excitation lasts " << pulse << " s, less than two steps of integrator.dt = " << dt
      << " s: the steps would miss it; " << (neg ? "raise drive.t1" : "lower drive.f")
      << " or lower integrator.dt";
    throw InputError(scene.path, neg ? "drive.t1" : "drive.f", m.str());
  }
  if (!(period >= 2.0 * dt)) {
    std::ostringstream m;
    m << "the tap period is " << period << " s, less than two steps of integrator.dt = " << dt
      << " s";
    throw InputError(scene.path, neg ? "drive.period" : "drive.relax", m.str());
  }
}

// frames and trajectory frames the [render] schedule would write over the run
void check_frames(const SceneSpec& scene, double nominal, double particles) {
  const RenderSpec& r = scene.render;
  const double steps = nominal / scene.integrator.dt;
  if (r.enabled) {
    double frames = 0.0;
    std::string key;
    // frame times closer than a thousandth of a step all fall into one step's frame
    if (r.schedule == RenderSchedule::Time && !(r.fps * r.slowmo * scene.integrator.dt <= 1000.0)) {
      std::ostringstream m;
      m << "render.fps × render.slowmo = " << r.fps * r.slowmo
        << " frames per simulated second is more than 1000 per step of integrator.dt = "
        << scene.integrator.dt << " s; lower render.slowmo";
      throw InputError(scene.path, "render.slowmo", m.str());
    }
    switch (r.schedule) {
      case RenderSchedule::Time:
        // at most one frame per step
        frames = std::min(std::max(nominal - r.start, 0.0) * r.fps * r.slowmo, steps);
        key = "render.slowmo";
        break;
      case RenderSchedule::Steps:
        frames = steps / std::max(r.every, 1);
        key = "render.every";
        break;
      case RenderSchedule::Taps:
      case RenderSchedule::Rest:
        frames = (r.schedule == RenderSchedule::Taps ? 2.0 : 1.0) * std::max(scene.drive.taps, 0);
        key = "drive.taps";
        break;
    }
    if (!(frames <= kMaxFrames)) {
      std::ostringstream m;
      m << "the [render] schedule asks for " << frames << " frames (≈ " << frames / 100.0 / 3600.0
        << " h at 100 frames/s); at most " << kMaxFrames
        << " per run: raise render.every, lower render.fps or " << key << ", or record fewer taps";
      throw InputError(scene.path, key, m.str());
    }
  }
  if (r.trajectory_every > 0) {
    const double bytes = steps / r.trajectory_every * particles * 100.0;
    if (!(bytes <= kMaxTrajectoryBytes)) {
      std::ostringstream m;
      m << "trajectory.xyz would grow to ≈ " << bytes / 1e12 << " TB ("
        << steps / r.trajectory_every << " frames of " << particles
        << " particles); raise render.trajectory_every";
      throw InputError(scene.path, "render.trajectory_every", m.str());
    }
  }
}

// particles and species pairs against the memory of this machine
void check_memory(const SceneSpec& scene, double particles) {
  const double species = static_cast<double>(scene.species.size());
  const double need = particles * kBytesPerParticle + species * species * kBytesPerSpeciesPair;
  const double have = physical_memory();
  if (need <= 0.8 * have) return;
  std::ostringstream m;
  m << "the run needs ≈ " << gib(need) << " of memory (" << particles << " particles at ≈ "
    << kBytesPerParticle << " bytes, " << species << " species → " << species * species
    << " species pairs at ≈ " << kBytesPerSpeciesPair << " bytes); this machine has " << gib(have);
  const bool pairs = species * species * kBytesPerSpeciesPair > particles * kBytesPerParticle;
  m << (pairs ? ": use fewer species" : ": lower the species counts");
  throw InputError(scene.path, pairs ? "species" : "species.count", m.str());
}

// a grain that moves more than its radius in one step passes through others unnoticed
void check_initial_speed(const SceneSpec& scene) {
  double r_min = std::numeric_limits<double>::infinity();
  for (const auto& sp : scene.species)
    if (sp.count > 0) r_min = std::min(r_min, sp.radius);
  const double dt = scene.integrator.dt;
  auto refuse = [&](const std::string& key, double speed) {
    std::ostringstream m;
    m << "an initial speed of " << speed << " m/s moves a grain " << speed * dt
      << " m in one step of integrator.dt = " << dt << " s, more than the smallest grain radius ("
      << r_min << " m): contacts would be missed and the state overflows";
    throw InputError(scene.path, key, m.str());
  };
  // the components are U(−a/2, a/2): the fastest grain moves at most a/√2
  // gravity alone moves a grain g·dt² in the first step
  const DriveSpec& d = scene.drive;
  const double g = d.g * std::max(1.0, is_tapping(d) ? d.g_p : 1.0);
  if (d.kind != DriveKind::None && d.kind != DriveKind::RandomForce && !(g * dt * dt <= r_min)) {
    std::ostringstream m;
    m << "gravity of " << g << " m/s² moves a grain " << g * dt * dt
      << " m in one step of integrator.dt = " << dt << " s, more than the smallest grain radius ("
      << r_min << " m)";
    throw InputError(scene.path, is_tapping(d) ? "drive.g_p" : "drive.g", m.str());
  }
  const double a = scene.prep.velocity_amplitude / std::sqrt(2.0);
  if (!(a * dt <= r_min)) refuse("preparation.velocity_amplitude", a);
  for (std::size_t i = 0; i < scene.prep.particles.size(); ++i) {
    const auto& p = scene.prep.particles[i];
    const double v = std::hypot(p.vx, p.vy);
    if (!(v * dt <= r_min)) refuse("preparation.particle[" + std::to_string(i) + "].vx/vy", v);
  }
}

// φ is the grain area inside the test rectangle over its area: a rectangle reaching outside
// the box reads low for ever, one wholly outside reads 0. Checked for a rectangle the scene
// gives and for every tapping run (whose φ is the result); the default rectangle of other
// runs is not used for anything
void check_test_rect(const SceneSpec& scene) {
  const auto& r = scene.output.test_rect;
  const OutputSpec defaults;
  const bool given = !std::equal(std::begin(r), std::end(r), std::begin(defaults.test_rect));
  if (scene.box.kind == BoxKind::Ring1D || !(given || is_tapping(scene.drive))) return;
  const double W = scene.box.width, H = scene.box.height, tol = 1e-9 * std::max(W, H);
  if (r[0] >= -tol && r[1] >= -tol && r[2] <= W + tol && r[3] <= H + tol) return;
  std::ostringstream m;
  m << "the rectangle [" << r[0] << ", " << r[1] << ", " << r[2] << ", " << r[3]
    << "] reaches outside the box [0, 0, " << W << ", " << H
    << "]; the packing fraction is measured inside the box"
    << (given ? "" : " (this is the default rectangle: give output.test_rect for this box)");
  throw InputError(scene.path, "output.test_rect", m.str());
}

}  // namespace

void check_run_bounds(const SceneSpec& scene, double nominal) {
  double particles = 0.0;
  for (const auto& sp : scene.species) particles += std::max(sp.count, 0);
  check_memory(scene, particles);
  check_step_count(scene, nominal, particles);
  check_tap_length(scene);
  check_initial_speed(scene);
  check_test_rect(scene);
  check_frames(scene, nominal, particles);
}

}  // namespace gs
