// the 1D ring (docs/physics.md §5.2): an elastic gas (ε = 1) of equal masses only exchanges
// velocities, so in reduced coordinates (T.3.16) the particles are independent "ghosts" and, once
// they have moved many spacings, the N gaps on L′ are those of N uniform points: R/L′ ~ Beta(1,
// N−1) with ⟨R⟩ = L′/N, ⟨R²⟩ = 2L′²/(N(N+1)), ⟨R³⟩ = 6L′³/(N(N+1)(N+2)) (exponential for large N).
// Also: the ring-neighbour broad phase emits exactly the neighbour pairs with the right image.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "broadphase/broadphase.hpp"
#include "core/rng.hpp"
#include "measure/memory_records.hpp"
#include "measure/rfm_observer.hpp"
#include "scene/parse.hpp"
#include "sim/simulation.hpp"
#include "world/prepare.hpp"

namespace gs {
std::unique_ptr<BroadPhase> make_ring_neighbours();  // broadphase/ring_neighbours.cpp

namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("gs_rfm_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// N = 200 elastic rods on L′ = 1 m, fast random initial velocities (components U(−1, 1) m/s)
// so that by t = 0.2 s every ghost has moved ~20 spacings; then 200 samples 2 ms apart
constexpr const char* kElasticRing = R"(
[model]
kind = "S"
rotation = false
[[material]]
name = "elastic"
eps_n = 1.0
eps_t = 1.0
[[species]]
name = "rod"
radius = 0.0015
mass = 3.53e-5
count = 200
[box]
kind = "ring"
reduced_length = 1.0
[preparation]
seed = 11
velocity_amplitude = 2.0
[integrator]
dt = 2e-6
[drive]
kind = "random_force"
[rfm]
sample_every = 1000
discard_time = 0.2
blocks = 20
gap_min = 1e-9
gap_bins = 90
)";

TEST(RfmRing, ElasticGasHasUniformPointGaps) {
  SceneSpec s = parse_scene_string(kElasticRing, "elastic_ring.toml");
  ASSERT_TRUE(s.rfm.enabled);
  World w = make_world(s);
  place_particles(w, s);
  Simulation sim(std::move(w), SimSettings::from(s));
  const fs::path dir = temp_dir("ring");
  test::MemoryRecords records;
  RfmObserver obs(s, records);
  obs.start(sim, dir.string());
  const auto steps = static_cast<std::int64_t>(std::llround(0.6 / s.integrator.dt));
  std::vector<double> x0(sim.world().s.x);
  bool ordered = true;
  for (std::int64_t k = 0; k < steps; ++k) {
    sim.step();
    obs.after_step(sim);
  }
  obs.finish(sim);
  // order preserved: each particle is still its predecessor's forward neighbour
  const World& wr = sim.world();
  for (std::size_t i = 0; i + 1 < wr.size(); ++i) {
    double g = wr.separation(i, i + 1).x;
    if (g < 0) ordered = false;
  }
  EXPECT_TRUE(ordered);

  const double n = 200.0;
  ASSERT_GE(obs.samples(), 190);
  // the series went to the record sink, one row per sample (transient included), never to a
  // file of the observer's own; the summary is a document of the sink
  const auto& series = *records.tables.at((dir / "rfm_series.csv").string());
  EXPECT_EQ(series.rows.size(), static_cast<std::size_t>(steps / 1000 + 1));
  EXPECT_GE(series.rows.size(), static_cast<std::size_t>(obs.samples()));
  EXPECT_FALSE(fs::exists(dir / "rfm_series.csv"));
  EXPECT_EQ(records.documents.count((dir / "rfm.json").string()), 1u);
  EXPECT_FALSE(fs::exists(dir / "rfm.json"));
  // so did every end-of-run table: the observer opened no file of its own
  for (const char* f :
       {"temperature.csv", "moments.csv", "hist_velocity.csv", "hist_postcollision.csv",
        "velocity.csv", "hist_freepath.csv", "freepath.csv", "gh.csv", "gap_moments.csv"})
    EXPECT_EQ(records.tables.count((dir / f).string()), 1u) << f;
  EXPECT_TRUE(fs::is_empty(dir));
  // a raw histogram carries its binning and totals as metadata
  const auto& raw = *records.tables.at((dir / "hist_freepath.csv").string());
  ASSERT_FALSE(raw.meta.empty());
  EXPECT_EQ(raw.meta.front().first, "scale");
  const auto& m = *records.tables.at((dir / "gap_moments.csv").string());
  const std::vector<double> mom = m.col("moment"), err = m.col("error");
  // ⟨R⟩ = L′/N up to the overlaps of touching pairs (δ ≲ 3e-5 m ≪ L′/N = 5e-3 m)
  EXPECT_NEAR(mom[0], 1.0 / n, 1e-4 / n);
  // ⟨R²⟩ and ⟨R³⟩ within 4 block errors, and the errors small enough to mean something
  const double r2 = 2.0 / (n * (n + 1)), r3 = 6.0 / (n * (n + 1) * (n + 2));
  EXPECT_NEAR(mom[1], r2, 4.0 * err[1]);
  EXPECT_LT(err[1] / r2, 0.03);
  EXPECT_NEAR(mom[2], r3, 4.0 * err[2]);
  EXPECT_LT(err[2] / r3, 0.06);

  // G₁ against the Beta(1, N−1) law: the largest CDF difference over the bin edges
  // (≈ 40 000 gaps, a few thousand independent: KS noise ≈ 0.02)
  const rfm::GapStatistics* g = obs.gaps();
  ASSERT_NE(g, nullptr);
  const rfm::Histogram& h1 = g->histogram(0);
  double cum = h1.underflow(), worst = 0.0;
  for (int i = 0; i < h1.binning().n; ++i) {
    cum += h1.counts()[static_cast<std::size_t>(i)];
    const double exact = 1.0 - std::pow(1.0 - h1.binning().edge(i + 1), n - 1);
    worst = std::max(worst, std::abs(cum / h1.total() - exact));
  }
  EXPECT_LT(worst, 0.03);
  std::printf(
      "elastic ring N = 200: <R>N = %.5f, <R^2>/exact = %.4f +- %.4f, <R^3>/exact = %.4f +- "
      "%.4f, KS distance %.4f\n",
      mom[0] * n, mom[1] / r2, err[1] / r2, mom[2] / r3, err[2] / r3, worst);
  // G_h for h = 2: a sum of two gaps, ⟨R_{i,i+2}⟩ = 2L′/N
  double mean2 = 0.0;
  for (const auto& b : g->g(1)) mean2 += b.x * b.p * (b.hi - b.lo);
  EXPECT_NEAR(mean2, 2.0 / n, 0.05 * 2.0 / n);
  fs::remove_all(dir);
}

// the ring-neighbour broad phase: N keys, ascending, each neighbour pair once with the image
// that puts the partner ahead; every touching pair (brute force, minimum image) is among them
TEST(RfmRing, NeighbourBroadPhaseEmitsNeighbourPairs) {
  RngStream rng(3, 0);
  for (int n : {2, 3, 10, 57}) {
    const double d = 0.003, L = n * d + 0.05;
    SceneSpec s = parse_scene_string(std::string(R"(
[model]
kind = "S"
[[species]]
name = "rod"
radius = 0.0015
count = )") + std::to_string(n) + "\n[box]\nkind = \"ring\"\nwidth = " +
                                         std::to_string(L) + "\n",
                                     "ring.toml");
    World w = make_world(s);
    place_particles(w, s);
    auto bp = make_ring_neighbours();
    std::vector<PairKey> keys;
    for (int trial = 0; trial < 50; ++trial) {
      // random ordered gaps (some overlapping), shifted by whole boxes at random (unwrapped)
      double x = rng.uniform(-3.0, 3.0) * L;
      const double slack = L - n * d;
      std::vector<double> gaps(n);
      double sum = 0.0;
      for (double& g : gaps) sum += (g = rng.uniform());
      for (int i = 0; i < n; ++i) {
        w.s.x[i] = x + std::floor(rng.uniform(-2.0, 3.0)) * L;
        x += d + slack * gaps[i] / sum - (rng.uniform() < 0.3 ? 0.1 * d : 0.0);
      }
      bp->update(w, keys);
      ASSERT_EQ(keys.size(), static_cast<std::size_t>(n));
      EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
      EXPECT_EQ(std::adjacent_find(keys.begin(), keys.end()), keys.end());
      for (PairKey k : keys) {
        const std::uint32_t i = key_i(k), j = key_j(k);
        EXPECT_LT(i, j);
        EXPECT_TRUE(j == i + 1 || (i == 0 && j == static_cast<std::uint32_t>(n - 1)));
        // the image puts j within one diameter of a neighbour position of i
        const double dx = w.s.x[j] + image_sx(key_image(k)) * L - w.s.x[i];
        EXPECT_LT(std::abs(dx), L - d + 1e-12);
        EXPECT_EQ(image_sy(key_image(k)), 0);
      }
      // every touching pair is there with its minimum image (n ≥ 3: one image touches)
      if (n >= 3) {
        for (int i = 0; i < n; ++i)
          for (int j = i + 1; j < n; ++j) {
            double dx = w.s.x[j] - w.s.x[i];
            const int sx = -static_cast<int>(std::nearbyint(dx / L));
            dx += sx * L;
            if (std::abs(dx) < d) {
              const PairKey k = make_key(i, j, make_image(sx, 0));
              EXPECT_TRUE(std::binary_search(keys.begin(), keys.end(), k)) << i << " " << j;
            }
          }
      }
    }
  }
}

// along a dissipative ring run with the cell grid, every touching pair (the keys the force
// loop used) is among the ring-neighbour keys, with the same image: the two broad phases give
// the same contacts, so the same forces bit for bit (the force loop sees sorted touching keys)
TEST(RfmRing, NeighbourBroadPhaseFindsEveryContactOfACellGridRun) {
  SceneSpec s = parse_scene_string(R"(
[model]
kind = "S"
[[material]]
name = "m"
eps_n = 0.1
[[species]]
name = "rod"
radius = 0.0015
mass = 3.53e-5
count = 100
[box]
kind = "ring"
reduced_length = 0.05
[preparation]
velocity_amplitude = 1.0
[integrator]
broad_phase = "cell_grid"
[drive]
kind = "random_force"
)",
                                   "ring.toml");
  World w = make_world(s);
  place_particles(w, s);
  Simulation sim(std::move(w), SimSettings::from(s));
  ASSERT_STREQ(sim.broadphase().name(), "cell_grid");
  auto bp = make_ring_neighbours();
  std::vector<PairKey> keys;
  long contacts = 0;
  for (int k = 0; k < 20000; ++k) {
    sim.step();
    bp->update(sim.world(), keys);
    for (PairKey c : sim.contacts().keys) {
      ASSERT_TRUE(std::binary_search(keys.begin(), keys.end(), c)) << "step " << k;
      ++contacts;
    }
  }
  EXPECT_GT(contacts, 20000);  // a dense, clustering ring: many contacts were compared
}

}  // namespace
}  // namespace gs
