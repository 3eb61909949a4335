// the prepared overlap (overlap(PolyRef, PolyRef), the contact hot loop's) against the general
// routine (overlap(Poly, Poly)), bit for bit, over one mix of resting contacts pressed δ/r =
// 10⁻⁴…10⁻¹ deep, deep and nested pairs, near misses, touching, vertex on vertex, vertex on
// edge, parallel edges, walls and random convex polygons. GS_OVERLAP_PAIRS sets the number of
// pairs (default 20 000, under a second; 10⁷ for a thorough run of any change to the routine)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>

#include "core/rng.hpp"
#include "geometry/polygon.hpp"
#include "geometry/prepared.hpp"
#include "random_shapes.hpp"

namespace gs {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRBig = 9e-3;       // the paper's big decagon, m
constexpr double kRSmall = 6.36e-3;  // the paper's small decagon, m

Vec2 dir(double a) { return {std::cos(a), std::sin(a)}; }

long pair_count() {
  const char* s = std::getenv("GS_OVERLAP_PAIRS");
  return s != nullptr ? std::max(1L, std::atol(s)) : 20000L;
}

// one random pair of kind `kind` (0–7)
void make_pair(RngStream& rng, int kind, Poly& a, Poly& b) {
  const double ra = rng.uniform() < 0.5 ? kRBig : kRSmall;
  const double rb = rng.uniform() < 0.5 ? kRBig : kRSmall;
  const Vec2 ca{rng.uniform(-1.0, 1.0), rng.uniform(0.0, 1.5)};
  const double phi = rng.uniform(0.0, 2.0 * kPi);  // direction a → b
  const double step = 2.0 * kPi / 10, apo = std::cos(kPi / 10);
  switch (kind) {
    case 0:
    case 1:
    case 2: {
      // resting: a vertex of a pressed a depth δ (δ/r log-uniform 10⁻⁴…10⁻¹) into an edge of b,
      // the edge tilted up to ±15° and the vertex anywhere along its middle 80 %
      const double ta = phi;  // a's vertex 0 points along phi
      const Vec2 va = ca + dir(phi) * ra;
      const double tilt = rng.uniform(-15.0, 15.0) * kPi / 180.0;
      const Vec2 m = dir(phi + kPi + tilt);  // b's outward edge normal, towards a
      const double depth = rb * std::exp(rng.uniform(std::log(1e-4), std::log(1e-1)));
      const double side = 2.0 * rb * std::sin(kPi / 10);
      const Vec2 cb = va - m * (apo * rb - depth) + perp(m) * (rng.uniform(-0.4, 0.4) * side);
      // b's edge 0 runs from vertex 0 (angle tb) to vertex 1: its normal is at tb + step / 2
      a = regular_polygon(10, ra, ca, ta);
      b = regular_polygon(10, rb, cb, phi + kPi + tilt - 0.5 * step);
      return;
    }
    case 3: {
      // vertex–vertex, vertex–edge and edge–edge at gaps of ±10⁻¹⁶…10⁻³ of the radius or 0
      const int sub = static_cast<int>(rng.uniform(0.0, 3.0));
      const double ta = sub == 2 ? phi - 0.5 * step : phi;
      const double tb = sub == 0 ? phi + kPi : phi + kPi - 0.5 * step;
      const double reach = (sub == 2 ? apo * ra : ra) + (sub == 0 ? rb : apo * rb);
      const int e = static_cast<int>(rng.uniform(0.0, 14.0));
      const double gap = e == 13 ? 0.0 : std::pow(10.0, -16.0 + e) * (rng.uniform() < 0.5 ? -1 : 1);
      const double slide = sub == 2 ? rng.uniform(-0.5, 0.5) * std::min(ra, rb) : 0.0;
      const Vec2 cb = ca + dir(phi) * (reach * (1.0 + gap)) + perp(dir(phi)) * slide;
      a = regular_polygon(10, ra, ca, ta);
      b = regular_polygon(10, rb, cb, tb);
      return;
    }
    case 4:
    case 5: {
      // random orientations, centre distance 0 (nested) to past the circumradius sum
      const double f = kind == 4 ? rng.uniform(0.9, 1.02) : rng.uniform(0.0, 1.05);
      a = regular_polygon(10, ra, ca, rng.uniform(0.0, 2.0 * kPi));
      b = regular_polygon(10, rb, ca + dir(phi) * (f * (ra + rb)), rng.uniform(0.0, 2.0 * kPi));
      return;
    }
    case 6: {
      // a decagon on a wall slab
      a = regular_polygon(10, ra, {ca.x, ra * rng.uniform(0.9, 1.02)}, phi);
      b = rectangle(-2.0, -0.01, 2.0, 0.0);
      return;
    }
    default: {
      a = test::random_convex(rng, {0.0, 0.0}, 1.0, 3 + static_cast<int>(rng.uniform(0.0, 15.0)));
      const Vec2 cb{rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0)};
      b = test::random_convex(rng, cb, rng.uniform(0.2, 2.0),
                              3 + static_cast<int>(rng.uniform(0.0, 15.0)));
      return;
    }
  }
}

bool same(const Overlap& f, const Overlap& g, bool centroid) {
  return f.area == g.area && f.crossings == g.crossings && f.c1 == g.c1 && f.c2 == g.c2 &&
         (!centroid || f.centroid == g.centroid);
}

TEST(PreparedOverlapMix, BitwiseTheGeneralRoutine) {
  const long count = pair_count();
  RngStream rng(31, 0);
  PolyStore st;
  st.resize(2, kMaxPolyVerts - 1);
  long touching = 0, resting = 0, two = 0, other = 0;
  Poly a, b;
  for (long i = 0; i < count; ++i) {
    const int kind = static_cast<int>(i % 8);
    make_pair(rng, kind, a, b);
    st.set(0, a);
    st.set(1, b);
    for (int swap = 0; swap < 2; ++swap) {
      const PolyRef pa = st.ref(swap), pb = st.ref(1 - swap);
      const Overlap g = swap ? overlap(b, a) : overlap(a, b);
      const Overlap f = overlap(pa, pb);
      // the prepared routine computes the centroid only without a contact line
      const bool centroid = g.crossings < 2 || g.c1 == g.c2;
      ASSERT_TRUE(same(f, g, centroid)) << "pair " << i << " kind " << kind << " swap " << swap;
      touching += g.area > 0.0;
      resting += kind < 3 && g.area > 0.0;
      (g.crossings == 2 ? two : other) += g.area > 0.0;
    }
  }
  // the mix reaches what it means to: resting contacts (every one of kinds 0–2 touches) and
  // overlaps without exactly two crossings (nested, deep)
  EXPECT_EQ(resting, 2 * ((count + 7) / 8 + (count + 6) / 8 + (count + 5) / 8));
  EXPECT_GT(two, count / 2);
  EXPECT_GT(other, count / 400);
  RecordProperty("pairs", std::to_string(count));
  RecordProperty("touching", std::to_string(touching));
}

}  // namespace
}  // namespace gs
