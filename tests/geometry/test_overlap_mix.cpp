// the prepared overlap (overlap(PolyRef, PolyRef), the contact hot loop's, computed in a frame
// local to the pair) and the general routine (overlap(Poly, Poly), world frame) against an
// extended-precision reference, over one mix of resting contacts pressed δ/r = 10⁻⁴…10⁻¹ deep,
// deep and nested pairs, near misses, touching, vertex on vertex, vertex on edge, parallel
// edges, walls and random convex polygons: the prepared routine's error in area, contact point,
// normal and centroid within the general routine's bound, and the same degenerate cases.
// GS_OVERLAP_PAIRS sets the number of pairs (default 20 000, about a second; 10⁷ for a thorough
// run of any change to the routine)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>

#include "core/rng.hpp"
#include "extended_overlap.hpp"
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

TEST(PreparedOverlapMix, WithinTheWorldFrameBoundOfTheReference) {
  const long count = pair_count();
  RngStream rng(31, 0);
  PolyStore st;
  st.resize(2, kMaxPolyVerts - 1);
  long resting = 0, lines = 0;
  // the largest errors over the pairs with a contact line, per routine (0: world frame,
  // 1: prepared), as multiples of ε·X·D (area), ε·D² (area), ε·L (point), ε·L/ℓ (normal),
  // L = X + D
  double worst[2][4] = {};
  // resting pairs (kinds 0–2): the largest relative area error in ε, per routine
  double rel[2] = {};
  Poly a, b;
  for (long i = 0; i < count; ++i) {
    const int kind = static_cast<int>(i % 8);
    make_pair(rng, kind, a, b);
    st.set(0, a);
    st.set(1, b);
    for (int swap = 0; swap < 2; ++swap) {
      const test::PairCheck c = swap ? test::check_pair(b, a, st.ref(1), st.ref(0))
                                     : test::check_pair(a, b, st.ref(0), st.ref(1));
      ASSERT_EQ(c.failure, "") << "pair " << i << " kind " << kind << " swap " << swap;
      if (!c.line) continue;
      const test::Scale& s = c.scale;
      const test::Errors* e[2] = {&c.world, &c.prepared};
      for (int r = 0; r < 2; ++r) {
        worst[r][0] = std::max(worst[r][0], e[r]->area / (s.X * s.D));
        worst[r][1] = std::max(worst[r][1], e[r]->area / (s.D * s.D));
        worst[r][2] = std::max(worst[r][2], e[r]->point / (s.X + s.D));
        worst[r][3] = std::max(worst[r][3], e[r]->normal * s.l / (s.X + s.D));
        if (kind < 3) rel[r] = std::max(rel[r], e[r]->area / s.A);
      }
      ++lines;
      resting += kind < 3;
    }
  }
  for (int r = 0; r < 2; ++r) {
    const std::string who = r == 0 ? "world_" : "prepared_";
    RecordProperty(who + "area_per_XD", std::to_string(worst[r][0]));
    RecordProperty(who + "area_per_D2", std::to_string(worst[r][1]));
    RecordProperty(who + "point_per_L", std::to_string(worst[r][2]));
    RecordProperty(who + "normal_per_L_over_l", std::to_string(worst[r][3]));
    RecordProperty(who + "resting_rel_area_per_eps", std::to_string(rel[r]));
  }
  // the local frame's gain: at the pile's scale (X ≈ 1.5 m, D ≈ 30 mm) the prepared routine's
  // area error in units of ε·D² is an order of magnitude below the world frame's
  EXPECT_LT(worst[1][1], 0.1 * worst[0][1]);
  EXPECT_LT(rel[1], 0.01 * rel[0]);
  // the contact line: the worst cases (ill-conditioned crossings) no more than twice the world
  // frame's
  EXPECT_LE(worst[1][2], 2.0 * worst[0][2]);
  EXPECT_LE(worst[1][3], 2.0 * worst[0][3]);
  // the mix reaches what it means to: resting contacts (every one of kinds 0–2 has a contact
  // line) and the other kinds
  EXPECT_EQ(resting, 2 * ((count + 7) / 8 + (count + 6) / 8 + (count + 5) / 8));
  EXPECT_GT(lines - resting, count / 4);
  RecordProperty("pairs", std::to_string(count));
}

}  // namespace
}  // namespace gs
