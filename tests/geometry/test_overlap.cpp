// overlap of convex polygons (docs/physics.md §2.1, §7): areas against analytic values, boundary
// crossings at known coordinates, containment and touching, and properties of random pairs
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/rng.hpp"
#include "geometry/polygon.hpp"
#include "random_shapes.hpp"

namespace gs {
namespace {

constexpr double kPi = std::numbers::pi;
// areas are sums of ≲ 40 coordinate products, each crossing point a few ulp off: round-off is
// ≲ 1e-14 relative, 1e-12 leaves margin while catching any wrong vertex
constexpr double kRel = 1e-12;
constexpr double kRBig = 9e-3;       // the paper's big decagon, m
constexpr double kRSmall = 6.36e-3;  // the paper's small decagon, m

double deg(double d) { return d * kPi / 180.0; }

bool finite(Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }
bool finite(const Overlap& o) {
  return std::isfinite(o.area) && finite(o.c1) && finite(o.c2) && finite(o.centroid);
}

// the two crossings equal {p, q} in either order, to an absolute tolerance
void expect_crossings(const Overlap& o, Vec2 p, Vec2 q, double tol) {
  ASSERT_EQ(o.crossings, 2);
  const bool direct = norm(o.c1 - p) <= tol && norm(o.c2 - q) <= tol;
  const bool swapped = norm(o.c1 - q) <= tol && norm(o.c2 - p) <= tol;
  EXPECT_TRUE(direct || swapped) << "c1 = (" << o.c1.x << ", " << o.c1.y << "), c2 = (" << o.c2.x
                                 << ", " << o.c2.y << ")";
}

// two axis-aligned unit squares offset by (0.3, 0.6): a 0.7 × 0.4 rectangle, crossings at the
// corners where the edges meet
TEST(Overlap, OffsetSquares) {
  const Poly a = rectangle(0.0, 0.0, 1.0, 1.0);
  const Poly b = rectangle(0.3, 0.6, 1.3, 1.6);
  for (const Overlap& o : {overlap(a, b), overlap(b, a)}) {
    EXPECT_NEAR(o.area, 0.7 * 0.4, kRel);
    expect_crossings(o, {1.0, 0.6}, {0.3, 1.0}, 1e-15);
    EXPECT_NEAR(o.centroid.x, 0.65, 1e-15);
    EXPECT_NEAR(o.centroid.y, 0.8, 1e-15);
  }
}

// a square and the same square turned by 45° about its centre meet in a regular octagon of
// inradius h: area 8h²tan(π/8) = 8h²(√2 − 1); the eight crossings lie on its circumcircle,
// so the farthest pair is a diameter 2h/cos(π/8)
TEST(Overlap, SquareRotated45) {
  const double h = 0.02;
  const Vec2 c{0.4, 0.3};
  const Poly a = rectangle(c.x - h, c.y - h, c.x + h, c.y + h);
  const Poly b = regular_polygon(4, h * std::sqrt(2.0), c, 0.0);  // vertices on the axes
  const Overlap o = overlap(a, b);
  const double want = 8.0 * h * h * (std::sqrt(2.0) - 1.0);
  EXPECT_NEAR(o.area, want, kRel * want);
  EXPECT_EQ(o.crossings, 8);
  EXPECT_NEAR(norm(o.c2 - o.c1), 2.0 * h / std::cos(kPi / 8.0), 1e-14);
  EXPECT_NEAR(o.centroid.x, c.x, 1e-15);
  EXPECT_NEAR(o.centroid.y, c.y, 1e-15);
  EXPECT_NEAR(overlap(b, a).area, want, kRel * want);
}

// a diamond whose top and bottom vertices lie exactly on the square's edge: half the diamond
// overlaps, and the crossings are those two vertices (a degenerate case handled exactly)
TEST(Overlap, DiamondVerticesOnEdge) {
  const Poly a = rectangle(0.0, 0.0, 2.0, 2.0);
  Poly b;
  for (Vec2 p : {Vec2{3, 1}, Vec2{2, 2}, Vec2{1, 1}, Vec2{2, 0}}) b.push(p);
  for (const Overlap& o : {overlap(a, b), overlap(b, a)}) {
    EXPECT_NEAR(o.area, 1.0, kRel);
    expect_crossings(o, {2.0, 0.0}, {2.0, 2.0}, 0.0);
  }
}

// a decagon against a large square whose edge passes through the decagon's centre, at any
// angle: half the area (central symmetry), crossings symmetric about the centre
TEST(Overlap, DecagonHalfPlaneThroughCentre) {
  RngStream rng(3, 5);
  const Vec2 c{0.25, 0.12};
  const double half = 0.5 * ngon_area(10, kRBig);
  for (int k = 0; k < 100; ++k) {
    const Poly d = regular_polygon(10, kRBig, c, rng.uniform(0.0, 2.0 * kPi));
    const double a = rng.uniform(0.0, 2.0 * kPi);
    // a 1 m square, one edge through c, lying on the side of direction (cos a, sin a)
    const Vec2 n{std::cos(a), std::sin(a)};
    const Poly wall = place(rectangle(0.0, -0.5, 1.0, 0.5), c, a);
    const Overlap o = overlap(d, wall);
    EXPECT_NEAR(o.area, half, kRel * half);
    ASSERT_EQ(o.crossings, 2);
    EXPECT_NEAR(norm((o.c1 + o.c2) * 0.5 - c), 0.0, 1e-15);
    EXPECT_NEAR(dot(o.c1 - c, n), 0.0, 1e-15);  // both on the cutting line
    // the centroid of the half lies on the far side, at distance (area moment)/(half area)
    EXPECT_GT(dot(o.centroid - c, n), 0.0);
    EXPECT_NEAR(overlap(wall, d).area, half, kRel * half);
  }
}

// area of the cap x >= d of the decagon with a vertex at (r, 0): a triangle of half-width
// (r − d)·cot18° for d >= r cos36° (edge slope sin36°/(1 − cos36°) = cot18°), plus a strip
// below whose half-width rises from r sin36° at slope (sin72° − sin36°)/(cos36° − cos72°)
double cap_area(double r, double d) {
  const double c36 = r * std::cos(deg(36)), s36 = r * std::sin(deg(36));
  const double cot18 = 1.0 / std::tan(deg(18));
  if (d >= c36) return (r - d) * (r - d) * cot18;
  const double k =
      (std::sin(deg(72)) - std::sin(deg(36))) / (std::cos(deg(36)) - std::cos(deg(72)));
  const double w = c36 - d;
  return (r - c36) * (r - c36) * cot18 + 2.0 * (w * s36 + 0.5 * k * w * w);
}
// the half-height of that decagon at abscissa d
double cap_half_width(double r, double d) {
  const double c36 = r * std::cos(deg(36)), s36 = r * std::sin(deg(36));
  if (d >= c36) return (r - d) / std::tan(deg(18));
  const double k =
      (std::sin(deg(72)) - std::sin(deg(36))) / (std::cos(deg(36)) - std::cos(deg(72)));
  return s36 + k * (c36 - d);
}

// a decagon cut by a wall at distance d from its centre: the analytic cap, crossings at ±y(d).
// Centred at the origin: with d/r = 0.999 the cap is only 9 µm deep, and a centre at 0.1 m
// would put an input rounding of ulp(0.1)/9 µm ≈ 1.5e-12 on its depth (3e-12 on its area)
TEST(Overlap, DecagonWallAtDistance) {
  const double r = kRBig;
  const Vec2 c{0.0, 0.0};
  const Poly d = regular_polygon(10, r, c, 0.0);
  for (double f : {0.999, 0.95, 0.85, 0.8, 0.6, 0.4}) {
    const Poly wall = rectangle(c.x + f * r, c.y - 1.0, c.x + 1.0, c.y + 1.0);
    const Overlap o = overlap(d, wall);
    const double want = cap_area(r, f * r);
    EXPECT_NEAR(o.area, want, kRel * want) << "d/r = " << f;
    const double y = cap_half_width(r, f * r);
    expect_crossings(o, {c.x + f * r, c.y - y}, {c.x + f * r, c.y + y}, 1e-15);
  }
}

// two identical decagons, vertex to vertex along x at centre distance D: by mirror symmetry
// about x = D/2 the overlap is twice the cap beyond D/2
TEST(Overlap, IdenticalDecagonsVertexToVertex) {
  const double r = kRSmall;
  for (double f : {0.999, 0.97, 0.9, 0.82, 0.7}) {
    const double D = 2.0 * f * r;
    const Overlap o = overlap(regular_polygon(10, r), regular_polygon(10, r, {D, 0.0}, kPi));
    const double want = 2.0 * cap_area(r, f * r);
    EXPECT_NEAR(o.area, want, kRel * want) << "D/2r = " << f;
    const double y = cap_half_width(r, f * r);
    expect_crossings(o, {f * r, -y}, {f * r, y}, 1e-15);
    EXPECT_NEAR(o.centroid.x, 0.5 * D, 1e-15);
    EXPECT_NEAR(o.centroid.y, 0.0, 1e-15);
  }
}

// the same pair turned by an arbitrary angle and moved into the box: same area, crossings
// moved with it (tests that nothing depends on axis alignment or the origin)
TEST(Overlap, IdenticalDecagonsRotatedAndMoved) {
  const double r = kRBig, f = 0.93, D = 2.0 * f * r;
  const double phi = 0.7321;
  const Vec2 x0{0.31, 0.47}, u{std::cos(phi), std::sin(phi)};
  const Overlap o =
      overlap(regular_polygon(10, r, x0, phi), regular_polygon(10, r, x0 + u * D, phi + kPi));
  const double want = 2.0 * cap_area(r, f * r);
  EXPECT_NEAR(o.area, want, kRel * want);
  const double y = cap_half_width(r, f * r);
  const Vec2 mid = x0 + u * (f * r);
  expect_crossings(o, mid - perp(u) * y, mid + perp(u) * y, 1e-15);
}

// two identical decagons face to face (flat edges at x = ±r cos18°): the cap beyond d, for
// r cos54° <= d <= a = r cos18°, is a strip of half-width r sin18° + (a − x)·tan54°
// (the edge from the 18° to the 54° vertex is perpendicular to the 36° direction)
TEST(Overlap, IdenticalDecagonsFaceToFace) {
  const double r = kRBig, a = r * std::cos(deg(18)), s18 = r * std::sin(deg(18));
  const double t54 = std::tan(deg(54));
  for (double f : {0.999, 0.98, 0.9, 0.8, 0.7}) {
    const double d = f * a, D = 2.0 * d, w = a - d;
    const Overlap o =
        overlap(regular_polygon(10, r, {}, deg(18)), regular_polygon(10, r, {D, 0.0}, deg(18)));
    const double want = 2.0 * (2.0 * s18 * w + t54 * w * w);
    EXPECT_NEAR(o.area, want, kRel * want) << "d/a = " << f;
    const double y = s18 + t54 * w;
    expect_crossings(o, {d, -y}, {d, y}, 1e-15);
  }
}

// a small decagon wholly inside a big one: area of the small one, no crossings
TEST(Overlap, ContainmentHasNoCrossings) {
  const Poly big = regular_polygon(10, kRBig, {0.1, 0.1}, 0.2);
  const Poly small = regular_polygon(10, kRSmall, {0.1 + 1e-3, 0.1 - 5e-4}, 1.1);
  const double want = ngon_area(10, kRSmall);
  for (const Overlap& o : {overlap(small, big), overlap(big, small)}) {
    EXPECT_NEAR(o.area, want, kRel * want);
    EXPECT_EQ(o.crossings, 0);
    EXPECT_NEAR(o.centroid.x, 0.1 + 1e-3, 1e-15);
    EXPECT_NEAR(o.centroid.y, 0.1 - 5e-4, 1e-15);
  }
  // identical polygons: the whole area
  EXPECT_NEAR(overlap(big, big).area, ngon_area(10, kRBig), kRel * ngon_area(10, kRBig));
}

// touching and just separated pairs: zero area, every output finite
TEST(Overlap, TouchingAndSeparatedAreZeroAndFinite) {
  const Poly a = rectangle(0.0, 0.0, 1.0, 1.0);
  const std::vector<Poly> others = {
      rectangle(1.0, 0.0, 2.0, 1.0),          // shared edge
      rectangle(1.0, 0.5, 2.0, 1.5),          // collinear edges, partly shared
      rectangle(1.0, 1.0, 2.0, 2.0),          // shared vertex
      rectangle(1.0 + 1e-12, 0.0, 2.0, 1.0),  // just separated
      regular_polygon(4, 0.5, {1.5, 0.5}),    // a diamond touching with its vertex
      regular_polygon(4, 0.5, {1.5, 2.5}),    // far apart
  };
  for (const Poly& b : others)
    for (const Overlap& o : {overlap(a, b), overlap(b, a)}) {
      EXPECT_TRUE(finite(o));
      EXPECT_EQ(o.area, 0.0);
    }
  // decagons tip to tip, and tip to tip with a hair's gap
  const double r = kRBig;
  for (double gap : {0.0, 1e-15, 1e-9}) {
    const Overlap o =
        overlap(regular_polygon(10, r), regular_polygon(10, r, {2 * r + gap, 0}, kPi));
    EXPECT_TRUE(finite(o));
    EXPECT_LE(o.area, 1e-30);
  }
}

// shared edges with positive overlap: exact area, a contact line across the overlap
TEST(Overlap, CollinearEdgesAndSharedCorners) {
  const Poly a = rectangle(0.0, 0.0, 2.0, 1.0);
  const Poly b = rectangle(1.0, 0.0, 3.0, 1.0);
  for (const Overlap& o : {overlap(a, b), overlap(b, a)}) {
    EXPECT_TRUE(finite(o));
    EXPECT_DOUBLE_EQ(o.area, 1.0);
    ASSERT_GE(o.crossings, 2);
    EXPECT_EQ(o.c1.x, o.c2.x);  // a vertical contact line: the normal is along x
    EXPECT_DOUBLE_EQ(std::abs(o.c1.y - o.c2.y), 1.0);
  }
  // a square in the corner of a bigger one (two shared edges, one shared vertex)
  const Poly big = rectangle(0.0, 0.0, 2.0, 2.0), corner = rectangle(1.0, 1.0, 2.0, 2.0);
  for (const Overlap& o : {overlap(big, corner), overlap(corner, big)}) {
    EXPECT_TRUE(finite(o));
    EXPECT_DOUBLE_EQ(o.area, 1.0);
  }
}

// ---- random convex pairs against an independent computation ----

// area of a ∩ b by Green's theorem: ½∮(x dy − y dx) over the parts of each boundary that lie
// inside the other polygon, each found by Cyrus–Beck parametric clipping of the edge
double green_overlap_area(const Poly& a, const Poly& b, Vec2 o) {
  auto inside_part = [&](const Poly& edges, const Poly& clip) {
    double s = 0.0;
    for (int i = 0; i < edges.n; ++i) {
      const Vec2 p = edges[i] - o, q = edges[(i + 1) % edges.n] - o;
      double t0 = 0.0, t1 = 1.0;
      for (int k = 0; k < clip.n && t0 < t1; ++k) {
        const Vec2 v = clip[k] - o, e = clip[(k + 1) % clip.n] - clip[k];
        // inside where cross(e, x − v) >= 0, linear in t: f0 + t·df
        const double f0 = cross(e, p - v), df = cross(e, q - p);
        if (df == 0.0) {
          if (f0 < 0.0) t1 = -1.0;
        } else if (df > 0.0) {
          t0 = std::max(t0, -f0 / df);
        } else {
          t1 = std::min(t1, -f0 / df);
        }
      }
      if (t0 < t1) s += 0.5 * cross(p + (q - p) * t0, p + (q - p) * t1);
    }
    return s;
  };
  return inside_part(a, b) + inside_part(b, a);
}

// all proper crossings of the two boundaries, by testing every edge pair
std::vector<Vec2> brute_crossings(const Poly& a, const Poly& b) {
  std::vector<Vec2> out;
  for (int i = 0; i < a.n; ++i)
    for (int k = 0; k < b.n; ++k) {
      const Vec2 p = a[i], r = a[(i + 1) % a.n] - p, q = b[k], s = b[(k + 1) % b.n] - q;
      const double den = cross(r, s);
      if (den == 0.0) continue;
      const double t = cross(q - p, s) / den, u = cross(q - p, r) / den;
      if (t >= 0.0 && t < 1.0 && u >= 0.0 && u < 1.0) out.push_back(p + r * t);
    }
  return out;
}

TEST(Overlap, RandomConvexPairsProperties) {
  RngStream rng(2024, 9);
  int with_area = 0, contained = 0;
  for (int k = 0; k < 3000; ++k) {
    const double ra = rng.uniform(0.2, 1.0), rb = rng.uniform(0.2, 1.0);
    const Poly a = test::random_convex(rng, {0.0, 0.0}, ra, 3 + k % 12);
    const double dist = rng.uniform(0.0, ra + rb), ang = rng.uniform(0.0, 2 * kPi);
    const Poly b = (k % 5 == 0)
                       ? regular_polygon(10, rb, {dist * std::cos(ang), dist * std::sin(ang)}, ang)
                       : test::random_convex(rng, {dist * std::cos(ang), dist * std::sin(ang)}, rb,
                                             3 + (k / 3) % 12);
    const Overlap ab = overlap(a, b), ba = overlap(b, a);
    const double amin = std::min(signed_area(a), signed_area(b));
    ASSERT_TRUE(finite(ab) && finite(ba));
    // symmetric, bounded by the smaller polygon, equal to the Green's-theorem area
    EXPECT_NEAR(ab.area, ba.area, kRel * amin);
    EXPECT_LE(ab.area, amin * (1.0 + kRel));
    EXPECT_NEAR(ab.area, green_overlap_area(a, b, {}), kRel * amin);
    // the crossings: as many as the brute-force edge-pair test finds, on both boundaries,
    // and the chosen pair is the farthest apart
    const std::vector<Vec2> xs = brute_crossings(a, b);
    EXPECT_EQ(ab.crossings, static_cast<int>(xs.size()));
    EXPECT_EQ(ba.crossings, static_cast<int>(xs.size()));
    if (ab.crossings >= 2) {
      double dmax = 0.0;
      for (size_t i = 0; i < xs.size(); ++i)
        for (size_t j = i + 1; j < xs.size(); ++j) dmax = std::max(dmax, norm(xs[j] - xs[i]));
      EXPECT_NEAR(norm(ab.c2 - ab.c1), dmax, 1e-12);
      for (Vec2 c : {ab.c1, ab.c2, ba.c1, ba.c2}) {
        EXPECT_LE(test::boundary_distance(a, c), 1e-14);
        EXPECT_LE(test::boundary_distance(b, c), 1e-14);
      }
    }
    if (ab.area > 0.0) {
      ++with_area;
      if (ab.crossings == 0) ++contained;
      EXPECT_NEAR(ab.centroid.x, ba.centroid.x, 1e-12);
      EXPECT_NEAR(ab.centroid.y, ba.centroid.y, 1e-12);
    }
  }
  // the sample exercised overlaps and containments
  EXPECT_GT(with_area, 1000);
  EXPECT_GT(contained, 10);
}

// the paper's bidisperse decagons in contact at random orientations: the same checks
TEST(Overlap, PaperDecagonsRandomContacts) {
  RngStream rng(5, 5);
  for (int k = 0; k < 2000; ++k) {
    const double ang = rng.uniform(0.0, 2 * kPi);
    // centre distance between the apothem sum and the circumradius sum: overlap or near miss
    const double apo = (kRBig + kRSmall) * std::cos(kPi / 10.0);
    const double dist = rng.uniform(0.97 * apo, kRBig + kRSmall);
    const Vec2 ca{0.2, 0.3}, cb = ca + Vec2{std::cos(ang), std::sin(ang)} * dist;
    const Poly a = regular_polygon(10, kRBig, ca, rng.uniform(0.0, 2 * kPi));
    const Poly b = regular_polygon(10, kRSmall, cb, rng.uniform(0.0, 2 * kPi));
    const Overlap o = overlap(a, b);
    const double amin = ngon_area(10, kRSmall);
    EXPECT_NEAR(o.area, overlap(b, a).area, kRel * amin);
    EXPECT_NEAR(o.area, green_overlap_area(a, b, ca), kRel * amin);
    EXPECT_EQ(o.crossings, static_cast<int>(brute_crossings(a, b).size()));
    // shallow contacts cross exactly twice
    if (o.area > 0.0) {
      EXPECT_EQ(o.crossings, 2);
    }
  }
}

}  // namespace
}  // namespace gs
