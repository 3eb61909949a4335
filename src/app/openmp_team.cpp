#include "app/openmp_team.hpp"

#include <sched.h>

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

}  // namespace gs
