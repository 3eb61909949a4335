// prepared convex polygons: per-polygon quantities computed once, by the same expressions
// overlap(Poly, Poly) uses, so that the prepared overlap reproduces it bit for bit
#include "geometry/prepared.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace gs {

void PolyStore::resize(std::size_t count, int max_n) {
  // unchanged: nothing written (the hot loop calls this every step; a serial pass over n_
  // would pull every thread's lines to the calling thread)
  const std::size_t stride = static_cast<std::size_t>(std::max(max_n, 0)) + 1;
  if (count == n_.size() && stride == stride_) return;
  stride_ = stride;
  data_.resize(count * 2 * stride_);
  n_.assign(count, 0);
  meta_.resize(count);
}

bool is_regular(int n, const double* x, const double* y) {
  if (n < 3) return false;
  // every edge as long as edge 0, every turn (cross product of consecutive edges over the
  // squared length: the sine of the exterior angle) as turn 0, and that turn positive
  double l0 = 0.0, t0 = 0.0;
  for (int k = 0; k < n; ++k) {
    const int k1 = k + 1 == n ? 0 : k + 1, k2 = k1 + 1 == n ? 0 : k1 + 1;
    const Vec2 e{x[k1] - x[k], y[k1] - y[k]}, f{x[k2] - x[k1], y[k2] - y[k1]};
    const double l = norm(e), t = cross(e, f) / (l * norm(f));
    if (k == 0) {
      l0 = l;
      t0 = t;
      if (!(l0 > 0.0) || !(t0 > 1e-6)) return false;
    } else if (!(std::abs(l - l0) <= 1e-9 * l0) || !(std::abs(t - t0) <= 1e-9)) {
      return false;
    }
  }
  return true;
}

// PolyRef::near of a regular polygon: a point x within distance q of edge k's midpoint M has,
// against edge j (outward unit normal n_j, apothem ρ about the vertex mean m), the signed
// distance n_j·(x − m) − ρ ≤ n_j·(M − m) + q − ρ = ρ·(cos Δ − 1) + q, Δ the angle between
// the normals: ≥ 2·(2π/n) for every edge but k and its neighbours. So q < ρ·(1 − cos(4π/n))
// keeps x strictly inside those lines (L1 distances bound L2 ones); rounded down by 1e-6 for
// the polygon's own rounding. Polygons under 5 sides: 0 (every edge is k or a neighbour).
double near_bound(int n, const double* x, const double* y) {
  if (n < 5) return 0.0;
  double mx = 0.0, my = 0.0;
  for (int k = 0; k < n; ++k) {
    mx += x[k];
    my += y[k];
  }
  mx /= n;
  my /= n;
  double rho = 1e300;  // the smallest apothem
  for (int k = 0; k < n; ++k) {
    const int k1 = k + 1 == n ? 0 : k + 1;
    rho = std::min(rho, std::hypot(0.5 * (x[k] + x[k1]) - mx, 0.5 * (y[k] + y[k1]) - my));
  }
  const double pi = 3.14159265358979323846;
  return rho * (1.0 - std::cos(4.0 * pi / n)) * (1.0 - 1e-6);
}

BodyExtent body_extent(const Poly& body) {
  double r2 = 0.0, l2 = 0.0;
  double x[kMaxPolyVerts] = {}, y[kMaxPolyVerts] = {};
  for (int k = 0; k < body.n; ++k) {
    r2 = std::max(r2, norm2(body.v[k]));
    l2 = std::max(l2, norm2(body.v[k + 1 == body.n ? 0 : k + 1] - body.v[k]));
    x[k] = body.v[k].x;
    y[k] = body.v[k].y;
  }
  return {std::sqrt(r2), std::sqrt(l2), is_regular(body.n, x, y) ? near_bound(body.n, x, y) : 0.0};
}

