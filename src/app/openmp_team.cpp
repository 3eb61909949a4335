#include "app/openmp_team.hpp"

#include <sched.h>

#include <cstdlib>
#include <initializer_list>

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

bool wait_policy_chosen() {
  // libgomp ignores an empty value as it ignores a missing one
  for (const char* name : {"OMP_WAIT_POLICY", "GOMP_SPINCOUNT"}) {
    const char* v = std::getenv(name);
    if (v != nullptr && *v != '\0') return true;
  }
  return false;
}

}  // namespace gs
