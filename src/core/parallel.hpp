// shared rules of the OpenMP loops. Every parallel loop either writes disjoint elements, or
// combines per-item results in a fixed order that does not depend on the thread count
// (per-candidate results gathered per particle in candidate order; sums over fixed blocks), so
// a run's results are bitwise the same on any number of threads. Below the thresholds the
// same bodies run as plain serial loops (no OpenMP runtime calls at all).
#pragma once
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs {

/// items of ~100 ns (polygon pairs) worth a parallel region
inline constexpr std::size_t kParallelMin = 1000;
/// items of a few ns (disk pairs, elementwise particle loops) worth a parallel region
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
/// the relative speeds of a team's threads, as the force pass measures them on its
/// per-particle work (the vCPUs of a virtual machine can run at different, drifting speeds:
/// docs/threads.md). Every per-particle split follows them, so equal work takes equal time.
/// Only where work goes changes, never a result. Updated between parallel regions by the
/// thread that runs the team; read inside regions. One per process: it describes the
/// machine, whichever simulation measured it.
class ThreadSpeeds {
 public:
  static ThreadSpeeds& get() {
    static ThreadSpeeds s;
    return s;
  }
  /// measured for a team of nt (> 1) threads?
  bool has(int nt) const { return nt > 1 && static_cast<std::size_t>(nt) + 1 == cum_.size(); }
  /// the first item of thread t's share of n (t = nt gives n)
  std::size_t split(std::size_t n, int t) const {
    const auto ut = static_cast<std::size_t>(t);
    if (ut + 1 >= cum_.size()) return n;
    return std::min(n, static_cast<std::size_t>(static_cast<double>(n) * cum_[ut]));
  }
  /// one measurement: thread t did items[t] in seconds[t]. Each thread's weight moves a quarter
  /// of the way towards its share of the summed rates, and never below a quarter of an equal
  /// share; a measurement without time or items is ignored
  void update(const double* items, const double* seconds, int nt) {
    if (nt < 2) return;
    const auto unt = static_cast<std::size_t>(nt);
    double total = 0.0;
    rate_.assign(unt, 0.0);
    for (std::size_t t = 0; t < unt; ++t) {
      if (!(items[t] > 0.0) || !(seconds[t] > 0.0)) return;
      rate_[t] = items[t] / seconds[t];
      total += rate_[t];
    }
    if (!(total > 0.0) || !std::isfinite(total)) return;
    if (!has(nt)) {  // start from equal shares
      w_.assign(unt, 1.0 / static_cast<double>(nt));
    }
    double sum = 0.0;
    for (std::size_t t = 0; t < unt; ++t) {
      w_[t] += 0.25 * (rate_[t] / total - w_[t]);
      w_[t] = std::max(w_[t], 0.25 / static_cast<double>(nt));
      sum += w_[t];
    }
    next_.assign(unt + 1, 0.0);
    double moved = has(nt) ? 0.0 : 1.0;
    for (std::size_t t = 0; t < unt; ++t) {
      next_[t + 1] = next_[t] + w_[t] / sum;
      if (has(nt)) moved = std::max(moved, std::abs(next_[t + 1] - cum_[t + 1]));
    }
    next_[unt] = 1.0;
    // the split moves only for a real difference: each particle that changes threads moves
    // its data between the cores' caches, and the step-to-step jitter of the timings is ~3%
    if (moved > kMinShift) cum_.swap(next_);
  }
  /// the smallest change of a split point (fraction of the items) that is applied
  static constexpr double kMinShift = 0.02;
  /// forget the measurements: equal shares again
  void reset() {
    cum_.clear();
    w_.clear();
  }

 private:
  std::vector<double> w_, cum_;      ///< weights; the applied cumulative fractions (nt + 1)
  std::vector<double> rate_, next_;  ///< scratch
};

/// thread t of nt's contiguous share of n items: [n·t/nt, n·(t+1)/nt), or by the measured
/// thread speeds (ThreadSpeeds) when there are some for nt (every parallel loop over
/// particles splits by this, so a thread meets the same particles in each)
struct ItemRange {
  std::size_t begin, end;
};
inline ItemRange thread_share(std::size_t n, int t, int nt) {
  const ThreadSpeeds& sp = ThreadSpeeds::get();
  if (sp.has(nt)) return {sp.split(n, t), sp.split(n, t + 1)};
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
/// per thread (static schedule)
template <class Body>
void parallel_ranges(std::size_t n, std::size_t threshold, Body&& body) {
#ifdef _OPENMP
  if (run_parallel(n, threshold)) {
#pragma omp parallel
    {
      const ItemRange r = thread_share(n, team_thread(), team_size());
      body(r.begin, r.end);
    }
    return;
  }
#endif
  (void)threshold;
  body(std::size_t{0}, n);
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
