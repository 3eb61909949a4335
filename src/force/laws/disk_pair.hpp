// Model S's pair evaluator (docs/physics.md §3): disks by their centre distance, the linear
// spring–dashpot with optional friction, no history (force/laws/pair_evaluator.hpp). A pair is a
// distance and a few products, cheaper than a mispredicted branch, so it also offers the loop's
// sparse ways a branch-free preselection
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "contact/contact_set.hpp"
#include "contact/narrow.hpp"
#include "force/laws/disk_law.hpp"
#include "force/laws/pair_evaluator.hpp"
#include "world/world.hpp"

namespace gs {

class DiskPairEvaluator {
 public:
  static constexpr BodyKind kShape = BodyKind::Disk;
  static constexpr bool kTorque = false;  // central forces: no contact torque
  static constexpr bool kHistory = false;
  static constexpr bool kCheap = true;
  static constexpr std::size_t kChunk = 512;

  DiskPairEvaluator(const World& w, const ContactSettings& settings);

  /// the common radius of the candidate list `generation` found (nothing to place)
  std::size_t begin(const World& w, std::uint64_t generation) {
    find_common_radius(w, generation);
    return 0;
  }
  void place(const World&, std::size_t, std::size_t) {}
  /// the radius every disk has, or NaN where they differ (found by begin())
  double common_radius() const { return common_radius_; }

  [[gnu::always_inline]] bool pair(const World& w, PairKey key, HistoryCursor& /*history*/,
                                   double /*dt*/, PairForce& pf, PairResult& pr) const {
    const std::uint32_t N = static_cast<std::uint32_t>(w.size());
    const std::uint32_t i = key_i(key), j = key_j(key);
    const bool wall = j >= N;
    const PlacedBody a{{w.s.x[i], w.s.y[i]}, w.radius[i], nullptr, {}, nullptr};
    const ContactGeom g =
        wall ? narrow<kShape, BodyKind::Wall>(a, PlacedBody{{}, 0.0, nullptr, {}, &w.walls[j - N]})
             : narrow<kShape, kShape>(
                   a,
                   PlacedBody{image_pos(w, j, key_image(key)), w.radius[j], nullptr, {}, nullptr});
    if (!g.touching) return false;
    Vec2 vrel{w.s.vx[i], w.s.vy[i]};
    if (!wall) vrel -= Vec2{w.s.vx[j], w.s.vy[j]};
    const Vec2 t = perp(g.n);
    const law::DiskLawParams& p = params_[pair_index(nsp_, w.sp[i], wall ? nsp_ : w.sp[j])];
    const law::DiskForce df =
        law::linear_spring_dashpot(p, g.overlap, dot(vrel, g.n), dot(vrel, t));
    const Vec2 F = g.n * df.fn + t * df.ft;
    pf = {F.x, F.y, 0.0, 0.0};
    pr.degenerate = false;
    pr.s = g.s;
    pr.n = g.n;
    pr.fn = df.fn;
    pr.ft = df.ft;
    pr.overlap = g.overlap;
    pr.h = g.overlap;
    return true;
  }

  /// the candidates [k0, k1) that pair() may find touching, in order, into `sel` (their
  /// indices); returns their count. Disk pairs by narrow<Disk, Disk>'s own test, wall pairs all
  std::size_t select(const World& w, const std::vector<PairKey>& cand, std::size_t k0,
                     std::size_t k1, std::vector<std::uint32_t>& sel) const;
  /// the lines that pair() and the force sum will touch beyond x, y and r (which select()
  /// has just read) for the `m` selected candidates, fetched at once
  static void prefetch(const World& w, const std::vector<PairKey>& cand,
                       const std::vector<std::uint32_t>& sel, std::size_t m, const double* fx,
                       const double* fy);

  const law::DiskLawParams& params(std::size_t a, std::size_t b) const {
    return params_[pair_index(nsp_, a, b)];
  }
  /// the binary contact time of species a against b (b = species: a wall), s
  double contact_time(const World& w, std::size_t a, std::size_t b) const;

 private:
  void find_common_radius(const World& w, std::uint64_t generation);
  std::size_t nsp_ = 0;
  std::vector<law::DiskLawParams> params_;  ///< pair_index layout
  /// the radius every disk has, or NaN where they differ: then select() reads no radii (at
  /// 10⁶ disks a memory stream of its own). Found once per candidate list (generation),
  /// which is made for the radii it is used with
  double common_radius_ = 0.0;
  std::uint64_t common_radius_generation_ = 0;  ///< 0: not found for any list
  std::size_t common_radius_n_ = 0;
};

}  // namespace gs
