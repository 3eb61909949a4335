// the 1D ring's broad phase (docs/physics.md §5.2): the disks keep their order along the line, so
// the only pairs that can ever touch are ring neighbours (i, i+1) and (N−1, 0). Every step emits
// exactly those N pairs (N = 2: the two sides of the one pair), each with the periodic image
// that puts the partner *ahead* of its predecessor: the forward gap x_{i+1} + s·L − x_i lies
// in [−d, L − d), so a neighbour is found even when it overlaps by up to a whole diameter and
// never through the rest of the ring. O(N) without sorting or cells: each pair's shift is kept
// and only recomputed when its gap leaves that window (after World::rewrap moved a particle),
// so a step costs one multiply-add and two comparisons per particle plus a copy of the keys.
// The force loop keeps only the pairs that actually touch.
#include <cmath>
#include <memory>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "broadphase/broadphase.hpp"

namespace gs {
namespace {

class RingNeighbours final : public BroadPhase {
 public:
  const char* name() const override { return "ring_neighbours"; }

  using BroadPhase::update;
  const std::vector<PairKey>& update(const World& w, const ThreadTeam&) override {
    const std::size_t n = w.size();
    if (n < 2) {
      if (!keys_.empty()) new_generation();
      keys_.clear();
      shift_.clear();
      return keys_;
    }
    const double L = w.Lx;
    // pair k links `behind` = k and `ahead` = k + 1 (the last one: N−1 → 0); its shift is
    // kept from step to step and recomputed only when the forward gap leaves [−d, L − d)
    if (shift_.size() != n) {
      shift_.assign(n, 0);
      stale_ = true;
      for (std::size_t k = 0; k < n; ++k) shift_[k] = forward_shift(w, k, (k + 1) % n, L);
    }
    // first a branch-free pass that only asks whether any gap left its window (it vectorises;
    // almost every step the answer is no), then the fix-up where one did
    const double* x = w.s.x.data();
    const double* r = w.radius.data();
    const int* sh = shift_.data();
    bool out = false;
    std::size_t k = 0;
#if defined(__SSE2__)
    {
      // two pairs at a time (the same operations per lane as the loop below)
      const __m128d vl = _mm_set1_pd(L), sign = _mm_set1_pd(-0.0);
      __m128d any = _mm_setzero_pd();
      for (; k + 3 <= n; k += 2) {
        const __m128d dij = _mm_add_pd(_mm_loadu_pd(r + k), _mm_loadu_pd(r + k + 1));
        const __m128i s2 = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(sh + k));
        const __m128d gap =
            _mm_sub_pd(_mm_add_pd(_mm_loadu_pd(x + k + 1), _mm_mul_pd(_mm_cvtepi32_pd(s2), vl)),
                       _mm_loadu_pd(x + k));
        any = _mm_or_pd(any, _mm_or_pd(_mm_cmplt_pd(gap, _mm_xor_pd(dij, sign)),
                                       _mm_cmpge_pd(gap, _mm_sub_pd(vl, dij))));
      }
      out = _mm_movemask_pd(any) != 0;
    }
#endif
    for (; k + 1 < n; ++k) {
      const double dij = r[k] + r[k + 1];
      const double gap = x[k + 1] + sh[k] * L - x[k];
      out |= (gap < -dij) | (gap >= L - dij);
    }
    if (out || !in_window(w, n - 1, 0, L)) {
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t a = k + 1 == n ? 0 : k + 1;
        if (!in_window(w, k, a, L)) {
          shift_[k] = forward_shift(w, k, a, L);
          stale_ = true;
        }
      }
    }
    if (stale_) {
      build(n);
      new_generation();
    }
    return keys_;
  }

 private:
  // does pair k = (behind, ahead) still have its forward gap in [−d, L − d) with its shift?
  bool in_window(const World& w, std::size_t behind, std::size_t ahead, double L) const {
    const double dij = w.radius[behind] + w.radius[ahead];
    const double gap = w.s.x[ahead] + shift_[behind] * L - w.s.x[behind];
    return !(gap < -dij || gap >= L - dij);
  }

  // the image s of `ahead` that makes it the forward neighbour of `behind`
  static int forward_shift(const World& w, std::size_t behind, std::size_t ahead, double L) {
    const double gap = w.s.x[ahead] - w.s.x[behind];
    const double dij = w.radius[behind] + w.radius[ahead];
    return static_cast<int>(std::ceil((-dij - gap) / L));
  }

  // ascending keys: (0, 1), the closing pair (0, N−1), then (1, 2) … (N−2, N−1). In the
  // closing pair 0 is the forward neighbour of N−1 (shift s), so N−1 seen from 0 is at −s
  void build(std::size_t n) {
    keys_.clear();
    const auto last = static_cast<std::uint32_t>(n - 1);
    const PairKey first = make_key(0, 1, make_image(shift_[0], 0));
    const PairKey closing = make_key(0, last, make_image(-shift_[n - 1], 0));
    if (n == 2 && closing < first) {
      keys_.push_back(closing);
      keys_.push_back(first);
    } else {
      keys_.push_back(first);
      if (closing != first) keys_.push_back(closing);
    }
    for (std::size_t i = 1; i + 1 < n; ++i)
      keys_.push_back(make_key(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i + 1),
                               make_image(shift_[i], 0)));
    stale_ = false;
  }

  std::vector<int> shift_;     ///< image shift of each neighbour pair, box lengths
  std::vector<PairKey> keys_;  ///< the keys for the current shifts, ascending
  bool stale_ = true;          ///< keys_ must be rebuilt
};

}  // namespace

/// the ring-neighbour broad phase (select it for BoxKind::Ring1D in make_broadphase)
std::unique_ptr<BroadPhase> make_ring_neighbours() { return std::make_unique<RingNeighbours>(); }

}  // namespace gs
