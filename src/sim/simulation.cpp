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
#include "integrate/vv_kernel.hpp"

namespace gs {

Simulation::Simulation(World w) : Simulation(std::move(w), BroadPhaseKind::Auto) {}

Simulation::Simulation(World w, BroadPhaseKind bp)
    : w_(std::move(w)),
      dt_(w_.scene.integrator.dt),
      broad_kind_(bp == BroadPhaseKind::Auto ? w_.scene.integrator.broad_phase : bp),
      broad_(make_broadphase(broad_kind_, w_)),
      model_(w_),
      integ_(make_integrator(w_.scene.integrator.kind)) {
  if (w_.id.size() != w_.size()) {  // a World assembled without add_particle: labels = slots
    w_.id.resize(w_.size());
    for (std::size_t k = 0; k < w_.size(); ++k) w_.id[k] = static_cast<std::uint32_t>(k);
  }
  sort_every_ = resolved_sort_every(w_);
  set_kick_fusion(true);
  // forces at the initial state start the integrator
  drive();
  compute_accelerations(w_.s.step, broad_->update(w_));
  auto ch = channels();
  integ_->init(ch, dt_);
  // the energy yardstick of the blow-up check: 5% of the start's kinetic + elastic energy, or
  // of lifting every grain by one radius, whichever is larger
  energy_ref_ = mechanical_energy();
  double lift = 0.0;
  for (std::size_t i = 0; i < w_.size(); ++i) lift += w_.mass[i] * norm(gravity_) * w_.radius[i];
  energy_slack_ = 0.05 * std::max(w_.kinetic_energy(), lift) + 1e-300;
}

bool Simulation::conservative_drive() const {
  return w_.scene.drive.kind == DriveKind::None || w_.scene.drive.kind == DriveKind::Gravity;
}

double Simulation::mechanical_energy() const {
  double e = w_.kinetic_energy();
  // contact elastic energy: exact for the linear spring; the overlap-area law has no closed
  // form (A(δ) depends on the path), so polygons count it as 0 — a lower bound, which keeps the
  // check one-sided: kinetic + gravitational energy can never exceed the start's total
  if (!w_.polygons()) {
    for (const ContactRecord& c : contacts_.records) {
      const MaterialSpec& m = w_.materials[w_.species[w_.sp[key_i(c.key)]].material];
      e += 0.5 * m.ks * c.overlap * c.overlap;
    }
  }
  for (std::size_t i = 0; i < w_.size(); ++i)
    e -= w_.mass[i] * (gravity_.x * w_.s.x[i] + gravity_.y * w_.s.y[i]);
  return e;
}

// disks (x and y channels; polygons keep correct()): the integrator's kick, where it has one,
// inside the acceleration pass
void Simulation::set_kick_fusion(bool on) {
  const bool want = on && !w_.polygons();
  fused_ = integ_->fuse_kick(want, kick_form_) && want;
}

bool Simulation::driven() const { return w_.scene.drive.kind != DriveKind::None; }

std::vector<Channel> Simulation::channels() {
  State& s = w_.s;
  std::vector<Channel> ch{{s.x, s.vx, s.ax}};
  if (w_.box != BoxKind::Ring1D) ch.push_back({s.y, s.vy, s.ay});
  if (w_.rotation) ch.push_back({s.th, s.w, s.aw});
  return ch;
}

namespace {

// what the acceleration pass reads and writes, as plain arrays
struct AccelArrays {
  const double *fx, *fy, *tq, *inv_mass, *inv_inertia, *mass;
  const std::uint64_t* keys;
  double *ax, *ay, *aw;
  double *vx, *vy;      ///< the kick's velocities (fused)
  double c_new, c_old;  ///< the kick v += c_new·a_{n+1} − c_old·a_n, s (fused)
  double *qx, *qy;      ///< the positions the next step's prediction advances (ahead)
  double dt;            ///< Δt, s
  bool ahead;           ///< after the kick, the next step's prediction (vv_predict_dof)
  bool half;            ///< ... of the half-step velocity (KickForm::predict_half)
  bool prefetch;        ///< state beyond the caches: the kick's lines fetched during the noise
  BroadPhase::SkinTest skin;  ///< ahead: the broad phase's displacement test, made here (x0)
  Vec2 g;
  double sigma;
  std::int64_t index;
};

// from this many particles on the state outgrows the L2 cache (≈ 100 B per disk): the fused
// kick fetches its lines ahead
constexpr std::size_t kPrefetchFrom = 32768;

// accelerations of particles [b, e): contact force, gravity and the random kick of the step;
// returns Σ m·kick over the range (the ring's momentum kick, for its mean)
template <bool kNoise, bool kRing, bool kSpin>
double accelerate(const AccelArrays& a, std::size_t b, std::size_t e) {
  // the arrays and constants as restrict locals: a store into one output may then not be
  // taken to change an input or a constant, which would be reloaded for every particle
  const double* __restrict fx = a.fx;
  const double* __restrict fy = a.fy;
  const double* __restrict im_ = a.inv_mass;
  const std::uint64_t* __restrict keys = a.keys;
  double* __restrict axo = a.ax;
  double* __restrict ayo = a.ay;
  const double gx = a.g.x, gy = a.g.y, sigma = a.sigma;
  const std::int64_t index = a.index;
  double kick_sum = 0.0;
  const ZigguratTables& zt = ZigguratTables::get();
  // the normals of a sub-block first, its common draws in one pass without branches
  // (noise_normals_block): with the rare rejections inline this loop spilled registers and
  // overlapped few particles' draws
  constexpr std::size_t kSub = 64;
  alignas(64) double z0s[kNoise ? kSub : 1], z1s[kNoise ? kSub : 1];
  const std::size_t sub = kNoise ? kSub : e - b;  // without noise: one block
  for (std::size_t k = b; k < e; k += sub) {
    const std::size_t m = std::min(sub, e - k);
    if constexpr (kNoise) noise_normals_block(zt, keys + k, index, kRing, m, z0s, z1s);
    for (std::size_t q = 0; q < m; ++q) {
      const std::size_t i = k + q;
      const double im = im_[i];
      double ax = fx[i] * im + gx;
      double ay = kRing ? 0.0 : fy[i] * im + gy;
      if constexpr (kNoise) {
        const double ex = sigma * z0s[q] * im;
        ax += ex;
        if constexpr (kRing)
          kick_sum += ex * a.mass[i];
        else
          ay += sigma * z1s[q] * im;
      }
      axo[i] = ax;
      if constexpr (!kRing) ayo[i] = ay;
      if constexpr (kSpin) a.aw[i] = a.tq[i] * a.inv_inertia[i];
    }
  }
  return kick_sum;
}

// the integrator's kick v += c_new·a_new − c_old·a_old, then a ← a_new, over one channel's
// [0, m) (vectorises); kAhead: then the next step's prediction of the same DOFs, as
// VelocityVerlet::predict would make it (Simulation::run: one pass over the state less)
template <bool kAhead, bool kHalf>
void kick_block(std::size_t m, double c_new, double c_old, double dt, const double* __restrict an,
                double* __restrict a, double* __restrict v, double* __restrict q) {
  for (std::size_t k = 0; k < m; ++k) {
    double vk = v[k] + an[k] * c_new - a[k] * c_old;
    a[k] = an[k];
    if constexpr (kAhead) {
      double qk = q[k];
      vv_predict_dof<kHalf>(dt, an[k], qk, vk);
      q[k] = qk;
    }
    v[k] = vk;
  }
}
void kick_block(const AccelArrays& a, std::size_t m, const double* an, double* acc, double* v,
                double* q) {
  if (!a.ahead)
    kick_block<false, false>(m, a.c_new, a.c_old, a.dt, an, acc, v, q);
  else if (a.half)
    kick_block<true, true>(m, a.c_new, a.c_old, a.dt, an, acc, v, q);
  else
    kick_block<true, false>(m, a.c_new, a.c_old, a.dt, an, acc, v, q);
}

// has a particle of the block [k, k + m) moved beyond the broad phase's skin? (a.skin, ahead:
// the positions just predicted, still in the L1 cache)
bool skin_moved_block(const AccelArrays& a, std::size_t k, std::size_t m) {
  const double* __restrict x = a.qx + k;
  const double* __restrict y = a.qy + k;
  const double* __restrict x0 = a.skin.x0 + k;
  const double* __restrict y0 = a.skin.y0 + k;
  const double lim2 = a.skin.lim2;
  int moved = 0;
  for (std::size_t q = 0; q < m; ++q) moved |= skin_moved(x[q] - x0[q], y[q] - y0[q], lim2);
  return moved != 0;
}

// disks with the fused kick: the accelerations of a block into a buffer that stays in the L1
// cache, then the kick over the block, which still sees a_n (the noise loop is scalar and full
// of rare branches; the kick inside it cost 13% more than this at 10⁴ disks); ahead, with
// a.skin, the broad phase's displacement test of the predicted block too (returned: has any
// particle of [b, e) moved beyond the skin?)
template <bool kNoise, bool kRing>
bool accelerate_kick(const AccelArrays& a, std::size_t b, std::size_t e) {
  const bool test = a.skin.x0 != nullptr;  // given only ahead, disks in a plane
  bool moved = false;
  constexpr std::size_t kBlock = 256, kSub = 32;
  alignas(64) double bx[kBlock], by[kBlock];
  AccelArrays to = a;  // particle k + q of `a` is q of `to`
  to.ax = bx;
  to.ay = by;
  for (std::size_t k = b; k < e; k += kBlock) {
    const std::size_t m = std::min(kBlock, e - k);
    to.fx = a.fx + k;
    to.fy = a.fy + k;
    to.inv_mass = a.inv_mass + k;
    to.mass = a.mass + k;
    if (kNoise) to.keys = a.keys + k;
    // the kick's lines of the block are fetched while the noise is drawn (the noise loop is
    // compute bound; at 10⁶ disks the kick otherwise waits on memory)
    for (std::size_t q = 0; q < m; q += a.prefetch ? kSub : m) {
      if (!a.prefetch) {
        accelerate<kNoise, kRing, false>(to, 0, m);
        break;
      }
      accelerate<kNoise, kRing, false>(to, q, std::min(m, q + kSub));
      for (std::size_t l = k + q; l < k + std::min(m, q + kSub); l += 8) {
        __builtin_prefetch(a.ax + l, 1);
        __builtin_prefetch(a.vx + l, 1);
        if (a.ahead) __builtin_prefetch(a.qx + l, 1);
        if constexpr (!kRing) {
          __builtin_prefetch(a.ay + l, 1);
          __builtin_prefetch(a.vy + l, 1);
          if (a.ahead) __builtin_prefetch(a.qy + l, 1);
        }
        if (test) {
          __builtin_prefetch(a.skin.x0 + l);
          __builtin_prefetch(a.skin.y0 + l);
        }
      }
    }
    kick_block(a, m, bx, a.ax + k, a.vx + k, a.qx + k);
    if (!kRing) kick_block(a, m, by, a.ay + k, a.vy + k, a.qy + k);
    if (test && !moved) moved = skin_moved_block(a, k, m);
  }
  return moved;
}

// the 1D ring's accelerations with noise: the kicks' mean momentum is removed, summed over
// fixed blocks and added in block order (T.2.18), so this pass needs every particle's kick
// before any acceleration is final: the first pass writes them to `pre`, the second the
// final ones (and, `kick`, the integrator's kick while a_n is still in ax)
void accelerate_ring_noise(const AccelArrays& a, std::size_t n, bool kick,
                           std::vector<double>& block_sums, std::vector<double>& pre) {
  block_sums.assign((n + kSumBlock - 1) / kSumBlock, 0.0);
  pre.resize(n);
  AccelArrays first = a;
  first.ax = pre.data();
  parallel_chunks(n, kParallelMinCheap, kSumBlock, [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e; k += kSumBlock)
      block_sums[k / kSumBlock] =
          accelerate<true, true, false>(first, k, std::min(e, k + kSumBlock));
  });
  double mean = 0.0;
  for (double m : block_sums) mean += m;
  if (n > 0) mean /= static_cast<double>(n);
  parallel_ranges(n, kParallelMinCheap, [&](std::size_t b, std::size_t e) {
    const double* __restrict p = pre.data();
    const double* __restrict im = a.inv_mass;
    double* __restrict ax = a.ax;
    if (!kick) {
      for (std::size_t i = b; i < e; ++i) ax[i] = p[i] - mean * im[i];
      return;
    }
    // the final accelerations of [b, e) in blocks that stay in the L1 cache, each kicked (and
    // predicted, ahead) as accelerate_kick's blocks are
    constexpr std::size_t kBlock = 256;
    alignas(64) double an[kBlock];
    for (std::size_t k = b; k < e; k += kBlock) {
      const std::size_t m = std::min(kBlock, e - k);
      for (std::size_t q = 0; q < m; ++q) an[q] = p[k + q] - mean * im[k + q];
      kick_block(a, m, an, ax + k, a.vx + k, a.qx + k);
    }
  });
}

// a lap of the step's clock, where there is one
void lap(StageClock* clock, Stage s) {
  if (clock != nullptr) clock->lap(s);
}

}  // namespace

