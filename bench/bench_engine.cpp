// whole-engine benchmarks: the overlaps of the settled 1184-decagon paper pile's pairs, one
// force evaluation and whole steps of that pile, and steps of a 10⁴-disk forced periodic fluid.
// Counters report particle-steps/s.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <utility>
#include <vector>

#include "geometry/prepared.hpp"
#include "run_steps.hpp"
#include "scene/parse.hpp"
#include "sim/builders.hpp"
#include "sim/simulation.hpp"
#include "sim/state_file.hpp"
#include "world/prepare.hpp"

namespace gs {
namespace {

// the paper pile's scene (scenes/) with the given integrator
SceneSpec pile_scene(IntegratorKind integ) {
  SceneSpec s = parse_scene_file(std::string(GS_SOURCE_DIR) + "/scenes/paper_pile.toml");
  s.integrator.kind = integ;
  return s;
}

// the paper pile, settled: positions from scenes/data (made by gransim run)
World settled_pile(IntegratorKind integ) {
  World w = make_world(pile_scene(integ));
  read_state_file(w, std::string(GS_SOURCE_DIR) + "/scenes/data/paper_pile_settled.csv");
  return w;
}

void BM_PileForceEvaluation(benchmark::State& st) {
  World w = settled_pile(IntegratorKind::Gear6);
  auto bp = make_broadphase(BroadPhaseKind::Box2DTree, w);
  ContactModel model(w, contact_settings(pile_scene(IntegratorKind::Gear6)));
  ThreadTeam team;
  ContactSet cs;
  ForceBuffer f;
  std::vector<PairKey> cand;
  bp->update(w, cand);
  for (auto _ : st) {
    f.reset(w.size());
    benchmark::DoNotOptimize(model.evaluate(w, cand, cs, f, 5e-5, team));
  }
  st.counters["contacts"] = static_cast<double>(cs.keys.size());
  st.counters["particles/s"] = benchmark::Counter(static_cast<double>(w.size()) * st.iterations(),
                                                  benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PileForceEvaluation)->Unit(benchmark::kMicrosecond);

// the prepared decagon overlap on the settled pile's own pairs (every grain pair whose bounding
// circles meet, in index order): the contact hot loop's kernel on the overlaps the pile has,
// shallow and mostly face to face, which BM_DecagonOverlapPrepared's deep random pairs are not
void BM_PileOverlaps(benchmark::State& st) {
  const World w = settled_pile(IntegratorKind::Gear6);
  PolyStore shapes;
  shapes.resize(w.size(), 10);
  for (std::size_t i = 0; i < w.size(); ++i)
    shapes.set_placed(i, w.species[w.sp[i]].body, {w.s.x[i], w.s.y[i]}, w.s.th[i]);
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < w.size(); ++i)
    for (std::size_t j = i + 1; j < w.size(); ++j) {
      const double r = shapes.ref(i).radius + shapes.ref(j).radius;
      if (norm2(shapes.ref(i).mean - shapes.ref(j).mean) < r * r) pairs.push_back({i, j});
    }
  std::size_t touching = 0;
  for (auto _ : st) {
    touching = 0;
    for (const auto& [i, j] : pairs) {
      const Overlap o = overlap(shapes.ref(i), shapes.ref(j));
      touching += o.area > 0.0;
      benchmark::DoNotOptimize(o);
    }
  }
  st.counters["pairs"] = static_cast<double>(pairs.size());
  st.counters["touching"] = static_cast<double>(touching);
  st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(pairs.size()));
}
BENCHMARK(BM_PileOverlaps)->Unit(benchmark::kMicrosecond);

void BM_PileStep(benchmark::State& st) {
  const auto integ = static_cast<IntegratorKind>(st.range(0));
  const auto bpk = static_cast<BroadPhaseKind>(st.range(1));
  Simulation sim(settled_pile(integ), SimSettings::from(pile_scene(integ)), bpk);
  std::int64_t steps = 0;
  for (auto _ : st) steps += run_iteration(sim);
  st.SetLabel(std::string(to_string(integ)) + "/" + sim.broadphase().name());
  const double n = static_cast<double>(sim.world().size());
  st.counters["contacts/N"] = static_cast<double>(sim.contacts().keys.size()) / n;
  st.counters["candidates/N"] = static_cast<double>(sim.last_forces().candidates) / n;
  st.counters["particle-steps/s"] =
      benchmark::Counter(static_cast<double>(sim.world().size()) * static_cast<double>(steps),
                         benchmark::Counter::kIsRate);
  // wall time per step (an iteration is kRunBatch steps), s
  st.counters["s/step"] = benchmark::Counter(
      static_cast<double>(steps), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_PileStep)
    ->Args({static_cast<int>(IntegratorKind::Gear6), static_cast<int>(BroadPhaseKind::Box2DTree)})
    ->Args({static_cast<int>(IntegratorKind::Gear6), static_cast<int>(BroadPhaseKind::CellGrid)})
    ->Args({static_cast<int>(IntegratorKind::VelocityVerlet),
            static_cast<int>(BroadPhaseKind::Box2DTree)})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();  // wall time: with 2 threads the main thread's CPU time misses the waits

void BM_DiskFluidStep(benchmark::State& st) {
  SceneSpec s = build::disk_gas(static_cast<int>(st.range(0)), 0.353, 0.6, 0.6, 1);
  s.drive.kind = DriveKind::RandomForce;
  World w = make_world(s);
  place_particles(w, s);
  Simulation sim(std::move(w), SimSettings::from(s));
  sim.run(200);  // leave the lattice-like start
  std::int64_t steps = 0;
  for (auto _ : st) steps += run_iteration(sim);
  st.counters["particle-steps/s"] =
      benchmark::Counter(static_cast<double>(sim.world().size()) * static_cast<double>(steps),
                         benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DiskFluidStep)->Arg(10000)->Unit(benchmark::kMicrosecond)->UseRealTime();

}  // namespace
}  // namespace gs
