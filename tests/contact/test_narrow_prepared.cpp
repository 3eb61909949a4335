// the narrow phase on prepared polygons (the registry's, which the force loop calls) against
// the general one: identical contact geometry, bit for bit, for decagon pairs and decagon–wall
// pairs
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contact/narrow.hpp"
#include "core/rng.hpp"
#include "geometry/prepared.hpp"

namespace gs {
namespace {

constexpr double kPi = std::numbers::pi;

void expect_same(const ContactGeom& f, const ContactGeom& g) {
  ASSERT_EQ(f.touching, g.touching);
  if (!g.touching) return;
  ASSERT_EQ(f.degenerate, g.degenerate);
  ASSERT_EQ(f.overlap, g.overlap);
  ASSERT_EQ(f.chord, g.chord);
  ASSERT_EQ(f.s, g.s);
  ASSERT_EQ(f.n, g.n);
}

TEST(NarrowPrepared, DecagonPairsMatchGeneral) {
  RngStream rng(21, 0);
  const Poly big = regular_polygon(10, 9e-3), small = regular_polygon(10, 6.36e-3);
  PolyStore st;
  st.resize(2, 10);
  int touching = 0, degenerate = 0;
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
    expect_same(fast, g);
    if (HasFatalFailure()) return;
    touching += g.touching;
    degenerate += g.degenerate;
  }
  EXPECT_GT(touching, 12000);
  EXPECT_GT(degenerate, 10);  // one inside the other: the centroid path
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
                g);
    if (HasFatalFailure()) return;
    touching += g.touching;
  }
  EXPECT_GT(touching, 3000);
}

}  // namespace
}  // namespace gs
