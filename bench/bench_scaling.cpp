// Cost flatness: whole steps of the randomly forced periodic disk fluid (thesis disks, φ = 0.353,
// ε_n = ε_t = 0.6, D = 1e-8 N²s, velocity Verlet at Δt = 1e-6 s, cell grid) at N = 10³ … 10⁶,
// one thread, so the counter is particle-steps per second per core; bench/summary.py prints
// the cost per particle-step relative to N = 10⁴.
//
// Every size is measured in the same *stationary* state. Out of its lattice-like start the
// fluid needs ≈ 10⁴ steps to settle (candidate pairs per disk 1.2 → 0.41), and Google Benchmark
// runs a small system for many more steps than a large one, so a plain warm-up would compare
// sizes in different states. Hence N = 10³ and 10⁴ run 12 000 steps from their start; 10⁵ and
// 10⁶ are the settled 10⁴ box tiled 5 × 2 and 10 × 10 (a periodic state of the larger box; the
// copies' random forces differ, so they decorrelate), in the cell order the spatial sort keeps
// (integrator.sort_every, auto from 5·10⁴ disks). BM_FluidMixedOrder gives the same 10⁶ state
// with the particles numbered at random — where an unsorted run drifts as the fluid mixes — (and
// 5·10⁴, 10⁵: where the auto sort starts) and BM_SortParticles one sort.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <memory>
#include <numeric>
#include <random>

#include "one_thread.hpp"
#include "run_steps.hpp"
#include "sim/builders.hpp"
#include "sim/simulation.hpp"
#include "world/prepare.hpp"

namespace gs {
namespace {

constexpr int kSettleSteps = 12000;

SceneSpec fluid(int n) {
  SceneSpec s = build::disk_gas(n, 0.353, 0.6, 0.6, 1);
  s.drive.kind = DriveKind::RandomForce;
  return s;
}

// the settled fluid of n disks (run from its own start)
const World& settled(int n) {
  static std::map<int, World> cache;
  auto it = cache.find(n);
  if (it == cache.end()) {
    const SceneSpec s = fluid(n);
    World w = make_world(s);
    place_particles(w, s);
    Simulation sim(std::move(w), SimSettings::from(s));
    sim.run(kSettleSteps);
    it = cache.emplace(n, sim.world()).first;
  }
  return it->second;
}

// the settled 10⁴ box tiled kx × ky; `shuffle`: the particles numbered at random
World tiled(int kx, int ky, bool shuffle) {
  const World& base = settled(10000);
  SceneSpec s = fluid(10000 * kx * ky);
  s.box.width = base.Lx * kx;
  s.box.height = base.Ly * ky;
  World w = make_world(s);
  for (int ty = 0; ty < ky; ++ty)
    for (int tx = 0; tx < kx; ++tx)
      for (std::size_t i = 0; i < base.size(); ++i) {
        const Vec2 p = base.unwrapped(i);
        const double x = p.x - base.Lx * std::floor(p.x / base.Lx) + tx * base.Lx;
        const double y = p.y - base.Ly * std::floor(p.y / base.Ly) + ty * base.Ly;
        w.add_particle(base.sp[i], {x, y}, 0.0, {base.s.vx[i], base.s.vy[i]});
      }
  if (shuffle) {
    std::vector<std::uint32_t> perm(w.size());
    std::iota(perm.begin(), perm.end(), 0u);
    std::shuffle(perm.begin(), perm.end(), std::mt19937_64(7));
    w.permute(perm);
    std::iota(w.id.begin(), w.id.end(), 0u);  // labels in the new, random slot order
  }
  return w;
}

// the measured simulations, kept between Google Benchmark's calls (set-up runs once)
Simulation& fluid_at(int n, bool mixed) {
  static std::map<std::pair<int, bool>, std::unique_ptr<Simulation>> cache;
  auto& slot = cache[{n, mixed}];
  if (!slot) {
    World w;
    if (n == 50000)
      w = tiled(5, 1, mixed);
    else if (n == 100000)
      w = tiled(5, 2, mixed);
    else if (n == 1000000)
      w = tiled(10, 10, mixed);
    else
      w = settled(n);
    SimSettings settings = SimSettings::from(fluid(n));  // the same for every n
    if (mixed) settings.sort_every = 0;
    slot = std::make_unique<Simulation>(std::move(w), settings);
    if (slot->sort_every() > 0) slot->sort_particles();  // as a sorting run keeps it
    slot->run(50);
  }
  return *slot;
}

void report(benchmark::State& st, const Simulation& sim, std::int64_t steps) {
  const double n = static_cast<double>(sim.world().size());
  st.counters["particle-steps/s"] =
      benchmark::Counter(n * static_cast<double>(steps), benchmark::Counter::kIsRate);
  st.counters["contacts/N"] = static_cast<double>(sim.contacts().keys.size()) / n;
  st.counters["candidates/N"] = static_cast<double>(sim.last_forces().candidates) / n;
}

// steps of the stationary fluid: in the order the sort keeps, or numbered at random
void fluid_steps(benchmark::State& st, bool mixed) {
  const OneThread one;  // the rate is per core
  Simulation& sim = fluid_at(static_cast<int>(st.range(0)), mixed);
  std::int64_t steps = 0;
  for (auto _ : st) steps += run_iteration(sim);
  report(st, sim, steps);
}
void BM_FluidCostScaling(benchmark::State& st) { fluid_steps(st, false); }
void BM_FluidMixedOrder(benchmark::State& st) { fluid_steps(st, true); }
BENCHMARK(BM_FluidCostScaling)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(50000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_FluidMixedOrder)
    ->Arg(50000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// one spatial sort: of the mixed 10⁶ state (range 1 = 0; each iteration sorts a fresh copy
// of it), and of the sorted state (1: the same simulation sorted again and again, its
// buffers kept, as a run that sorts every 1000 steps pays)
void BM_SortParticles(benchmark::State& st) {
  const OneThread one;
  const int n = static_cast<int>(st.range(0));
  if (st.range(1) == 1) {
    Simulation& sim = fluid_at(n, false);
    for (auto _ : st) sim.sort_particles();
    return;
  }
  const World from = fluid_at(n, true).world();
  for (auto _ : st) {
    st.PauseTiming();
    World w = from;
    SimSettings settings = SimSettings::from(fluid(n));
    settings.sort_every = 1000;
    Simulation sim(std::move(w), settings);
    st.ResumeTiming();
    sim.sort_particles();
  }
}
BENCHMARK(BM_SortParticles)
    ->Args({1000000, 0})
    ->Args({1000000, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

}  // namespace
}  // namespace gs
