// RangeBalancer: contiguous per-thread ranges that converge to equal measured times
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "core/balance.hpp"

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
  for (int t = 0; t < 8; ++t)
    busy += b.begin(t) < 504 && b.end(t) > 500;
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

}  // namespace
}  // namespace gs
