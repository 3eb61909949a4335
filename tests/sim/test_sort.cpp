// the periodic spatial sort (integrator.sort_every, Simulation::sort_particles): every
// per-slot array moves together, the slots end in cell order, the dynamics is that of the
// unsorted run up to round-off (each particle keeps its random-force stream), every
// integrator's history follows, results stay bitwise independent of the thread count, and a
// checkpoint resumes a sorted run bit for bit
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "scene/parse.hpp"
#include "sim/checkpoint.hpp"
#include "sim/state_file.hpp"
#include "test_world.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs {
namespace {

// a randomly forced periodic gas, dense enough that contacts come and go
SceneSpec gas(int n, int sort_every, IntegratorKind kind = IntegratorKind::VelocityVerlet) {
  SceneSpec s = build::disk_gas(n, 0.4, 0.6, 0.6, 11);
  s.drive.kind = DriveKind::RandomForce;
  s.drive.D = 1e-7;
  s.integrator.kind = kind;
  s.integrator.sort_every = sort_every;
  return s;
}

Simulation make_sim(const SceneSpec& s) {
  World w = make_world(s);
  place_particles(w, s);
  return Simulation(std::move(w), SimSettings::from(s));
}

// largest difference by label between two runs' positions and velocities, relative to the
// box and to the largest speed
double max_label_difference(const World& a, const World& b) {
  const std::vector<std::uint32_t> sa = a.slots_by_id(), sb = b.slots_by_id();
  double vmax = 0.0, dx = 0.0, dv = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const std::size_t i = sa[k], j = sb[k];
    vmax = std::max(vmax, std::hypot(a.s.vx[i], a.s.vy[i]));
    dx = std::max({dx, std::abs(a.s.x[i] - b.s.x[j]), std::abs(a.s.y[i] - b.s.y[j])});
    dv = std::max({dv, std::abs(a.s.vx[i] - b.s.vx[j]), std::abs(a.s.vy[i] - b.s.vy[j])});
  }
  return std::max(dx / a.Lx, dv / vmax);
}

TEST(SortParticles, MovesEverythingOfASlotTogetherIntoCellOrder) {
  Simulation sim = make_sim(gas(3000, 0));
  sim.run(300);
  const World before = sim.world();
  const std::vector<PairKey> keys_before = sim.contacts().keys;
  ASSERT_GT(keys_before.size(), 20u);
  // the contacts as (label, label) → force on the larger label's particle
  auto forces_by_label = [](const Simulation& s) {
    const World& w = s.world();
    std::map<std::pair<std::uint32_t, std::uint32_t>, Vec2> out;
    for (const ContactRecord& r : s.contacts().records) {
      std::uint32_t a = w.id[key_i(r.key)], b = w.id[key_j(r.key)];
      Vec2 F = r.n * r.fn + perp(r.n) * r.ft;  // on j
      if (a > b) {
        std::swap(a, b);
        F = F * -1.0;
      }
      out[{a, b}] = F;
    }
    return out;
  };
  const auto f_before = forces_by_label(sim);

  sim.sort_particles();
  const World& w = sim.world();
  EXPECT_EQ(sim.order_generation(), 1u);
  const std::vector<std::uint32_t>& perm = sim.last_order();
  ASSERT_EQ(perm.size(), w.size());
  std::size_t moved = 0, mismatched = 0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    const std::size_t o = perm[k];
    moved += o != k;
    mismatched += w.id[k] != before.id[o] || w.s.x[k] != before.s.x[o] ||
                  w.s.y[k] != before.s.y[o] || w.s.vx[k] != before.s.vx[o] ||
                  w.s.vy[k] != before.s.vy[o] || w.s.ax[k] != before.s.ax[o] ||
                  w.s.ay[k] != before.s.ay[o] || w.radius[k] != before.radius[o] ||
                  w.mass[k] != before.mass[o] || w.sp[k] != before.sp[o] ||
                  w.s.wrap_x[k] != before.s.wrap_x[o];
  }
  // from the lattice-ordered start, 300 steps of mixing move about a quarter of the grains
  EXPECT_GT(moved, w.size() / 10) << "too few particles changed slots for a real test";
  EXPECT_EQ(mismatched, 0u);
  // cell order: rows of cells one diameter high, bottom to top; left to right within a row
  const double cell = 2.0 * w.max_radius;
  std::size_t out_of_order = 0;
  auto fold = [](double v, double L) { return v - L * std::floor(v / L); };
  for (std::size_t k = 1; k < w.size(); ++k) {
    const double r0 = std::floor(fold(w.s.y[k - 1], w.Ly) / cell);
    const double r1 = std::floor(fold(w.s.y[k], w.Ly) / cell);
    const double c0 = std::floor(fold(w.s.x[k - 1], w.Lx) / cell);
    const double c1 = std::floor(fold(w.s.x[k], w.Lx) / cell);
    out_of_order += r1 < r0 || (r1 == r0 && c1 < c0);
  }
  EXPECT_EQ(out_of_order, 0u);
  // the same contacts between the same particles with the same forces
  EXPECT_EQ(sim.contacts().keys.size(), keys_before.size());
  EXPECT_TRUE(std::is_sorted(sim.contacts().keys.begin(), sim.contacts().keys.end()));
  const auto f_after = forces_by_label(sim);
  ASSERT_EQ(f_after.size(), f_before.size());
  for (const auto& [pair, F] : f_before) {
    ASSERT_TRUE(f_after.count(pair));
    EXPECT_NEAR(f_after.at(pair).x, F.x, 1e-15 * std::abs(F.x) + 1e-300);
    EXPECT_NEAR(f_after.at(pair).y, F.y, 1e-15 * std::abs(F.y) + 1e-300);
  }
}

