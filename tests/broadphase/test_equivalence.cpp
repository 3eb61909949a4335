// the two broad phases must give the same contact set: random dense configurations of
// decagons (walled box) and disks (periodic box), checked against brute force
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "broadphase/broadphase.hpp"
#include "contact/narrow.hpp"
#include "core/rng.hpp"
#include "sim/builders.hpp"
#include "world/prepare.hpp"

namespace gs {
namespace {

// keep only the candidates whose shapes really touch
std::set<PairKey> touching(const World& w, const std::vector<PairKey>& cand) {
  std::set<PairKey> out;
  const std::uint32_t N = static_cast<std::uint32_t>(w.size());
  for (PairKey k : cand) {
    const std::uint32_t i = key_i(k), j = key_j(k);
    const Poly pi = w.shape(i);
    const BodyView bi{{w.s.x[i], w.s.y[i]}, w.radius[i], &pi};
    bool t;
    if (j >= N) {
      t = polygon_wall(bi, w.walls[j - N]).touching;
    } else {
      const Poly pj = w.shape(j);
      t = polygon_polygon(bi, BodyView{{w.s.x[j], w.s.y[j]}, w.radius[j], &pj}).touching;
    }
    if (t) out.insert(k);
  }
  return out;
}

// every pair by brute force
std::set<PairKey> brute(const World& w) {
  std::vector<PairKey> all;
  const std::uint32_t N = static_cast<std::uint32_t>(w.size());
  for (std::uint32_t i = 0; i < N; ++i) {
    for (std::uint32_t j = i + 1; j < N; ++j) all.push_back(make_key(i, j, kNoImage));
    for (std::uint32_t k = 0; k < w.walls.size(); ++k) all.push_back(make_key(i, N + k, kNoImage));
  }
  return touching(w, all);
}

TEST(BroadPhase, TreeAndGridFindTheSameContactsOnDenseRandomPiles) {
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
    SceneSpec s = build::decagon_pile(400, 0.2, 0.25, seed);
    World w = make_world(s);
    place_particles(w, s);
    // scatter the grains densely (overlaps allowed) over the box and a little into the walls
    RngStream r(seed, 99);
    for (std::size_t i = 0; i < w.size(); ++i) {
      w.s.x[i] = r.uniform(-0.005, 0.205);
      w.s.y[i] = r.uniform(-0.005, 0.255);
      w.s.th[i] = r.uniform(0, 6.3);
    }
    std::vector<PairKey> a, b;
    auto tree = make_box2d_tree();
    auto grid = make_cell_grid();
    tree->update(w, a);
    grid->update(w, b);
    ASSERT_TRUE(std::is_sorted(a.begin(), a.end()));
    ASSERT_TRUE(std::is_sorted(b.begin(), b.end()));
    const auto ta = touching(w, a), tb = touching(w, b), tr = brute(w);
    EXPECT_GT(tr.size(), 500u);  // dense: many contacts
    EXPECT_EQ(ta, tr) << "seed " << seed;
    EXPECT_EQ(tb, tr) << "seed " << seed;
    // move the grains a little and update again (the tree keeps persistent pairs)
    for (std::size_t i = 0; i < w.size(); ++i) {
      w.s.x[i] += r.uniform(-0.004, 0.004);
      w.s.y[i] += r.uniform(-0.004, 0.004);
    }
    tree->update(w, a);
    grid->update(w, b);
    EXPECT_EQ(touching(w, a), brute(w));
    EXPECT_EQ(touching(w, b), brute(w));
  }
}

TEST(BroadPhase, PeriodicGridFindsPairsAcrossTheBoundary) {
  SceneSpec s = build::disk_gas(300, 0.5, 0.9, 0.9, 3);
  World w = make_world(s);
  place_particles(w, s);
  RngStream r(3, 7);
  for (std::size_t i = 0; i < w.size(); ++i) {
    w.s.x[i] = r.uniform(0, w.Lx) + w.Lx * std::floor(r.uniform(-2, 2));  // unwrapped
    w.s.y[i] = r.uniform(0, w.Ly);
  }
  std::vector<PairKey> got;
  make_cell_grid()->update(w, got);
  std::set<std::pair<std::uint32_t, std::uint32_t>> g, ref;
  // candidates may include near misses (the Verlet skin): keep those that touch via their image
  for (PairKey k : got) {
    const std::uint32_t i = key_i(k), j = key_j(k);
    const Vec2 d{w.s.x[j] + image_sx(key_image(k)) * w.Lx - w.s.x[i],
                 w.s.y[j] + image_sy(key_image(k)) * w.Ly - w.s.y[i]};
    if (norm(d) < w.radius[i] + w.radius[j]) g.insert({i, j});
  }
  for (std::uint32_t i = 0; i < w.size(); ++i)
    for (std::uint32_t j = i + 1; j < w.size(); ++j) {
      const Vec2 d = w.separation(i, j);
      if (norm(d) < w.radius[i] + w.radius[j]) ref.insert({i, j});
    }
  EXPECT_GT(ref.size(), 50u);
  EXPECT_EQ(g, ref);
}

}  // namespace
}  // namespace gs
