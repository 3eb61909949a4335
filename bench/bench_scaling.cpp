// Cost flatness: whole steps of the randomly forced periodic disk fluid (thesis disks, φ = 0.353,
// ε_n = ε_t = 0.6, D = 1e-8 N²s, velocity Verlet at Δt = 1e-6 s, cell grid) at N = 10³ … 10⁶,
// the box scaled with √N so φ stays the same. One thread, so the counter is particle-steps per
// second per core; bench/summary.py prints the cost per particle-step relative to N = 10⁴.
// Every size gets the same warm-up (100 steps out of the random start, whose lattice sites are 2%
// of a diameter apart): the disks have barely met yet (contacts/N ≈ 0.01), so this measures the
// broad phase, the noise, the integrator and a sparse force loop, the parts whose cost could grow
// with N. The 10⁶ case costs ≈ 10–30 s (set-up and warm-up included).
#include <benchmark/benchmark.h>

#include "sim/builders.hpp"
#include "sim/simulation.hpp"
#include "world/prepare.hpp"

#include "one_thread.hpp"

namespace gs {
namespace {

void BM_FluidCostScaling(benchmark::State& st) {
  const OneThread one;  // the rate is per core
  SceneSpec s = build::disk_gas(static_cast<int>(st.range(0)), 0.353, 0.6, 0.6, 1);
  s.drive.kind = DriveKind::RandomForce;
  World w = make_world(s);
  place_particles(w);
  Simulation sim(std::move(w));
  sim.run(100);  // leave the lattice-like start (the same for every N)
  for (auto _ : st) sim.step();
  const double n = static_cast<double>(sim.world().size());
  st.counters["particle-steps/s"] =
      benchmark::Counter(n * static_cast<double>(st.iterations()), benchmark::Counter::kIsRate);
  st.counters["contacts/N"] = static_cast<double>(sim.contacts().keys.size()) / n;
  st.counters["candidates/N"] = static_cast<double>(sim.last_forces().candidates) / n;
}
BENCHMARK(BM_FluidCostScaling)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace gs
