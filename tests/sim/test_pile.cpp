// piles: a 300-decagon pile with the paper's parameters settles to rest with a plausible φ;
// determinism: the same scene gives bitwise the same state, with either broad phase
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "measure/packing.hpp"
#include "scene/parse.hpp"
#include "sim/state_file.hpp"
#include "test_world.hpp"
#include "world/prepare.hpp"

namespace gs {
namespace {

using testing::state_hash;

// velocity Verlet at the paper's Δt: Gear 6 at Δt = 5e-5 s sits at the edge of its stability
// region for these contacts (ω·Δt ≈ 0.3 for a small grain with four contacts; Gear 6 with the
// paper's damping ζ = γ/2 = 0.25 is stable only to ω·Δt ≈ 0.28, see IntegratorStability) and
// keeps a residual jitter; it comes to rest at the paper's check step Δt = 1e-5 s
TEST(Pile, ThreeHundredDecagonsSettleToRestWithPlausiblePhi) {
  SceneSpec s = build::decagon_pile(300, 0.24, 1.0, 3);
  s.integrator.kind = IntegratorKind::VelocityVerlet;
  testing::TestWorld tw(s);
  Simulation& sim = tw.start();
  sim.run(static_cast<std::int64_t>(3.0 / s.integrator.dt));
  const World& w = sim.world();
  double top = 0;
  for (std::size_t i = 0; i < w.size(); ++i) top = std::max(top, w.s.y[i]);
  // a window a few grains from the walls and below the free surface
  const double phi = phi_in_rect(w, 0.04, 0.04, 0.20, top - 0.06);
  std::printf(
      "[ measured ] 300-decagon pile: phi = %.4f, max speed %.2e m/s, KE %.2e J, "
      "height %.3f m, Z = %.2f\n",
      phi, max_speed(w), w.kinetic_energy(), top, mean_coordination(w, sim.contacts()));
  EXPECT_GT(phi, 0.78);
  EXPECT_LT(phi, 0.86);
  // at rest: the largest speed is three orders below the fall speed (√(2gh) ≈ 3 m/s from the
  // column) and the kinetic energy per grain is below 1e-9 J (a 9 mm grain falling 0.1 mm has
  // 2e-7 J); what remains is slow creep of a few grains
  EXPECT_LT(max_speed(w), 1e-2);
  EXPECT_LT(w.kinetic_energy() / w.size(), 1e-9);
}

TEST(Determinism, SameSceneSameHashEitherBroadPhase) {
  SceneSpec s = build::decagon_pile(60, 0.12, 0.6, 5);
  auto run = [&](BroadPhaseKind bp) {
    SceneSpec c = s;
    c.integrator.broad_phase = bp;
    testing::TestWorld tw(c);
    tw.start().run(4000);
    return state_hash(tw.world());
  };
  const std::uint64_t a = run(BroadPhaseKind::Box2DTree), b = run(BroadPhaseKind::Box2DTree);
  const std::uint64_t c = run(BroadPhaseKind::CellGrid);
  EXPECT_EQ(a, b);
  // contacts are sorted by (i, j, image) before forces: the broad phase cannot matter
  EXPECT_EQ(a, c);
}

#ifdef _OPENMP
// forces are computed per pair in parallel and summed in key order: the thread count cannot
// change a single bit of the trajectory
TEST(Determinism, SameHashForOneAndTwoThreads) {
  // the settled paper pile: ~3500 candidate pairs, well above the parallel threshold
  const std::string src = GS_SOURCE_DIR;
  SceneSpec s = parse_scene_file(src + "/scenes/paper_pile.toml");
  auto run = [&](int threads) {
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    World w = make_world(s);
    read_state_file(w, src + "/scenes/data/paper_pile_settled.csv");
    Simulation sim(std::move(w), SimSettings::from(s));
    sim.run(100);
    omp_set_num_threads(before);
    return state_hash(sim.world());
  };
  EXPECT_EQ(run(1), run(2));
}

// the same for Model S: a randomly forced periodic fluid (pair loop, per-particle sums, fused
// noise) and a 10⁴-disk ring (its kick mean is a blocked sum over 3 blocks)
std::uint64_t threads_hash(const SceneSpec& s, int threads, std::int64_t steps) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  World w = make_world(s);
  place_particles(w, s);
  Simulation sim(std::move(w), SimSettings::from(s));
  sim.run(steps);
  omp_set_num_threads(before);
  return state_hash(sim.world());
}

TEST(Determinism, SameHashForOneAndTwoThreadsDiskFluidAndRing) {
  SceneSpec fluid = build::disk_gas(3000, 0.5, 0.6, 0.6, 2);
  fluid.drive.kind = DriveKind::RandomForce;
  EXPECT_EQ(threads_hash(fluid, 1, 300), threads_hash(fluid, 2, 300));
  SceneSpec ring = parse_scene_file(std::string(GS_SOURCE_DIR) + "/scenes/rfm1d_reference.toml");
  ring.species[0].count = 10000;
  EXPECT_EQ(threads_hash(ring, 1, 300), threads_hash(ring, 2, 300));
}
#endif

}  // namespace
}  // namespace gs
