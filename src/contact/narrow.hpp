// narrow phase: a [shape][partner] table of pure functions from two placed bodies to the
// contact geometry (SPEC 2.1 for polygons, SPEC 3 for disks). Periodic images arrive as a shift
// already applied to the partner's position.
#pragma once
#include "core/vec.hpp"
#include "geometry/polygon.hpp"
#include "world/world.hpp"

namespace gs {

/// what the force laws need to know about one touching pair
struct ContactGeom {
  bool touching = false;
  Vec2 n;              ///< unit normal from i towards j (or into the wall)
  Vec2 s;              ///< contact point, m
  double overlap = 0;  ///< polygons: overlap area A (m²); disks: penetration δ (m)
  double chord = 0;    ///< polygons: contact-line length |c2 − c1| (m)
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
ContactGeom disk_disk(const BodyView& a, const BodyView& b);
ContactGeom disk_wall(const BodyView& a, const Wall& w);

/// the table: partner kind 0 = disk, 1 = polygon, 2 = wall; nullptr = unsupported pairing
enum PartnerKind { kPartnerDisk = 0, kPartnerPolygon = 1, kPartnerWall = 2 };
using PairFn = ContactGeom (*)(const BodyView&, const BodyView&);
using WallFn = ContactGeom (*)(const BodyView&, const Wall&);
inline constexpr PairFn kPairTable[2][2] = {
    {disk_disk, nullptr},        // disk × {disk, polygon}
    {nullptr, polygon_polygon},  // polygon × {disk, polygon}
};
inline constexpr WallFn kWallTable[2] = {disk_wall, polygon_wall};

}  // namespace gs
