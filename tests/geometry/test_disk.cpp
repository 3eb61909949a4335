// exact area of a disk inside a rectangle (φ of disk packings): closed forms for symmetric
// cuts, circular segments and strips, additivity, and a fine 1D quadrature of chord lengths
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/rng.hpp"
#include "geometry/polygon.hpp"

namespace gs {
namespace {

constexpr double kPi = std::numbers::pi;
// the closed form combines four asin/sqrt terms of O(1), each good to a few ulp, and scales by
// r²: 1e-12 relative to πr² is two orders above round-off and far below any formula error
constexpr double kRel = 1e-12;

// full, half, quarter and empty
TEST(DiskAreaInRect, FullHalfQuarterNone) {
  const Vec2 c{0.3, 0.2};
  const double r = 1.5e-3, full = kPi * r * r, tol = kRel * full;
  EXPECT_NEAR(disk_area_in_rect(c, r, 0.0, 0.0, 1.0, 1.0), full, tol);
  // rectangle sides tangent to the disk still contain all of it
  EXPECT_NEAR(disk_area_in_rect(c, r, c.x - r, c.y - r, c.x + r, c.y + r), full, tol);
  // a side through the centre: half a disk, from each of the four sides
  EXPECT_NEAR(disk_area_in_rect(c, r, c.x, 0.0, 1.0, 1.0), full / 2, tol);
  EXPECT_NEAR(disk_area_in_rect(c, r, 0.0, 0.0, c.x, 1.0), full / 2, tol);
  EXPECT_NEAR(disk_area_in_rect(c, r, 0.0, c.y, 1.0, 1.0), full / 2, tol);
  EXPECT_NEAR(disk_area_in_rect(c, r, 0.0, 0.0, 1.0, c.y), full / 2, tol);
  // a corner at the centre: a quarter
  EXPECT_NEAR(disk_area_in_rect(c, r, c.x, c.y, 1.0, 1.0), full / 4, tol);
  EXPECT_NEAR(disk_area_in_rect(c, r, 0.0, 0.0, c.x, c.y), full / 4, tol);
  // outside, and tangent from outside
  EXPECT_EQ(disk_area_in_rect(c, r, 0.5, 0.5, 1.0, 1.0), 0.0);
  EXPECT_EQ(disk_area_in_rect(c, r, c.x + r, 0.0, 1.0, 1.0), 0.0);
}

// a side at distance d from the centre cuts a circular segment r²acos(d/r) − d√(r² − d²)
TEST(DiskAreaInRect, CircularSegments) {
  const Vec2 c{0.05, -0.02};
  const double r = 0.01, full = kPi * r * r;
  for (double f : {-0.9, -0.5, -0.1, 0.0, 0.2, 0.6, 0.95, 0.9999}) {
    const double d = f * r;
    const double seg = r * r * std::acos(f) - d * std::sqrt(r * r - d * d);
    EXPECT_NEAR(disk_area_in_rect(c, r, c.x + d, -1.0, 1.0, 1.0), seg, kRel * full) << f;
    EXPECT_NEAR(disk_area_in_rect(c, r, -1.0, c.y + d, 1.0, 1.0), seg, kRel * full) << f;
    EXPECT_NEAR(disk_area_in_rect(c, r, -1.0, -1.0, c.x - d, 1.0), seg, kRel * full) << f;
  }
}

// a centred strip |y − c_y| <= h holds 2(h√(r² − h²) + r² asin(h/r))
TEST(DiskAreaInRect, CentredStrip) {
  const Vec2 c{1.0, 2.0};
  const double r = 0.25, full = kPi * r * r;
  for (double f : {0.05, 0.3, 0.7, 0.99}) {
    const double h = f * r;
    const double want = 2.0 * (h * std::sqrt(r * r - h * h) + r * r * std::asin(f));
    EXPECT_NEAR(disk_area_in_rect(c, r, 0.0, c.y - h, 2.0, c.y + h), want, kRel * full);
    EXPECT_NEAR(disk_area_in_rect(c, r, c.x - h, 0.0, c.x + h, 4.0), want, kRel * full);
  }
  // a small rectangle wholly inside the disk is simply its own area
  EXPECT_NEAR(disk_area_in_rect(c, r, c.x - 0.1, c.y - 0.05, c.x + 0.12, c.y + 0.1), 0.22 * 0.15,
              kRel * full);
}

// any point splits the plane into four quadrants whose areas sum to πr²
TEST(DiskAreaInRect, QuadrantsSumToDisk) {
  RngStream rng(17, 3);
  const Vec2 c{0.2, 0.1};
  const double r = 9e-3, full = kPi * r * r, big = 1.0;
  for (int k = 0; k < 1000; ++k) {
    const double px = c.x + rng.uniform(-1.2, 1.2) * r, py = c.y + rng.uniform(-1.2, 1.2) * r;
    const double sum =
        disk_area_in_rect(c, r, -big, -big, px, py) + disk_area_in_rect(c, r, px, -big, big, py) +
        disk_area_in_rect(c, r, -big, py, px, big) + disk_area_in_rect(c, r, px, py, big, big);
    EXPECT_NEAR(sum, full, kRel * full);
  }
}

// independent check: integrate the length of the vertical chord inside [y0, y1] over x by the
// composite midpoint rule. The √ end points limit its error to O((h/r)^1.5) ≈ 1e-8 relative
// for N = 2·10⁵ cells, well inside the 1e-6 asked for
double chord_quadrature(Vec2 c, double r, double x0, double y0, double x1, double y1) {
  const int n = 200000;
  const double a = std::max(x0, c.x - r), b = std::min(x1, c.x + r);
  if (a >= b) return 0.0;
  const double h = (b - a) / n;
  double s = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = a + (i + 0.5) * h;
    const double half = std::sqrt(std::max(0.0, r * r - (x - c.x) * (x - c.x)));
    s += std::max(0.0, std::min(y1, c.y + half) - std::max(y0, c.y - half));
  }
  return s * h;
}

TEST(DiskAreaInRect, MatchesChordQuadrature) {
  RngStream rng(23, 4);
  const Vec2 c{0.0, 0.0};
  const double r = 1.0;
  for (int k = 0; k < 40; ++k) {
    // rectangles with sides anywhere from outside to through the disk
    double x0 = rng.uniform(-1.3, 1.3), x1 = rng.uniform(-1.3, 1.3);
    double y0 = rng.uniform(-1.3, 1.3), y1 = rng.uniform(-1.3, 1.3);
    if (x0 > x1) std::swap(x0, x1);
    if (y0 > y1) std::swap(y0, y1);
    const double exact = disk_area_in_rect(c, r, x0, y0, x1, y1);
    const double quad = chord_quadrature(c, r, x0, y0, x1, y1);
    EXPECT_NEAR(exact, quad, 1e-6 * kPi) << x0 << " " << y0 << " " << x1 << " " << y1;
  }
}

// degenerate inputs give zero, not NaN
TEST(DiskAreaInRect, DegenerateInputs) {
  EXPECT_EQ(disk_area_in_rect({0, 0}, 0.0, -1, -1, 1, 1), 0.0);
  EXPECT_EQ(disk_area_in_rect({0, 0}, 1.0, 1, -1, -1, 1), 0.0);  // x1 < x0
  EXPECT_EQ(disk_area_in_rect({0, 0}, 1.0, 0, 0, 0, 1), 0.0);    // zero width
}

}  // namespace
}  // namespace gs