// the drive at the current time: gravity of the moment, the random force's streams
void Simulation::drive() {
  gravity_ = gravity_at(w_.scene.drive, w_.s.t);
  const std::size_t n = w_.size();
  const bool noise = w_.scene.drive.kind == DriveKind::RandomForce;
  if (noise && noise_keys_.size() != n) {  // each particle's stream follows its label
    const std::vector<std::uint64_t> by_label = random_force_keys(w_.scene.prep.seed, n);
    noise_keys_.resize(n);
    for (std::size_t k = 0; k < n; ++k) noise_keys_[k] = by_label[w_.id[k]];
  }
}

// narrow phase → laws (contact forces summed, body forces, accelerations) → correct, at the
// current (predicted) state, in one pass over the particles; `clock`: the stages' laps
void Simulation::compute_accelerations(std::int64_t index, const std::vector<PairKey>& cand,
                                       std::span<const Channel> correct, bool ahead,
                                       StageClock* clock) {
  const std::size_t n = w_.size();
  State& s = w_.s;
  const bool noise = w_.scene.drive.kind == DriveKind::RandomForce;
  const bool ring = w_.box == BoxKind::Ring1D;  // x only: no ay (and no torques, disks)
  const bool spin = w_.polygons();              // polygons: contact torques
  forces_.tq.resize(spin ? n : 0);  // evaluate() sizes the buffers too; the arrays below need them
  forces_.fx.resize(n);
  forces_.fy.resize(n);
  const bool kick = fused_ && !correct.empty();
  // ahead with the fused kick (disks in a plane): the broad phase's displacement test of the
  // predicted positions is made in the kick's pass, on lines it holds, not by update()
  BroadPhase::SkinTest skin;
  if (ahead && kick && !ring && !spin) skin = broad_->skin_test();
  if (skin.n != n) skin = {};
  const AccelArrays a{forces_.fx.data(),
                      forces_.fy.data(),
                      forces_.tq.data(),
                      w_.inv_mass.data(),
                      w_.inv_inertia.data(),
                      w_.mass.data(),
                      noise ? noise_keys_.data() : nullptr,
                      s.ax.data(),
                      s.ay.data(),
                      s.aw.data(),
                      s.vx.data(),
                      s.vy.data(),
                      kick_form_.new_frac * dt_,
                      kick_form_.old_frac * dt_,
                      s.x.data(),
                      s.y.data(),
                      dt_,
                      ahead,
                      kick_form_.predict_half,
                      n >= kPrefetchFrom,
                      skin,
                      gravity_,
                      noise ? std::sqrt(2.0 * w_.scene.drive.D / dt_) : 0.0,  // T.2.16
                      index};
  using T = std::true_type;
  using F = std::false_type;
  // each particle's acceleration from its own force: computed inside the force pass by the
  // thread that summed the force (and predicts and corrects the particle), except the 1D
  // ring's noise, whose mean kick needs every particle first. A fused kick (disks, velocity
  // Verlet) is the correction, applied where the acceleration is computed
  std::atomic<bool> moved{false};  // an OR: the same answer whatever the thread count
  if (ahead && !predicts_in_pass())
    throw std::logic_error("compute_accelerations: no prediction ahead on this path");
  auto go = [&](auto nz, auto rg, auto sp) {
    constexpr bool kNz = decltype(nz)::value, kRg = decltype(rg)::value;
    [[maybe_unused]] constexpr bool kSp = decltype(sp)::value;
    if constexpr (kNz && kRg) {
      stats_ = model_.evaluate(w_, cand, contacts_, forces_, dt_, broad_->generation(), {}, clock);
      accelerate_ring_noise(a, n, kick, kick_, ring_pre_);
      lap(clock, Stage::Laws);
      if (!correct.empty() && !kick) integ_->correct(correct, dt_);
    } else {
      auto after = [&](std::size_t b, std::size_t e) {
        StageClock* const own = team_thread() == 0 ? clock : nullptr;  // the first thread laps
        if constexpr (!kSp) {
          if (kick) {  // laws and correction in one pass over each block (counted as correct)
            if (accelerate_kick<kNz, kRg>(a, b, e)) moved.store(true, std::memory_order_relaxed);
            lap(own, Stage::Correct);
            return;
          }
        }
        accelerate<kNz, kRg, kSp>(a, b, e);
        lap(own, Stage::Laws);
        if (!correct.empty()) integ_->correct_range(correct, b, e);
        if (ahead) integ_->predict_range(correct, b, e);
        lap(own, Stage::Correct);
        if constexpr (kSp) {
          if (ahead) {  // the next step's polygons, placed while their state is at hand
            model_.place_ahead(w_, b, e);
            lap(own, Stage::NarrowPhase);
          }
        }
      };
      stats_ = model_.evaluate(w_, cand, contacts_, forces_, dt_, broad_->generation(),
                               RangeFn(after), clock);
      if (ahead && kSp) model_.placed_ahead();
      if (skin.x0 != nullptr) broad_->set_moved(moved.load());
    }
    lap(clock, Stage::Correct);
  };
  if (noise) {
    if (ring)
      go(T{}, T{}, F{});
    else if (spin)
      go(T{}, F{}, T{});
    else
      go(T{}, F{}, F{});
  } else {
    if (ring)
      go(F{}, T{}, F{});
    else if (spin)
      go(F{}, F{}, T{});
    else
      go(F{}, F{}, F{});
  }
}

