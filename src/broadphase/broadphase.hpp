// broad phase: candidate pairs that may touch (a superset of the touching pairs: bounding
// circles within a margin), as sorted keys (i, j, image).
// Two implementations that must agree: Box2D 2.4.1's dynamic AABB tree (walled boxes; the only
// code that sees Box2D) and a uniform cell grid (any box, needed for periodic ones).
#pragma once
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/team.hpp"
#include "world/world.hpp"

namespace gs {

/// a candidate pair key: particle i, partner j (j >= N means wall j − N), periodic image of j
/// relative to i: j is shifted by (sx·Lx, sy·Ly), stored as ((sx+128) << 8) | (sy+128), so
/// kNoImage is the unshifted partner. Positions are kept within ±64 box lengths (sim).
/// Sorting keys orders contacts by (i, j, image), so forces never depend on report order.
using PairKey = std::uint64_t;
inline constexpr std::uint32_t kNoImage = (128u << 8) | 128u;
constexpr std::uint32_t make_image(int sx, int sy) {
  return (static_cast<std::uint32_t>(sx + 128) << 8) | static_cast<std::uint32_t>(sy + 128);
}
constexpr PairKey make_key(std::uint32_t i, std::uint32_t j, std::uint32_t image) {
  return (static_cast<PairKey>(i) << 40) | (static_cast<PairKey>(j) << 16) | image;
}
constexpr std::uint32_t key_i(PairKey k) { return static_cast<std::uint32_t>(k >> 40); }
constexpr std::uint32_t key_j(PairKey k) {
  return static_cast<std::uint32_t>((k >> 16) & 0xffffffu);
}
constexpr std::uint32_t key_image(PairKey k) { return static_cast<std::uint32_t>(k & 0xffffu); }
/// the shift (in box lengths) that an image code applies to j
constexpr int image_sx(std::uint32_t image) { return static_cast<int>(image >> 8) - 128; }
constexpr int image_sy(std::uint32_t image) { return static_cast<int>(image & 0xffu) - 128; }

class BroadPhase {
 public:
  virtual ~BroadPhase() = default;
  /// the candidate pairs of the current state, sorted ascending, no duplicates: every pair
  /// whose bounding circles (or circle and wall box) overlap is among them. The list stays
  /// valid until the next call. `team`: how its particle loops split among the threads (the
  /// simulation's, as its other particle loops)
  virtual const std::vector<PairKey>& update(const World& w, const ThreadTeam& team) = 0;
  /// the same on equal shares (outside a simulation)
  const std::vector<PairKey>& update(const World& w) { return update(w, ThreadTeam{}); }
  /// the same, copied into out
  void update(const World& w, std::vector<PairKey>& out) { out = update(w); }
  virtual const char* name() const = 0;
  /// changes whenever update() may have returned a different list than the call before (the
  /// force loop keeps a per-particle index of the candidates while it stays the same); never
  /// 0, and unique over every broad phase of the process, so that a broad phase built anew
  /// (after a spatial sort) cannot repeat its predecessor's value
  std::uint64_t generation() const { return generation_; }
  /// how many lists this broad phase has made (new generations)
  std::uint64_t builds() const { return builds_; }

  /// a Verlet-skin list's displacement test, for a caller that moves every particle in a pass
  /// of its own (Simulation's prediction ahead) and may make the test there, on lines it
  /// already holds: particle i has moved too far when skin_moved(x_i − x0[i], y_i − y0[i],
  /// lim2). x0 is null where the broad phase has no such test (or no list yet); n particles
  struct SkinTest {
    const double* x0 = nullptr;
    const double* y0 = nullptr;
    double lim2 = 0.0;
    std::size_t n = 0;
  };
  virtual SkinTest skin_test() const { return {}; }
  /// the answer of skin_test() over every particle at the positions the next update() will
  /// see; that update() uses it instead of reading the positions again, and forgets it
  void set_moved(bool moved) { told_ = moved ? Told::Moved : Told::Still; }

 protected:
  enum class Told { Nothing, Still, Moved };
  /// what set_moved() said since the last update(), forgotten
  Told take_told() {
    const Told t = told_;
    told_ = Told::Nothing;
    return t;
  }
  Told told_ = Told::Nothing;
  /// a value no broad phase of this process has had
  static std::uint64_t fresh_generation() {
    static std::atomic<std::uint64_t> next{1};
    return next.fetch_add(1, std::memory_order_relaxed);
  }
  void new_generation() {
    generation_ = fresh_generation();
    ++builds_;
  }
  std::uint64_t generation_ = fresh_generation();
  std::uint64_t builds_ = 0;
};

/// the broad phase a scene asks for (Auto: the ring's neighbours in 1D, else the cell grid)
std::unique_ptr<BroadPhase> make_broadphase(BroadPhaseKind kind, const World& w);
std::unique_ptr<BroadPhase> make_cell_grid();
std::unique_ptr<BroadPhase> make_box2d_tree();
/// 1D ring: only the (i, i+1) neighbour pairs in ring order
std::unique_ptr<BroadPhase> make_ring_neighbours();

/// the skin test of a displacement (dx, dy) against lim2 = (skin/2)²: one expression for the
/// broad phase and for a caller that makes the test for it (BroadPhase::SkinTest)
inline bool skin_moved(double dx, double dy, double lim2) { return dx * dx + dy * dy > lim2; }

/// does a circle (c, r) overlap an axis-aligned box [lo, hi]?
inline bool circle_box_overlap(Vec2 c, double r, Vec2 lo, Vec2 hi) {
  const double dx = c.x < lo.x ? lo.x - c.x : (c.x > hi.x ? c.x - hi.x : 0.0);
  const double dy = c.y < lo.y ? lo.y - c.y : (c.y > hi.y ? c.y - hi.y : 0.0);
  return dx * dx + dy * dy < r * r;
}

}  // namespace gs
