// the OpenMP team a run gets: its thread count and the CPUs its threads may run on (run.json
// reports both)
#pragma once

namespace gs {

/// the team of a parallel region: threads, and distinct CPUs in the union of their masks
struct OpenMpTeam {
  int threads = 1;
  int cpus = 1;
};
OpenMpTeam openmp_team();

/// the spin count gransim gives the runs it starts with several threads each (docs/threads.md):
/// the runtime's default lets a waiting thread sleep after ~300 000 rounds, and on virtual
/// machines the wake-up costs so much that two threads can run slower than one
inline constexpr const char* kSpinCount = "GOMP_SPINCOUNT=10000000";

/// has the user chosen the OpenMP runtime's wait policy (OMP_WAIT_POLICY or GOMP_SPINCOUNT set
/// and not empty)? The runtime reads it once, as it loads: only a new process can change it
bool wait_policy_chosen();

}  // namespace gs