// the sorted run follows the unsorted one to round-off (sums over particles run in another
// order) for every integrator, and each particle keeps its noise: a lost stream or history
// would show at the size of a kick
TEST(SortParticles, SortedRunFollowsTheUnsortedOne) {
  for (IntegratorKind kind : {IntegratorKind::VelocityVerlet, IntegratorKind::Gear6,
                              IntegratorKind::PositionVerlet, IntegratorKind::SemiImplicitEuler}) {
    Simulation plain = make_sim(gas(2000, 0, kind));
    Simulation sorted = make_sim(gas(2000, 25, kind));
    plain.run(400);
    sorted.run(400);
    EXPECT_EQ(sorted.order_generation(), 15u);
    EXPECT_EQ(plain.order_generation(), 0u);
    const double diff = max_label_difference(plain.world(), sorted.world());
    EXPECT_LT(diff, 1e-9) << to_string(kind);
    // and the state did move away from the start (not a trivially equal pair of runs)
    std::size_t relabelled = 0;
    for (std::size_t k = 0; k < sorted.world().size(); ++k) relabelled += sorted.world().id[k] != k;
    EXPECT_GT(relabelled, 100u) << to_string(kind);
  }
  // without following its stream, the first sort would move kicks between particles
  Simulation plain = make_sim(gas(2000, 0));
  Simulation sorted = make_sim(gas(2000, 0));
  plain.run(30);
  sorted.run(30);
  sorted.sort_particles();
  plain.run(30);
  sorted.run(30);
  EXPECT_LT(max_label_difference(plain.world(), sorted.world()), 1e-12);
}

