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

}  // namespace

// the prepared polygon lies at the grain's own place, so shift a copy (the general routine,
// which gives the prepared one's bits where both apply)
ContactGeom polygon_image(const PlacedBody& a, const PlacedBody& b) {
  const Poly pa = unprepared(*a.poly);
  Poly pb = unprepared(*b.poly);
  for (int v = 0; v < pb.n; ++v) pb.v[v] += b.shift;
  return polygon_polygon(BodyView{a.c, a.r, &pa}, BodyView{b.c, b.r, &pb});
}

ContactGeom polygon_polygon(const BodyView& a, const BodyView& b) {
  return contact_from_overlap(overlap(*a.poly, *b.poly), b.c - a.c);
}

ContactGeom polygon_wall(const BodyView& a, const Wall& w) {
  // the wall lies on the far side of its inner face: point the normal into the wall
  return contact_from_overlap(overlap(*a.poly, w.poly), w.normal);
}

}  // namespace gs
