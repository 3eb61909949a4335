// uniform cell grid with a Verlet skin: pairs closer than r_i + r_j + skin are found by a
// counting sort into cells (O(N)) and reused until some grain has moved more than skin/2 since
// (so no pair can have come within contact unseen); periodic boxes wrap cells and use the
// minimum image, fixed per pair until the next rebuild
#include <algorithm>
#include <atomic>
#include <cmath>

#include "broadphase/broadphase.hpp"
#include "core/team.hpp"

namespace gs {
namespace {

class CellGrid final : public BroadPhase {
 public:
  const char* name() const override { return "cell_grid"; }

  using BroadPhase::update;
  const std::vector<PairKey>& update(const World& w, const ThreadTeam& team) override {
    // the caller's own test of these positions (set_moved), or ours
    const Told told = take_told();
    const bool rebuild = w.size() != bx_.size() ||
                         (told == Told::Nothing ? needs_rebuild(w, team) : told == Told::Moved);
    if (rebuild) {
      build(w, team);
      new_generation();
    }
    return pairs_;
  }

 private:
  // has a grain of [b, e) moved more than half the skin since the last build? Branch-free
  // (the whole range is read anyway): the loop vectorises
  bool moved_beyond(const World& w, std::size_t b, std::size_t e) const {
    const double lim = lim2();
    const double* __restrict x = w.s.x.data();
    const double* __restrict y = w.s.y.data();
    const double* __restrict x0 = bx_.data();
    const double* __restrict y0 = by_.data();
    int m = 0;
    for (std::size_t i = b; i < e; ++i) {
      m |= static_cast<int>(skin_moved(x[i] - x0[i], y[i] - y0[i], lim));
    }
    return m != 0;
  }

  double lim2() const { return 0.25 * skin_ * skin_; }
  SkinTest skin_test() const override {
    if (bx_.empty()) return {};
    return {bx_.data(), by_.data(), lim2(), bx_.size()};
  }

  // has any grain moved more than half the skin since the last build? (update() has checked
  // that the list is of these particles)
  bool needs_rebuild(const World& w, const ThreadTeam& team) const {
    const std::size_t n = w.size();
    std::atomic<bool> moved{false};  // an OR: the same answer whatever the thread count
    parallel_ranges(team, n, kParallelMinCheap, [&](std::size_t b, std::size_t e) {
      if (moved_beyond(w, b, e)) moved.store(true, std::memory_order_relaxed);
    });
    return moved.load();
  }