void Simulation::run(std::int64_t n) {
  for (std::int64_t k = 0; k < n; ++k) advance(k + 1 < n);
}

// may step `from`'s correction predict the next step? Only inside run() (nothing outside sees
// the state between the two steps), with the fused kick (disks) or an integrator that predicts
// by ranges (Gear 6), and where nothing between the steps reads or edits the state: no drift
// removal, health check or wrapping after `from`, no sort before the next step
bool Simulation::may_predict_ahead(std::int64_t from) const {
  const std::int64_t next = from + 1;  // the step count once `from` is done
  return predicts_in_pass() && !removes_drift_after(next) && !checks_health_after(next) &&
         !sorts_before(next);
}

// the fused kick predicts (disks), or the integrator after correct_range() (Gear 6; not on the
// noisy ring, whose correction is the integrator's whole-channel correct())
bool Simulation::predicts_in_pass() const {
  const bool ring_noise =
      w_.box == BoxKind::Ring1D && w_.scene.drive.kind == DriveKind::RandomForce;
  return (fused_ && !w_.polygons()) || (integ_->predicts_by_range() && !ring_noise);
}

bool Simulation::removes_drift_after(std::int64_t step) const {
  const DriveSpec& d = w_.scene.drive;
  return d.kind == DriveKind::RandomForce && w_.box != BoxKind::Ring1D && d.com_removal_every > 0 &&
         step % d.com_removal_every == 0;
}

