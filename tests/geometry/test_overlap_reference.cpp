// overlap() and intersect() against the branchy Sutherland–Hodgman pass they replaced
// (reference_overlap.hpp): the same numbers bit for bit, so the rewrite leaves simulation
// trajectories unchanged; random, near-degenerate, containing and random convex pairs
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/rng.hpp"
#include "geometry/polygon.hpp"
#include "random_shapes.hpp"
#include "reference_overlap.hpp"

namespace gs {
namespace {

constexpr double kPi = std::numbers::pi;

// every field, bitwise (the general routine always computes the centroid)
void expect_as_before(const Poly& a, const Poly& b, int& touching) {
  const Overlap g = overlap(a, b);
  const Overlap r = ref::overlap(a, b);
  ASSERT_EQ(g.area, r.area);
  ASSERT_EQ(g.crossings, r.crossings);
  ASSERT_EQ(g.c1, r.c1);
  ASSERT_EQ(g.c2, r.c2);
  ASSERT_EQ(g.centroid, r.centroid);
  const Poly p = intersect(a, b), q = ref::intersect(a, b);
  ASSERT_EQ(p.n, q.n);
  for (int i = 0; i < p.n; ++i) ASSERT_EQ(p.v[i], q.v[i]);
  touching += r.area > 0.0;
}

Vec2 dir(double a) { return {std::cos(a), std::sin(a)}; }

TEST(OverlapReference, DecagonPairsAsBefore) {
  RngStream rng(21, 0);
  int touching = 0;
  for (int i = 0; i < 20000; ++i) {
    const double ra = (i & 1) ? 9e-3 : 6.36e-3, rb = (i & 2) ? 9e-3 : 6.36e-3;
    const double f = rng.uniform() < 0.7 ? rng.uniform(0.9, 1.0) : rng.uniform(0.0, 1.05);
    const Vec2 ca{rng.uniform(0.0, 0.5), rng.uniform(0.0, 0.5)};
    const Vec2 cb = ca + dir(rng.uniform(0.0, 2.0 * kPi)) * (f * (ra + rb));
    expect_as_before(regular_polygon(10, ra, ca, rng.uniform(0.0, 2.0 * kPi)),
                     regular_polygon(10, rb, cb, rng.uniform(0.0, 2.0 * kPi)), touching);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(touching, 14000);
}

// vertex on vertex and edge along edge at gaps from ±1e-16 to ±1e-3 of the radius and exactly
// zero: the exact repeats, on-the-line vertices and merges of the clip
TEST(OverlapReference, NearDegenerateAsBefore) {
  RngStream rng(22, 0);
  const double step = 2.0 * kPi / 10, apo = std::cos(kPi / 10);
  int touching = 0;
  for (int i = 0; i < 12000; ++i) {
    const double r = 9e-3;
    const double phi = (i % 4 == 0) ? 0.0 : rng.uniform(0.0, 2.0 * kPi);  // axis-aligned too
    const int kind = i % 3;
    const double ta = kind == 2 ? phi - 0.5 * step : phi;
    const double tb = kind == 0 ? phi + kPi : phi + kPi - 0.5 * step;
    const double reach = (kind == 2 ? apo * r : r) + (kind == 0 ? r : apo * r);
    const int e = static_cast<int>(rng.uniform(0.0, 17.0));
    const double gap = e == 16 ? 0.0 : std::pow(10.0, -16.0 + e) * (rng.uniform() < 0.5 ? -1 : 1);
    const double slide = kind == 2 ? rng.uniform(-0.5, 0.5) * r : 0.0;
    const Vec2 ca = (i & 8) ? Vec2{0.0, 0.0} : Vec2{rng.uniform(0.0, 0.5), rng.uniform(0.0, 0.5)};
    const Vec2 cb = ca + dir(phi) * (reach * (1.0 + gap)) + perp(dir(phi)) * slide;
    expect_as_before(regular_polygon(10, r, ca, ta), regular_polygon(10, r, cb, tb), touching);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(touching, 3000);
}

// shared edges and vertices exactly on lines: squares on a grid, rectangles against walls
TEST(OverlapReference, GridAlignedAsBefore) {
  RngStream rng(23, 0);
  int touching = 0;
  for (int i = 0; i < 4000; ++i) {
    const double x0 = std::floor(rng.uniform(0.0, 8.0)) * 0.25,
                 y0 = std::floor(rng.uniform(0.0, 8.0)) * 0.25;
    const double x1 = std::floor(rng.uniform(0.0, 8.0)) * 0.25,
                 y1 = std::floor(rng.uniform(0.0, 8.0)) * 0.25;
    const Poly a = rectangle(x0, y0, x0 + 0.5, y0 + 0.75);
    const Poly b = rectangle(x1, y1, x1 + 1.0, y1 + 0.5);
    expect_as_before(a, b, touching);
    expect_as_before(b, a, touching);
    expect_as_before(regular_polygon(4, 0.5, {x0, y0}, 0.25 * kPi), b, touching);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(touching, 1000);
}

TEST(OverlapReference, RandomConvexAsBefore) {
  RngStream rng(24, 0);
  int touching = 0;
  for (int i = 0; i < 10000; ++i) {
    const Poly a = test::random_convex(rng, {0.0, 0.0}, 1.0, 3 + i % 20);
    const Vec2 cb{rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5)};
    const Poly b = test::random_convex(rng, cb, rng.uniform(0.1, 3.0), 3 + (i / 20) % 20);
    expect_as_before(a, b, touching);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(touching, 3000);
}

}  // namespace
}  // namespace gs
