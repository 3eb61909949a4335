// the thread scheduling of one simulation: how its team of threads splits the particles in
// every per-particle loop (by the threads' measured speeds), and the force pass's chunk
// ranges, steal ranges and placing (PassSchedule). Each Simulation owns one, so two
// simulations in one process never move each other's splits; a loop outside a simulation
// splits equally (parallel_ranges without a team). Where work goes never changes a result.
#pragma once
#include <cstddef>

#include "core/balance.hpp"
#include "core/parallel.hpp"
#include "core/pass_schedule.hpp"

namespace gs {

class ThreadTeam {
 public:
  /// thread t of nt's contiguous share of n particles: by the measured speeds where there are
  /// some for nt threads, else equal. Every particle loop of the simulation splits by it, so a
  /// thread predicts, sums, accelerates and corrects the same particles (docs/threads.md)
  ItemRange particles(std::size_t n, int t, int nt) const {
    if (speeds_.has(nt)) return {speeds_.split(n, t), speeds_.split(n, t + 1)};
    return equal_share(n, t, nt);
  }
  /// the force pass's schedule: plan() before its region, its calls inside, then update()
  PassSchedule& pass() { return pass_; }
  /// after the force pass's region: its ranges and the particle split move towards the
  /// measured times
  void update() { pass_.update(speeds_); }
  const ThreadSpeeds& speeds() const { return speeds_; }
  /// the particle split's measurements (a test can feed its own)
  ThreadSpeeds& speeds() { return speeds_; }

 private:
  ThreadSpeeds speeds_;
  PassSchedule pass_;
};

/// body(begin, end) over [0, n) in parallel on the team's particle split (parallel_shares)
template <class Body>
void parallel_ranges(const ThreadTeam& team, std::size_t n, std::size_t threshold, Body&& body) {
  parallel_shares(
      n, threshold, [&team](std::size_t m, int t, int nt) { return team.particles(m, t, nt); },
      body);
}

}  // namespace gs
