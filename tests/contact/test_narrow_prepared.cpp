// the narrow phase on prepared polygons (the registry's, which the force loop calls, computed in
// a frame local to the pair) against the general one (world frame): the same contact geometry to
// the general routine's rounding, twice its error bound against the exact value
// (tests/geometry/extended_overlap.hpp), for decagon pairs and decagon–wall pairs
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "contact/narrow.hpp"
#include "core/rng.hpp"
#include "geometry/prepared.hpp"

namespace gs {
namespace {

constexpr double kPi = std::numbers::pi;

// X: the world coordinate scale, D: the pair's size; bounds as in extended_overlap.hpp, c = 16.
// `line`: the overlap has exactly two crossings (with more, the contact line is the pair
// farthest apart, a choice that near-ties flip with the rounding of either routine)
void expect_same(const ContactGeom& f, const ContactGeom& g, double X, double D, bool line) {
  const double e = 2.0 * 16.0 * std::numeric_limits<double>::epsilon() / 2;
  const double tiny = e * X * D;
  if (std::max(f.overlap, g.overlap) <= tiny) return;  // touching to round-off either way
  ASSERT_EQ(f.touching, g.touching);
  ASSERT_EQ(f.degenerate, g.degenerate);
  ASSERT_NEAR(f.overlap, g.overlap, tiny);
  if (!g.degenerate && !line) return;
  const double ds = g.degenerate ? e * X * (1.0 + D * D / g.overlap) : e * X;
  ASSERT_NEAR(f.s.x, g.s.x, ds);
  ASSERT_NEAR(f.s.y, g.s.y, ds);
  if (g.degenerate) {
    ASSERT_EQ(f.n, g.n);  // the direction between the centres
  } else {
    ASSERT_NEAR(f.chord, g.chord, 2.0 * e * X);
    ASSERT_NEAR(f.n.x, g.n.x, e * X / g.chord);
    ASSERT_NEAR(f.n.y, g.n.y, e * X / g.chord);
  }
}

TEST(NarrowPrepared, DecagonPairsMatchGeneral) {
  RngStream rng(21, 0);
  const Poly big = regular_polygon(10, 9e-3), small = regular_polygon(10, 6.36e-3);
  PolyStore st;
  st.resize(2, 10);
  int touching = 0, degenerate = 0, deep = 0;
  for (int i = 0; i < 20000; ++i) {
    const Poly& ba = (i & 1) ? big : small;
    const Poly& bb = (i & 2) ? big : small;
    const double ra = (i & 1) ? 9e-3 : 6.36e-3, rb = (i & 2) ? 9e-3 : 6.36e-3;
    const Vec2 ca{rng.uniform(0.0, 0.5), rng.uniform(0.0, 0.5)};
    const double ang = rng.uniform(0.0, 2.0 * kPi);
    const double f = i % 10 == 0 ? rng.uniform(0.0, 0.9) : rng.uniform(0.9, 1.02);
    const Vec2 cb = ca + Vec2{std::cos(ang), std::sin(ang)} * (f * (ra + rb));
    const double ta = rng.uniform(-10.0, 10.0), tb = rng.uniform(-10.0, 10.0);
    st.set_placed(0, ba, ca, ta);
    st.set_placed(1, bb, cb, tb);
    const Poly pa = place(ba, ca, ta), pb = place(bb, cb, tb);
    const ContactGeom g = polygon_polygon(BodyView{ca, ra, &pa}, BodyView{cb, rb, &pb});
    const PolyRef ra_ = st.ref(0), rb_ = st.ref(1);
    const ContactGeom fast = narrow<BodyKind::Polygon, BodyKind::Polygon>(
        PlacedBody{ca, 0.0, &ra_, {}, nullptr}, PlacedBody{cb, 0.0, &rb_, {}, nullptr});
    expect_same(fast, g, 0.52, 2.0 * (ra + rb), overlap(pa, pb).crossings == 2);
    deep += overlap(pa, pb).crossings > 2;
    if (HasFatalFailure()) return;
    touching += g.touching;
    degenerate += g.degenerate;
  }
  EXPECT_GT(touching, 12000);
  EXPECT_GT(degenerate, 10);  // one inside the other: the centroid path
  EXPECT_LT(deep, 20000 / 10);
}

TEST(NarrowPrepared, DecagonWallMatchesGeneral) {
  RngStream rng(22, 0);
  Wall w;
  w.poly = rectangle(-0.01, -0.01, 0.49, 0.0);
  w.normal = {0.0, -1.0};
  PolyStore st;
  st.resize(2, 10);
  st.set(1, w.poly);
  const Poly body = regular_polygon(10, 9e-3);
  int touching = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vec2 c{rng.uniform(0.0, 0.48), 9e-3 * rng.uniform(0.85, 1.02)};
    const double th = rng.uniform(0.0, 2.0 * kPi);
    st.set_placed(0, body, c, th);
    const Poly p = place(body, c, th);
    const ContactGeom g = polygon_wall(BodyView{c, 9e-3, &p}, w);
    const PolyRef r0 = st.ref(0), r1 = st.ref(1);
    expect_same(narrow<BodyKind::Polygon, BodyKind::Wall>(PlacedBody{c, 0.0, &r0, {}, nullptr},
                                                          PlacedBody{{}, 0.0, &r1, {}, &w}),
                g, 0.5, 1.0, overlap(p, w.poly).crossings == 2);
    if (HasFatalFailure()) return;
    touching += g.touching;
  }
  EXPECT_GT(touching, 3000);
}

}  // namespace
}  // namespace gs
