#include "sim/simulation.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>
#include <type_traits>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "drive/random_force.hpp"
#include "drive/schedule.hpp"
#include "integrate/range_stepping.hpp"
#include "integrate/schemes.hpp"

namespace gs {

namespace {

// a stage of the Simulation's own (the drive, what runs between steps): a whole pass
class OwnStage final : public StepStage {
 public:
  using Runs = bool (*)(Simulation&, const StepContext&);
  using Pass = void (*)(Simulation&, StepContext&);
  OwnStage(Stage id, Runs runs, Pass pass) : id_(id), runs_(runs), pass_(pass) {}
  Stage id() const override { return id_; }
  bool runs(const StepContext& c) const override { return runs_(c.sim, c); }
  void pass(StepContext& c) override { pass_(c.sim, c); }

 private:
  Stage id_;
  Runs runs_;
  Pass pass_;
};

// velocity Verlet corrects disks by the kick an executor may apply inside its force pass, and
// polygons from the half-step velocity
IntegratorSettings integrator_settings(const SimSettings& s, const World& w) {
  return {s.integrator, w.polygons() ? VerletCorrection::HalfStepVelocity : VerletCorrection::Kick};
}

}  // namespace

Simulation::Simulation(World w, const SimSettings& settings, BroadPhaseKind bp)
    : settings_(settings),
      w_(std::move(w)),
      dt_(settings_.dt),
      broad_kind_(bp == BroadPhaseKind::Auto ? settings_.broad_phase : bp),
      broad_(make_broadphase(broad_kind_, w_)),
      model_(w_, settings_.contact),
      integ_(make_integrator(integrator_settings(settings_, w_))) {
  if (w_.id.size() != w_.size()) {  // a World assembled without add_particle: labels = slots
    w_.id.resize(w_.size());
    for (std::size_t k = 0; k < w_.size(); ++k) w_.id[k] = static_cast<std::uint32_t>(k);
  }
  sort_every_ = resolved_sort_every(w_, settings_.sort_every);
  sort_trigger_ = Trigger::every_steps(sort_every_);
  const DriveSpec& d = settings_.drive;
  if (d.kind == DriveKind::RandomForce && w_.box != BoxKind::Ring1D)
    drift_trigger_ = Trigger::every_steps(d.com_removal_every);
  health_trigger_ = Trigger::every_steps(settings_.health.check_every);
  // a step: what runs between steps (the sort), the drive, the physics, the constraints
  stages_.push_back(std::make_unique<OwnStage>(
      Stage::Health,
      [](Simulation& sim, const StepContext& c) {
        return !c.start && sim.sorts_before(sim.w_.s.step);
      },
      [](Simulation& sim, StepContext& c) {
        sim.sort_particles();  // slots in cell order: the broad phase and the arrays anew
        c.parts.emplace(sim.parts());
        c.ch = sim.channels();
      }));
  stages_.push_back(std::make_unique<OwnStage>(
      Stage::Drive, [](Simulation&, const StepContext&) { return true; },
      [](Simulation& sim, StepContext& c) {
        // the step ends at t + Δt: the drive of that moment (the start: of the moment)
        if (!c.start) sim.w_.s.t = static_cast<double>(sim.w_.s.step + 1) * sim.dt_;
        sim.drive();
      }));
  stages_.push_back(make_predict_stage());
  stages_.push_back(make_broad_phase_stage());
  stages_.push_back(make_pairs_stage());
  stages_.push_back(make_accelerate_stage());
  stages_.push_back(make_correct_stage());
  stages_.push_back(make_predict_next_stage());
  stages_.push_back(make_place_next_stage());
  stages_.push_back(std::make_unique<OwnStage>(
      Stage::Health, [](Simulation&, const StepContext& c) { return !c.start; },
      [](Simulation& sim, StepContext&) { sim.constrain(); }));
  // forces at the initial state start the integrator
  evaluate_start();
  auto ch = channels();
  integ_->init(ch, dt_);
  take_energy_yardstick();
}

StepContext Simulation::context(bool start) {
  StepContext c{*this};
  c.parts.emplace(parts());
  c.ch = channels();
  c.start = start;
  c.index = start ? w_.s.step : w_.s.step + 1;
  c.trace = trace_;
  return c;
}

void Simulation::evaluate_start() {
  StepContext c = context(true);
  exec_->run(stages_, c, nullptr);
}

// the energy yardstick of the blow-up check: 5% of the start's kinetic + elastic energy, or of
// lifting every grain by one radius, whichever is larger
void Simulation::take_energy_yardstick() {
  energy_ref_ = mechanical_energy();
  double lift = 0.0;
  for (std::size_t i = 0; i < w_.size(); ++i) lift += w_.mass[i] * norm(gravity_) * w_.radius[i];
  energy_slack_ = 0.05 * std::max(w_.kinetic_energy(), lift) + 1e-300;
}

bool Simulation::conservative_drive() const {
  return settings_.drive.kind == DriveKind::None || settings_.drive.kind == DriveKind::Gravity;
}

double Simulation::mechanical_energy() const {
  double e = w_.kinetic_energy();
  // contact elastic energy: exact for the linear spring; the overlap-area law has no closed
  // form (A(δ) depends on the path), so polygons count it as 0 — a lower bound, which keeps the
  // check one-sided: kinetic + gravitational energy can never exceed the start's total
  if (!w_.polygons()) {
    const std::size_t n = w_.size(), walls = w_.species.size();
    for (const ContactRecord& c : contacts_.records) {
      const std::uint32_t i = key_i(c.key), j = key_j(c.key);
      // the pair's spring as the law has it (a wall's index is the species count)
      const double ks = model_.disk_stiffness(w_.sp[i], j >= n ? walls : w_.sp[j]);
      e += 0.5 * ks * c.overlap * c.overlap;
    }
  }
  for (std::size_t i = 0; i < w_.size(); ++i)
    e -= w_.mass[i] * (gravity_.x * w_.s.x[i] + gravity_.y * w_.s.y[i]);
  return e;
}

bool Simulation::driven() const { return settings_.drive.kind != DriveKind::None; }

std::vector<Channel> Simulation::channels() {
  State& s = w_.s;
  std::vector<Channel> ch{{s.x, s.vx, s.ax}};
  if (w_.box != BoxKind::Ring1D) ch.push_back({s.y, s.vy, s.ay});
  if (w_.rotation) ch.push_back({s.th, s.omega, s.alpha});
  return ch;
}

// the drive at the current time: gravity of the moment, the random force's streams
void Simulation::drive() {
  gravity_ = gravity_at(settings_.drive, w_.clock_origin, w_.s.t);
  const std::size_t n = w_.size();
  const bool noise = settings_.drive.kind == DriveKind::RandomForce;
  if (noise && noise_keys_.size() != n) {  // each particle's stream follows its label
    const std::vector<std::uint64_t> by_label = random_force_keys(settings_.seed, n);
    noise_keys_.resize(n);
    for (std::size_t k = 0; k < n; ++k) noise_keys_[k] = by_label[w_.id[k]];
  }
}

StepParts Simulation::parts() const {
  // the executor writes the parts; a const Simulation asks it only what it would do
  auto& self = const_cast<Simulation&>(*this);
  return {self.w_, *broad_,    self.model_, self.contacts_, self.forces_, self.stats_,
          *integ_, self.team_, noise_keys_, gravity_,       dt_,          settings_.drive};
}

void Simulation::run(std::int64_t n) {
  for (std::int64_t k = 0; k < n; ++k) advance(k + 1 < n);
}

// may step `from`'s correction predict the next step? Only inside run() (nothing outside sees
// the state between the two steps), and where nothing between the steps reads or edits the
// state: no drift removal, health check or wrapping after `from`, no sort before the next
// step (the executor decides whether it can)
bool Simulation::may_predict_ahead(std::int64_t from) const {
  const std::int64_t next = from + 1;  // the step count once `from` is done
  return !removes_drift_after(next) && !checks_health_after(next) && !sorts_before(next);
}

bool Simulation::removes_drift_after(std::int64_t step) const {
  return drift_trigger_.at_step(step);
}

bool Simulation::checks_health_after(std::int64_t step) const {
  return health_trigger_.at_step(step);
}

bool Simulation::sorts_before(std::int64_t step) const {
  return step > 0 && sort_trigger_.at_step(step);
}

// one step: the list of stages, run by the executor, which charges each stage's wall time to
// profile()
void Simulation::advance(bool then_predict) {
  ++profile_.steps;
  StepContext c = context(false);
  c.may_ahead = then_predict && may_predict_ahead(w_.s.step);
  StageClock clock(profile_, w_.s.step);
  exec_->run(stages_, c, &clock);
}

// the step is done: drift removal every K steps, the periodic health check
void Simulation::constrain() {
  ++w_.s.step;
  if (removes_drift_after(w_.s.step)) remove_com_velocity(w_);
  if (checks_health_after(w_.s.step)) {
    health_check();
    w_.rewrap();  // periodic: keep |x| within 32 box lengths (image shifts fit in 8 bits)
  }
}

// every grain at rest where it is; the channels' velocities through the integrator (which keeps
// its history consistent), the rest (ω of grains that do not rotate) directly
void Simulation::zero_velocities() {
  auto ch = channels();
  integ_->zero_velocities(ch);
  State& s = w_.s;
  std::fill(s.vx.begin(), s.vx.end(), 0.0);
  std::fill(s.vy.begin(), s.vy.end(), 0.0);
  std::fill(s.omega.begin(), s.omega.end(), 0.0);
}

// non-finite state, overlaps beyond the scene threshold, or energy growing without driving
// input stop the run with a diagnosis
void Simulation::check_finite() const {
  const State& s = w_.s;
  for (std::size_t i = 0; i < w_.size(); ++i) {
    if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || !std::isfinite(s.vx[i]) ||
        !std::isfinite(s.vy[i]) || !std::isfinite(s.omega[i])) {
      std::ostringstream m;
      m << "non-finite position or velocity of particle " << w_.id[i] << " at step " << s.step
        << " (t = " << s.t << " s); ";
      if (s.step <= 1)
        // no integration error grows in one step: the scene's numbers overflow by themselves
        m << "already at the first step: an initial velocity, the gravity or a force is too "
             "large for double precision (check [[preparation.particle]] velocities and the "
             "[drive] keys)";
      else
        m << "dt = " << dt_ << " s is " << dt_ / model_.min_contact_time()
          << " contact times: the integration blew up, try dt <= " << model_.min_contact_time() / 20
          << " s";
      throw HealthError(m.str());
    }
  }
}

