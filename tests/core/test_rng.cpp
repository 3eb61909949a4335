// counter-based random streams: reproducible, independent of draw order, right moments
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.hpp"

namespace gs {
namespace {

TEST(Rng, SameKeyAndCounterGiveTheSameValue) {
  RngStream a(42, 7), b(42, 7), c(42, 8);
  for (int k = 0; k < 100; ++k) {
    const auto va = a.next_u64();
    EXPECT_EQ(va, b.next_u64());
    EXPECT_NE(va, c.next_u64());
  }
  // jumping the counter reproduces a value without drawing the ones before it
  RngStream d(42, 7);
  d.counter = 49;
  RngStream e(42, 7);
  for (int k = 0; k < 49; ++k) e.next_u64();
  EXPECT_EQ(d.next_u64(), e.next_u64());
}

TEST(Rng, UniformAndNormalMoments) {
  RngStream r(1, 2);
  const int n = 400000;
  double s1 = 0, s2 = 0, z1 = 0, z2 = 0, z4 = 0;
  for (int k = 0; k < n; ++k) {
    const double u = r.uniform();
    ASSERT_GT(u, 0.0);
    ASSERT_LT(u, 1.0);
    s1 += u;
    s2 += u * u;
    double a, b;
    r.normal_pair(a, b);
    for (double z : {a, b}) {
      z1 += z;
      z2 += z * z;
      z4 += z * z * z * z;
    }
  }
  // 5σ bounds: mean of U(0,1) has σ = √(1/12/n); normal moments use 2n samples
  EXPECT_NEAR(s1 / n, 0.5, 5 * std::sqrt(1.0 / 12 / n));
  EXPECT_NEAR(s2 / n - 0.25, 1.0 / 12, 5 * std::sqrt(1.0 / 180 / n));
  EXPECT_NEAR(z1 / (2 * n), 0.0, 5 / std::sqrt(2.0 * n));
  EXPECT_NEAR(z2 / (2 * n), 1.0, 5 * std::sqrt(2.0 / (2 * n)));
  EXPECT_NEAR(z4 / (2 * n), 3.0, 5 * std::sqrt(96.0 / (2 * n)));
}

}  // namespace
}  // namespace gs

namespace gs {
namespace {

// the ziggurat sampler against the normal distribution: moments, tail probabilities and the
// CDF at fixed points (10⁶ samples: binomial errors ~ √(p(1−p)/n))
TEST(Rng, ZigguratIsStandardNormal) {
  RngStream r(9, 4);
  const int n = 1000000;
  double m1 = 0, m2 = 0, m4 = 0;
  int beyond2 = 0, beyond3 = 0, beyond4 = 0, below_m1 = 0, below_05 = 0;
  for (int k = 0; k < n; ++k) {
    const double z = r.normal_fast();
    m1 += z;
    m2 += z * z;
    m4 += z * z * z * z;
    beyond2 += std::abs(z) > 2;
    beyond3 += std::abs(z) > 3;
    beyond4 += std::abs(z) > 4;
    below_m1 += z < -1;
    below_05 += z < 0.5;
  }
  auto check = [&](int count, double p, const char* what) {
    EXPECT_NEAR(count / double(n), p, 5 * std::sqrt(p * (1 - p) / n)) << what;
  };
  EXPECT_NEAR(m1 / n, 0.0, 5 / std::sqrt(double(n)));
  EXPECT_NEAR(m2 / n, 1.0, 5 * std::sqrt(2.0 / n));
  EXPECT_NEAR(m4 / n, 3.0, 5 * std::sqrt(96.0 / n));
  check(beyond2, std::erfc(2 / std::sqrt(2.0)), "P(|z|>2)");
  check(beyond3, std::erfc(3 / std::sqrt(2.0)), "P(|z|>3)");
  check(beyond4, std::erfc(4 / std::sqrt(2.0)), "P(|z|>4)");
  check(below_m1, 0.5 * std::erfc(1 / std::sqrt(2.0)), "P(z<-1)");
  check(below_05, 0.5 * std::erfc(-0.5 / std::sqrt(2.0)), "P(z<0.5)");
}

}  // namespace
}  // namespace gs
