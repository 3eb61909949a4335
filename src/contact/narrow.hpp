// narrow phase: pure functions from two placed bodies to the contact geometry (the pair loop
// picks one per model: force/forces.cpp) (docs/physics.md §2.1 for polygons, §3 for disks).
// Periodic images arrive as a shift already applied to the partner's position.
#pragma once
#include <cmath>

#include "core/vec.hpp"
#include "geometry/polygon.hpp"
#include "geometry/prepared.hpp"
#include "world/world.hpp"

namespace gs {

/// what the force laws need to know about one touching pair
struct ContactGeom {
  bool touching = false;
  Vec2 n;                   ///< unit normal from i towards j (or into the wall)
  Vec2 s;                   ///< contact point, m
  double overlap = 0;       ///< polygons: overlap area A (m²); disks: penetration δ (m)
  double chord = 0;         ///< polygons: contact-line length |c2 − c1| (m)
  bool degenerate = false;  ///< polygons: one inside the other, no boundary crossings
};

/// one body as the narrow phase sees it: centre, bounding radius, world-frame polygon if any
struct BodyView {
  Vec2 c;
  double r = 0;
  const Poly* poly = nullptr;
};

ContactGeom polygon_polygon(const BodyView& a, const BodyView& b);
ContactGeom polygon_wall(const BodyView& a, const Wall& w);
/// the same contacts, bit for bit, from polygons prepared once per step (the hot loop);
/// `toward` points from i to j (polygon pairs: xj − xi) or into the wall (its normal)
ContactGeom polygon_polygon(const PolyRef& a, const PolyRef& b, Vec2 toward);

// disks are cheap enough that the call would cost as much as the test: inline
inline ContactGeom disk_disk(const BodyView& a, const BodyView& b) {
  ContactGeom g;
  const Vec2 d = b.c - a.c;
  const double dist2 = norm2(d), rr = a.r + b.r;
  if (dist2 >= rr * rr || dist2 == 0.0) return g;
  const double dist = std::sqrt(dist2);
  g.touching = true;
  g.n = d / dist;
  g.overlap = rr - dist;
  g.s = a.c + g.n * (a.r - 0.5 * g.overlap);
  return g;
}

inline ContactGeom disk_wall(const BodyView& a, const Wall& w) {
  ContactGeom g;
  // penetration of the disk through the wall's inner face (a half-plane)
  const double delta = dot(a.c, w.normal) + a.r - w.offset;
  if (delta <= 0.0) return g;
  g.touching = true;
  g.n = w.normal;
  g.overlap = delta;
  g.s = a.c + w.normal * (a.r - 0.5 * delta);
  return g;
}

}  // namespace gs