void Simulation::health_check() {
  check_finite();
  const State& s = w_.s;
  if (stats_.max_overlap_rel > settings_.health.max_overlap) {
    std::ostringstream m;
    m << "overlap of " << stats_.max_overlap_rel
      << " grain radii exceeds health.max_overlap = " << settings_.health.max_overlap << " at step "
      << s.step << " (t = " << s.t
      << " s): grains interpenetrate; the force law is too soft for the driving, or dt = " << dt_
      << " s is too large (contact time " << model_.min_contact_time() << " s)";
    throw HealthError(m.str());
  }
  if (conservative_drive()) {
    const double e = mechanical_energy();
    if (e > energy_ref_ + energy_slack_) {
      // find the fastest particle: the likely seat of the instability
      std::size_t worst = 0;
      double v2 = -1;
      for (std::size_t i = 0; i < w_.size(); ++i) {
        const double q = s.vx[i] * s.vx[i] + s.vy[i] * s.vy[i];
        if (q > v2) {
          v2 = q;
          worst = i;
        }
      }
      std::ostringstream m;
      m << "mechanical energy grew from " << energy_ref_ << " J to " << e
        << " J without driving input at step " << s.step << " (t = " << s.t
        << " s); fastest particle " << w_.id[worst] << " at " << std::sqrt(v2)
        << " m/s. The integration is unstable: dt = " << dt_ << " s is "
        << dt_ / model_.min_contact_time()
        << " contact times; try dt <= " << model_.min_contact_time() / 20 << " s";
      throw HealthError(m.str());
    }
    // dissipation only lowers the yardstick (only where the energy is exact)
    if (!w_.polygons()) energy_ref_ = std::min(energy_ref_, e);
  }
}

}  // namespace gs
