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

}  // namespace gs
