// the regular-polygon bound that lets the prepared overlap test only the facing edge's two
// neighbours (PolyRef::near): its value, that it holds, where it is withheld, and that the
// shortcut leaves every overlap bit for bit as the full search
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/rng.hpp"
#include "geometry/polygon.hpp"
#include "geometry/prepared.hpp"
#include "random_shapes.hpp"

namespace gs {
namespace {

constexpr double kPi = std::numbers::pi;

double near_of(const Poly& p) {
  PolyStore st;
  st.resize(1, p.n);
  st.set(0, p);
  return st.ref(0).near;
}

TEST(NearBound, AnalyticValueForRegularPolygons) {
  // ρ·(1 − cos(4π/n)), ρ = r·cos(π/n) the apothem, less 1e-6 of it
  for (int n : {5, 6, 10, 16, 40}) {
    const double r = 9e-3;
    const double want = r * std::cos(kPi / n) * (1.0 - std::cos(4.0 * kPi / n));
    EXPECT_NEAR(near_of(regular_polygon(n, r, {0.3, -0.2}, 0.7)), want, 2e-6 * want) << n;
  }
  // under 5 sides every edge is the facing one or a neighbour: no bound
  EXPECT_EQ(near_of(regular_polygon(4, 1.0)), 0.0);
  EXPECT_EQ(near_of(regular_polygon(3, 1.0)), 0.0);
}

TEST(NearBound, WithheldFromIrregularAndFarPolygons) {
  EXPECT_EQ(near_of(rectangle(0.0, 0.0, 2.0, 1.0)), 0.0);
  Poly p = regular_polygon(10, 1.0);
  p.v[3].x += 1e-6;  // one vertex moved by a millionth of the radius
  EXPECT_EQ(near_of(p), 0.0);
  RngStream rng(31, 0);
  EXPECT_EQ(near_of(test::random_convex(rng, {}, 1.0, 10)), 0.0);
  // placed: the body's bound less the rounding; none beyond 10⁶ sizes from the origin
  const Poly body = regular_polygon(10, 9e-3);
  PolyStore st;
  st.resize(1, 10);
  st.set_placed(0, body, {0.2, 0.1}, 1.3);
  EXPECT_NEAR(st.ref(0).near, near_of(body), 1e-12);
  st.set_placed(0, body, {2e4, 0.0}, 1.3);
  EXPECT_EQ(st.ref(0).near, 0.0);
}

// points within `near` (L1) of an edge midpoint lie strictly inside every other edge line but
// the two neighbours', by a margin far above round-off; and the bound is not loose: just past
// it, towards an edge two steps away, a point leaves that edge's line
TEST(NearBound, HoldsAndIsTight) {
  RngStream rng(32, 0);
  for (int n : {5, 7, 10, 13}) {
    const Poly p = regular_polygon(n, 1.0, {0.5, 0.25}, rng.uniform(0.0, 2.0 * kPi));
    const double near = near_of(p);
    ASSERT_GT(near, 0.0);
    auto side = [&](int j, Vec2 x) {  // > 0 outside edge j's line, in units of length
      const Vec2 e = p.v[(j + 1) % n] - p.v[j];
      return cross(x - p.v[j], e) / norm(e);
    };
    for (int k = 0; k < n; ++k) {
      const Vec2 m = 0.5 * (p.v[k] + p.v[(k + 1) % n]);
      for (int t = 0; t < 2000; ++t) {
        // a random point of the L1 ball of radius near about m
        const double u = rng.uniform(-1.0, 1.0), v = (1.0 - std::abs(u)) * rng.uniform(-1.0, 1.0);
        const Vec2 x = m + Vec2{u, v} * near;
        for (int j = 0; j < n; ++j) {
          const int d = (j - k + n) % n;
          if (d <= 1 || d == n - 1) continue;
          ASSERT_LT(side(j, x), -1e-9) << "n " << n << " edge " << k << " line " << j;
        }
      }
      // along the normal of edge k + 2, 1% past the bound (in L2, which the L1 bound also
      // covers): outside that edge's line
      const Vec2 e2 = p.v[(k + 3) % n] - p.v[(k + 2) % n];
      const Vec2 out2 = Vec2{e2.y, -e2.x} / norm(e2);
      EXPECT_GT(side((k + 2) % n, m + out2 * (1.01 * near / (1.0 - 1e-6))), 0.0);
    }
  }
}

// the shortcut in the prepared overlap changes nothing: the same pairs with the bound removed
// (every edge line tested) give the same results bit for bit
TEST(NearBound, OverlapSameWithoutTheShortcut) {
  RngStream rng(33, 0);
  PolyStore st;
  st.resize(2, 10);
  int touching = 0, shallow = 0;
  for (int i = 0; i < 20000; ++i) {
    const double ra = i % 2 ? 9e-3 : 6.36e-3, rb = 9e-3;
    const Vec2 ca{rng.uniform(0.0, 0.5), rng.uniform(0.0, 0.5)};
    const double f = i % 5 == 0 ? rng.uniform(0.3, 0.9) : rng.uniform(0.9, 1.0);
    const double phi = rng.uniform(0.0, 2.0 * kPi);
    st.set_placed(0, regular_polygon(10, ra), ca, rng.uniform(0.0, 2.0 * kPi));
    st.set_placed(1, regular_polygon(10, rb),
                  ca + Vec2{std::cos(phi), std::sin(phi)} * (f * (ra + rb)),
                  rng.uniform(0.0, 2.0 * kPi));
    const PolyRef a = st.ref(0), b = st.ref(1);
    ASSERT_GT(b.near, 0.0);
    PolyRef a0 = a, b0 = b;
    a0.near = b0.near = 0.0;
    const Overlap o = overlap(a, b), o0 = overlap(a0, b0);
    ASSERT_EQ(o.area, o0.area) << i;
    ASSERT_EQ(o.crossings, o0.crossings) << i;
    ASSERT_EQ(o.c1, o0.c1) << i;
    ASSERT_EQ(o.c2, o0.c2) << i;
    ASSERT_EQ(o.centroid, o0.centroid) << i;
    touching += o.area > 0.0;
    shallow += o.area > 0.0 && f > 0.97;
  }
  EXPECT_GT(touching, 15000);
  EXPECT_GT(shallow, 800);
}

}  // namespace
}  // namespace gs
