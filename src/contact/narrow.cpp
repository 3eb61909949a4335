#include "contact/narrow.hpp"

#include <cmath>

namespace gs {
namespace {

// polygon i of a prepared store as a Poly (the general routines' form)
Poly unprepared(const PolyRef& p) {
  Poly q;
  for (int k = 0; k < p.n; ++k) q.push({p.x[k], p.y[k]});
  return q;
}

// the contact frame (docs/physics.md §2.1) from an exact polygon overlap; `toward` points from
// i to j (or into the wall); inlined: it runs once per candidate pair
[[gnu::always_inline]] inline ContactGeom from_overlap(const Overlap& ov, Vec2 toward) {
  ContactGeom g;
  if (ov.area <= 0.0) return g;
  g.touching = true;
  g.overlap = ov.area;
  const Vec2 d = ov.c2 - ov.c1;
  const double d2 = norm2(d);
  if (ov.crossings >= 2 && d2 > 0.0) {
    // contact line c1→c2: the point is its midpoint, the normal is perpendicular to it
    // (1/|d|² beside |d|: the division does not wait for the square root)
    g.s = 0.5 * (ov.c1 + ov.c2);
    const double inv2 = 1.0 / d2;
    g.chord = std::sqrt(d2);
    g.n = perp(d) * (g.chord * inv2);
    if (dot(g.n, toward) < 0.0) g.n = -g.n;
  } else {
    // one polygon inside the other: unphysical, use the centre direction (docs/physics.md §2.1)
    g.degenerate = true;
    g.s = ov.centroid;
    const double d = norm(toward);
    g.n = d > 0.0 ? toward / d : Vec2{1.0, 0.0};
    g.chord = std::sqrt(ov.area);
  }
  return g;
}

// a periodic image: the prepared polygon lies at the grain's own place, so shift a copy
// (the general routine, which gives the prepared one's bits where both apply)
[[gnu::noinline]] ContactGeom image_overlap(const PlacedBody& a, const PlacedBody& b) {
  const Poly pa = unprepared(*a.poly);
  Poly pb = unprepared(*b.poly);
  for (int v = 0; v < pb.n; ++v) pb.v[v] += b.shift;
  return polygon_polygon(BodyView{a.c, a.r, &pa}, BodyView{b.c, b.r, &pb});
}

}  // namespace

template <>
ContactGeom narrow<BodyKind::Polygon, BodyKind::Polygon>(const PlacedBody& a, const PlacedBody& b) {
  if (b.shift == Vec2{}) [[likely]]
    return from_overlap(overlap(*a.poly, *b.poly), b.c - a.c);
  return image_overlap(a, b);
}

template <>
ContactGeom narrow<BodyKind::Polygon, BodyKind::Wall>(const PlacedBody& a, const PlacedBody& b) {
  return from_overlap(overlap(*a.poly, *b.poly), b.wall->normal);
}

ContactGeom polygon_polygon(const BodyView& a, const BodyView& b) {
  return from_overlap(overlap(*a.poly, *b.poly), b.c - a.c);
}

ContactGeom polygon_wall(const BodyView& a, const Wall& w) {
  // the wall lies on the far side of its inner face: point the normal into the wall
  return from_overlap(overlap(*a.poly, w.poly), w.normal);
}

}  // namespace gs
