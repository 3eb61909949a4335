// private helpers of the geometry module: a working vertex ring without zero-initialisation,
// shoelace sums, and one Sutherland–Hodgman half-plane clip shared by clip_half_plane and
// area_in_rect (overlap.cpp has a variant that also tracks boundary crossings)
#pragma once
#include "core/vec.hpp"
#include "geometry/polygon.hpp"

namespace gs::detail {

/// a polygon under clipping: plain coordinate arrays (left uninitialised, so a ring on the
/// stack costs nothing to create in the hot loop)
template <int Cap>
struct Ring {
  int n = 0;
  double x[Cap];  ///< vertex abscissae, m
  double y[Cap];  ///< vertex ordinates, m

  Vec2 operator[](int i) const { return {x[i], y[i]}; }
  void push(Vec2 p) {
    x[n] = p.x;
    y[n] = p.y;
    ++n;
  }
  void assign(const Poly& p) {
    n = p.n;
    for (int i = 0; i < p.n; ++i) {
      x[i] = p.v[i].x;
      y[i] = p.v[i].y;
    }
  }
  Poly to_poly() const {
    Poly p;
    for (int i = 0; i < n; ++i) p.push({x[i], y[i]});
    return p;
  }
};

/// twice the signed area of a ring, summed relative to vertex 0 so that polygons far from the
/// origin keep their relative precision
template <class R>
double twice_area(const R& r) {
  if (r.n < 3) return 0.0;
  const Vec2 o = r[0];
  double a2 = 0.0;
  Vec2 p = r[1] - o;
  for (int i = 2; i < r.n; ++i) {
    const Vec2 q = r[i] - o;
    a2 += cross(p, q);
    p = q;
  }
  return a2;
}

/// area centroid of a ring (fan of triangles from vertex 0); falls back to the vertex mean
/// when the area vanishes so that degenerate rings never give NaN
template <class R>
Vec2 ring_centroid(const R& r) {
  if (r.n <= 0) return {};
  const Vec2 o = r[0];
  double a2 = 0.0;
  Vec2 s{};
  if (r.n >= 3) {
    Vec2 p = r[1] - o;
    for (int i = 2; i < r.n; ++i) {
      const Vec2 q = r[i] - o;
      const double c = cross(p, q);
      a2 += c;
      s += (p + q) * c;
      p = q;
    }
  }
  if (a2 != 0.0) return o + s / (3.0 * a2);
  // degenerate: the mean of the vertices
  Vec2 m{};
  for (int i = 0; i < r.n; ++i) m += r[i] - o;
  return o + m / static_cast<double>(r.n);
}

/// clip ring `in` to the side side(x) <= 0 (points on the line are kept) into `out`.
/// A crossing point is interpolated only between vertices of opposite status, so the
/// denominator never vanishes; when the inside vertex lies exactly on the line it is reused
/// instead of an interpolated copy.
template <class R, class Side>
void clip_ring(const R& in, R& out, Side side) {
  out.n = 0;
  const int n = in.n;
  if (n == 0) return;
  Vec2 p = in[n - 1];
  double sp = side(p);
  for (int i = 0; i < n; ++i) {
    const Vec2 q = in[i];
    const double sq = side(q);
    if (sq <= 0.0) {
      // q inside: the entering crossing first when p was outside
      if (sp > 0.0 && sq != 0.0) out.push(p + (q - p) * (sp / (sp - sq)));
      out.push(q);
    } else if (sp < 0.0) {
      // leaving (when p lay on the line it was written already and is the crossing)
      out.push(p + (q - p) * (sp / (sp - sq)));
    }
    p = q;
    sp = sq;
  }
}

}  // namespace gs::detail
