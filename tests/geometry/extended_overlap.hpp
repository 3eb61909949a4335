// test helper: an extended-precision reference for the overlap of convex polygons, the errors
// of overlap(Poly, Poly) (world frame) and overlap(PolyRef, PolyRef) (local frame) against it,
// and the bound both are held to
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geometry/polygon.hpp"
#include "geometry/prepared.hpp"

namespace gs::test {

static_assert(std::numeric_limits<long double>::digits >= 64, "the reference needs long double");

// the reference: Sutherland–Hodgman clipping of a by b's edge lines in long double (64-bit
// significand), every coordinate relative to a's first vertex (exact: the pairs lie within a
// factor two of it), tracking the crossings as the routines do; rounding ~1e-19 of the pair's
// scale, three digits below the routines' own
using LD = long double;
struct RefOverlap {
  LD area = 0, cx = 0, cy = 0;        // area and centroid, relative to the frame
  int crossings = 0;                  // distinct crossings
  LD x1 = 0, y1 = 0, x2 = 0, y2 = 0;  // the pair farthest apart
};
inline RefOverlap reference(const Poly& a, const Poly& b, Vec2 o) {
  struct V {
    LD x, y;
    bool cross, edge_a;  // on both boundaries; the edge to the next vertex lies on a's
  };
  std::vector<V> r, t;
  for (int i = 0; i < a.n; ++i) r.push_back({LD(a.v[i].x) - o.x, LD(a.v[i].y) - o.y, false, true});
  for (int k = 0; k < b.n && !r.empty(); ++k) {
    const Vec2 p0 = b.v[k], p1 = b.v[k + 1 == b.n ? 0 : k + 1];
    const LD bx = LD(p0.x) - o.x, by = LD(p0.y) - o.y;
    const LD ex = LD(p1.x) - p0.x, ey = LD(p1.y) - p0.y;
    auto side = [&](const V& v) { return (v.x - bx) * ey - (v.y - by) * ex; };
    t.clear();
    auto push = [&](V v) {
      if (!t.empty() && t.back().x == v.x && t.back().y == v.y) {
        t.back().cross = t.back().cross || v.cross;
        t.back().edge_a = v.edge_a;
      } else {
        t.push_back(v);
      }
    };
    for (std::size_t i = 0; i < r.size(); ++i) {
      const V& p = r[i == 0 ? r.size() - 1 : i - 1];
      const V& q = r[i];
      const LD sp = side(p), sq = side(q);
      auto at = [&](bool edge_a) {
        const LD u = sp / (sp - sq);
        return V{p.x + (q.x - p.x) * u, p.y + (q.y - p.y) * u, p.edge_a, edge_a};
      };
      if (sq <= 0) {
        if (sp > 0) push(sq == 0 ? V{q.x, q.y, p.edge_a, p.edge_a} : at(p.edge_a));
        push(q);
      } else if (sp <= 0) {
        push(sp == 0 ? V{p.x, p.y, p.edge_a, false} : at(false));
      }
    }
    if (t.size() > 1 && t.back().x == t[0].x && t.back().y == t[0].y) {
      t[0].cross = t[0].cross || t.back().cross;
      t.pop_back();
    }
    r.swap(t);
  }
  RefOverlap f;
  LD a2 = 0, sx = 0, sy = 0;
  for (std::size_t i = 1; i + 1 < r.size(); ++i) {
    const LD px = r[i].x - r[0].x, py = r[i].y - r[0].y;
    const LD qx = r[i + 1].x - r[0].x, qy = r[i + 1].y - r[0].y;
    const LD c = px * qy - py * qx;
    a2 += c;
    sx += (px + qx) * c;
    sy += (py + qy) * c;
  }
  if (a2 > 0) {
    f.area = a2 / 2;
    f.cx = r[0].x + sx / (3 * a2);
    f.cy = r[0].y + sy / (3 * a2);
  }
  std::vector<const V*> xs;
  for (const V& v : r) {
    bool seen = false;
    for (const V* w : xs) seen = seen || (w->x == v.x && w->y == v.y);
    if (v.cross && !seen) xs.push_back(&v);
  }
  f.crossings = static_cast<int>(xs.size());
  LD best = -1;
  for (std::size_t i = 0; i < xs.size(); ++i)
    for (std::size_t j = i + 1; j < xs.size(); ++j) {
      const LD dx = xs[j]->x - xs[i]->x, dy = xs[j]->y - xs[i]->y;
      if (dx * dx + dy * dy > best) {
        best = dx * dx + dy * dy;
        f.x1 = xs[i]->x, f.y1 = xs[i]->y, f.x2 = xs[j]->x, f.y2 = xs[j]->y;
      }
    }
  return f;
}

// errors of one routine's result against the reference, each in units of ε = 2⁻⁵³
struct Errors {
  double area = 0, point = 0, normal = 0, centroid = 0;
};
inline Errors errors(const Overlap& g, const RefOverlap& f, Vec2 o) {
  constexpr double eps = std::numeric_limits<double>::epsilon() / 2;
  Errors e;
  e.area = static_cast<double>(std::abs(LD(g.area) - f.area)) / eps;
  // contact point (midpoint of the contact line) and normal (its perpendicular: the sine of
  // the angle between the lines)
  const LD gx1 = LD(g.c1.x) - o.x, gy1 = LD(g.c1.y) - o.y;
  const LD gx2 = LD(g.c2.x) - o.x, gy2 = LD(g.c2.y) - o.y;
  const LD px = (gx1 + gx2) / 2 - (f.x1 + f.x2) / 2, py = (gy1 + gy2) / 2 - (f.y1 + f.y2) / 2;
  e.point = static_cast<double>(std::sqrt(px * px + py * py)) / eps;
  const LD dx = gx2 - gx1, dy = gy2 - gy1, fx = f.x2 - f.x1, fy = f.y2 - f.y1;
  e.normal = static_cast<double>(std::abs(dx * fy - dy * fx) /
                                 std::sqrt((dx * dx + dy * dy) * (fx * fx + fy * fy))) /
             eps;
  const LD cx = LD(g.centroid.x) - o.x - f.cx, cy = LD(g.centroid.y) - o.y - f.cy;
  e.centroid = static_cast<double>(std::sqrt(cx * cx + cy * cy)) / eps;
  return e;
}

// the error bounds both routines are held to, in units of ε, for a pair of scale D (the sum of
// the bounding boxes' diagonals) at world coordinates up to X, with an overlap of area A and
// contact line ℓ: area c·X·D (the world frame rounds every crossing to ε·X); contact point c·(X +
// D) (the result is rounded to ε·X, the clip's own arithmetic to ε·D); normal c·(X + D)/ℓ; centroid
// c·(X + D)·(1 + D²/A) (a cap's centroid moves with the rounding of its thin side)
struct Scale {
  double X, D, A, l;
};
inline constexpr double kC = 16.0;
inline bool within(const Errors& e, const Scale& s) {
  return e.area <= kC * s.X * s.D && e.centroid <= kC * (s.X + s.D) * (1.0 + s.D * s.D / s.A);
}
// the contact line's crossings are ill-conditioned where an edge meets a clip line at a small
// angle θ (errors grow as 1/sin θ in either routine, and which routine rounds luckier is a
// matter of the pair): per pair only a gross bound (a wrong crossing would be off by ~D); the
// mix's worst cases are compared in test_overlap_mix
inline bool line_within(const Errors& p, const Scale& s) {
  const double L = s.X + s.D;
  return p.point <= 1e4 * L && p.normal <= 1e4 * L / s.l;
}  // one pair checked both ways: the degenerate cases as the world-frame routine (no overlap, no
// contact line) wherever the reference area exceeds the bound, and both routines within it
struct PairCheck {
  std::string failure;  // empty: passed
  Errors world, prepared;
  Scale scale;
  bool line = false;  // a normal contact line (two crossings, not vanishing)
};
inline PairCheck check_pair(const Poly& a, const Poly& b, const PolyRef& pa, const PolyRef& pb) {
  PairCheck c;
  const Vec2 o = a.v[0];
  const RefOverlap f = reference(a, b, o);
  const Overlap g = overlap(a, b);
  const Overlap h = overlap(pa, pb, true);
  double X = 0;
  for (const Poly* r : {&a, &b})
    for (int k = 0; k < r->n; ++k) X = std::max({X, std::abs(r->v[k].x), std::abs(r->v[k].y)});
  const Aabb ba = bounds(a), bb = bounds(b);
  const double D = std::hypot(ba.hi.x - ba.lo.x, ba.hi.y - ba.lo.y) +
                   std::hypot(bb.hi.x - bb.lo.x, bb.hi.y - bb.lo.y);
  const double l = static_cast<double>(std::hypot(f.x2 - f.x1, f.y2 - f.y1));
  c.scale = {X, D, static_cast<double>(f.area), l};
  const bool line_g = g.crossings >= 2 && !(g.c1 == g.c2);
  const bool line_h = h.crossings >= 2 && !(h.c1 == h.c2);
  const double tiny = kC * X * D * std::numeric_limits<double>::epsilon();
  if (!(f.area > tiny)) {
    if (h.area > tiny) c.failure = "prepared: an overlap where the reference has none";
    return c;
  }
  if ((h.area > 0.0) != (g.area > 0.0)) c.failure = "overlap found by one routine only";
  if (line_h != line_g) c.failure = "contact line found by one routine only";
  c.line = line_g && f.crossings == 2 && l > 1e-9 * D;
  c.world = errors(g, f, o);
  c.prepared = errors(h, f, o);
  auto report = [&](const char* who, const Errors& e) {
    return std::string(who) + " beyond the bound: area/(X D) " + std::to_string(e.area / (X * D)) +
           " point/L " + std::to_string(e.point / (X + D)) + " normal l/L " +
           std::to_string(e.normal * l / (X + D)) + " centroid " +
           std::to_string(e.centroid / ((X + D) * (1.0 + D * D / c.scale.A))) + " crossings " +
           std::to_string(f.crossings) + "/" + std::to_string(h.crossings) + " l/D " +
           std::to_string(l / D);
  };
  if (!within(c.world, c.scale)) c.failure = report("world frame", c.world);
  if (!within(c.prepared, c.scale)) c.failure = report("prepared", c.prepared);
  if (c.line && !line_within(c.prepared, c.scale))
    c.failure = report("prepared contact line", c.prepared);
  return c;
}

}  // namespace gs::test
