// contiguous ranges of a loop's items, one per thread, moved step by step so that the threads
// finish together: each thread times its own range, and the split points move towards where
// the measured cost per item says they should be. The ranges stay contiguous and change little
// from step to step, so a thread keeps its data in its own cache (docs/threads.md); which
// thread runs which item never changes a result (every loop that uses this writes per-item
// slots, combined in a fixed order).
#pragma once
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace gs {

class RangeBalancer {
 public:
  /// ranges of n items for nt threads: kept from the last step when n and nt are unchanged;
  /// a new n (the item list was rebuilt) keeps each split point's fraction of the items, since
  /// a rebuilt list covers the same work in the same order (the cell grid rebuilds its
  /// candidate list every few dozen steps while a pile moves); a new nt starts equal. Call
  /// before the loop, outside the parallel region.
  void plan(std::size_t n, int nt) {
    const auto t = static_cast<std::size_t>(nt < 1 ? 1 : nt);
    if (n == n_ && t + 1 == cut_.size()) return;
    if (t + 1 == cut_.size() && n_ > 0) {
      const double scale = static_cast<double>(n) / static_cast<double>(n_);
      for (double& c : cut_) c *= scale;
      cut_[t] = static_cast<double>(n);
    } else {
      cut_.assign(t + 1, 0.0);
      for (std::size_t k = 0; k <= t; ++k)
        cut_[k] = static_cast<double>(n) * static_cast<double>(k) / static_cast<double>(t);
      time_.assign(t * kPad, 0.0);
      done_.assign(t * kPad, kAll);
    }
    n_ = n;
    bound_.assign(t + 1, 0);
    for (std::size_t k = 0; k <= t; ++k)
      bound_[k] = std::min(n, static_cast<std::size_t>(std::llround(cut_[k])));
  }
  std::size_t threads() const { return bound_.empty() ? 0 : bound_.size() - 1; }
  /// thread t's items [begin(t), end(t))
  std::size_t begin(int t) const { return bound_[static_cast<std::size_t>(t)]; }
  std::size_t end(int t) const { return bound_[static_cast<std::size_t>(t) + 1]; }
  /// thread t's seconds for its range this step (each thread writes its own, padded, slot)
  void record(int t, double seconds) { record(t, seconds, kAll); }
  /// the same for the first `done` items of its range only (others took the rest: StealRanges)
  void record(int t, double seconds, std::size_t done) {
    time_[static_cast<std::size_t>(t) * kPad] = seconds;
    done_[static_cast<std::size_t>(t) * kPad] = done;
  }

  /// after the loop: move each split point half way towards where the measured costs (each
  /// range's seconds spread evenly over its items) would put equal shares. Half steps damp the
  /// timer's noise and a single slow step (an interrupt) moves a split point by half its excess.
  void update() {
    const std::size_t nt = threads();
    if (nt < 2 || n_ == 0) return;
    // cost density of each current range: its seconds over the items it ran (an empty range,
    // or one whose items all went to other threads, gets the mean density of the rest)
    std::vector<double>& dens = dens_;
    dens.assign(nt, -1.0);
    double t_sum = 0.0, i_sum = 0.0;
    for (std::size_t t = 0; t < nt; ++t) {
      const double len = cut_[t + 1] - cut_[t];
      const std::size_t d = done_[t * kPad];
      const double items = d == kAll ? len : static_cast<double>(d);
      const double sec = time_[t * kPad];
      if (!(sec >= 0.0) || !std::isfinite(sec)) return;
      if (items > 0.5) {
        dens[t] = sec / items;
        t_sum += sec;
        i_sum += items;
      }
    }
    if (!(t_sum > 0.0) || !(i_sum > 0.0)) return;
    double total = 0.0;  // the whole loop's cost at these densities
    for (std::size_t t = 0; t < nt; ++t) {
      if (dens[t] < 0.0) dens[t] = t_sum / i_sum;
      total += dens[t] * (cut_[t + 1] - cut_[t]);
    }
    if (!(total > 0.0) || !std::isfinite(total)) return;
    // the ideal split points: the cumulative cost at each reaches k/nt of the total
    std::vector<double>& ideal = ideal_;
    ideal.assign(nt + 1, 0.0);
    ideal[nt] = static_cast<double>(n_);
    double before = 0.0;  // cost of the ranges before range r
    std::size_t r = 0;
    for (std::size_t k = 1; k < nt; ++k) {
      const double want = total * static_cast<double>(k) / static_cast<double>(nt);
      while (r + 1 < nt && before + dens[r] * (cut_[r + 1] - cut_[r]) < want) {
        before += dens[r] * (cut_[r + 1] - cut_[r]);
        ++r;
      }
      ideal[k] = dens[r] > 0.0 ? cut_[r] + (want - before) / dens[r] : cut_[r];
    }
    for (std::size_t k = 1; k < nt; ++k) {
      cut_[k] += 0.25 * (ideal[k] - cut_[k]);
      if (cut_[k] < cut_[k - 1]) cut_[k] = cut_[k - 1];
      if (cut_[k] > static_cast<double>(n_)) cut_[k] = static_cast<double>(n_);
      bound_[k] = static_cast<std::size_t>(std::llround(cut_[k]));
    }
  }

 private:
  static constexpr std::size_t kPad = 8;  // one 64-byte line per thread's timing
  static constexpr std::size_t kAll = static_cast<std::size_t>(-1);  // done: the whole range
  std::size_t n_ = 0;
  std::vector<double> cut_;  ///< split points as reals (the smoothing's state)
  std::vector<std::size_t>
      bound_;  ///< split points rounded: thread t runs [bound_[t], bound_[t+1])
  std::vector<double> time_;
  std::vector<std::size_t> done_;     ///< items each range ran itself (kAll: all of them)
  std::vector<double> dens_, ideal_;  ///< update()'s scratch, kept (it runs every step)
};

/// each thread's range of a loop's items, taken from the front by its owner and, once a
/// thread has run out, one by one from the back of another's: the step-to-step jitter of a
/// shared host (a range planned by the last step's times finishing 5% late) is absorbed
/// instead of waited for. Only for loops whose items write per-item slots (which thread runs
/// an item changes nothing). Front and back share one atomic word, so an item is taken once.
class StealRanges {
 public:
  /// before the parallel region: nt ranges, all empty
  void reset(std::size_t nt) {
    if (nt != n_) {
      slots_ = std::make_unique<Slot[]>(nt);
      n_ = nt;
    }
    for (std::size_t t = 0; t < nt; ++t) slots_[t].w.store(0, std::memory_order_relaxed);
  }
  std::size_t ranges() const { return n_; }
  /// thread t's range [b, e) (before any take)
  void set(std::size_t t, std::size_t b, std::size_t e) {
    slots_[t].w.store(pack(b, std::max(b, e)), std::memory_order_relaxed);
  }
  /// the owner's next items [first, first + count): a quarter of what is left, 1 … `batch`
  /// (few atomic operations while the range is long, single items near its end); false when
  /// nothing is left
  bool take_front(std::size_t t, std::size_t batch, std::size_t& first, std::size_t& count) {
    std::atomic<std::uint64_t>& a = slots_[t].w;
    std::uint64_t w = a.load(std::memory_order_relaxed);
    for (;;) {
      const std::size_t f = front(w), b = back(w);
      if (f >= b) return false;
      const std::size_t c = std::clamp<std::size_t>((b - f) / 4, 1, batch);
      if (a.compare_exchange_weak(w, pack(f + c, b), std::memory_order_acq_rel,
                                  std::memory_order_relaxed)) {
        first = f;
        count = c;
        return true;
      }
    }
  }
  /// one item from the back of thread v's range; false when it is empty
  bool take_back(std::size_t v, std::size_t& item) {
    std::atomic<std::uint64_t>& a = slots_[v].w;
    std::uint64_t w = a.load(std::memory_order_relaxed);
    for (;;) {
      const std::size_t f = front(w), b = back(w);
      if (f >= b) return false;
      if (a.compare_exchange_weak(w, pack(f, b - 1), std::memory_order_acq_rel,
                                  std::memory_order_relaxed)) {
        item = b - 1;
        return true;
      }
    }
  }

 private:
  struct alignas(64) Slot {
    std::atomic<std::uint64_t> w{0};
  };
  static std::uint64_t pack(std::size_t f, std::size_t b) {
    return (static_cast<std::uint64_t>(f) << 32) | static_cast<std::uint32_t>(b);
  }
  static std::size_t front(std::uint64_t w) { return static_cast<std::size_t>(w >> 32); }
  static std::size_t back(std::uint64_t w) { return static_cast<std::size_t>(w & 0xffffffffu); }
  std::unique_ptr<Slot[]> slots_;
  std::size_t n_ = 0;
};

/// the relative speeds of a team's threads, as the force pass measures them on its
/// per-particle work (the vCPUs of a virtual machine can run at different, drifting speeds:
/// docs/threads.md); a ThreadTeam splits its particles by them (core/team.hpp), so equal work
/// takes equal time. Only where work goes changes, never a result. Updated between parallel
/// regions by the thread that runs the team; read inside regions.
class ThreadSpeeds {
 public:
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

}  // namespace gs
