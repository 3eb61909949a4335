// the force loop's parallel pair evaluation and per-particle sums give, bit for bit, the forces
// of the plain serial loop over the touching pairs in key order (F on j, −F on i), for either
// model, with or without a cached candidate index
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/parallel.hpp"
#include "scene/parse.hpp"
#include "sim/state_file.hpp"
#include "test_world.hpp"

namespace gs {
namespace {

using testing::Threads;

// the serial reference: every touching pair in key order, as the force loop once summed them
void serial_sums(const World& w, const ContactSet& cs, std::vector<double>& fx,
                 std::vector<double>& fy) {
  const std::uint32_t N = static_cast<std::uint32_t>(w.size());
  fx.assign(w.size(), 0.0);
  fy.assign(w.size(), 0.0);
  for (const ContactRecord& r : cs.records) {
    const Vec2 F = r.n * r.fn + perp(r.n) * r.ft;
    const std::uint32_t i = key_i(r.key), j = key_j(r.key);
    fx[i] -= F.x;
    fy[i] -= F.y;
    if (j < N) {
      fx[j] += F.x;
      fy[j] += F.y;
    }
  }
}

void expect_serial_sums(const World& w, const SimSettings& set, BroadPhaseKind bpk) {
  const Threads two(2);  // the parallel path (the candidates are above its thresholds)
  auto bp = make_broadphase(bpk, w);
  ContactModel model(w, set.contact);
  ThreadTeam threads;
  ContactSet cs;
  ForceBuffer f;
  const std::vector<PairKey>& cand = bp->update(w);
#ifdef _OPENMP
  ASSERT_TRUE(run_parallel(cand.size(), ContactModel::parallel_pairs_from(w.polygons(), w.size())))
      << cand.size() << " candidates: below the parallel threshold";
#endif
  model.evaluate(w, cand, cs, f, set.dt, threads, bp->generation());
  ASSERT_GT(cs.records.size(), w.size()) << "a dense packing: more contacts than grains";
  ASSERT_EQ(cs.keys.size(), cs.records.size());
  for (std::size_t k = 0; k < cs.keys.size(); ++k) {
    ASSERT_EQ(cs.keys[k], cs.records[k].key);
    if (k > 0) {
      ASSERT_LT(cs.keys[k - 1], cs.keys[k]);
    }
  }
  std::vector<double> fx, fy;
  serial_sums(w, cs, fx, fy);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < w.size(); ++i) differ += fx[i] != f.fx[i] || fy[i] != f.fy[i];
  EXPECT_EQ(differ, 0u) << "particles whose force differs from the serial sum";
  // a second evaluation on the same list with the cached index, and one without: identical,
  // and (disks, whose law has no history) identical to the first, whose sums came from the
  // touching pairs alone (no contacts the step before)
  ForceBuffer f2, f3;
  ContactSet cs2 = cs, cs3 = cs;
  model.evaluate(w, cand, cs2, f2, set.dt, threads, bp->generation());
  model.evaluate(w, cand, cs3, f3, set.dt, threads, 0);
  EXPECT_EQ(f2.fx, f3.fx);
  EXPECT_EQ(f2.fy, f3.fy);
  EXPECT_EQ(f2.tq, f3.tq);
  if (!w.polygons()) {  // (polygon contacts carry a history from the first evaluation)
    EXPECT_EQ(f2.fx, f.fx);
    EXPECT_EQ(f2.fy, f.fy);
  }
}

TEST(ForceSums, SettledDecagonPileMatchesSerialLoop) {
  const std::string src = GS_SOURCE_DIR;
  const SceneSpec s = parse_scene_file(src + "/scenes/paper_pile.toml");
  World w = make_world(s);
  read_state_file(w, src + "/scenes/data/paper_pile_settled.csv");
  expect_serial_sums(w, SimSettings::from(s), BroadPhaseKind::CellGrid);
  expect_serial_sums(w, SimSettings::from(s), BroadPhaseKind::Box2DTree);
}

TEST(ForceSums, DenseDiskFluidMatchesSerialLoop) {
  // 6000 disks placed at φ = 0.5, then grown by 30 % (φ = 0.85): most disks touch several
  SceneSpec s = build::disk_gas(6000, 0.5, 0.6, 0.6, 3);
  World w = make_world(s);
  place_particles(w, s);
  for (double& r : w.radius) r *= 1.3;
  w.max_radius *= 1.3;
  expect_serial_sums(w, SimSettings::from(s), BroadPhaseKind::CellGrid);
}

// two evaluations of the same pairs: the same contacts, records and forces, bit for bit
void expect_same_evaluation(const ContactSet& a, const ForceBuffer& fa, const ContactSet& b,
                            const ForceBuffer& fb) {
  EXPECT_EQ(a.keys, b.keys);
  EXPECT_EQ(fa.fx, fb.fx);
  EXPECT_EQ(fa.fy, fb.fy);
  ASSERT_EQ(a.records.size(), b.records.size());
  for (std::size_t k = 0; k < a.records.size(); ++k) {
    EXPECT_EQ(a.records[k].fn, b.records[k].fn);
    EXPECT_EQ(a.records[k].ft, b.records[k].ft);
  }
}

// the serial disk loop picks the touching pairs by a branch-free pass first when few touched
// last step (the contact set is small against the candidates); with a large contact set it
// visits every candidate. Both must give the same contacts and forces, bit for bit: a periodic
// gas, a walled box with disks on the walls, and the 1D ring
void expect_same_disk_paths(const World& w, const SimSettings& set, std::size_t min_contacts) {
  auto bp = make_broadphase(BroadPhaseKind::Auto, w);
  const std::vector<PairKey>& cand = bp->update(w);
  ContactModel model(w, set.contact);
  ThreadTeam threads;
  ContactSet sparse, packed;  // sparse: no contacts last step; packed: as many as candidates
  packed.keys.assign(cand.size(), PairKey{0});
  ForceBuffer f1, f2;
  model.evaluate(w, cand, sparse, f1, set.dt, threads, bp->generation());
  model.evaluate(w, cand, packed, f2, set.dt, threads, bp->generation());
  ASSERT_GE(sparse.keys.size(), min_contacts);
  ASSERT_LT(3 * sparse.keys.size(), cand.size()) << "not a sparse scene: the test needs one";
  expect_same_evaluation(sparse, f1, packed, f2);
  std::vector<double> fx, fy;
  serial_sums(w, sparse, fx, fy);
  EXPECT_EQ(fx, f1.fx);
  EXPECT_EQ(fy, f1.fy);
}

// a periodic gas at φ = 0.3 under the random force, at its lattice-like start
Simulation forced_gas(int n, std::uint64_t seed) {
  SceneSpec s = build::disk_gas(n, 0.3, 0.6, 0.6, seed);
  s.drive.kind = DriveKind::RandomForce;
  World w = make_world(s);
  place_particles(w, s);
  return Simulation(std::move(w), SimSettings::from(s));
}

TEST(ForceSums, DiskPrefilterKeepsThePairs) {
  {  // periodic gas at φ = 0.3, randomly forced out of its lattice: contacts across the
     // boundary too
    Simulation sim = forced_gas(3000, 5);
    sim.run(400);
    const World& w = sim.world();
    expect_same_disk_paths(w, sim.settings(), 10);
  }
  {  // the gas with every third disk from the second 2 % larger: the selection reads each
     // pair's radii (one common radius spares those loads)
    Simulation sim = forced_gas(3000, 5);
    sim.run(400);
    World w = sim.world();
    const double r0 = w.radius[0];
    for (std::size_t i = 1; i < w.size(); i += 3) w.radius[i] *= 1.02;
    w.max_radius *= 1.02;
    // pairs of large disks 2.01 r0 apart: touching, and apart by one common radius r0
    std::size_t big = 0;
    for (std::size_t i = 1; i + 3 < w.size(); i += 30, ++big) {
      w.s.x[i + 3] = w.s.x[i] + 2.01 * r0;
      w.s.y[i + 3] = w.s.y[i];
    }
    ASSERT_GT(big, 10u);
    expect_same_disk_paths(w, sim.settings(), big);
  }
  {  // walled box: a loose column of disks shifted onto the left wall and the floor
    SceneSpec s = build::disk_gas(400, 0.3, 0.6, 0.6, 6);
    s.box.kind = BoxKind::Walls;
    World w = make_world(s);
    place_particles(w, s);
    const double r0 = w.radius[0];
    std::size_t on_wall = 0;
    for (std::size_t i = 0; i < w.size(); ++i) {
      w.s.x[i] -= 0.9 * r0 * (w.s.x[i] < 3 * r0);
      w.s.y[i] -= 0.9 * r0 * (w.s.y[i] < 3 * r0);
      on_wall += w.s.x[i] < r0 || w.s.y[i] < r0;
    }
    ASSERT_GT(on_wall, 0u);
    expect_same_disk_paths(w, SimSettings::from(s), on_wall);
  }
  {  // the 1D ring
    const SceneSpec ring =
        parse_scene_file(std::string(GS_SOURCE_DIR) + "/scenes/rfm1d_reference.toml");
    World w = make_world(ring);
    place_particles(w, ring);
    // every tenth disk's forward neighbour moved to overlap it by a quarter diameter
    for (std::size_t i = 0; i + 1 < w.size(); i += 10) w.s.x[i + 1] = w.s.x[i] + 1.5 * w.radius[i];
    expect_same_disk_paths(w, SimSettings::from(ring), w.size() / 10);
  }
}

// the force loop's largest overlap and largest overlap over the smaller radius are those of its
// contact records, bit for bit: where every disk has one radius the loops divide the largest
// overlap by it once (no division per contact), else they divide per contact. The serial loop
// (one thread) and the parallel one (two)
TEST(ForceSums, LargestOverlapsAreTheRecordsMaxima) {
  for (const int threads : {1, 2})
    for (const bool mixed : {false, true}) {
      const Threads team(threads);
      SceneSpec s = build::disk_gas(6000, 0.6, 0.6, 0.6, 9);
      s.box.kind = BoxKind::Walls;
      World w = make_world(s);
      place_particles(w, s);
      // grown by 30% (most disks touch, some the walls); mixed: every third 2% more
      for (double& r : w.radius) r *= 1.3;
      for (std::size_t i = 1; mixed && i < w.size(); i += 3) w.radius[i] *= 1.02;
      w.max_radius *= 1.3 * 1.02;
      auto bp = make_broadphase(BroadPhaseKind::CellGrid, w);
      const std::vector<PairKey>& cand = bp->update(w);
#ifdef _OPENMP
      ASSERT_EQ(run_parallel(cand.size(), ContactModel::parallel_pairs_from(false, w.size())),
                threads == 2);
#endif
      const SimSettings set = SimSettings::from(s);
      ContactModel model(w, set.contact);
      ThreadTeam thread_team;
      ContactSet cs;
      ForceBuffer f;
      const ForceStats st = model.evaluate(w, cand, cs, f, set.dt, thread_team, bp->generation());
      const auto N = static_cast<std::uint32_t>(w.size());
      double h = 0.0, rel = 0.0;
      std::size_t walls = 0;
      for (const ContactRecord& r : cs.records) {
        const std::uint32_t i = key_i(r.key), j = key_j(r.key);
        walls += j >= N;
        h = std::max(h, r.overlap);
        rel =
            std::max(rel, r.overlap / (j >= N ? w.radius[i] : std::min(w.radius[i], w.radius[j])));
      }
      ASSERT_GT(cs.records.size(), w.size()) << "a packing: more contacts than disks";
      ASSERT_GT(walls, 0u);
      EXPECT_EQ(st.max_overlap, h) << threads << " threads, mixed radii: " << mixed;
      EXPECT_EQ(st.max_overlap_rel, rel) << threads << " threads, mixed radii: " << mixed;
      EXPECT_GT(rel, 0.1);  // grown by 30%: overlaps of a good part of a radius
    }
}

// a dilute periodic gas of 10⁴ disks: its particle loops run on the team, its 10³–8·10³
// candidate pairs, too cheap for a region of their own, join the team's region
// (ContactModel::parallel_pairs_from). Two threads give the one-thread serial loop's contacts,
// records and forces bit for bit: summed from the touching pairs (few touched last step), and
// through the per-particle index, cached and made anew (many touched last step)
TEST(ForceSums, DiluteLargeGasPairsOnTheTeam) {
  const SceneSpec s = build::disk_gas(10000, 0.1, 0.6, 0.6, 8);
  World w = make_world(s);
  place_particles(w, s);
  // every 25th disk's successor moved onto it (a quarter diameter deep): 400 contacts
  for (std::size_t i = 0; i + 1 < w.size(); i += 25) {
    w.s.x[i + 1] = w.s.x[i] + 1.5 * w.radius[i];
    w.s.y[i + 1] = w.s.y[i];
  }
  auto bp = make_broadphase(BroadPhaseKind::CellGrid, w);
  const std::vector<PairKey> cand = bp->update(w);
  ASSERT_GE(w.size(), kParallelMinCheap);
  ASSERT_GE(cand.size(), kParallelMin);
  ASSERT_LT(cand.size(), kParallelMinCheap) << "the pairs alone would not start a region";
  const SimSettings set = SimSettings::from(s);
  ContactModel one(w, set.contact), team(w, set.contact);
  ThreadTeam threads;
  ContactSet cs1, cs2, cs3, cs4, cs5;
  cs4.keys.assign(cand.size(), PairKey{0});  // "as many contacts as candidates last step"
  cs5.keys = cs4.keys;
  ForceBuffer f1, f2, f3, f4, f5;
  {
    const Threads single(1);
    one.evaluate(w, cand, cs1, f1, set.dt, threads, bp->generation());
  }
  {
    const Threads two(2);
#ifdef _OPENMP
    ASSERT_TRUE(run_parallel(cand.size(), ContactModel::parallel_pairs_from(false, w.size())));
#endif
    team.evaluate(w, cand, cs2, f2, set.dt, threads, bp->generation());
    team.evaluate(w, cand, cs3, f3, set.dt, threads, 0);
    team.evaluate(w, cand, cs4, f4, set.dt, threads,
                  bp->generation());  // index made
    team.evaluate(w, cand, cs5, f5, set.dt, threads,
                  bp->generation());  // and reused
  }
  ASSERT_GE(cs1.keys.size(), 400u);
  expect_same_evaluation(cs2, f2, cs1, f1);
  expect_same_evaluation(cs3, f3, cs1, f1);
  expect_same_evaluation(cs4, f4, cs1, f1);
  expect_same_evaluation(cs5, f5, cs1, f1);
  std::vector<double> fx, fy;
  serial_sums(w, cs1, fx, fy);
  EXPECT_EQ(fx, f1.fx);
  EXPECT_EQ(fy, f1.fy);
}

// one buffer reused from evaluation to evaluation (the serial path clears only the last
// evaluation's touched entries where few touched) gives, bit for bit, the forces of a fresh
// buffer every time: a gas whose contacts change, then a dense packing in the same buffer,
// then the gas again, then a smaller world, and after someone wrote into the buffer and reset
TEST(ForceSums, ReusedBufferEqualsAFreshOne) {
  Simulation sim = forced_gas(3000, 5);
  auto bp = make_broadphase(BroadPhaseKind::Auto, sim.world());
  const SimSettings& set = sim.settings();
  ContactModel model(sim.world(), set.contact);
  ThreadTeam threads;
  ForceBuffer reused;
  std::size_t sparse_calls = 0, touched_max = 0;
  auto expect_fresh = [&](const World& w, const char* what) {
    const std::vector<PairKey>& cand = bp->update(w);
    ContactSet cs1, cs2;
    ForceBuffer fresh;
    model.evaluate(w, cand, cs1, reused, set.dt, threads, 0);
    model.evaluate(w, cand, cs2, fresh, set.dt, threads, 0);
    ASSERT_EQ(reused.fx.size(), w.size()) << what;
    std::size_t differ = 0;
    for (std::size_t i = 0; i < w.size(); ++i)
      differ += std::signbit(reused.fx[i]) != std::signbit(fresh.fx[i]) ||
                reused.fx[i] != fresh.fx[i] || reused.fy[i] != fresh.fy[i];
    EXPECT_EQ(differ, 0u) << what;
    sparse_calls += reused.sparse;
    touched_max = std::max(touched_max, reused.touched.size());
  };
  for (int k = 0; k < 30; ++k) {  // the gas: contacts come and go between evaluations
    sim.run(40);
    expect_fresh(sim.world(), "gas");
  }
  EXPECT_GT(sparse_calls, 20u) << "the sparse clearing was not exercised";
  EXPECT_GT(touched_max, 10u);
  World dense = sim.world();  // grown by 60 %: most disks touch, every entry is written
  for (double& r : dense.radius) r *= 1.6;
  dense.max_radius *= 1.6;
  bp = make_broadphase(BroadPhaseKind::Auto, dense);
  expect_fresh(dense, "dense");
  EXPECT_FALSE(reused.sparse);
  bp = make_broadphase(BroadPhaseKind::Auto, sim.world());
  expect_fresh(sim.world(), "gas after the dense packing");
  expect_fresh(sim.world(), "gas again");
  // a buffer written by someone else must be reset: then it is cleared in full
  std::fill(reused.fx.begin(), reused.fx.end(), 7.0);
  reused.reset(reused.fx.size());
  expect_fresh(sim.world(), "after reset");
  // a smaller world in the same buffer
  Simulation small = forced_gas(1000, 9);
  small.run(400);
  ContactModel model2(small.world(), small.settings().contact);
  bp = make_broadphase(BroadPhaseKind::Auto, small.world());
  const std::vector<PairKey>& cand = bp->update(small.world());
  ContactSet cs1, cs2;
  ForceBuffer fresh;
  model2.evaluate(small.world(), cand, cs1, reused, small.dt(), threads, 0);
  model2.evaluate(small.world(), cand, cs2, fresh, small.dt(), threads, 0);
  EXPECT_EQ(reused.fx, fresh.fx);
  EXPECT_EQ(reused.fy, fresh.fy);
}

}  // namespace
}  // namespace gs