TEST(SortParticles, BitwiseTheSameOnOneAndTwoThreads) {
#ifdef _OPENMP
  const int before = omp_get_max_threads();
  std::uint64_t hash[2] = {0, 0};
  for (int t = 1; t <= 2; ++t) {
    omp_set_num_threads(t);
    // 12 000 disks: above the parallel thresholds of the force loop and the particle passes
    Simulation sim = make_sim(gas(12000, 40));
    sim.run(130);
    EXPECT_EQ(sim.order_generation(), 3u);
    hash[t - 1] = testing::state_hash(sim.world());
  }
  omp_set_num_threads(before);
  EXPECT_EQ(hash[0], hash[1]);
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

// a checkpoint between two sorts, read back: the resumed run is the uninterrupted one, bit for
// bit (labels, slots, integrator history, noise streams, and the next sort at the same step)
TEST(SortParticles, CheckpointResumesASortedRunBitForBit) {
  for (IntegratorKind kind : {IntegratorKind::VelocityVerlet, IntegratorKind::Gear6}) {
    SceneSpec s = gas(2500, 50, kind);
    Simulation straight = make_sim(s);
    straight.run(260);
    Simulation first = make_sim(s);
    first.run(130);
    const std::string bytes = encode_checkpoint(first, s, CheckpointExtras{});
    Simulation resumed = restore_simulation(decode_checkpoint(bytes, "memory"));
    EXPECT_EQ(resumed.world().id, first.world().id);
    resumed.run(130);
    EXPECT_EQ(testing::state_hash(resumed.world()), testing::state_hash(straight.world()))
        << to_string(kind);
    EXPECT_EQ(resumed.world().id, straight.world().id);
  }
}

// a walled box: disks on the walls and the floor keep their wall contacts through the sort
TEST(SortParticles, WalledBoxFollowsTheUnsortedRun) {
  auto walled = [](int sort_every) {
    SceneSpec s = build::disk_gas(1500, 0.35, 0.6, 0.6, 6);
    s.box.kind = BoxKind::Walls;
    s.drive.kind = DriveKind::Gravity;
    s.integrator.sort_every = sort_every;
    World w = make_world(s);
    place_particles(w, s);
    const double r0 = w.radius[0];  // the grains near the left wall and the floor pressed in
    for (std::size_t i = 0; i < w.size(); ++i) {
      w.s.x[i] -= 0.3 * r0 * (w.s.x[i] < 3 * r0);
      w.s.y[i] -= 0.3 * r0 * (w.s.y[i] < 3 * r0);
    }
    return Simulation(std::move(w), SimSettings::from(s));
  };
  Simulation plain = walled(0), sorted = walled(30);
  std::size_t wall_contacts = 0;  // summed over the steps: grains pushed off the walls
  for (int k = 0; k < 600; ++k) {
    plain.step();
    sorted.step();
    for (PairKey key : sorted.contacts().keys) wall_contacts += key_j(key) >= sorted.world().size();
  }
  EXPECT_EQ(sorted.order_generation(), 19u);
  EXPECT_GT(wall_contacts, 100u) << "the test needs grains against the walls";
  EXPECT_LT(max_label_difference(plain.world(), sorted.world()), 1e-9);
}

// files list particles by label: the state file of a sorted run is the unsorted run's, row
// for row (to round-off)
TEST(SortParticles, StateFileRowsFollowLabels) {
  Simulation plain = make_sim(gas(2000, 0)), sorted = make_sim(gas(2000, 40));
  plain.run(200);
  sorted.run(200);
  ASSERT_GT(sorted.order_generation(), 0u);
  const std::string dir = ::testing::TempDir();
  write_state_file(plain.world(), dir + "/plain.csv");
  write_state_file(sorted.world(), dir + "/sorted.csv");
  World a = plain.world(), b = sorted.world();
  read_state_file(a, dir + "/plain.csv");
  read_state_file(b, dir + "/sorted.csv");
  ASSERT_EQ(a.size(), b.size());
  double dx = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(b.id[k], k);  // read back in file order: labels are the rows
    dx = std::max({dx, std::abs(a.s.x[k] - b.s.x[k]), std::abs(a.s.y[k] - b.s.y[k])});
  }
  EXPECT_LT(dx, 1e-12 * a.Lx);
  // and a row is the particle of that label in the sorted world's own slots
  const std::vector<std::uint32_t> slot = sorted.world().slots_by_id();
  EXPECT_EQ(b.s.x[7], sorted.world().s.x[slot[7]]);
  EXPECT_EQ(b.s.vy[1234], sorted.world().s.vy[slot[1234]]);
}

TEST(SortParticles, AutoIntervalAndSceneChecks) {
  auto resolved = [](const SceneSpec& s) {
    World w = make_world(s);
    place_particles(w, s);
    return resolved_sort_every(w, s.integrator.sort_every);
  };
  EXPECT_EQ(resolved(gas(kAutoSortMinParticles, -1)), kAutoSortEvery);
  EXPECT_EQ(resolved(gas(2000, -1)), 0);
  EXPECT_EQ(resolved(gas(kAutoSortMinParticles, 0)), 0);
  const std::string src = GS_SOURCE_DIR;
  EXPECT_EQ(resolved(parse_scene_file(src + "/scenes/paper_pile.toml")), 0);

  // the scene refuses a sort where the slots carry meaning or history
  auto error_of = [&](const std::string& file, const std::string& set) {
    try {
      parse_scene_file(src + "/scenes/" + file, {set});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string poly = error_of("paper_pile.toml", "integrator.sort_every=100");
  EXPECT_NE(poly.find("integrator.sort_every"), std::string::npos) << poly;
  EXPECT_NE(poly.find("Model S"), std::string::npos) << poly;
  const std::string ring = error_of("rfm1d_reference.toml", "integrator.sort_every=100");
  EXPECT_NE(ring.find("ring order"), std::string::npos) << ring;
  EXPECT_NE(error_of("paper_pile.toml", "integrator.sort_every=-2").find("sort_every"),
            std::string::npos);
  EXPECT_EQ(error_of("bench_fluid_10k.toml", "integrator.sort_every=100"), "");
}

}  // namespace
}  // namespace gs
