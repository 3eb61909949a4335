// the 1D ring's broad phase (SPEC 5.2): the disks keep their order along the line, so the
// only pairs that can ever touch are ring neighbours (i, i+1) and (N−1, 0). Every step emits
// exactly those N pairs (N = 2: the two sides of the one pair), each with the periodic image
// that puts the partner *ahead* of its predecessor: the forward gap x_{i+1} + s·L − x_i lies
// in [−d, L − d), so a neighbour is found even when it overlaps by up to a whole diameter and
// never through the rest of the ring. O(N), no sorting, no cells; the force loop keeps only
// the pairs that actually touch. Positions are unwrapped (World never wraps them every step).
#include <cmath>
#include <memory>

#include "broadphase/broadphase.hpp"

namespace gs {
namespace {

class RingNeighbours final : public BroadPhase {
 public:
  const char* name() const override { return "ring_neighbours"; }

  void update(const World& w, std::vector<PairKey>& out) override {
    out.clear();
    const std::size_t n = w.size();
    if (n < 2) return;
    const double L = w.Lx;
    // the image s of `ahead` that makes it the forward neighbour of `behind`
    auto forward_shift = [&](std::size_t behind, std::size_t ahead) {
      const double gap = w.s.x[ahead] - w.s.x[behind];
      const double dij = w.radius[behind] + w.radius[ahead];
      return static_cast<int>(std::ceil((-dij - gap) / L));
    };
    out.reserve(n);
    // ascending keys: (0, 1), the closing pair (0, N−1), then (1, 2) … (N−2, N−1). In the
    // closing pair 0 is the forward neighbour of N−1 (shift s), so N−1 seen from 0 is at −s
    const auto last = static_cast<std::uint32_t>(n - 1);
    const PairKey first = make_key(0, 1, make_image(forward_shift(0, 1), 0));
    const PairKey closing = make_key(0, last, make_image(-forward_shift(n - 1, 0), 0));
    if (n == 2 && closing < first) {
      out.push_back(closing);
      out.push_back(first);
    } else {
      out.push_back(first);
      if (closing != first) out.push_back(closing);
    }
    for (std::size_t i = 1; i + 1 < n; ++i)
      out.push_back(make_key(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i + 1),
                             make_image(forward_shift(i, i + 1), 0)));
  }
};

}  // namespace

/// the ring-neighbour broad phase (select it for BoxKind::Ring1D in make_broadphase)
std::unique_ptr<BroadPhase> make_ring_neighbours() { return std::make_unique<RingNeighbours>(); }

}  // namespace gs