// c + rotate(v, cos θ, sin θ), as place(); edges and mean as finish(), in straight loops over
// the vertex arrays. The bounds come from the body's extent, not from the placed vertices
// (which would need a second pass waiting for the mean):
//  - radius: the rotated offset w_k = fl(rotate(v_k)) has |w_k| ≤ |v_k|·(1 + 5·2⁻⁵³); the vertex
//    fl(c + w_k) lies within |w_k| + 2⁻⁵³·|c + w_k|₁ of c, and c within |m − c|₁ of the mean m:
//      max|vertex − m| ≤ (reach + |m.x − c.x| + |m.y − c.y|)·(1 + 1e-12) + 1e-15·(|c.x| + |c.y|)
//    with a wide allowance for the rounding of these sums (the last term covers placements far
//    from the origin, where the rounding of c + w_k is larger than the body's own);
//  - longest edge: an edge differs from the rotated body edge by the rounding of the rotation
//    (relative 1e-15) and of the two vertices (2⁻⁵³·|c + w|₁ each), hence
//      len ≤ (len_body + 1e-15·(|c.x| + |c.y| + 2·reach))·(1 + 1e-12).
void PolyStore::set_placed(std::size_t i, const Poly& body, const BodyExtent& ext, Vec2 c,
                           double theta) {
  assert(static_cast<std::size_t>(body.n) < stride_);
  const int n = body.n;
  const double cs = std::cos(theta), sn = std::sin(theta);
  double* __restrict const x = data_.data() + i * 2 * stride_;
  double* __restrict const y = x + stride_;
  n_[i] = n;
  if (n == 0) {
    meta_[i] = {};
    return;
  }
  // one pass: each vertex and the running sums of the mean (in vertex order from zero, as
  // vertex_mean), then vertex 0 again
  double x0 = c.x + (cs * body.v[0].x - sn * body.v[0].y);
  double y0 = c.y + (sn * body.v[0].x + cs * body.v[0].y);
  double mx = 0.0 + x0, my = 0.0 + y0;
  x[0] = x0;
  y[0] = y0;
  for (int k = 1; k < n; ++k) {
    const double bx = body.v[k].x, by = body.v[k].y;
    const double qx = c.x + (cs * bx - sn * by), qy = c.y + (sn * bx + cs * by);
    x[k] = qx;
    y[k] = qy;
    mx += qx;
    my += qy;
  }
  x[n] = x0;
  y[n] = y0;
  const Vec2 m{mx / static_cast<double>(n), my / static_cast<double>(n)};
  const double c1 = std::abs(c.x) + std::abs(c.y);
  const double r =
      (ext.reach + std::abs(m.x - c.x) + std::abs(m.y - c.y)) * (1.0 + 1e-12) + 1e-15 * c1;
  const double len = (ext.len + 1e-15 * (c1 + 2.0 * ext.reach)) * (1.0 + 1e-12);
  // near: less the placement's rounding, ~1e-16 of |c|₁ + reach (bodies placed over 10⁶ of
  // their sizes from the origin get no bound)
  const double near = c1 <= 1e6 * ext.reach ? ext.near - 1e-14 * (c1 + ext.reach) : 0.0;
  meta_[i] = {m, r, len, near};
}

void PolyStore::set(std::size_t i, const Poly& p) {
  assert(static_cast<std::size_t>(p.n) < stride_);
  double* x = data_.data() + i * 2 * stride_;
  double* y = x + stride_;
  for (int k = 0; k < p.n; ++k) {
    x[k] = p.v[k].x;
    y[k] = p.v[k].y;
  }
  n_[i] = p.n;
  finish(i);
}

// vertex 0 repeated after the last, and the vertex mean (as vertex_mean: summed from zero in
// vertex order, then divided by n); l2: the longest edge² (edges v[k+1] − v[k], as clip_all)
Vec2 PolyStore::edges(std::size_t i, double& l2) {
  const int n = n_[i];
  double* x = data_.data() + i * 2 * stride_;
  double* y = x + stride_;
  x[n] = n > 0 ? x[0] : 0.0;
  y[n] = n > 0 ? y[0] : 0.0;
  Vec2 m{};
  l2 = 0.0;
  for (int k = 0; k < n; ++k) {
    const double ex = x[k + 1] - x[k], ey = y[k + 1] - y[k];
    l2 = std::max(l2, ex * ex + ey * ey);
    m += Vec2{x[k], y[k]};
  }
  if (n > 0) m = m / static_cast<double>(n);
  return m;
}

// edges and mean, then the largest distance of a vertex from the mean
void PolyStore::finish(std::size_t i) {
  double l2 = 0.0;
  const Vec2 m = edges(i, l2);
  const double* x = data_.data() + i * 2 * stride_;
  const double* y = x + stride_;
  double r2 = 0.0;
  for (int k = 0; k < n_[i]; ++k) r2 = std::max(r2, norm2(Vec2{x[k], y[k]} - m));
  // rounded up: the circle must hold every vertex despite the rounding of these sums
  meta_[i] = {m, std::sqrt(r2) * (1.0 + 1e-12), std::sqrt(l2) * (1.0 + 1e-12),
              is_regular(n_[i], x, y) ? near_bound(n_[i], x, y) : 0.0};
}

Poly PolyStore::poly(std::size_t i) const {
  const PolyRef r = ref(i);
  Poly p;
  for (int k = 0; k < r.n; ++k) p.push({r.x[k], r.y[k]});
  return p;
}

}  // namespace gs
