// Random Force Model benchmarks: whole steps of the 2D reference fluid (scenes/rfm2d_reference:
// N = 2000, φ = 0.353, ε = 0.6, noise D = 1e-8) and of the 1D ring (scenes/rfm1d_reference:
// N = 1000, L′ = 1 m, ε = 0.1), with and without the RFM observer, on one thread so the counter
// reads particle-steps per second per core; and the ring-neighbour broad phase on its own.
// The fluids are warmed up out of their lattice starts first.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>

#include "measure/rfm_observer.hpp"
#include "one_thread.hpp"
#include "output/csv.hpp"
#include "run_steps.hpp"
#include "scene/parse.hpp"
#include "sim/simulation.hpp"
#include "world/prepare.hpp"

namespace gs {
std::unique_ptr<BroadPhase> make_ring_neighbours();  // broadphase/ring_neighbours.cpp

namespace {

// a scene of scenes/ with overrides
SceneSpec reference(const char* scene, std::vector<std::string> sets) {
  return parse_scene_file(std::string(GS_SOURCE_DIR) + "/scenes/" + scene, sets);
}

// the scene's fluid after `warm` seconds of driving (uniform start for the 2D fluid: the
// square lattice of the reference scene is a dense block that takes ~0.1 s to spread)

std::unique_ptr<Simulation> warmed(const SceneSpec& s, double warm) {
  World w = make_world(s);
  place_particles(w, s);
  auto sim = std::make_unique<Simulation>(std::move(w), SimSettings::from(s));
  sim->run(static_cast<std::int64_t>(warm / s.integrator.dt));
  return sim;
}

void rate(benchmark::State& st, const Simulation& sim, std::int64_t steps) {
  st.counters["particle-steps/s"] =
      benchmark::Counter(static_cast<double>(sim.world().size()) * static_cast<double>(steps),
                         benchmark::Counter::kIsRate);
  st.counters["contacts"] = static_cast<double>(sim.contacts().keys.size());
}

// the 2D reference fluid; range(0) = 1 adds the RFM observer (sampling every 1000 steps,
// S(k) and g(R) every 10th sample, contacts followed every step)
void BM_Rfm2DReferenceStep(benchmark::State& st) {
  const OneThread one;  // the rate is per core
  const SceneSpec scene = reference("rfm2d_reference.toml", {"preparation.placement=uniform"});
  auto sim = warmed(scene, 0.05);
  std::unique_ptr<RfmObserver> obs;
  const std::string dir = (std::filesystem::temp_directory_path() / "gs_bench_rfm2d").string();
  if (st.range(0)) {
    std::filesystem::create_directories(dir);
    SceneSpec s = scene;
    s.rfm.discard_time = 0.0;
    obs = std::make_unique<RfmObserver>(s, csv_records());
    obs->start(*sim, dir);
  }
  std::int64_t steps = 0;
  for (auto _ : st) steps += run_iteration(*sim, obs.get());
  rate(st, *sim, steps);
  st.SetLabel(st.range(0) ? "with RFM observer" : "bare");
  if (obs) std::filesystem::remove_all(dir);
}
BENCHMARK(BM_Rfm2DReferenceStep)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond)->MinTime(3.0);

// the 1D ring (cell-grid broad phase, as selected by the scene)
void BM_Rfm1DRingStep(benchmark::State& st) {
  const OneThread one;  // the rate is per core
  const SceneSpec scene = reference("rfm1d_reference.toml", {});
  auto sim = warmed(scene, 0.05);
  std::unique_ptr<RfmObserver> obs;
  const std::string dir = (std::filesystem::temp_directory_path() / "gs_bench_rfm1d").string();
  if (st.range(0)) {
    std::filesystem::create_directories(dir);
    SceneSpec s = scene;
    s.rfm.discard_time = 0.0;
    obs = std::make_unique<RfmObserver>(s, csv_records());
    obs->start(*sim, dir);
  }
  std::int64_t steps = 0;
  for (auto _ : st) steps += run_iteration(*sim, obs.get());
  rate(st, *sim, steps);
  st.SetLabel(std::string(sim->broadphase().name()) +
              (st.range(0) ? ", with RFM observer" : ", bare"));
  if (obs) std::filesystem::remove_all(dir);
}
BENCHMARK(BM_Rfm1DRingStep)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond)->MinTime(3.0);

// the ring-neighbour broad phase alone (always a full O(N) pass; the cell grid is not timed
// this way: with a Verlet skin it returns its cached list when nothing moves)
void BM_RingNeighbours(benchmark::State& st) {
  const OneThread one;  // the rate is per core
  auto sim = warmed(reference("rfm1d_reference.toml", {}), 0.01);
  auto bp = make_ring_neighbours();
  std::vector<PairKey> keys;
  for (auto _ : st) {
    bp->update(sim->world(), keys);
    benchmark::DoNotOptimize(keys.data());
  }
  st.counters["particles/s"] = benchmark::Counter(
      static_cast<double>(sim->world().size()) * static_cast<double>(st.iterations()),
      benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RingNeighbours)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace gs
