// test helper: the clipping overlap of convex polygons as it stood before the branch-free
// rewrite (Sutherland–Hodgman with a per-vertex branch, all in one place, kept verbatim in its
// arithmetic), so that tests can show overlap() still gives the same numbers bit for bit and
// simulation trajectories are unchanged
#pragma once
#include <cstdint>

#include "core/vec.hpp"
#include "geometry/polygon.hpp"

namespace gs::ref {

inline constexpr std::uint8_t kCross = 1;
inline constexpr std::uint8_t kEdgeA = 2;
inline constexpr int kRingCap = 2 * kMaxPolyVerts + 4;

struct TaggedRing {
  int n = 0;
  double x[kRingCap];
  double y[kRingCap];
  std::uint8_t f[kRingCap];

  Vec2 operator[](int i) const { return {x[i], y[i]}; }
  void push(Vec2 p, std::uint8_t flags) {
    if (n > 0 && x[n - 1] == p.x && y[n - 1] == p.y) {
      f[n - 1] = static_cast<std::uint8_t>((f[n - 1] & kCross) | flags);
      return;
    }
    x[n] = p.x;
    y[n] = p.y;
    f[n] = flags;
    ++n;
  }
  void close() {
    if (n > 1 && x[n - 1] == x[0] && y[n - 1] == y[0]) {
      f[0] = static_cast<std::uint8_t>(f[0] | (f[n - 1] & kCross));
      --n;
    }
  }
};

inline bool clip_tagged(const TaggedRing& in, TaggedRing& out, Vec2 o, Vec2 e) {
  const int n = in.n;
  double s[kRingCap];
  double smax = -1.0, smin = 1.0;
  for (int i = 0; i < n; ++i) {
    s[i] = (in.x[i] - o.x) * e.y - (in.y[i] - o.y) * e.x;
    smax = s[i] > smax ? s[i] : smax;
    smin = s[i] < smin ? s[i] : smin;
  }
  out.n = 0;
  if (smax <= 0.0) return false;
  if (smin > 0.0) return true;
  Vec2 p = in[n - 1];
  std::uint8_t fp = in.f[n - 1];
  double sp = s[n - 1];
  for (int i = 0; i < n; ++i) {
    const Vec2 q = in[i];
    const std::uint8_t fq = in.f[i];
    const double sq = s[i];
    const std::uint8_t on_a = fp & kEdgeA;
    const std::uint8_t cross_mark = on_a ? kCross : 0;
    if (sq <= 0.0) {
      if (sp > 0.0) {
        const Vec2 x = sq == 0.0 ? q : p + (q - p) * (sp / (sp - sq));
        out.push(x, static_cast<std::uint8_t>(cross_mark | on_a));
      }
      out.push(q, fq);
    } else if (sp <= 0.0) {
      const Vec2 x = sp == 0.0 ? p : p + (q - p) * (sp / (sp - sq));
      out.push(x, cross_mark);
    }
    p = q;
    fp = fq;
    sp = sq;
  }
  out.close();
  return true;
}

inline Vec2 vertex_mean(const Poly& p) {
  Vec2 m{};
  for (int i = 0; i < p.n; ++i) m += p.v[i];
  return p.n > 0 ? m / static_cast<double>(p.n) : m;
}

inline int facing_edge(const Poly& a, const Poly& b) {
  const Vec2 d = vertex_mean(a) - vertex_mean(b);
  int best = 0;
  double best_score = -1e300;
  for (int k = 0; k < b.n; ++k) {
    const Vec2 e = b.v[k + 1 == b.n ? 0 : k + 1] - b.v[k];
    const double score = e.y * d.x - e.x * d.y;
    if (score > best_score) {
      best_score = score;
      best = k;
    }
  }
  return best;
}

inline const TaggedRing& clip_all(const Poly& a, const Poly& b, TaggedRing& r1, TaggedRing& r2) {
  r1.n = a.n;
  for (int i = 0; i < a.n; ++i) {
    r1.x[i] = a.v[i].x;
    r1.y[i] = a.v[i].y;
    r1.f[i] = kEdgeA;
  }
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

inline double twice_area(const TaggedRing& r) {
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

inline Vec2 ring_centroid(const TaggedRing& r) {
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
  Vec2 m{};
  for (int i = 0; i < r.n; ++i) m += r[i] - o;
  return o + m / static_cast<double>(r.n);
}

inline Overlap finish(const TaggedRing& r) {
  Overlap o;
  if (r.n == 0) return o;
  const double a2 = twice_area(r);
  o.area = a2 > 0.0 ? 0.5 * a2 : 0.0;
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
  o.centroid = ring_centroid(r);
  return o;
}

/// overlap(a, b) as computed before the rewrite
inline Overlap overlap(const Poly& a, const Poly& b) {
  TaggedRing r1, r2;
  return finish(clip_all(a, b, r1, r2));
}

/// intersect(a, b) as computed before the rewrite
inline Poly intersect(const Poly& a, const Poly& b) {
  TaggedRing r1, r2;
  const TaggedRing& r = clip_all(a, b, r1, r2);
  Poly p;
  for (int i = 0; i < r.n; ++i) p.push({r.x[i], r.y[i]});
  return p;
}

}  // namespace gs::ref