namespace gs {
namespace {

// random placement numbers its grains in lattice order (rows upward, left to right within a
// hexagonal row), so that neighbours in space are near in memory; the sites stay random
TEST(Placement, RandomSitesAreNumberedInLatticeOrder) {
  SceneSpec s = build::disk_gas(5000, 0.3, 0.6, 0.6, 7);
  World w = make_world(s);
  place_particles(w, s);
  ASSERT_EQ(w.size(), 5000u);
  std::size_t backwards = 0, row_gaps = 0;
  double mean_y = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    mean_y += w.s.y[i] / static_cast<double>(w.size());
    if (i == 0) continue;
    const bool same_row = w.s.y[i] == w.s.y[i - 1];
    backwards += same_row ? w.s.x[i] <= w.s.x[i - 1] : w.s.y[i] < w.s.y[i - 1];
    row_gaps += !same_row;
  }
  EXPECT_EQ(backwards, 0u) << "grains out of lattice order";
  // random sites: at φ = 0.3 of the box the rows are only partly filled, and a row change
  // skips rows now and then; the grains spread over the whole box (mean height ≈ L/2)
  EXPECT_GT(row_gaps, 20u);
  EXPECT_NEAR(mean_y / w.Ly, 0.5, 0.05);
}

}  // namespace
}  // namespace gs
