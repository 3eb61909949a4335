// a benchmark that reports a per-core rate runs on one OpenMP thread, and gives the thread
// count back when it ends (so benchmarks after it in the same process run as asked)
#pragma once
#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs {

struct OneThread {
#ifdef _OPENMP
  int before = omp_get_max_threads();
  OneThread() { omp_set_num_threads(1); }
  ~OneThread() { omp_set_num_threads(before); }
#endif
  OneThread(const OneThread&) = delete;
  OneThread& operator=(const OneThread&) = delete;
};

}  // namespace gs
