// the OpenMP team a run gets: its thread count and the CPUs its threads may run on (run.json
// reports both), and the CPU mask to restart the process with (src/main.cpp)
#pragma once

namespace gs {

/// the team of a parallel region: threads, and distinct CPUs in the union of their masks
struct OpenMpTeam {
  int threads = 1;
  int cpus = 1;
};
OpenMpTeam openmp_team();

/// Widen the calling thread's CPU mask to every CPU of the runtime's places. With
/// OMP_PROC_BIND the runtime binds the first thread to one CPU as it loads; a process that
/// then restarts itself (execv keeps the mask) would start with that one CPU only, and the
/// runtime would bind every thread of the new process to it. No places (no binding asked
/// for): nothing to do. Returns whether the mask was changed.
bool widen_to_places();

}  // namespace gs
