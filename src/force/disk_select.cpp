// the disk loops of sparse scenes: the serial loop's pass before the pairs
// (ContactModel::evaluate_serial: which candidates may touch, and the lines their evaluation
// will need), and the parallel loop's sums from the few touching pairs
#include <algorithm>
#include <limits>
#include <type_traits>

#include "force/forces.hpp"

namespace gs {

void ContactModel::find_common_radius(const World& w, std::uint64_t generation) {
  const std::size_t n = w.size();
  if (generation != 0 && generation == common_radius_generation_ && n == common_radius_n_) return;
  common_radius_generation_ = generation;  // an unknown list (0) is looked at every time
  common_radius_n_ = n;
  common_radius_ = n > 0 ? w.radius[0] : 0.0;
  for (std::size_t i = 1; i < n; ++i)
    if (w.radius[i] != common_radius_) {
      common_radius_ = std::numeric_limits<double>::quiet_NaN();
      break;
    }
}

// the candidates that disk_pair may find touching, in order, into sel_: disk pairs by the
// very test of disk_disk (same expressions, so the same decisions), wall pairs all. Where
// every disk has the same radius (find_common_radius) r_i + r_j is that radius twice, the same
// bits without the loads
std::size_t ContactModel::select_disk_pairs(const World& w, const std::vector<PairKey>& cand,
                                            std::size_t k0, std::size_t k1) {
  const auto N = static_cast<std::uint32_t>(w.size());
  const double* x = w.s.x.data();
  const double* y = w.s.y.data();
  const double* r = w.radius.data();
  sel_.resize(k1 - k0);
  std::uint32_t* sel = sel_.data();
  std::size_t m = 0;
  const double rc = common_radius_;
  auto select = [&](auto common) {
    constexpr bool kCommon = decltype(common)::value;
    auto reach = [&](std::uint32_t i, std::uint32_t j) { return kCommon ? rc + rc : r[i] + r[j]; };
    if (w.box == BoxKind::Ring1D) {
      // the ring: no walls, every y is 0 and no image is shifted in y, so d.y is exactly 0
      // and d.x alone gives disk_disk's decision (norm2(d) = d.x² + 0 to the last bit)
      for (std::size_t k = k0; k < k1; ++k) {
        const PairKey key = cand[k];
        const std::uint32_t i = key_i(key), j = key_j(key);
        const double dx = x[j] + image_sx(key_image(key)) * w.Lx - x[i];
        const double dist2 = dx * dx, rr = reach(i, j);
        sel[m] = static_cast<std::uint32_t>(k);
        m += static_cast<std::size_t>(!((dist2 >= rr * rr) | (dist2 == 0.0)));
      }
      return;
    }
    for (std::size_t k = k0; k < k1; ++k) {
      const PairKey key = cand[k];
      const std::uint32_t i = key_i(key), j = key_j(key);
      const bool wall = j >= N;
      const std::uint32_t jj = wall ? i : j;  // a wall's index is no particle: read i instead
      const std::uint32_t image = key_image(key);
      const Vec2 d =
          Vec2{x[jj] + image_sx(image) * w.Lx, y[jj] + image_sy(image) * w.Ly} - Vec2{x[i], y[i]};
      const double dist2 = norm2(d), rr = reach(i, jj);
      sel[m] = static_cast<std::uint32_t>(k);
      m += static_cast<std::size_t>(wall | !((dist2 >= rr * rr) | (dist2 == 0.0)));
    }
  };
  if (rc == rc)
    select(std::true_type{});  // not NaN: one radius
  else
    select(std::false_type{});
  return m;
}

// the lines that disk_pair and the force sum touch beyond x, y and r (which the selection has
// just read), for the block's m selected pairs: in a large dilute box they lie far apart and
// each is a cache miss, so the misses overlap instead of coming one after another
void ContactModel::prefetch_disk_pairs(const World& w, const std::vector<PairKey>& cand,
                                       std::size_t m, const ForceBuffer& f) const {
  const auto N = static_cast<std::uint32_t>(w.size());
  for (std::size_t q = 0; q < m; ++q) {
    const PairKey key = cand[sel_[q]];
    for (const std::uint32_t p : {key_i(key), key_j(key)}) {
      if (p >= N) continue;  // a wall
      __builtin_prefetch(&w.s.vx[p]);
      __builtin_prefetch(&w.s.vy[p]);
      __builtin_prefetch(&w.sp[p]);
      __builtin_prefetch(&f.fx[p], 1);
      __builtin_prefetch(&f.fy[p], 1);
    }
  }
}

// the disk forces of particles [b, e) from this step's touching pairs (compacted, in candidate
// order), from zero: for each particle the same terms in the same order as the per-particle
// index gives (its pairs in ascending candidate order), so bitwise the same. A walk over the
// few touching pairs instead of over every particle's candidates (a sparse gas: 0.44
// candidates and 0.005 contacts per disk); it reads the compacted keys, a few lines, not the
// other threads' touch flags
void ContactModel::sums_from_touching(const World& w, ForceBuffer& f, std::size_t b,
                                      std::size_t e) const {
  const auto N = static_cast<std::uint32_t>(w.size());
  std::fill(f.fx.begin() + static_cast<std::ptrdiff_t>(b),
            f.fx.begin() + static_cast<std::ptrdiff_t>(e), 0.0);
  std::fill(f.fy.begin() + static_cast<std::ptrdiff_t>(b),
            f.fy.begin() + static_cast<std::ptrdiff_t>(e), 0.0);
  for (std::size_t q = 0; q < next_.keys.size(); ++q) {
    const std::uint32_t i = key_i(next_.keys[q]), j = key_j(next_.keys[q]);
    const bool own_i = i >= b && i < e, own_j = j < N && j >= b && j < e;
    if (!own_i && !own_j) continue;
    const PairForce& r = pair_f_[touching_k_[q]];
    if (own_i) {
      f.fx[i] -= r.fx;
      f.fy[i] -= r.fy;
    }
    if (own_j) {
      f.fx[j] += r.fx;
      f.fy[j] += r.fy;
    }
  }
}

}  // namespace gs
