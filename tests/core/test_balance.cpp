// RangeBalancer: contiguous per-thread ranges that converge to equal measured times
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <thread>
#include <vector>

#include "core/balance.hpp"
#include "core/parallel.hpp"

namespace gs {
namespace {

// one simulated step: each thread's time = the cost of its items ÷ its speed
void step(RangeBalancer& b, const std::vector<double>& cost, const std::vector<double>& speed) {
  for (int t = 0; t < static_cast<int>(b.threads()); ++t) {
    double s = 0.0;
    for (std::size_t i = b.begin(t); i < b.end(t); ++i) s += cost[i];
    b.record(t, s / speed[static_cast<std::size_t>(t)]);
  }
  b.update();
}

// the ranges tile [0, n) in order
void expect_tiling(const RangeBalancer& b, std::size_t n) {
  ASSERT_GE(b.threads(), 1u);
  EXPECT_EQ(b.begin(0), 0u);
  EXPECT_EQ(b.end(static_cast<int>(b.threads()) - 1), n);
  for (int t = 0; t + 1 < static_cast<int>(b.threads()); ++t) {
    EXPECT_EQ(b.end(t), b.begin(t + 1));
    EXPECT_LE(b.begin(t), b.end(t));
  }
}

TEST(RangeBalancer, StartsWithEqualRanges) {
  RangeBalancer b;
  b.plan(10, 3);
  expect_tiling(b, 10);
  EXPECT_EQ(b.end(0), 3u);  // 10/3 rounded
  EXPECT_EQ(b.end(1), 7u);  // 20/3 rounded
}

TEST(RangeBalancer, SplitFollowsAnUnevenCost) {
  // 100 items, the first 30 cost 3, the rest 1 (total 160): equal shares split at 80/3 ≈ 26.7
  std::vector<double> cost(100, 1.0);
  std::fill(cost.begin(), cost.begin() + 30, 3.0);
  RangeBalancer b;
  b.plan(cost.size(), 2);
  for (int k = 0; k < 60; ++k) step(b, cost, {1.0, 1.0});
  expect_tiling(b, 100);
  EXPECT_NEAR(static_cast<double>(b.end(0)), 80.0 / 3.0, 1.0);
  // planning again with the same size keeps the learnt split; a new size keeps its fraction
  // (a rebuilt list of the same work); a new thread count starts over
  b.plan(100, 2);
  EXPECT_NEAR(static_cast<double>(b.end(0)), 80.0 / 3.0, 1.0);
  b.plan(200, 2);
  EXPECT_NEAR(static_cast<double>(b.end(0)), 160.0 / 3.0, 2.0);
  expect_tiling(b, 200);
  b.plan(200, 4);
  EXPECT_EQ(b.end(0), 50u);
  expect_tiling(b, 200);
  RangeBalancer c;
  c.plan(101, 2);
  EXPECT_EQ(c.end(0), 51u);  // 50.5 rounded away from zero
  c.plan(0, 2);              // an empty list, then items again: equal shares
  expect_tiling(c, 0);
  c.plan(10, 2);
  EXPECT_EQ(c.end(0), 5u);
}

TEST(RangeBalancer, SlowerThreadGetsLessWork) {
  // uniform items, 4 threads, thread 1 runs at half speed: shares 2:1:2:2 of 700 items
  const std::vector<double> cost(700, 1.0);
  const std::vector<double> speed{1.0, 0.5, 1.0, 1.0};
  RangeBalancer b;
  b.plan(cost.size(), 4);
  for (int k = 0; k < 80; ++k) step(b, cost, speed);
  expect_tiling(b, 700);
  EXPECT_NEAR(static_cast<double>(b.end(0) - b.begin(0)), 200.0, 2.0);
  EXPECT_NEAR(static_cast<double>(b.end(1) - b.begin(1)), 100.0, 2.0);
  EXPECT_NEAR(static_cast<double>(b.end(2) - b.begin(2)), 200.0, 2.0);
  EXPECT_NEAR(static_cast<double>(b.end(3) - b.begin(3)), 200.0, 2.0);
}

TEST(RangeBalancer, ConcentratedCostAndDegenerateInput) {
  // all the cost in 4 items of 1000, 8 threads: ranges may empty, never cross or leave [0, n)
  std::vector<double> cost(1000, 0.0);
  for (int i = 500; i < 504; ++i) cost[static_cast<std::size_t>(i)] = 1.0;
  RangeBalancer b;
  b.plan(cost.size(), 8);
  for (int k = 0; k < 100; ++k) {
    step(b, cost, std::vector<double>(8, 1.0));
    expect_tiling(b, 1000);
  }
  // the busy items end up spread over several threads, not all with one
  int busy = 0;
  for (int t = 0; t < 8; ++t) busy += b.begin(t) < 504 && b.end(t) > 500;
  EXPECT_GE(busy, 3);
  // zero and non-finite timings leave the split as it was
  const std::size_t before = b.end(3);
  for (int t = 0; t < 8; ++t) b.record(t, 0.0);
  b.update();
  EXPECT_EQ(b.end(3), before);
  b.record(0, std::nan(""));
  b.update();
  EXPECT_EQ(b.end(3), before);
  expect_tiling(b, 1000);
  // one thread, no items
  RangeBalancer one;
  one.plan(5, 1);
  one.record(0, 1.0);
  one.update();
  expect_tiling(one, 5);
  RangeBalancer none;
  none.plan(0, 2);
  none.update();
  expect_tiling(none, 0);
}

// a range partly run by another thread (StealRanges): its density is its seconds over the
// items it ran itself. Two threads, 1000 items of equal cost, split 500/500; in the same second
// thread 0 ran its 500 (and helped), thread 1 only 250: densities 0.002 and 0.004 s per item
// over the current ranges, total cost 3 s, equal shares at 1.5 s → split at 500 + 0.5/0.004 =
// 625; the split moves a quarter of the way (500 → 531.25). Counting thread 1's whole range as
// run would have given it density 0.002 and left the split at 500
TEST(RangeBalancer, PartlyStolenRangeCountsTheItemsItRan) {
  RangeBalancer b;
  b.plan(1000, 2);
  b.record(0, 1.0, 500);
  b.record(1, 1.0, 250);
  b.update();
  expect_tiling(b, 1000);
  EXPECT_EQ(b.end(0), 531u);
  // a range whose items all went elsewhere gets the other's density: no move
  RangeBalancer c;
  c.plan(1000, 2);
  c.record(0, 1.0, 500);
  c.record(1, 0.0, 0);
  c.update();
  EXPECT_EQ(c.end(0), 500u);
}

// every item of every range is taken exactly once, by its owner from the front or by another
// thread from the back, while both run at the same time
TEST(StealRanges, EveryItemOnceUnderContention) {
  constexpr std::size_t kN = 200000;
  for (int round = 0; round < 5; ++round) {
    StealRanges r;
    r.reset(2);
    r.set(0, 0, 150000);  // thread 0's range is 3× thread 1's: thread 1 will steal
    r.set(1, 150000, kN);
    std::vector<std::atomic<int>> hits(kN);
    for (auto& h : hits) h.store(0);
    std::atomic<std::size_t> stolen{0};
    auto work = [&](std::size_t t) {
      std::size_t first = 0, count = 0;
      while (r.take_front(t, 8, first, count)) {
        EXPECT_LE(count, 8u);
        for (std::size_t i = first; i < first + count; ++i) hits[i].fetch_add(1);
      }
      std::size_t item = 0;
      while (r.take_back(1 - t, item)) {
        hits[item].fetch_add(1);
        stolen.fetch_add(1);
      }
    };
    std::thread a(work, 0), b(work, 1);
    a.join();
    b.join();
    for (std::size_t i = 0; i < kN; ++i) ASSERT_EQ(hits[i].load(), 1) << "item " << i;
    EXPECT_GT(stolen.load(), 0u) << "round " << round;  // the short range's thread helped
  }
  // an empty range gives nothing; a range set empty (e < b) too
  StealRanges r;
  r.reset(1);
  r.set(0, 5, 3);
  std::size_t f = 0, c = 0;
  EXPECT_FALSE(r.take_front(0, 8, f, c));
  EXPECT_FALSE(r.take_back(0, f));
}

}  // namespace
}  // namespace gs
