#include "sim/simulation.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "drive/random_force.hpp"
#include "drive/schedule.hpp"

namespace gs {

Simulation::Simulation(World w) : Simulation(std::move(w), BroadPhaseKind::Auto) {}

Simulation::Simulation(World w, BroadPhaseKind bp)
    : w_(std::move(w)),
      dt_(w_.scene.integrator.dt),
      broad_(make_broadphase(bp == BroadPhaseKind::Auto ? w_.scene.integrator.broad_phase : bp, w_)),
      model_(w_),
      integ_(make_integrator(w_.scene.integrator.kind)) {
  // forces at the initial state start the integrator
  compute_accelerations(w_.s.step);
  auto ch = channels();
  integ_->init(ch, dt_);
}

bool Simulation::driven() const { return w_.scene.drive.kind != DriveKind::None; }

std::vector<Channel> Simulation::channels() {
  State& s = w_.s;
  std::vector<Channel> ch{{s.x, s.vx, s.ax}};
  if (w_.box != BoxKind::Ring1D) ch.push_back({s.y, s.vy, s.ay});
  if (w_.rotation) ch.push_back({s.th, s.w, s.aw});
  return ch;
}

// broad phase → narrow phase and laws → body forces → accelerations at the current state
void Simulation::compute_accelerations(std::int64_t index) {
  const std::size_t n = w_.size();
  broad_->update(w_, candidates_);
  forces_.reset(n);
  stats_ = model_.evaluate(w_, candidates_, contacts_, forces_, dt_);
  gravity_ = gravity_at(w_.scene.drive, w_.s.t);
  State& s = w_.s;
  for (std::size_t i = 0; i < n; ++i) {
    s.ax[i] = forces_.fx[i] * w_.inv_mass[i] + gravity_.x;
    s.ay[i] = forces_.fy[i] * w_.inv_mass[i] + gravity_.y;
    s.aw[i] = forces_.tq[i] * w_.inv_inertia[i];
  }
  if (w_.scene.drive.kind == DriveKind::RandomForce)
    add_random_force(w_, w_.scene.prep.seed, index, w_.scene.drive.D, dt_, s.ax, s.ay);
}

void Simulation::step() {
  auto ch = channels();
  // predict positions and velocities at t + Δt, evaluate forces there, correct
  integ_->predict(ch, dt_);
  w_.s.t = static_cast<double>(w_.s.step + 1) * dt_;
  compute_accelerations(w_.s.step + 1);
  integ_->correct(ch, dt_);
  ++w_.s.step;
  // 2D drift control: remove the centre-of-mass velocity every K steps
  const DriveSpec& d = w_.scene.drive;
  if (d.kind == DriveKind::RandomForce && w_.box != BoxKind::Ring1D && d.com_removal_every > 0 &&
      w_.s.step % d.com_removal_every == 0)
    remove_com_velocity(w_);
  if (w_.scene.health.check_every > 0 && w_.s.step % w_.scene.health.check_every == 0) {
    health_check();
    w_.rewrap();  // periodic: keep |x| within 32 box lengths (image shifts fit in 8 bits)
  }
}

// non-finite state or overlaps beyond the scene threshold stop the run with a diagnosis
void Simulation::health_check() const {
  const State& s = w_.s;
  for (std::size_t i = 0; i < w_.size(); ++i) {
    if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || !std::isfinite(s.vx[i]) ||
        !std::isfinite(s.vy[i]) || !std::isfinite(s.w[i])) {
      std::ostringstream m;
      m << "non-finite position or velocity of particle " << i << " at step " << s.step
        << " (t = " << s.t << " s); dt = " << dt_ << " s is "
        << dt_ / model_.min_contact_time() << " contact times: the integration blew up, try dt <= "
        << model_.min_contact_time() / 20 << " s";
      throw HealthError(m.str());
    }
  }
  if (stats_.max_overlap_rel > w_.scene.health.max_overlap) {
    std::ostringstream m;
    m << "overlap of " << stats_.max_overlap_rel << " grain radii exceeds health.max_overlap = "
      << w_.scene.health.max_overlap << " at step " << s.step << " (t = " << s.t
      << " s): grains interpenetrate; the force law is too soft for the driving, or dt = " << dt_
      << " s is too large (contact time " << model_.min_contact_time() << " s)";
    throw HealthError(m.str());
  }
}

}  // namespace gs
