// polygon construction, areas, centroids, mass and inertia (docs/physics.md §1.1), half-plane and
// rectangle clipping (docs/physics.md §2.5, §7)
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "geometry/polygon.hpp"
#include "random_shapes.hpp"

namespace gs {
namespace {

constexpr double kPi = std::numbers::pi;
// every area below is a sum of at most ~40 products of coordinates each correct to a few ulp,
// so round-off is ≲ 1e-14 relative; 1e-12 leaves two orders of margin and still catches any
// wrong vertex (an error of one part in 10⁶ of a coordinate would show at 1e-6)
constexpr double kRel = 1e-12;
// the decagon radii of the paper (section IV), m
constexpr double kRBig = 9e-3;
constexpr double kRSmall = 6.36e-3;

double deg(double d) { return d * kPi / 180.0; }

// regular polygon: vertices on the circle, counter-clockwise, centred where asked
TEST(RegularPolygon, VerticesOnCircleCounterClockwise) {
  const Vec2 c{0.31, 0.17};
  const Poly p = regular_polygon(10, kRBig, c, 0.3);
  ASSERT_EQ(p.n, 10);
  for (int k = 0; k < p.n; ++k) {
    EXPECT_NEAR(norm(p[k] - c), kRBig, 1e-15);
    const Vec2 e0 = p[(k + 1) % 10] - p[k], e1 = p[(k + 2) % 10] - p[(k + 1) % 10];
    EXPECT_GT(cross(e0, e1), 0.0);
  }
  EXPECT_NEAR(std::atan2(p[0].y - c.y, p[0].x - c.x), 0.3, 1e-12);
  EXPECT_NEAR(centroid(p).x, c.x, 1e-15);
  EXPECT_NEAR(centroid(p).y, c.y, 1e-15);
}

// bad vertex counts are reported, not turned into garbage
TEST(RegularPolygon, RejectsBadVertexCounts) {
  EXPECT_THROW(regular_polygon(2, 1.0), InputError);
  EXPECT_THROW(regular_polygon(kMaxPolyVerts + 1, 1.0), InputError);
  EXPECT_THROW(ngon_area(2, 1.0), InputError);
  EXPECT_THROW(ngon_inertia(1, 1.0, 1.0), InputError);
}

// placing a body-frame polygon equals building it in place
TEST(Place, MatchesRegularPolygonBuiltInPlace) {
  const Poly body = regular_polygon(10, kRSmall);
  const Poly a = place(body, {0.2, 0.4}, 1.234);
  const Poly b = regular_polygon(10, kRSmall, {0.2, 0.4}, 1.234);
  for (int k = 0; k < 10; ++k) {
    EXPECT_NEAR(a[k].x, b[k].x, 1e-16);
    EXPECT_NEAR(a[k].y, b[k].y, 1e-16);
  }
}

// shoelace: rectangle, triangle centroid, and relative precision far from the origin
TEST(Area, RectangleTriangleAndFarFromOrigin) {
  EXPECT_DOUBLE_EQ(signed_area(rectangle(0.0, 0.0, 2.0, 3.0)), 6.0);
  Poly t;
  t.push({0, 0});
  t.push({4, 0});
  t.push({1, 3});
  EXPECT_DOUBLE_EQ(signed_area(t), 6.0);
  EXPECT_NEAR(centroid(t).x, 5.0 / 3.0, 1e-15);
  EXPECT_NEAR(centroid(t).y, 1.0, 1e-15);
  // clockwise order gives the negative area
  Poly cw;
  for (int i = 2; i >= 0; --i) cw.push(t[i]);
  EXPECT_DOUBLE_EQ(signed_area(cw), -6.0);
  // a 1 mm square 1 km away: summing about vertex 0 keeps the relative error at round-off
  const Poly far = rectangle(1000.0, 1000.0, 1000.001, 1000.001);
  const double side = 1000.001 - 1000.0;  // the representable side length
  EXPECT_NEAR(signed_area(far), side * side, kRel * side * side);
}

// ngon_area: (n/2) r² sin(2π/n) against squares, hexagons, the shoelace and the circle limit
TEST(NgonArea, KnownPolygonsAndCircleLimit) {
  const double r = 0.7;
  EXPECT_NEAR(ngon_area(4, r), 2.0 * r * r, kRel * r * r);
  EXPECT_NEAR(ngon_area(6, r), 1.5 * std::sqrt(3.0) * r * r, kRel * r * r);
  EXPECT_NEAR(ngon_area(10, kRBig), signed_area(regular_polygon(10, kRBig, {0.1, 0.2}, 0.4)),
              kRel * kRBig * kRBig);
  // the deficit from πr² is πr²·(2π/n)²/6 to leading order (Taylor series of sin)
  for (int n : {100, 1000, 10000}) {
    const double deficit = 1.0 - ngon_area(n, r) / (kPi * r * r);
    const double expected = (2.0 * kPi / n) * (2.0 * kPi / n) / 6.0;
    EXPECT_NEAR(deficit / expected, 1.0, 1e-3) << "n = " << n;  // next term is O(1/n²) smaller
  }
  // the paper's grains: 544 big + 640 small decagons cover 0.2056 m² (section IV)
  EXPECT_NEAR(544 * ngon_area(10, kRBig) + 640 * ngon_area(10, kRSmall), 0.2056, 5e-5);
}

// ngon_inertia for a square: the rectangle formula m(a² + b²)/12 with a = b = r√2
TEST(NgonInertia, SquareMatchesRectangleFormula) {
  const double r = 0.05, m = 2.5, a = r * std::sqrt(2.0);
  EXPECT_NEAR(ngon_inertia(4, r, m), m * (a * a + a * a) / 12.0, kRel * m * r * r);
  // and the polygon second moment of a placed square, times the density
  const Poly sq = regular_polygon(4, r, {0.3, -0.2}, 0.7);
  const double rho = m / signed_area(sq);
  EXPECT_NEAR(rho * polar_moment(sq, {0.3, -0.2}), ngon_inertia(4, r, m), 1e-11 * m * r * r);
}

// second moment of a triangle with a vertex at the origin, by the three edge-midpoint rule
// (exact for quadratic integrands: Strang & Fix), an integration independent of the formula
double triangle_polar_moment(Vec2 p, Vec2 q) {
  const double area = 0.5 * cross(p, q);
  const Vec2 m1 = p * 0.5, m2 = (p + q) * 0.5, m3 = q * 0.5;
  return area / 3.0 * (norm2(m1) + norm2(m2) + norm2(m3));
}

// ngon_inertia for the decagon against integration over its ten centre triangles
TEST(NgonInertia, DecagonMatchesTriangleQuadrature) {
  for (double r : {kRBig, kRSmall}) {
    const double rho = 1.0;  // kg/m², the paper's density
    const Poly d = regular_polygon(10, r, {}, 0.37);
    double j = 0.0;
    for (int k = 0; k < 10; ++k) j += rho * triangle_polar_moment(d[k], d[(k + 1) % 10]);
    const double m = rho * ngon_area(10, r);
    EXPECT_NEAR(ngon_inertia(10, r, m), j, kRel * j);
    EXPECT_NEAR(rho * polar_moment(d, {}), j, kRel * j);
  }
}

// the disk is the n → ∞ limit of the n-gon, J → m r²/2 with a deficit O(1/n²)
TEST(DiskInertia, IsTheLimitOfRegularPolygons) {
  const double r = 0.01, m = 0.3;
  EXPECT_DOUBLE_EQ(disk_inertia(r, m), 0.5 * m * r * r);
  // (1 + 2cos²(π/n))/3 = 1 − (2/3) sin²(π/n)
  const int n = 1000;
  const double s = std::sin(kPi / n);
  EXPECT_NEAR(ngon_inertia(n, r, m) / disk_inertia(r, m), 1.0 - 2.0 / 3.0 * s * s, 1e-14);
  EXPECT_NEAR(ngon_inertia(n, r, m) / disk_inertia(r, m), 1.0, 1e-5);
}

// points inside, on and outside a polygon
TEST(Contains, InsideOnAndOutside) {
  const Poly sq = rectangle(0.0, 0.0, 1.0, 1.0);
  EXPECT_TRUE(contains(sq, {0.5, 0.5}));
  EXPECT_TRUE(contains(sq, {1.0, 0.5}));
  EXPECT_FALSE(contains(sq, {1.0 + 1e-12, 0.5}));
  const Aabb b = bounds(regular_polygon(10, 1.0));
  EXPECT_DOUBLE_EQ(b.hi.x, 1.0);
  EXPECT_DOUBLE_EQ(b.lo.x, -1.0);
  EXPECT_NEAR(b.hi.y, std::sin(deg(72.0)), 1e-15);
}

// half-plane through the centre of a centrally symmetric polygon: exactly half, any angle
TEST(ClipHalfPlane, DecagonThroughCentreIsHalf) {
  RngStream rng(7, 1);
  const Vec2 c{0.21, 0.33};
  for (int k = 0; k < 50; ++k) {
    const Poly d = regular_polygon(10, kRBig, c, rng.uniform(0.0, 2.0 * kPi));
    const double a = rng.uniform(0.0, 2.0 * kPi);
    const Vec2 n{std::cos(a), std::sin(a)};
    const double half = 0.5 * ngon_area(10, kRBig);
    EXPECT_NEAR(signed_area(clip_half_plane(d, n, dot(c, n))), half, kRel * half);
  }
}

// the cap x >= d of the decagon with a vertex at (r, 0); its edges to the vertices at ±36°
// and ±72° bound it. For d >= r cos36° the cap is a triangle of half-width (r − d)·cot18°
// (edge slope sin36°/(1 − cos36°) = cot18°); below, a trapezoid strip of width d..r cos36°
// with half-width rising from r sin36° at slope (sin72° − sin36°)/(cos36° − cos72°).
double decagon_cap(double r, double d) {
  const double c36 = r * std::cos(deg(36)), s36 = r * std::sin(deg(36));
  const double cot18 = 1.0 / std::tan(deg(18));
  if (d >= c36) return (r - d) * (r - d) * cot18;
  const double k =
      (std::sin(deg(72)) - std::sin(deg(36))) / (std::cos(deg(36)) - std::cos(deg(72)));
  const double w = c36 - d;
  return (r - c36) * (r - c36) * cot18 + 2.0 * (w * s36 + 0.5 * k * w * w);
}

TEST(ClipHalfPlane, DecagonCapsAtDistance) {
  const double r = kRBig;
  for (double f : {0.99, 0.9, 0.85, 0.809017, 0.7, 0.5, 0.35}) {  // r cos72° = 0.309 r
    const double d = f * r;
    const Poly cap = clip_half_plane(regular_polygon(10, r), {-1.0, 0.0}, -d);
    const double want = decagon_cap(r, d);
    EXPECT_NEAR(signed_area(cap), want, kRel * want) << "d/r = " << f;
  }
}

// a decagon fully inside, and half outside, the measuring rectangle
TEST(AreaInRect, InsideAndHalfOutside) {
  const Vec2 c{0.2, 0.25};
  const Poly d = regular_polygon(10, kRBig, c, 0.1);
  const double full = ngon_area(10, kRBig);
  EXPECT_NEAR(area_in_rect(d, 0.0, 0.0, 0.4, 0.4), full, kRel * full);
  EXPECT_NEAR(area_in_rect(d, c.x, 0.0, 0.4, 0.4), 0.5 * full, kRel * full);
  EXPECT_NEAR(area_in_rect(d, 0.0, c.y, 0.4, 0.4), 0.5 * full, kRel * full);
  // with a vertex on the x axis the decagon is mirror-symmetric about both axes: a quarter
  const Poly d0 = regular_polygon(10, kRBig, c, 0.0);
  EXPECT_NEAR(area_in_rect(d0, c.x, c.y, 0.4, 0.4), 0.25 * full, kRel * full);
  EXPECT_EQ(area_in_rect(d, 0.3, 0.0, 0.4, 0.4), 0.0);
  // a rectangle side along a polygon edge
  EXPECT_DOUBLE_EQ(area_in_rect(rectangle(0, 0, 1, 1), 0.0, 0.0, 1.0, 0.5), 0.5);
  EXPECT_NEAR(area_in_rect(d0, c.x + 0.8 * kRBig, -1, 1, 1), decagon_cap(kRBig, 0.8 * kRBig),
              kRel * full);
}

// the four quadrants around any point partition the polygon: their areas sum to the total
TEST(AreaInRect, RandomQuadrantsSumToTotal) {
  RngStream rng(11, 2);
  for (int k = 0; k < 500; ++k) {
    const Poly p = test::random_convex(rng, {rng.uniform(-1, 1), rng.uniform(-1, 1)},
                                       rng.uniform(0.01, 1.0), 3 + k % 15);
    const Aabb b = bounds(p);
    const double px = rng.uniform(b.lo.x, b.hi.x), py = rng.uniform(b.lo.y, b.hi.y);
    const double big = 10.0;
    const double sum = area_in_rect(p, -big, -big, px, py) + area_in_rect(p, px, -big, big, py) +
                       area_in_rect(p, -big, py, px, big) + area_in_rect(p, px, py, big, big);
    const double total = signed_area(p);
    EXPECT_NEAR(sum, total, kRel * total);
    // and the clipping agrees with the general intersection with the rectangle polygon
    const double x0 = rng.uniform(b.lo.x, b.hi.x), y0 = rng.uniform(b.lo.y, b.hi.y);
    const double x1 = rng.uniform(x0, b.hi.x + 0.1), y1 = rng.uniform(y0, b.hi.y + 0.1);
    EXPECT_NEAR(area_in_rect(p, x0, y0, x1, y1),
                signed_area(intersect(p, rectangle(x0, y0, x1, y1))), kRel * total);
  }
}

}  // namespace
}  // namespace gs
