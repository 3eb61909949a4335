// test helpers: random convex polygons (convex hulls of random points), deterministic
#pragma once
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/rng.hpp"
#include "geometry/polygon.hpp"

namespace gs::test {

/// convex hull (Andrew's monotone chain), counter-clockwise, collinear points dropped
inline Poly convex_hull(std::vector<Vec2> pts) {
  std::sort(pts.begin(), pts.end(),
            [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  const int n = static_cast<int>(pts.size());
  std::vector<Vec2> h(2 * n);
  int k = 0;
  // lower hull, then upper hull
  for (int i = 0; i < n; ++i) {
    while (k >= 2 && cross(h[k - 1] - h[k - 2], pts[i] - h[k - 2]) <= 0.0) --k;
    h[k++] = pts[i];
  }
  for (int i = n - 2, t = k + 1; i >= 0; --i) {
    while (k >= t && cross(h[k - 1] - h[k - 2], pts[i] - h[k - 2]) <= 0.0) --k;
    h[k++] = pts[i];
  }
  Poly p;
  for (int i = 0; i < k - 1; ++i) p.push(h[i]);
  return p;
}

/// a random convex polygon: the hull of `npts` points uniform in a disk of radius r around c
/// (at least a triangle)
inline Poly random_convex(RngStream& rng, Vec2 c, double r, int npts) {
  for (;;) {
    std::vector<Vec2> pts;
    for (int i = 0; i < npts; ++i) {
      const double rho = r * std::sqrt(rng.uniform());
      const double a = rng.uniform(0.0, 2.0 * std::numbers::pi);
      pts.push_back({c.x + rho * std::cos(a), c.y + rho * std::sin(a)});
    }
    Poly p = convex_hull(pts);
    if (p.n >= 3) return p;
  }
}

/// distance from x to the boundary of polygon p
inline double boundary_distance(const Poly& p, Vec2 x) {
  double best = 1e300;
  for (int i = 0, j = p.n - 1; i < p.n; j = i++) {
    const Vec2 a = p.v[j], e = p.v[i] - p.v[j];
    const double t = std::clamp(dot(x - a, e) / norm2(e), 0.0, 1.0);
    best = std::min(best, norm(x - (a + e * t)));
  }
  return best;
}

}  // namespace gs::test
