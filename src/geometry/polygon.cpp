// convex polygons: construction, areas, moments, half-plane and rectangle clipping
// (docs/physics.md §1.1, §2.5)
#include "geometry/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "geometry/clip.hpp"

namespace gs {

namespace {

// reject n-gons that are not polygons (or, as vertex lists, do not fit a fixed-capacity Poly)
void check_ngon(int n, const char* who, int max_n = 1 << 30) {
  if (n < 3 || n > max_n)
    throw InputError(who, "n",
                     "a regular polygon needs 3.." + std::to_string(max_n) + " vertices, got " +
                         std::to_string(n));
}

// a working ring large enough for any clip of a Poly by a few lines
using Ring = detail::Ring<kMaxPolyVerts + 8>;

}  // namespace

// shoelace formula (relative to vertex 0 for precision far from the origin)
double signed_area(const Poly& p) { return 0.5 * detail::twice_area(p); }

Vec2 centroid(const Poly& p) { return detail::ring_centroid(p); }

// vertex k at angle θ + 2πk/n, counter-clockwise
Poly regular_polygon(int n, double r, Vec2 c, double theta) {
  check_ngon(n, "regular_polygon", kMaxPolyVerts);
  Poly p;
  const double step = 2.0 * std::numbers::pi / n;
  for (int k = 0; k < n; ++k) {
    const double a = theta + step * k;
    p.push({c.x + r * std::cos(a), c.y + r * std::sin(a)});
  }
  return p;
}

// corners counter-clockwise from the lower left
Poly rectangle(double x0, double y0, double x1, double y1) {
  Poly p;
  p.push({x0, y0});
  p.push({x1, y0});
  p.push({x1, y1});
  p.push({x0, y1});
  return p;
}

// rotate by θ about the body origin, then translate to c
Poly place(const Poly& body, Vec2 c, double theta) {
  const double cs = std::cos(theta), sn = std::sin(theta);
  Poly p;
  p.n = body.n;
  for (int i = 0; i < body.n; ++i) p.v[i] = c + rotate(body.v[i], cs, sn);
  return p;
}

// one Sutherland–Hodgman pass; the side function is measured from a point on the line
Poly clip_half_plane(const Poly& p, Vec2 n, double d) {
  Ring in, out;
  in.assign(p);
  const double nn = norm2(n);
  const Vec2 o = nn > 0.0 ? n * (d / nn) : Vec2{};
  detail::clip_ring(in, out, [&](Vec2 x) { return dot(x - o, n); });
  return out.to_poly();
}

// componentwise min and max over the vertices
Aabb bounds(const Poly& p) {
  Aabb b{p.v[0], p.v[0]};
  for (int i = 1; i < p.n; ++i) {
    b.lo.x = std::min(b.lo.x, p.v[i].x);
    b.lo.y = std::min(b.lo.y, p.v[i].y);
    b.hi.x = std::max(b.hi.x, p.v[i].x);
    b.hi.y = std::max(b.hi.y, p.v[i].y);
  }
  return b;
}

// inside (or on) every counter-clockwise edge
bool contains(const Poly& p, Vec2 x) {
  if (p.n < 3) return false;
  for (int i = 0, j = p.n - 1; i < p.n; j = i++)
    if (cross(p.v[i] - p.v[j], x - p.v[j]) < 0.0) return false;
  return true;
}

// exact clip against the four sides; whole-inside and disjoint polygons skip the clipping
double area_in_rect(const Poly& p, double x0, double y0, double x1, double y1) {
  if (p.n < 3 || !(x0 < x1) || !(y0 < y1)) return 0.0;
  const Aabb b = bounds(p);
  if (b.hi.x <= x0 || b.lo.x >= x1 || b.hi.y <= y0 || b.lo.y >= y1) return 0.0;
  if (b.lo.x >= x0 && b.hi.x <= x1 && b.lo.y >= y0 && b.hi.y <= y1)
    return 0.5 * detail::twice_area(p);
  // clip only against the sides the polygon actually crosses
  Ring r1, r2;
  r1.assign(p);
  Ring* cur = &r1;
  Ring* dst = &r2;
  auto pass = [&](auto side) {
    detail::clip_ring(*cur, *dst, side);
    Ring* t = cur;
    cur = dst;
    dst = t;
  };
  if (b.lo.x < x0) pass([x0](Vec2 q) { return x0 - q.x; });
  if (b.hi.x > x1) pass([x1](Vec2 q) { return q.x - x1; });
  if (b.lo.y < y0) pass([y0](Vec2 q) { return y0 - q.y; });
  if (b.hi.y > y1) pass([y1](Vec2 q) { return q.y - y1; });
  return 0.5 * detail::twice_area(*cur);
}

// ∫|x−o|² dA = (1/12) Σ (p_i × p_{i+1}) (|p_i|² + p_i·p_{i+1} + |p_{i+1}|²), p relative to o
double polar_moment(const Poly& p, Vec2 o) {
  double j = 0.0;
  for (int i = 0, k = p.n - 1; i < p.n; k = i++) {
    const Vec2 a = p.v[k] - o, b = p.v[i] - o;
    j += cross(a, b) * (norm2(a) + dot(a, b) + norm2(b));
  }
  return j / 12.0;
}

// n isosceles triangles of apex angle 2π/n (docs/physics.md §1.1)
double ngon_area(int n, double r) {
  check_ngon(n, "ngon_area");
  return 0.5 * n * r * r * std::sin(2.0 * std::numbers::pi / n);
}

// J = (m r²/6)(1 + 2cos²(π/n)) (docs/physics.md §1.1)
double ngon_inertia(int n, double r, double mass) {
  check_ngon(n, "ngon_inertia");
  const double c = std::cos(std::numbers::pi / n);
  return mass * r * r / 6.0 * (1.0 + 2.0 * c * c);
}

// J = m r²/2 (docs/physics.md §1.1)
double disk_inertia(double r, double mass) { return 0.5 * mass * r * r; }

}  // namespace gs
