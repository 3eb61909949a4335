// shared rules of the OpenMP loops. Every parallel loop either writes disjoint elements, or
// combines per-item results in a fixed order that does not depend on the thread count
// (per-candidate results gathered per particle in candidate order; sums over fixed blocks), so
// a run's results are bitwise the same on any number of threads. Below the thresholds the
// same bodies run as plain serial loops (no OpenMP runtime calls at all).
#pragma once
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <ctime>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs {

/// items as costly as a polygon pair (a clip and an area) worth a parallel region
inline constexpr std::size_t kParallelMin = 1000;
/// items as cheap as a disk pair or an elementwise particle loop worth a parallel region: the
/// region's start and barrier must be shared by many of them
inline constexpr std::size_t kParallelMinCheap = 8192;

/// the block length of deterministic blocked sums and scans: results depend on it, never on
/// the thread count (one block, n <= kSumBlock, is the plain left-to-right sum)
inline constexpr std::size_t kSumBlock = 4096;

/// will a loop of n items with this threshold run in parallel?
inline bool run_parallel(std::size_t n, std::size_t threshold) {
#ifdef _OPENMP
  return n >= threshold && omp_get_max_threads() > 1 && !omp_in_parallel();
#else
  (void)n;
  (void)threshold;
  return false;
#endif
}

/// this thread's number in its team, the team's size, the threads a new region would get
/// (0, 1, 1 without OpenMP)
inline int team_thread() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}
inline int team_size() {
#ifdef _OPENMP
  return omp_get_num_threads();
#else
  return 1;
#endif
}
inline int max_team_size() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}
/// thread t of nt's contiguous share of n items, equal ones: [n·t/nt, n·(t+1)/nt). A
/// simulation's particle loops split by its ThreadTeam instead (core/team.hpp)
struct ItemRange {
  std::size_t begin, end;
};
inline ItemRange equal_share(std::size_t n, int t, int nt) {
  const auto ut = static_cast<std::size_t>(t), unt = static_cast<std::size_t>(nt);
  return {n * ut / unt, n * (ut + 1) / unt};
}

/// wall-clock seconds (for timing a thread's share of a loop)
inline double wall_seconds() {
#ifdef _OPENMP
  return omp_get_wtime();
#else
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
#endif
}

/// this process' CPU time, all threads, s: a run's cost whatever else the machine was doing
inline double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// a non-owning reference to a callable body(begin, end) over a range of items: no allocation,
/// for passing a per-range step into a hot loop (the callable must outlive the reference)
class RangeFn {
 public:
  RangeFn() = default;
  template <class F>
  explicit RangeFn(F& f)
      : obj_(const_cast<void*>(static_cast<const void*>(&f))),
        call_([](void* o, std::size_t b, std::size_t e) { (*static_cast<F*>(o))(b, e); }) {}
  explicit operator bool() const { return call_ != nullptr; }
  void operator()(std::size_t b, std::size_t e) const { call_(obj_, b, e); }

 private:
  void* obj_ = nullptr;
  void (*call_)(void*, std::size_t, std::size_t) = nullptr;
};

/// body(begin, end) over [0, n): one serial call, or in parallel over contiguous ranges, one
/// per thread, thread t of nt's range share(n, t, nt) (asked once per thread and region)
template <class Share, class Body>
void parallel_shares(std::size_t n, std::size_t threshold, const Share& share, Body&& body) {
#ifdef _OPENMP
  if (run_parallel(n, threshold)) {
#pragma omp parallel
    {
      const ItemRange r = share(n, team_thread(), team_size());
      body(r.begin, r.end);
    }
    return;
  }
#endif
  (void)threshold;
  (void)share;
  body(std::size_t{0}, n);
}

/// the same over equal shares (a loop outside a simulation; a simulation's particle loops take
/// its ThreadTeam: core/team.hpp)
template <class Body>
void parallel_ranges(std::size_t n, std::size_t threshold, Body&& body) {
  parallel_shares(
      n, threshold, [](std::size_t m, int t, int nt) { return equal_share(m, t, nt); }, body);
}

/// body(begin, end) over [0, n) in chunks handed out dynamically (uneven item costs), or one
/// serial call
template <class Body>
void parallel_chunks(std::size_t n, std::size_t threshold, std::size_t chunk, Body&& body) {
#ifdef _OPENMP
  if (run_parallel(n, threshold)) {
    const auto nchunks = static_cast<std::int64_t>((n + chunk - 1) / chunk);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t c = 0; c < nchunks; ++c) {
      const std::size_t b = static_cast<std::size_t>(c) * chunk;
      body(b, b + chunk < n ? b + chunk : n);
    }
    return;
  }
#endif
  (void)threshold;
  (void)chunk;
  body(std::size_t{0}, n);
}

}  // namespace gs
