// overlap of two convex polygons (SPEC 2.1): Sutherland–Hodgman clipping of a by the edge
// lines of b, tracking which vertices of the result lie on both boundaries (the crossings)
#include <cmath>
#include <cstdint>

#include "geometry/clip.hpp"
#include "geometry/polygon.hpp"
#include "geometry/tagged_ring.hpp"

namespace gs {

namespace detail {

// area, crossings and (when asked for, or when there is no contact line) centroid of the
// clipped ring
Overlap finish_ring(const TaggedRing& r, bool want_centroid) {
  Overlap o;
  if (r.n == 0) return o;
  // area of the intersection polygon (degenerate rings: area 0)
  const double a2 = detail::twice_area(r);
  o.area = a2 > 0.0 ? 0.5 * a2 : 0.0;
  // distinct crossing points (indices into the ring)
  int xs[kRingCap];
  int nx = 0;
  for (int i = 0; i < r.n; ++i) {
    if (!(r.f[i] & kCross)) continue;
    bool seen = false;
    for (int k = 0; k < nx && !seen; ++k) seen = r.x[xs[k]] == r.x[i] && r.y[xs[k]] == r.y[i];
    if (!seen) xs[nx++] = i;
  }
  o.crossings = nx;
  if (nx == 1) o.c1 = o.c2 = r[xs[0]];
  if (nx >= 2) {
    // the pair farthest apart (the only pair in a normal contact)
    int bi = 0, bj = 1;
    double best = norm2(r[xs[1]] - r[xs[0]]);
    for (int i = 0; i < nx; ++i)
      for (int j = i + 1; j < nx; ++j) {
        const double d2 = norm2(r[xs[j]] - r[xs[i]]);
        if (d2 > best) {
          best = d2;
          bi = i;
          bj = j;
        }
      }
    o.c1 = r[xs[bi]];
    o.c2 = r[xs[bj]];
  }
  // centroid (degenerate rings: the vertex mean)
  if (want_centroid || nx < 2 || (o.c1.x == o.c2.x && o.c1.y == o.c2.y))
    o.centroid = detail::ring_centroid(r);
  return o;
}

}  // namespace detail

namespace {

using detail::kEdgeA;
using detail::TaggedRing;

// mean of the vertices (a cheap interior point of a convex polygon)
Vec2 vertex_mean(const Poly& p) {
  Vec2 m{};
  for (int i = 0; i < p.n; ++i) m += p.v[i];
  return p.n > 0 ? m / static_cast<double>(p.n) : m;
}

// the edge of b whose outward normal points most towards a: clipping by it first cuts a down
// to the small cap that penetrates b (or to nothing when they are apart), so that the
// remaining clips run on a few vertices only
int facing_edge(const Poly& a, const Poly& b) {
  const Vec2 d = vertex_mean(a) - vertex_mean(b);
  int best = 0;
  double best_score = -1e300;
  for (int k = 0; k < b.n; ++k) {
    const Vec2 e = b.v[k + 1 == b.n ? 0 : k + 1] - b.v[k];
    const double score = e.y * d.x - e.x * d.y;  // outward normal (e.y, −e.x) · d
    if (score > best_score) {
      best_score = score;
      best = k;
    }
  }
  return best;
}

// clip a by every edge line of b, facing edge first; returns the ring holding the result
const TaggedRing& clip_all(const Poly& a, const Poly& b, TaggedRing& r1, TaggedRing& r2) {
  r1.assign(a);
  for (int i = 0; i < a.n; ++i) r1.f[i] = kEdgeA;
  if (a.n < 3 || b.n < 3) {
    r1.n = 0;
    return r1;
  }
  TaggedRing* cur = &r1;
  TaggedRing* nxt = &r2;
  int k = facing_edge(a, b);
  for (int j = 0; j < b.n && cur->n > 0; ++j) {
    const int k1 = k + 1 == b.n ? 0 : k + 1;
    const Vec2 o = b.v[k];
    if (clip_tagged(*cur, *nxt, o, b.v[k1] - o)) {
      TaggedRing* t = cur;
      cur = nxt;
      nxt = t;
    }
    k = k1;
  }
  return *cur;
}

}  // namespace

Poly intersect(const Poly& a, const Poly& b) {
  TaggedRing r1, r2;
  const TaggedRing& r = clip_all(a, b, r1, r2);
  return r.to_poly();
}

Overlap overlap(const Poly& a, const Poly& b) {
  TaggedRing r1, r2;
  return detail::finish_ring(clip_all(a, b, r1, r2), true);
}

}  // namespace gs
