// contiguous ranges of a loop's items, one per thread, moved step by step so that the threads
// finish together: each thread times its own range, and the split points move towards where
// the measured cost per item says they should be. The ranges stay contiguous and change little
// from step to step, so a thread keeps its data in its own cache (docs/threads.md); which
// thread runs which item never changes a result (every loop that uses this writes per-item
// slots, combined in a fixed order).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
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
  void record(int t, double seconds) { time_[static_cast<std::size_t>(t) * kPad] = seconds; }

  /// after the loop: move each split point half way towards where the measured costs (each
  /// range's seconds spread evenly over its items) would put equal shares. Half steps damp the
  /// timer's noise and a single slow step (an interrupt) moves a split point by half its excess.
  void update() {
    const std::size_t nt = threads();
    if (nt < 2 || n_ == 0) return;
    double total = 0.0;
    for (std::size_t t = 0; t < nt; ++t) total += time_[t * kPad];
    if (!(total > 0.0) || !std::isfinite(total)) return;
    // cost density of each current range (an empty range gets the mean density)
    std::vector<double>& dens = dens_;
    dens.resize(nt);
    for (std::size_t t = 0; t < nt; ++t) {
      const double len = cut_[t + 1] - cut_[t];
      dens[t] = len > 0.5 ? time_[t * kPad] / len : total / static_cast<double>(n_);
    }
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
  std::size_t n_ = 0;
  std::vector<double> cut_;        ///< split points as reals (the smoothing's state)
  std::vector<std::size_t> bound_; ///< split points rounded: thread t runs [bound_[t], bound_[t+1])
  std::vector<double> time_;
  std::vector<double> dens_, ideal_;  ///< update()'s scratch, kept (it runs every step)
};

}  // namespace gs