bool Simulation::checks_health_after(std::int64_t step) const {
  return w_.scene.health.check_every > 0 && step % w_.scene.health.check_every == 0;
}

bool Simulation::sorts_before(std::int64_t step) const {
  return sort_every_ > 0 && step > 0 && step % sort_every_ == 0;
}

// one step, stage by stage; the stages' wall times go to profile()
void Simulation::advance(bool then_predict) {
  StageClock clock(profile_);
  if (sorts_before(w_.s.step)) sort_particles();  // between steps: slots in cell order
  clock.lap(Stage::Health);
  // the step ends at t + Δt: the drive of that moment
  w_.s.t = static_cast<double>(w_.s.step + 1) * dt_;
  drive();
  clock.lap(Stage::Drive);
  // positions and velocities at t + Δt, unless the last step's correction predicted them
  auto ch = channels();
  if (ahead_)
    ++ahead_steps_;
  else
    integ_->predict(ch, dt_);
  ahead_ = false;
  integ_->check_correct(ch, dt_);  // here: nothing may throw inside the force pass
  clock.lap(Stage::Predict);
  const std::vector<PairKey>& candidates = broad_->update(w_);
  clock.lap(Stage::BroadPhase);
  // narrow phase → laws → correct: each particle corrected by the thread that summed its
  // force and, with the next step following at once, predicted for it too (`ahead`)
  const bool ahead = then_predict && may_predict_ahead(w_.s.step);
  compute_accelerations(w_.s.step + 1, candidates, ch, ahead, &clock);
  ++w_.s.step;
  ahead_ = ahead;
  // constraints and health: drift removal every K steps, the periodic health check
  if (removes_drift_after(w_.s.step)) remove_com_velocity(w_);
  if (checks_health_after(w_.s.step)) {
    health_check();
    w_.rewrap();  // periodic: keep |x| within 32 box lengths (image shifts fit in 8 bits)
  }
  clock.lap(Stage::Health);
  ++profile_.steps;
}

// every grain at rest where it is; the channels' velocities through the integrator (which keeps
// its history consistent), the rest (ω of grains that do not rotate) directly
void Simulation::zero_velocities() {
  auto ch = channels();
  integ_->zero_velocities(ch);
  State& s = w_.s;
  std::fill(s.vx.begin(), s.vx.end(), 0.0);
  std::fill(s.vy.begin(), s.vy.end(), 0.0);
  std::fill(s.w.begin(), s.w.end(), 0.0);
}

// non-finite state, overlaps beyond the scene threshold, or energy growing without driving
// input stop the run with a diagnosis
void Simulation::check_finite() const {
  const State& s = w_.s;
  for (std::size_t i = 0; i < w_.size(); ++i) {
    if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || !std::isfinite(s.vx[i]) ||
        !std::isfinite(s.vy[i]) || !std::isfinite(s.w[i])) {
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
  if (stats_.max_overlap_rel > w_.scene.health.max_overlap) {
    std::ostringstream m;
    m << "overlap of " << stats_.max_overlap_rel
      << " grain radii exceeds health.max_overlap = " << w_.scene.health.max_overlap << " at step "
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