  void build(const World& w, const ThreadTeam& team) {
    std::vector<PairKey>& out = pairs_;
    out.clear();
    const std::size_t n = w.size();
    skin_ = 0.1 * 2.0 * w.max_radius;
    bx_.assign(w.s.x.begin(), w.s.x.end());
    by_.assign(w.s.y.begin(), w.s.y.end());
    if (n == 0) return;
    const bool periodic = w.box == BoxKind::Periodic || w.box == BoxKind::Ring1D;
    const bool ring = w.box == BoxKind::Ring1D;

    // grid extent: the periodic cell, or the bounding box of the grains in a walled box
    double x0 = 0, y0 = 0, wx = w.Lx, wy = ring ? 0.0 : w.Ly;
    if (!periodic) {
      double xmin = w.s.x[0], xmax = xmin, ymin = w.s.y[0], ymax = ymin;
      for (std::size_t i = 1; i < n; ++i) {
        xmin = std::min(xmin, w.s.x[i]);
        xmax = std::max(xmax, w.s.x[i]);
        ymin = std::min(ymin, w.s.y[i]);
        ymax = std::max(ymax, w.s.y[i]);
      }
      x0 = xmin;
      y0 = ymin;
      wx = xmax - xmin;
      wy = ymax - ymin;
    }
    double cell = 2.0 * w.max_radius + skin_;
    // never many more cells than grains (a far grain, a huge dilute box)
    cell = std::max(cell, ring ? wx / (4.0 * static_cast<double>(n))
                               : std::sqrt(wx * wy / (4.0 * static_cast<double>(n))));
    // cells along one axis, at most ~4 per grain: a grain astronomically far from the others
    // (a blown-up run, a hostile checkpoint) must not ask for more cells than an int counts;
    // the indices below are clamped to the grid, so grains beyond it share the edge cells
    // (more candidate pairs, never a missed one)
    const double most = 4.0 * static_cast<double>(n) + 16.0;
    auto axis = [most](double cells) {
      return cells >= 1.0 ? static_cast<int>(std::min(cells, most)) : 1;  // NaN: 1
    };
    nx_ = axis(std::floor(wx / cell));
    ny_ = ring ? 1 : axis(std::floor(wy / cell));
    if (!periodic) {  // walled: cells of exactly `cell`, one spare row and column
      nx_ = axis(std::floor(wx / cell)) + 1;
      ny_ = axis(std::floor(wy / cell)) + 1;
    }
    const double cx = periodic ? wx / nx_ : cell;
    const double cy = periodic ? (ring ? 1.0 : wy / ny_) : cell;

    // counting sort of particles into cells
    cell_of_.resize(n);
    start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      double px = w.s.x[i] - x0, py = ring ? 0.0 : w.s.y[i] - y0;
      if (periodic) {
        px -= wx * std::floor(px / wx);
        if (!ring) py -= wy * std::floor(py / wy);
      }
      // clamped as doubles: a far or non-finite position must not overflow the int
      auto index = [](double v, int cells) {
        return v >= 0.0 ? static_cast<int>(std::min(v, cells - 1.0)) : 0;
      };
      const int ix = index(px / cx, nx_);
      const int iy = index(py / cy, ny_);
      cell_of_[i] = iy * nx_ + ix;
      ++start_[cell_of_[i] + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    order_.resize(n);
    fill_ = start_;
    for (std::size_t i = 0; i < n; ++i) order_[fill_[cell_of_[i]]++] = static_cast<int>(i);

      // each grain's partners above it, sorted: in parallel into per-thread lists over
      // contiguous ranges of i, joined in range order (the same list for any thread count)
#pragma omp parallel if (run_parallel(n, kParallelMin))
    {
      const int t = team_thread(), nt = team_size();
#pragma omp single
      part_.resize(static_cast<std::size_t>(nt));
      std::vector<PairKey>& mine = part_[static_cast<std::size_t>(t)];
      mine.clear();
      const ItemRange r = team.particles(n, t, nt);
      for (std::size_t i = r.begin; i < r.end; ++i) partners(w, i, mine);
    }
    std::size_t total = 0;
    for (const auto& p : part_) total += p.size();
    out.reserve(total);
    for (const auto& p : part_) out.insert(out.end(), p.begin(), p.end());
  }

  // the partners j > i of grain i within reach (r_i + r_j + skin), and its walls, ascending
  void partners(const World& w, std::size_t i, std::vector<PairKey>& out) const {
    const std::uint32_t N = static_cast<std::uint32_t>(w.size());
    const bool periodic = w.box == BoxKind::Periodic || w.box == BoxKind::Ring1D;
    const bool ring = w.box == BoxKind::Ring1D;
    // neighbour cells (deduplicated when the grid is narrower than three cells)
    const int ix = cell_of_[i] % nx_, iy = cell_of_[i] / nx_;
    int cells[9], nc = 0;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        int jx = ix + dx, jy = iy + dy;
        if (periodic) {
          jx = (jx + nx_) % nx_;
          jy = (jy + ny_) % ny_;
        } else if (jx < 0 || jy < 0 || jx >= nx_ || jy >= ny_) {
          continue;
        }
        const int c = jy * nx_ + jx;
        if (std::find(cells, cells + nc, c) == cells + nc) cells[nc++] = c;
      }
    }
    const std::size_t first = out.size();
    const Vec2 pi{w.s.x[i], w.s.y[i]};
    for (int k = 0; k < nc; ++k) {
      for (int q = start_[cells[k]]; q < start_[cells[k] + 1]; ++q) {
        const std::size_t j = static_cast<std::size_t>(order_[q]);
        if (j <= i) continue;
        Vec2 d{w.s.x[j] - pi.x, w.s.y[j] - pi.y};
        int sx = 0, sy = 0;
        if (periodic) {
          // a shift beyond the 8 bits of an image code only arises in a state that has blown
          // up (non-finite or astronomically far positions): such a pair is no contact, and
          // its code would spill into the partner's index
          const double fx = std::nearbyint(d.x / w.Lx);
          const double fy = ring ? 0.0 : std::nearbyint(d.y / w.Ly);
          if (!(std::abs(fx) <= 127.0 && std::abs(fy) <= 127.0)) continue;
          sx = -static_cast<int>(fx);
          d.x += sx * w.Lx;
          if (!ring) {
            sy = -static_cast<int>(fy);
            d.y += sy * w.Ly;
          }
        }
        const double rr = w.radius[i] + w.radius[j] + skin_;
        if (d.x * d.x + d.y * d.y < rr * rr)
          out.push_back(make_key(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j),
                                 make_image(sx, sy)));
      }
    }
    // walls: circle against the wall's box
    for (std::size_t k = 0; k < w.walls.size(); ++k)
      if (circle_box_overlap(pi, w.radius[i] + skin_, w.walls[k].lo, w.walls[k].hi))
        out.push_back(
            make_key(static_cast<std::uint32_t>(i), N + static_cast<std::uint32_t>(k), kNoImage));
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
  }

  int nx_ = 1, ny_ = 1;
  double skin_ = 0.0;            ///< extra reach of the pair list, m
  std::vector<double> bx_, by_;  ///< positions at the last build, m
  std::vector<PairKey> pairs_;   ///< the pair list of the last build, sorted
  std::vector<int> cell_of_, start_, fill_, order_;
  std::vector<std::vector<PairKey>> part_;  ///< per-thread partner lists of a build
};

}  // namespace

std::unique_ptr<BroadPhase> make_cell_grid() { return std::make_unique<CellGrid>(); }

std::unique_ptr<BroadPhase> make_broadphase(BroadPhaseKind kind, const World& w) {
  // the 1D ring: neighbour contacts only, order preserved (docs/physics.md §5.2)
  if (kind == BroadPhaseKind::Auto && w.box == BoxKind::Ring1D) return make_ring_neighbours();
  // Auto: the cell grid everywhere, faster than Box2D's tree in both walled benchmark scenes
  // (docs/benchmarks.md); the tree stays selectable
  if (kind == BroadPhaseKind::Auto) kind = BroadPhaseKind::CellGrid;
  if (kind == BroadPhaseKind::Box2DTree && w.box != BoxKind::Walls)
    kind = BroadPhaseKind::CellGrid;  // Box2D has no periodic wrapping
  return kind == BroadPhaseKind::Box2DTree ? make_box2d_tree() : make_cell_grid();
}

}  // namespace gs
