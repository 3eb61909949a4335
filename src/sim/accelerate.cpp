// the accelerate stage and the kick stage (sim/stages.hpp): each particle's acceleration from
// its contact force, gravity and the random force; for disks under velocity Verlet, the kick
// and the next step's prediction in the same pass over each block
#include <algorithm>
#include <atomic>
#include <cmath>
#include <type_traits>

#include "core/parallel.hpp"
#include "drive/random_force.hpp"
#include "integrate/range_stepping.hpp"
#include "integrate/vv_kernel.hpp"
#include "sim/stages.hpp"

namespace gs {
namespace {

// what the acceleration pass reads and writes, as plain arrays
struct AccelArrays {
  const double *fx, *fy, *tq, *inv_mass, *inv_inertia, *mass;
  const std::uint64_t* keys;
  double *ax, *ay, *alpha;
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
      if constexpr (kSpin) a.alpha[i] = a.tq[i] * a.inv_inertia[i];
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
    double vk = vv_kick_dof(v[k], an[k], a[k], c_new, c_old);
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
// of rare branches, and a kick inside it would run at its pace); ahead, with
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
void accelerate_ring_noise(const ThreadTeam& team, const AccelArrays& a, std::size_t n, bool kick,
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
  parallel_ranges(team, n, kParallelMinCheap, [&](std::size_t b, std::size_t e) {
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

// the acceleration pass's arrays over the parts (the force buffer sized for them); `form`,
// `ahead`, `skin`: the fused kick's
AccelArrays accel_arrays(const StepParts& p, std::int64_t index, const KickForm& form = {},
                         bool ahead = false, BroadPhase::SkinTest skin = {}) {
  World& w = p.w;
  State& s = w.s;
  const std::size_t n = w.size();
  const bool noise = p.drive.kind == DriveKind::RandomForce;
  p.forces.tq.resize(w.polygons() ? n : 0);  // evaluate() sizes them too, maybe later
  p.forces.fx.resize(n);
  p.forces.fy.resize(n);
  return {p.forces.fx.data(),
          p.forces.fy.data(),
          p.forces.tq.data(),
          w.inv_mass.data(),
          w.inv_inertia.data(),
          w.mass.data(),
          noise ? p.noise_keys.data() : nullptr,
          s.ax.data(),
          s.ay.data(),
          s.alpha.data(),
          s.vx.data(),
          s.vy.data(),
          form.new_frac * p.dt,
          form.old_frac * p.dt,
          s.x.data(),
          s.y.data(),
          p.dt,
          ahead,
          form.predict_half,
          n >= kPrefetchFrom,
          skin,
          p.gravity,
          noise ? std::sqrt(2.0 * p.drive.D / p.dt) : 0.0,  // T.2.16
          index};
}

// body(noise, ring, spin) with the scene's three answers as compile-time constants: the
// acceleration loops are free of the branches the other cases need
template <class Body>
void dispatch(const StepParts& p, Body&& body) {
  using T = std::true_type;
  using F = std::false_type;
  const bool noise = p.drive.kind == DriveKind::RandomForce;
  const bool ring = p.w.box == BoxKind::Ring1D;  // x only: no ay (and no torques, disks)
  const bool spin = p.w.polygons();              // polygons: contact torques
  if (noise) {
    if (ring)
      body(T{}, T{}, F{});
    else if (spin)
      body(T{}, F{}, T{});
    else
      body(T{}, F{}, F{});
  } else {
    if (ring)
      body(F{}, T{}, F{});
    else if (spin)
      body(F{}, F{}, T{});
    else
      body(F{}, F{}, F{});
  }
}

// the accelerations of a pass (the force buffer's) and of its ranges
class AccelerateStage final : public StepStage {
 public:
  Stage id() const override { return Stage::Accelerate; }
  bool runs(const StepContext&) const override { return true; }
  bool by_range(const StepContext& c) const override { return !ring_noise(c.p()); }
  void prepare(StepContext& c) override { a_ = accel_arrays(c.p(), c.index); }
  void pass(StepContext& c) override {
    const StepParts& p = c.p();
    if (ring_noise(p)) {
      accelerate_ring_noise(p.team, a_, p.w.size(), false, block_sums_, pre_);
      return;
    }
    parallel_ranges(p.team, p.w.size(), kParallelMinCheap,
                    [&](std::size_t b, std::size_t e) { range(c, b, e); });
  }
  void range(StepContext& c, std::size_t b, std::size_t e) override {
    dispatch(c.p(), [&](auto nz, auto rg, auto sp) {
      constexpr bool kNz = decltype(nz)::value, kRg = decltype(rg)::value;
      constexpr bool kSp = decltype(sp)::value;
      if constexpr (!(kNz && kRg)) accelerate<kNz, kRg, kSp>(a_, b, e);
    });
  }

 private:
  AccelArrays a_{};
  std::vector<double> block_sums_, pre_;  ///< the ring's noise: kicks per block, a before the mean
};

// the accelerations and velocity Verlet's kick in one pass over each block of disks; run back
// to back, the next step's prediction too, and for disks in a plane the broad phase's
// displacement test of the predicted positions, on lines the pass holds (not by update())
class KickStage final : public StepStage {
 public:
  Stage id() const override { return Stage::Kick; }
  bool runs(const StepContext&) const override { return true; }
  bool by_range(const StepContext& c) const override { return !ring_noise(c.p()); }
  void prepare(StepContext& c) override {
    const StepParts& p = c.p();
    p.integ.ranges().check_correct(c.ch, p.dt);  // what correct() would throw, thrown here
    skin_ = {};
    if (c.ahead && p.w.box != BoxKind::Ring1D) skin_ = p.broad.skin_test();
    if (skin_.n != p.w.size()) skin_ = {};
    a_ = accel_arrays(p, c.index, *p.integ.ranges().kick_form(), c.ahead, skin_);
    moved_.store(false, std::memory_order_relaxed);
  }
  void pass(StepContext& c) override {
    const StepParts& p = c.p();
    if (ring_noise(p)) {
      accelerate_ring_noise(p.team, a_, p.w.size(), true, block_sums_, pre_);
      return;
    }
    parallel_ranges(p.team, p.w.size(), kParallelMinCheap,
                    [&](std::size_t b, std::size_t e) { range(c, b, e); });
  }
  void range(StepContext& c, std::size_t b, std::size_t e) override {
    dispatch(c.p(), [&](auto nz, auto rg, auto sp) {
      constexpr bool kNz = decltype(nz)::value, kRg = decltype(rg)::value;
      constexpr bool kSp = decltype(sp)::value;
      if constexpr (!kSp && !(kNz && kRg)) {
        if (accelerate_kick<kNz, kRg>(a_, b, e)) moved_.store(true, std::memory_order_relaxed);
      }
    });
  }
  void finish(StepContext& c) override {
    if (skin_.x0 != nullptr) c.p().broad.set_moved(moved_.load());
  }

 private:
  AccelArrays a_{};
  BroadPhase::SkinTest skin_;
  std::atomic<bool> moved_{false};        ///< an OR: the same answer whatever the thread count
  std::vector<double> block_sums_, pre_;  ///< the ring's noise: kicks per block, a before the mean
};

}  // namespace

bool ring_noise(const StepParts& p) {
  return p.w.box == BoxKind::Ring1D && p.drive.kind == DriveKind::RandomForce;
}

bool kick_possible(const StepParts& p) {
  return !p.w.polygons() && p.integ.ranges().kick_form().has_value();
}

std::unique_ptr<StepStage> make_accelerate_stage() { return std::make_unique<AccelerateStage>(); }
std::unique_ptr<StepStage> make_kick_stage() { return std::make_unique<KickStage>(); }

}  // namespace gs
