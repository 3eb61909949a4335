// the narrow phase: pure functions from two placed bodies to the contact frame
// (docs/physics.md §2.1 for polygons, §3 for disks), one per pairing of body kinds. The pair
// loop's evaluators call them by their kinds at compile time (narrow<A, B>); kNarrowPhase is
// the same functions as a [kind][kind] table, for callers that know the kinds only at run time.
// Periodic images arrive as a shift already applied to the partner's position.
#pragma once
#include <cmath>
#include <cstdint>

#include "core/vec.hpp"
#include "geometry/polygon.hpp"
#include "geometry/prepared.hpp"
#include "world/world.hpp"

namespace gs {

/// what the force laws need to know about one touching pair: the contact frame
struct ContactGeom {
  bool touching = false;
  Vec2 n;                   ///< unit normal from i towards j (or into the wall)
  Vec2 s;                   ///< contact point, m
  double overlap = 0;       ///< polygons: overlap area A (m²); disks: penetration δ (m)
  double chord = 0;         ///< polygons: contact-line length |c2 − c1| (m)
  bool degenerate = false;  ///< polygons: one inside the other, no boundary crossings
};

/// the kinds of body a pair joins: a grain's shape, or a wall (always the second body)
enum class BodyKind : std::uint8_t { Disk = 0, Polygon = 1, Wall = 2 };
inline constexpr int kBodyKinds = 3;
constexpr BodyKind body_kind(ShapeKind s) {
  return s == ShapeKind::Disk ? BodyKind::Disk : BodyKind::Polygon;
}

/// one body of a pair as the narrow phase reads it, placed for this step. Each function reads
/// only the fields of its kinds: disks c and r; polygons c and their prepared polygon (a
/// periodic image: the polygon at the grain's own place, and the shift to its image); walls
/// their prepared polygon and the wall itself
struct PlacedBody {
  Vec2 c;                         ///< centre (a periodic image's: shifted), m
  double r = 0;                   ///< disks: radius, m
  const PolyRef* poly = nullptr;  ///< polygons, walls: the prepared world-frame polygon
  Vec2 shift;                     ///< polygons: from the polygon's place to the image's (else 0)
  const Wall* wall = nullptr;     ///< walls
};

/// the narrow phase of a body of kind A against one of kind B; pairings without a function
/// (a disk against a polygon: a world is of one model) do not compile
template <BodyKind A, BodyKind B>
ContactGeom narrow(const PlacedBody& a, const PlacedBody& b) = delete;

// disks are cheap enough that a call would cost as much as the test: inline
template <>
inline ContactGeom narrow<BodyKind::Disk, BodyKind::Disk>(const PlacedBody& a,
                                                          const PlacedBody& b) {
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

template <>
inline ContactGeom narrow<BodyKind::Disk, BodyKind::Wall>(const PlacedBody& a,
                                                          const PlacedBody& b) {
  ContactGeom g;
  const Wall& w = *b.wall;
  // penetration of the disk through the wall's inner face (a half-plane)
  const double delta = dot(a.c, w.normal) + a.r - w.offset;
  if (delta <= 0.0) return g;
  g.touching = true;
  g.n = w.normal;
  g.overlap = delta;
  g.s = a.c + w.normal * (a.r - 0.5 * delta);
  return g;
}

/// the contact frame (docs/physics.md §2.1) from an exact polygon overlap; `toward` points from
/// i to j (or into the wall). Inline, as the polygon functions below: they run once per candidate
/// pair, and inlined into the pair loop their bodies and results stay in registers
[[gnu::always_inline]] inline ContactGeom contact_from_overlap(const Overlap& ov, Vec2 toward) {
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

/// a polygon against a periodic image of another: the image's polygon is b's shifted (out of
/// line: rare, and it copies both polygons)
ContactGeom polygon_image(const PlacedBody& a, const PlacedBody& b);

/// polygons by their exact overlap (prepared: bounding circles reject separated pairs); a
/// periodic image overlaps a shifted copy of b's polygon
template <>
[[gnu::always_inline]] inline ContactGeom narrow<BodyKind::Polygon, BodyKind::Polygon>(
    const PlacedBody& a, const PlacedBody& b) {
  if (b.shift == Vec2{}) [[likely]]
    return contact_from_overlap(overlap(*a.poly, *b.poly), b.c - a.c);
  return polygon_image(a, b);
}
/// the wall's polygon is its slab; the normal points into the wall
template <>
[[gnu::always_inline]] inline ContactGeom narrow<BodyKind::Polygon, BodyKind::Wall>(
    const PlacedBody& a, const PlacedBody& b) {
  return contact_from_overlap(overlap(*a.poly, *b.poly), b.wall->normal);
}

/// the registry at run time: kNarrowPhase[A][B] is &narrow<A, B>, nullptr where A cannot meet B
using NarrowFn = ContactGeom (*)(const PlacedBody&, const PlacedBody&);
inline constexpr NarrowFn kNarrowPhase[kBodyKinds][kBodyKinds] = {
    {&narrow<BodyKind::Disk, BodyKind::Disk>, nullptr, &narrow<BodyKind::Disk, BodyKind::Wall>},
    {nullptr, &narrow<BodyKind::Polygon, BodyKind::Polygon>,
     &narrow<BodyKind::Polygon, BodyKind::Wall>},
    {nullptr, nullptr, nullptr},  // a wall is always the second body
};
constexpr NarrowFn narrow_fn(BodyKind a, BodyKind b) {
  return kNarrowPhase[static_cast<int>(a)][static_cast<int>(b)];
}

/// one body with an unprepared world-frame polygon, for the general routines below
struct BodyView {
  Vec2 c;
  double r = 0;
  const Poly* poly = nullptr;
};
/// the same contacts, bit for bit, as the registry's polygon functions, from unprepared
/// polygons: the reference they are tested against, and for callers with a polygon at hand
ContactGeom polygon_polygon(const BodyView& a, const BodyView& b);
ContactGeom polygon_wall(const BodyView& a, const Wall& w);

}  // namespace gs
