// ThreadTeam: a simulation's particle split follows its own threads' measured speeds, and no
// other team's; parallel_ranges without a team splits equally
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "core/team.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs {
namespace {

void expect_share_tiling(const ThreadTeam& team, std::size_t n, int nt) {
  std::size_t next = 0;
  for (int t = 0; t < nt; ++t) {
    const ItemRange r = team.particles(n, t, nt);
    EXPECT_EQ(r.begin, next) << "thread " << t << " of " << nt << ", n = " << n;
    EXPECT_LE(r.begin, r.end);
    next = r.end;
  }
  EXPECT_EQ(next, n);
}

// `steps` measurements of a team of two whose thread 1 runs at 1/`slowdown` of thread 0's speed
void measure(ThreadTeam& team, std::size_t n, double slowdown, int steps) {
  for (int step = 0; step < steps; ++step) {
    double items[2], secs[2];
    for (int t = 0; t < 2; ++t) {
      const ItemRange r = team.particles(n, t, 2);
      items[t] = static_cast<double>(r.end - r.begin);
      secs[t] = items[t] * (t == 0 ? 1e-8 : slowdown * 1e-8);
    }
    team.speeds().update(items, secs, 2);
  }
}

TEST(ThreadTeam, SharesFollowTheMeasuredSpeeds) {
  ThreadTeam team;
  EXPECT_FALSE(team.speeds().has(2));
  EXPECT_EQ(team.particles(1184, 0, 2).end, 592u);  // equal before any measurement
  // thread 1 runs at half the speed of thread 0: after a few dozen steps thread 0 owns two
  // thirds of the particles and both take the same time
  const std::size_t n = 1184;
  measure(team, n, 2.0, 60);
  ASSERT_TRUE(team.speeds().has(2));
  EXPECT_NEAR(static_cast<double>(team.particles(n, 0, 2).end) / n, 2.0 / 3.0, 0.03);
  for (std::size_t m : {0u, 1u, 7u, 1184u, 1000000u}) expect_share_tiling(team, m, 2);
  EXPECT_FALSE(team.speeds().has(3));  // another team size: equal shares
  EXPECT_EQ(team.particles(999, 1, 3).begin, 333u);
  expect_share_tiling(team, 999, 3);
}

TEST(ThreadTeam, JitterDoesNotMoveTheSplitAndBadTimingsAreIgnored) {
  ThreadTeam team;
  ThreadSpeeds& sp = team.speeds();
  const double equal_items[2] = {500, 500}, equal_secs[2] = {1e-5, 1e-5};
  sp.update(equal_items, equal_secs, 2);
  const std::size_t first = team.particles(1000, 0, 2).end;
  EXPECT_EQ(first, 500u);
  // timings within ±1.5% of equal, alternating: the split point stays where it is
  for (int step = 0; step < 100; ++step) {
    const double j = step % 2 ? 1.015 : 0.985;
    const double secs[2] = {1e-5 * j, 1e-5 / j};
    sp.update(equal_items, secs, 2);
    EXPECT_EQ(team.particles(1000, 0, 2).end, first) << step;
  }
  // zero or non-finite timings and empty shares leave it alone
  const double zero[2] = {0.0, 1e-5}, nan[2] = {std::nan(""), 1e-5}, none[2] = {0, 500};
  sp.update(equal_items, zero, 2);
  sp.update(equal_items, nan, 2);
  sp.update(none, equal_secs, 2);
  EXPECT_EQ(team.particles(1000, 0, 2).end, first);
  // a thread a hundred times slower still keeps a quarter of an equal share
  measure(team, 1000, 100.0, 200);
  const ItemRange slow = team.particles(1000, 1, 2);
  EXPECT_GE(slow.end - slow.begin, 120u);
  EXPECT_LE(slow.end - slow.begin, 140u);
  sp.reset();
  EXPECT_EQ(team.particles(1000, 0, 2).end, 500u);
}

// two simulations in one process: one team's measurements never move the other's split
TEST(ThreadTeam, TwoTeamsKeepTheirOwnSpeeds) {
  ThreadTeam fast_second, slow_second;
  measure(slow_second, 1184, 2.0, 60);  // thread 1 at half speed: thread 0 takes ~2/3
  measure(fast_second, 1184, 0.5, 60);  // thread 1 at twice the speed: thread 0 takes ~1/3
  EXPECT_NEAR(static_cast<double>(slow_second.particles(1184, 0, 2).end) / 1184, 2.0 / 3.0, 0.03);
  EXPECT_NEAR(static_cast<double>(fast_second.particles(1184, 0, 2).end) / 1184, 1.0 / 3.0, 0.03);
  const ThreadTeam fresh;  // a third, never measured: equal shares
  EXPECT_EQ(fresh.particles(1184, 0, 2).end, 592u);
  EXPECT_EQ(equal_share(1184, 0, 2).end, 592u);
}

#ifdef _OPENMP
// each thread of a parallel_ranges region runs the team's share; without a team, equal shares
TEST(ThreadTeam, ParallelRangesRunTheTeamsSplit) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(2);
  ThreadTeam team;
  measure(team, kParallelMinCheap, 2.0, 60);
  const std::size_t n = 3 * kParallelMinCheap;
  auto ranges = [&](auto&& loop) {
    std::vector<ItemRange> got(2, ItemRange{0, 0});
    int runs = 0;
    loop([&](std::size_t b, std::size_t e) {
#pragma omp atomic
      ++runs;
      got[static_cast<std::size_t>(team_thread())] = {b, e};
    });
    EXPECT_EQ(runs, 2);
    return got;
  };
  const auto by_team = ranges([&](auto&& body) { parallel_ranges(team, n, 1, body); });
  const auto equal = ranges([&](auto&& body) { parallel_ranges(n, 1, body); });
  omp_set_num_threads(before);
  for (std::size_t t = 0; t < 2; ++t) {
    const ItemRange want = team.particles(n, static_cast<int>(t), 2);
    EXPECT_EQ(by_team[t].begin, want.begin);
    EXPECT_EQ(by_team[t].end, want.end);
    EXPECT_EQ(equal[t].begin, n * t / 2);
    EXPECT_EQ(equal[t].end, n * (t + 1) / 2);
  }
  EXPECT_NE(by_team[0].end, n / 2);  // the measured split is not the equal one
}
#endif

}  // namespace
}  // namespace gs
