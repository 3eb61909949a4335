// the thread scheduling of one parallel pass over chunks of items followed by per-particle
// work (the force pass): which thread runs which chunks and places which grains, and the
// timings that move those splits (and the team's particle split) from step to step; part of a
// simulation's ThreadTeam (core/team.hpp). Where work goes never
// changes a result: every chunk and particle writes its own slots (core/parallel.hpp)
#pragma once
#include <cstddef>
#include <vector>

#include "core/balance.hpp"
#include "core/parallel.hpp"

namespace gs {

class PassSchedule {
 public:
  /// before the parallel region: `chunks` chunks of items, and `place` grains to place first
  /// (0: none) on their own balanced ranges
  void plan(std::size_t chunks, std::size_t place) {
    chunks_ = chunks;
    place_ = place;
    balance_.plan(chunks, max_team_size());
    steal_.reset(balance_.threads());
    for (std::size_t t = 0; t < balance_.threads(); ++t)
      steal_.set(t, balance_.begin(static_cast<int>(t)), balance_.end(static_cast<int>(t)));
    items_.assign(balance_.threads(), 0.0);
    seconds_.assign(balance_.threads(), 0.0);
    if (place > 0) place_balance_.plan(place, max_team_size());
    planned_ = true;
  }

  // ---- inside the region, thread tid of nt ----

  /// place(b, e) over the thread's share of the grains to place, balanced on the placing's own
  /// time (split like the particles, the barrier after it would wait for the slower thread)
  template <class Place>
  void place(int tid, int nt, Place&& place) {
    const bool own = static_cast<std::size_t>(nt) == place_balance_.threads();
    const ItemRange r = own ? ItemRange{place_balance_.begin(tid), place_balance_.end(tid)}
                            : equal_share(place_, tid, nt);
    const double t0 = wall_seconds();
    place(r.begin, r.end);
    if (own) place_balance_.record(tid, wall_seconds() - t0);
  }
  /// the thread's contiguous range of chunks: candidates come sorted by their first particle,
  /// so its pairs are mostly those of its own particles and its slots stay in its own cache
  /// from step to step (chunks handed out dynamically move them between cores: docs/threads.md)
  ItemRange chunk_range(int tid, int nt) const {
    if (planned_for(nt)) return {balance_.begin(tid), balance_.end(tid)};
    return equal_share(chunks_, tid, nt);
  }
  /// run(c) for the thread's chunks: its own range from the front, timed for the balancer
  /// (where grains touch more a chunk costs more), then, once done, what is left of the other
  /// threads' ranges from their backs (the host's jitter, which the last step's times cannot
  /// foresee). Every chunk runs once
  template <class Run>
  void run_chunks(int tid, int nt, Run&& run) {
    if (!planned_for(nt)) {
      const ItemRange r = chunk_range(tid, nt);
      for (std::size_t c = r.begin; c < r.end; ++c) run(c);
      if (tid == 0) planned_ = false;  // the same for every thread: one writes it
      return;
    }
    const double t0 = wall_seconds();
    std::size_t first = 0, count = 0, own = 0;
    const auto t = static_cast<std::size_t>(tid);
    while (steal_.take_front(t, 8, first, count)) {
      for (std::size_t c = first; c < first + count; ++c) run(c);
      own += count;
    }
    balance_.record(tid, wall_seconds() - t0, own);
    for (std::size_t k = 1; k < static_cast<std::size_t>(nt); ++k) {
      std::size_t c = 0;
      while (steal_.take_back((t + k) % static_cast<std::size_t>(nt), c)) run(c);
    }
  }
  /// the thread did its `items` particles in `seconds` (the team's next particle split)
  void record_particles(int tid, int nt, std::size_t items, double seconds) {
    if (!planned_for(nt)) return;
    items_[static_cast<std::size_t>(tid)] = static_cast<double>(items);
    seconds_[static_cast<std::size_t>(tid)] = seconds;
  }

  /// after the region: the splits, and the team's particle split `speeds`, move towards the
  /// measured times (not when the team had another size than planned: equal ranges, no timing)
  void update(ThreadSpeeds& speeds) {
    if (!planned_) return;
    balance_.update();
    if (place_ > 0) place_balance_.update();
    speeds.update(items_.data(), seconds_.data(), static_cast<int>(balance_.threads()));
  }

 private:
  bool planned_for(int nt) const { return static_cast<std::size_t>(nt) == balance_.threads(); }
  std::size_t chunks_ = 0, place_ = 0;
  bool planned_ = false;                 ///< the team had the planned size (written by thread 0)
  RangeBalancer balance_;                ///< each thread's range of chunks
  StealRanges steal_;                    ///< the chunks still to run, per thread
  RangeBalancer place_balance_;          ///< each thread's grains to place
  std::vector<double> items_, seconds_;  ///< per thread: particles owned, seconds spent on them
};

}  // namespace gs
