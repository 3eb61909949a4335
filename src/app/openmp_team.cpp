#include "app/openmp_team.hpp"

#include <sched.h>

#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs {

OpenMpTeam openmp_team() {
  OpenMpTeam t;
  cpu_set_t all;
  CPU_ZERO(&all);
#ifdef _OPENMP
#pragma omp parallel
  {
    cpu_set_t mine;
    CPU_ZERO(&mine);
    const bool ok = sched_getaffinity(0, sizeof(mine), &mine) == 0;
#pragma omp critical(gs_openmp_team)
    {
      if (ok) CPU_OR(&all, &all, &mine);
      if (omp_get_thread_num() == 0) t.threads = omp_get_num_threads();
    }
  }
#else
  sched_getaffinity(0, sizeof(all), &all);
#endif
  t.cpus = CPU_COUNT(&all) > 0 ? CPU_COUNT(&all) : 1;
  return t;
}

bool widen_to_places() {
#ifdef _OPENMP
  const int places = omp_get_num_places();
  if (places <= 0) return false;
  cpu_set_t set;
  CPU_ZERO(&set);
  for (int p = 0; p < places; ++p) {
    std::vector<int> ids(static_cast<std::size_t>(omp_get_place_num_procs(p)));
    if (ids.empty()) continue;
    omp_get_place_proc_ids(p, ids.data());
    for (int id : ids)
      if (id >= 0 && id < CPU_SETSIZE) CPU_SET(id, &set);
  }
  return CPU_COUNT(&set) > 0 && sched_setaffinity(0, sizeof(set), &set) == 0;
#else
  return false;
#endif
}

}  // namespace gs
