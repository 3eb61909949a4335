// the step profile's sampling: long steps are all timed; short ones one in `stride`, picked so
// that the estimate is unbiased and no period of the run lines up with the timed steps
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "core/stage_clock.hpp"

namespace gs {
namespace {

TEST(StageClock, LongStepsAreAllTimed) {
  StepProfile p;
  p.adapt(StepProfile::kTimedStepMin);
  EXPECT_EQ(p.stride, 1u);
  for (std::int64_t s = 0; s < 1000; ++s) EXPECT_TRUE(p.times(s));
}

TEST(StageClock, StrideBringsTheTimedSpanToTheMinimum) {
  StepProfile p;
  p.adapt(10e-6);  // 8 × 10 µs ≥ 50 µs > 4 × 10 µs
  EXPECT_EQ(p.stride, 8u);
  p.adapt(1e-9);
  EXPECT_EQ(p.stride, StepProfile::kMaxStride);
  p.adapt(1.0);
  EXPECT_EQ(p.stride, 1u);
}

// the fraction of timed steps is 1/stride over consecutive steps and over every 1000th step
// (a sort or health-check period); binomial counts, 4σ bounds
TEST(StageClock, ShortStepsAreSampledOneInStrideWithoutAliasing) {
  StepProfile p;
  p.stride = 8;
  const auto check = [&](std::int64_t n, std::int64_t period) {
    std::int64_t timed = 0;
    for (std::int64_t k = 0; k < n; ++k) timed += p.times(k * period) ? 1 : 0;
    const double mean = static_cast<double>(n) / 8.0, sd = std::sqrt(mean * 7.0 / 8.0);
    EXPECT_NEAR(static_cast<double>(timed), mean, 4.0 * sd) << "period " << period;
  };
  check(80000, 1);
  check(16000, 1000);
  check(16000, 64);
}

TEST(StageClock, AStepNotTimedReadsNoClockAndChargesNothing) {
  StepProfile p;
  p.stride = 64;
  std::int64_t untimed = 0;
  while (p.times(untimed)) ++untimed;
  {
    StageClock c(p, untimed);
    c.lap(Stage::Pairs);
  }
  EXPECT_EQ(p.timed, 0u);
  EXPECT_EQ(p.total(), 0.0);
  std::int64_t timed = 0;
  while (!p.times(timed)) ++timed;
  {
    StageClock c(p, timed);
    volatile double x = 0.0;
    for (int i = 0; i < 100000; ++i) x = x + 1.0;
    c.lap(Stage::Pairs);
  }
  EXPECT_EQ(p.timed, 1u);
  EXPECT_GT(p[Stage::Pairs], 0.0);
  EXPECT_EQ(p[Stage::Predict], 0.0);
}

}  // namespace
}  // namespace gs
