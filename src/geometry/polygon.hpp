// convex polygons: fixed-capacity vertex arrays (no heap in hot loops), counter-clockwise
#pragma once
#include <array>
#include <cassert>

#include "core/vec.hpp"

namespace gs {

/// most vertices a clipped polygon can have (two 10-gons intersect in at most 20)
inline constexpr int kMaxPolyVerts = 40;

/// a convex polygon, vertices counter-clockwise, in world coordinates (m)
struct Poly {
  int n = 0;
  std::array<Vec2, kMaxPolyVerts> v{};

  void push(Vec2 p) {
    assert(n < kMaxPolyVerts);
    v[n++] = p;
  }
  Vec2 operator[](int i) const { return v[i]; }
};

/// signed area (positive for counter-clockwise), shoelace formula
double signed_area(const Poly& p);
/// area centroid (p must have non-zero area)
Vec2 centroid(const Poly& p);

/// vertices of a regular n-gon, circumradius r, centre c, orientation θ (vertex 0 at angle θ)
Poly regular_polygon(int n, double r, Vec2 c = {}, double theta = 0.0);
/// an axis-aligned rectangle [x0,x1]×[y0,y1] as a polygon
Poly rectangle(double x0, double y0, double x1, double y1);
/// a polygon given in body coordinates placed at position c with orientation θ
Poly place(const Poly& body, Vec2 c, double theta);

/// the part of p on the side dot(x, n) <= d of a line (half-plane clip, Sutherland–Hodgman).
/// Points on the line count as inside. Needs p.n < kMaxPolyVerts (the result may gain a vertex).
Poly clip_half_plane(const Poly& p, Vec2 n, double d);
/// intersection of two convex polygons (Sutherland–Hodgman; b is the clip polygon).
/// Needs a.n + b.n <= kMaxPolyVerts. Touching polygons give a degenerate (zero-area) result.
Poly intersect(const Poly& a, const Poly& b);
/// area of the intersection of a convex polygon with the rectangle [x0,x1]×[y0,y1]
double area_in_rect(const Poly& p, double x0, double y0, double x1, double y1);

/// an axis-aligned bounding box, m
struct Aabb {
  Vec2 lo;  ///< lower-left corner, m
  Vec2 hi;  ///< upper-right corner, m
};
/// the tightest axis-aligned box around p's vertices (p must have at least one vertex)
Aabb bounds(const Poly& p);
/// whether point x lies in the closed convex polygon p
bool contains(const Poly& p, Vec2 x);
/// polar second moment of area about the point o: ∫|x − o|² dA, m⁴ (J = ρ × this)
double polar_moment(const Poly& p, Vec2 o);

/// result of the overlap of two convex polygons (docs/physics.md §2.1)
struct Overlap {
  double area = 0.0;  ///< area of the intersection polygon, m²
  int crossings = 0;  ///< number of boundary crossing points found (2 for a normal contact)
  Vec2 c1, c2;        ///< the two boundary crossings (contact line c1→c2) when crossings >= 2
  Vec2 centroid;      ///< centroid of the intersection polygon (when area > 0)
};
/// exact overlap of convex polygons a and b: area, boundary crossings, centroid.
/// With more than two crossings (deep or near-degenerate overlaps) c1, c2 are the pair farthest
/// apart; with none (one inside the other) crossings = 0.
Overlap overlap(const Poly& a, const Poly& b);

/// area of a regular n-gon of circumradius r: (n/2) r² sin(2π/n), m²; mass = ρ × area
/// (docs/physics.md §1.1)
double ngon_area(int n, double r);
/// moment of inertia of a regular n-gon about its centre: (m r²/6)(1 + 2cos²(π/n))
/// (docs/physics.md §1.1)
double ngon_inertia(int n, double r, double mass);
/// moment of inertia of a disk: m r²/2
double disk_inertia(double r, double mass);
/// area of the part of a disk (centre c, radius r) inside the rectangle [x0,x1]×[y0,y1]
double disk_area_in_rect(Vec2 c, double r, double x0, double y0, double x1, double y1);

}  // namespace gs
