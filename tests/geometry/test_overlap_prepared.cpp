// the prepared overlap (PolyStore + overlap(PolyRef, PolyRef), the contact hot loop) against
// the general clipping routine overlap(Poly, Poly): bit for bit on random decagon pairs from
// tiny to deep overlaps, near misses, vertex–vertex, vertex–edge and edge–edge near-degenerate
// placements, walls, random convex polygons and polygons on a grid (exact coincidences)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "core/rng.hpp"
#include "geometry/polygon.hpp"
#include "geometry/prepared.hpp"
#include "random_shapes.hpp"

namespace gs {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRBig = 9e-3;       // the paper's big decagon, m
constexpr double kRSmall = 6.36e-3;  // the paper's small decagon, m

// counts of the cases seen, to show the test reaches the paths it means to
struct Tally {
  int pairs = 0, touching = 0, two_crossings = 0, other_crossings = 0;
};

// every field the general routine defines, bitwise (centroid: where the prepared one computes
// it, i.e. without a contact line)
void expect_same(const Poly& a, const Poly& b, Tally& t) {
  PolyStore st;
  st.resize(2, std::max(a.n, b.n));
  st.set(0, a);
  st.set(1, b);
  const Overlap g = overlap(a, b);
  const Overlap f = overlap(st.ref(0), st.ref(1));
  ++t.pairs;
  if (g.area > 0.0) ++t.touching;
  (g.crossings == 2 ? t.two_crossings : t.other_crossings) += g.area > 0.0;
  ASSERT_EQ(f.area, g.area) << "pair " << t.pairs;
  ASSERT_EQ(f.crossings, g.crossings) << "pair " << t.pairs;
  ASSERT_EQ(f.c1, g.c1) << "pair " << t.pairs;
  ASSERT_EQ(f.c2, g.c2) << "pair " << t.pairs;
  if (g.crossings < 2 || g.c1 == g.c2) {
    ASSERT_EQ(f.centroid, g.centroid) << "pair " << t.pairs;
  }
  // and with the roles swapped
  const Overlap g2 = overlap(b, a);
  const Overlap f2 = overlap(st.ref(1), st.ref(0));
  ASSERT_EQ(f2.area, g2.area);
  ASSERT_EQ(f2.crossings, g2.crossings);
  ASSERT_EQ(f2.c1, g2.c1);
  ASSERT_EQ(f2.c2, g2.c2);
}

Vec2 dir(double a) { return {std::cos(a), std::sin(a)}; }

TEST(PreparedOverlap, PlacementIsPlace) {
  RngStream rng(11, 0);
  const Poly body = regular_polygon(10, kRBig);
  PolyStore st;
  st.resize(1, 10);
  for (int i = 0; i < 200; ++i) {
    const Vec2 c{rng.uniform(-1.0, 1.0), rng.uniform(0.0, 2.0)};
    const double th = rng.uniform(-50.0, 50.0);
    st.set_placed(0, body, c, th);
    const Poly p = place(body, c, th);
    const PolyRef r = st.ref(0);
    ASSERT_EQ(r.n, p.n);
    for (int k = 0; k < p.n; ++k) {
      ASSERT_EQ(r.x[k], p.v[k].x);
      ASSERT_EQ(r.y[k], p.v[k].y);
      // the bounding circle holds every vertex
      ASSERT_LE(norm(p.v[k] - r.mean), r.radius);
      // edge k, the last one back to vertex 0 (the repeated vertex after the last)
      const Vec2 e = p.v[k + 1 == p.n ? 0 : k + 1] - p.v[k];
      ASSERT_EQ(r.ex(k), e.x) << "edge " << k;
      ASSERT_EQ(r.ey(k), e.y) << "edge " << k;
    }
  }
}

// the bounding radius of set_placed comes from the body's rotated offsets, not from the placed
// vertices: it must still hold every vertex (and stay tight) for placements far from the
// origin, bodies not centred on their vertex mean, and any angle
TEST(PreparedOverlap, PlacedRadiusIsABound) {
  RngStream rng(16, 0);
  PolyStore st;
  st.resize(1, 16);
  for (int i = 0; i < 20000; ++i) {
    const double r = std::pow(10.0, rng.uniform(-4.0, 1.0));
    const Vec2 off = (i & 1) ? Vec2{rng.uniform(-r, r), rng.uniform(-r, r)} : Vec2{};
    const Poly body = (i & 2) ? test::random_convex(rng, off, r, 3 + i % 14)
                              : regular_polygon(3 + i % 14, r, off, rng.uniform(0.0, 6.3));
    const double far = std::pow(10.0, rng.uniform(-2.0, 6.0));
    const Vec2 c{rng.uniform(-far, far), rng.uniform(-far, far)};
    st.set_placed(0, body, c, rng.uniform(-1e3, 1e3));
    const PolyRef p = st.ref(0);
    double dmax = 0.0;
    for (int k = 0; k < p.n; ++k) {
      // long double: the distance itself without the rounding of a double difference
      const long double dx = static_cast<long double>(p.x[k]) - p.mean.x;
      const long double dy = static_cast<long double>(p.y[k]) - p.mean.y;
      const double d = static_cast<double>(std::sqrt(dx * dx + dy * dy));
      ASSERT_LE(d, p.radius) << "placement " << i;
      dmax = std::max(dmax, d);
    }
    // not much looser than the farthest vertex: by (1 + √2)× the distance from the placement point
    // to the vertex mean (zero for the simulation's centred bodies) and round-off
    const double mc = norm(p.mean - c);
    EXPECT_LE(p.radius, dmax + 2.5 * mc + 1e-11 * r + 1e-14 * (std::abs(c.x) + std::abs(c.y)));
  }
}

// decagon pairs placed far from the origin (1e3 to 1e5 m), where the rounding of the
// coordinates is large against the decagons: the skipped clips must still be no-ops
TEST(PreparedOverlap, FarFromOriginBitwise) {
  RngStream rng(17, 0);
  const Poly big = regular_polygon(10, kRBig), small = regular_polygon(10, kRSmall);
  Tally t;
  for (int i = 0; i < 10000; ++i) {
    const double far = std::pow(10.0, rng.uniform(3.0, 5.0));
    const Vec2 ca{rng.uniform(-far, far), rng.uniform(-far, far)};
    const Vec2 cb =
        ca + dir(rng.uniform(0.0, 2.0 * kPi)) * ((kRBig + kRSmall) * rng.uniform(0.85, 1.0));
    PolyStore st;
    st.resize(2, 10);
    st.set_placed(0, big, ca, rng.uniform(0.0, 2.0 * kPi));
    st.set_placed(1, small, cb, rng.uniform(0.0, 2.0 * kPi));
    expect_same(st.poly(0), st.poly(1), t);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(t.touching, 7000);
}

// big–small and equal decagons, random orientations, centre distances from 0 (one inside the
// other) to past the circumradius sum (near misses)
TEST(PreparedOverlap, RandomDecagonPairsBitwise) {
  RngStream rng(12, 0);
  const double radii[3][2] = {{kRBig, kRSmall}, {kRBig, kRBig}, {kRSmall, kRSmall}};
  Tally t;
  for (int i = 0; i < 30000; ++i) {
    const double ra = radii[i % 3][0], rb = radii[i % 3][1];
    // mostly the contact range (0.9–1.0 of ra + rb), some deep and some apart
    const double u = rng.uniform();
    const double f = u < 0.7   ? rng.uniform(0.9, 1.0)
                     : u < 0.9 ? rng.uniform(0.0, 0.9)
                               : rng.uniform(1.0, 1.05);
    const Vec2 ca{rng.uniform(0.0, 0.5), rng.uniform(0.0, 0.5)};
    const Vec2 cb = ca + dir(rng.uniform(0.0, 2.0 * kPi)) * (f * (ra + rb));
    const Poly a = regular_polygon(10, ra, ca, rng.uniform(0.0, 2.0 * kPi));
    const Poly b = regular_polygon(10, rb, cb, rng.uniform(0.0, 2.0 * kPi));
    expect_same(a, b, t);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(t.two_crossings, 15000);
  EXPECT_GT(t.other_crossings, 100);  // deep overlaps: containment or four crossings
}

// placements at the edge of exactness: vertex on vertex, vertex on edge, edge along edge, at
// gaps and overlaps from −1e-3 to +1e-3 of the radius down to ±1e-16 and exactly zero
TEST(PreparedOverlap, NearDegenerateDecagonsBitwise) {
  RngStream rng(13, 0);
  const double step = 2.0 * kPi / 10;
  const double apo = std::cos(kPi / 10);  // apothem / circumradius
  Tally t;
  for (int i = 0; i < 12000; ++i) {
    const double ra = (i & 1) ? kRBig : kRSmall, rb = (i & 2) ? kRBig : kRSmall;
    const double phi = rng.uniform(0.0, 2.0 * kPi);  // direction a → b
    const int kind = i % 3;
    // a's vertex 0 (or the middle of edge 0) points along phi; b's towards a
    const double ta = kind == 2 ? phi - 0.5 * step : phi;
    const double tb = kind == 0 ? phi + kPi : phi + kPi - 0.5 * step;
    const double reach = (kind == 2 ? apo * ra : ra) + (kind == 0 ? rb : apo * rb);
    const int e = static_cast<int>(rng.uniform(0.0, 17.0));  // 10^-16 .. 10^-3, or 0
    const double gap = e == 16 ? 0.0 : std::pow(10.0, -16.0 + e) * (rng.uniform() < 0.5 ? -1 : 1);
    // a small lateral slide for the edge–edge case, a tiny twist for the others
    const double slide = kind == 2 ? rng.uniform(-0.5, 0.5) * std::min(ra, rb) : 0.0;
    const double twist = kind == 2 ? 0.0 : (rng.uniform() < 0.5 ? 0.0 : rng.uniform(-1e-9, 1e-9));
    const Vec2 ca{rng.uniform(0.0, 0.5), rng.uniform(0.0, 0.5)};
    const Vec2 cb = ca + dir(phi) * (reach * (1.0 + gap)) + perp(dir(phi)) * slide;
    const Poly a = regular_polygon(10, ra, ca, ta + twist);
    const Poly b = regular_polygon(10, rb, cb, tb);
    expect_same(a, b, t);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(t.touching, 3000);
}

// a decagon against a wall slab (the box's walls are long thin rectangles)
TEST(PreparedOverlap, DecagonAgainstWallBitwise) {
  RngStream rng(14, 0);
  const Poly floor = rectangle(-0.01, -0.01, 0.49, 0.0);
  const Poly side = rectangle(0.48, 0.0, 0.49, 1.2);
  Tally t;
  for (int i = 0; i < 5000; ++i) {
    const double r = (i & 1) ? kRBig : kRSmall;
    const double th = rng.uniform(0.0, 2.0 * kPi);
    const Vec2 c1{rng.uniform(-0.005, 0.485), r * rng.uniform(0.9, 1.02)};
    const Vec2 c2{0.48 - r * rng.uniform(0.9, 1.02), rng.uniform(0.0, 1.0)};
    expect_same(regular_polygon(10, r, c1, th), floor, t);
    expect_same(regular_polygon(10, r, c2, th), side, t);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(t.touching, 3000);
}

// random convex polygons of 3 to ~12 vertices, any relative size and placement
TEST(PreparedOverlap, RandomConvexPairsBitwise) {
  RngStream rng(15, 0);
  Tally t;
  for (int i = 0; i < 10000; ++i) {
    const Poly a = test::random_convex(rng, {0.0, 0.0}, 1.0, 3 + i % 15);
    const Vec2 cb{rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0)};
    const Poly b = test::random_convex(rng, cb, rng.uniform(0.2, 2.0), 3 + (i / 15) % 15);
    expect_same(a, b, t);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(t.touching, 2000);
}

// polygons with a vertex repeated (a zero-length edge), which the clips merge: the prepared
// overlap is still bitwise the general result
TEST(PreparedOverlap, RepeatedVertexBitwise) {
  RngStream rng(18, 0);
  Tally t;
  for (int i = 0; i < 4000; ++i) {
    const Poly d = regular_polygon(10, kRBig, {0.0, 0.0}, rng.uniform(0.0, 2.0 * kPi));
    Poly a;
    const int rep = i % 10;
    for (int k = 0; k < d.n; ++k) {
      a.push(d.v[k]);
      if (k == rep) a.push(d.v[k]);  // vertex rep twice
    }
    const Vec2 cb = dir(rng.uniform(0.0, 2.0 * kPi)) * ((kRBig + kRSmall) * rng.uniform(0.85, 1.0));
    const Poly b = regular_polygon(10, kRSmall, cb, rng.uniform(0.0, 2.0 * kPi));
    expect_same(a, b, t);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(t.touching, 2000);
}

// convex hulls of points on a grid of 1/8 (exact binary coordinates): side values exactly zero,
// shared vertices, edges along each other, crossings that land on a vertex, containment. These
// are the cases the clips merge (a vertex on the line, a repeated point), which rounding almost
// never produces in the pile
TEST(PreparedOverlap, LatticePolygonsBitwise) {
  RngStream rng(20, 0);
  Tally t;
  for (int i = 0; i < 20000; ++i) {
    const int half = (i & 1) ? 16 : 4;  // a coarse grid (many coincidences) or a finer one
    auto draw = [&] { return std::floor(rng.uniform(-half, half + 1.0)); };
    auto lattice = [&](double cx, double cy) {
      for (;;) {
        std::vector<Vec2> pts;
        const int n = 3 + i % 7;
        for (int k = 0; k < n; ++k) pts.push_back({(cx + draw()) * 0.125, (cy + draw()) * 0.125});
        const Poly p = test::convex_hull(pts);
        if (p.n >= 3) return p;
      }
    };
    const Poly a = lattice(0.0, 0.0);
    const Poly b = lattice(draw(), draw());
    expect_same(a, b, t);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(t.touching, 5000);
  EXPECT_GT(t.other_crossings, 500);
}

// pairs pressed together along the line of centres by δ/r from 10⁻⁶ to 0.3 (from where they
// first touch, found by bisection), at random orientations: a resting pile's shallow overlaps
// and the rarer deep ones, where the prepared routine skips most of its work. The count is
// GS_OVERLAP_PAIRS (default 2·10⁴; 10⁷ for the full check).
TEST(PreparedOverlap, PressedPairsAtScaleBitwise) {
  const char* env = std::getenv("GS_OVERLAP_PAIRS");
  const long count = env ? std::atol(env) : 20000;
  RngStream rng(19, 0);
  Tally t;
  for (long i = 0; i < count; ++i) {
    const double ra = (i & 1) ? kRBig : kRSmall, rb = (i & 2) ? kRBig : kRSmall;
    const Vec2 u = dir(rng.uniform(0.0, 2.0 * kPi));
    const double ta = rng.uniform(0.0, 2.0 * kPi), tb = rng.uniform(0.0, 2.0 * kPi);
    const Vec2 ca{rng.uniform(0.0, 0.5), rng.uniform(0.0, 0.5)};
    const Poly a = regular_polygon(10, ra, ca, ta);
    auto at = [&](double d) { return regular_polygon(10, rb, ca + u * d, tb); };
    double in = 0.5 * (ra + rb), out = ra + rb;  // overlapping, apart
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (in + out);
      (overlap(a, at(mid)).area > 0.0 ? in : out) = mid;
    }
    const double depth = std::pow(10.0, rng.uniform(-6.0, std::log10(0.3)));
    expect_same(a, at(out - std::min(ra, rb) * depth), t);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(t.two_crossings, count * 9 / 10);
}

}  // namespace
}  // namespace gs
