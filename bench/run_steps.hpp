// one benchmark iteration's steps, taken as `gransim run` takes them (app/run/run_loop.cpp): where
// nothing looks at the state in between, several at once (Simulation::run: a disk step's kick
// then predicts the next step); with an observer, as many as it lets pass (quiet_steps)
#pragma once
#include <algorithm>
#include <cstdint>

#include "sim/observer.hpp"
#include "sim/simulation.hpp"

namespace gs {

/// steps per iteration without an observer (the run loop's batches reach 64: this is fewer)
inline constexpr std::int64_t kRunBatch = 16;

/// run one iteration's steps (and the observer after the last); returns how many
inline std::int64_t run_iteration(Simulation& sim, Observer* obs = nullptr) {
  std::int64_t m = obs ? 1 + obs->quiet_steps(sim) : kRunBatch;
  if (sim.sort_every() > 0) m = std::min(m, sim.sort_every());  // one sort per observer call
  sim.run(m);
  if (obs) obs->after_step(sim);
  return m;
}

}  // namespace gs
