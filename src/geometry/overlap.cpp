// overlap of two convex polygons (docs/physics.md §2.1): Sutherland–Hodgman clipping of a by the
// edge lines of b, tracking which vertices of the result lie on both boundaries (the crossings)
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <utility>

#include "geometry/clip.hpp"
#include "geometry/polygon.hpp"
#include "geometry/prepared.hpp"

namespace gs {

namespace {

// vertex flags of the working ring
constexpr std::uint8_t kCross = 1;  // the vertex lies on the boundary of a and of b
constexpr std::uint8_t kEdgeA = 2;  // the edge from this vertex to the next lies on a's boundary

static_assert(kMaxPolyVerts < 64, "overlap(PolyRef, PolyRef) keeps one bit per edge");

// clipping a by k lines adds at most k vertices
constexpr int kRingCap = 2 * kMaxPolyVerts + 4;

/// a polygon under clipping, with per-vertex flags
struct TaggedRing : detail::Ring<kRingCap> {
  std::uint8_t f[kRingCap];  ///< kCross | kEdgeA per vertex

  // close the ring: a last vertex repeating the first folds into it
  void close() {
    if (n > 1 && x[n - 1] == x[0] && y[n - 1] == y[0]) {
      f[0] = static_cast<std::uint8_t>(f[0] | (f[n - 1] & kCross));
      --n;
    }
  }
};

// clip the ring (x, y, flags f; kFresh: a's own vertices, every edge on a's boundary, f unused)
// to the inside of b's edge from o along e (left of the edge, line included), into `out`.
// A new vertex on an edge of a's boundary is a crossing; the edge that follows an exit runs
// along b's edge line and so is not on a's boundary. Returns false, leaving `out` untouched,
// when the line cuts nothing off (the common case once a has been cut down to a small cap).
// a's vertices are read in place, with no copy into a ring.
template <bool kFresh>
bool clip_tagged(int n, const double* x, const double* y, const std::uint8_t* f, TaggedRing& out,
                 Vec2 o, Vec2 e) {
  if (n == 0) return false;
  // side of vertex i (> 0 outside; NaN counts as neither inside nor outside)
  auto side = [&](int i) { return (x[i] - o.x) * e.y - (y[i] - o.y) * e.x; };
  auto flags = [&](int i) -> unsigned { return kFresh ? kEdgeA : f[i]; };
  int m = 0;  // vertices written
  // append, merging an exact repeat of the previous vertex: crossing marks add up and the
  // outgoing-edge mark is the newer one (the zero-length edge between them disappears)
  auto push = [&](double px, double py, unsigned fl) {
    if (m > 0 && out.x[m - 1] == px && out.y[m - 1] == py) {
      out.f[m - 1] = static_cast<std::uint8_t>((out.f[m - 1] & kCross) | fl);
      return;
    }
    out.x[m] = px;
    out.y[m] = py;
    out.f[m] = static_cast<std::uint8_t>(fl);
    ++m;
  };
  // sides first: a clip that cuts nothing (most in the general routine) ends here
  double s[kRingCap];
  bool cut = false;
  for (int i = 0; i < n; ++i) {
    s[i] = side(i);
    cut |= s[i] > 0.0;
  }
  if (!cut) return false;
  // Sutherland–Hodgman pass over the edges p → q
  double px = x[n - 1], py = y[n - 1];
  double sp = s[n - 1];
  unsigned fp = flags(n - 1);
  for (int i = 0; i < n; ++i) {
    const double qx = x[i], qy = y[i];
    const double sq = s[i];
    const unsigned fq = flags(i);
    const unsigned on_a = fp & kEdgeA;
    const unsigned cross_mark = on_a ? kCross : 0;
    if (sq <= 0.0) {
      // entering: the crossing point (q itself when q lies on the line), then q
      if (sp > 0.0) {
        if (sq == 0.0) {
          push(qx, qy, cross_mark | on_a);
        } else {
          const double t = sp / (sp - sq);
          push(px + (qx - px) * t, py + (qy - py) * t, cross_mark | on_a);
        }
      }
      push(qx, qy, fq);
    } else if (sp <= 0.0) {
      // leaving: the crossing point (p itself when p lies on the line)
      if (sp == 0.0) {
        push(px, py, cross_mark);
      } else {
        const double t = sp / (sp - sq);
        push(px + (qx - px) * t, py + (qy - py) * t, cross_mark);
      }
    }
    px = qx;
    py = qy;
    fp = fq;
    sp = sq;
  }
  out.n = m;
  out.close();
  return true;
}

bool clip_tagged(const TaggedRing& in, TaggedRing& out, Vec2 o, Vec2 e) {
  return clip_tagged<false>(in.n, in.x, in.y, in.f, out, o, e);
}

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

// area, crossings and (when asked for, or when there is no contact line) centroid of the
// clipped ring
Overlap finish(const TaggedRing& r, bool want_centroid) {
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

}  // namespace

Poly intersect(const Poly& a, const Poly& b) {
  TaggedRing r1, r2;
  const TaggedRing& r = clip_all(a, b, r1, r2);
  return r.to_poly();
}

Overlap overlap(const Poly& a, const Poly& b) {
  TaggedRing r1, r2;
  return finish(clip_all(a, b, r1, r2), true);
}

// The same clips as clip_all, in the same order, on the same numbers (vertex means, edge
// vectors and side values are computed by identical expressions), so the ring and the result
// are bitwise those of overlap(Poly, Poly). What is skipped is provably a no-op there:
//  - pairs whose bounding circles are apart (every clip sequence then ends empty);
//  - clips by edge lines that leave every vertex of the current ring strictly inside. After the
//    facing edge has cut a down to the cap inside b, the cap lies in a box (centre c, half-widths
//    hx, hy), and the side value of any of its vertices against edge k is at most
//    s_k(c) + |e_k.y|·hx + |e_k.x|·hy; when that is negative by more than a round-off margin,
//    clip_tagged would find no vertex outside and return false. A clip that does cut only
//    shrinks the ring (its new vertices lie on old edges), so the box stays a bound for the rest
//    of the loop.
Overlap overlap(const PolyRef& a, const PolyRef& b) {
  if (a.n < 3 || b.n < 3) return {};
  const Vec2 dc = b.mean - a.mean;
  const double rr = a.radius + b.radius;
  if (norm2(dc) > rr * rr) return {};
  // facing edge of b, as facing_edge(): the first edge of the highest score, chosen without
  // a branch (which way each comparison goes is data: with branches this loop took a fifth of
  // the overlap's time in the settled pile)
  const Vec2 d = a.mean - b.mean;
  int k0 = 0;
  double best_score = -1e300;
  for (int k = 0; k < b.n; ++k) {
    const double score = b.ey(k) * d.x - b.ex(k) * d.y;
    const int take = -static_cast<int>(score > best_score);  // all ones where better
    k0 = (k & take) | (k0 & ~take);
    best_score = std::max(best_score, score);  // the same bits as `better ? score : best`
  }
  // the first clip reads a in place; only when it cuts nothing off does a become the ring
  TaggedRing r1, r2;
  TaggedRing* cur = &r1;
  TaggedRing* nxt = &r2;
  if (!clip_tagged<true>(a.n, a.x, a.y, nullptr, r1, {b.x[k0], b.y[k0]}, {b.ex(k0), b.ey(k0)})) {
    r1.n = a.n;
    for (int i = 0; i < a.n; ++i) {
      r1.x[i] = a.x[i];
      r1.y[i] = a.y[i];
      r1.f[i] = kEdgeA;
    }
  }
  if (cur->n == 0) return {};
  // a box around the cap: centre (cx, cy), half-widths hx, hy (no division or square root on
  // the way from the first clip to the next, which wait for this)
  const int nc = cur->n;
  double x0 = cur->x[0], x1 = x0, y0 = cur->y[0], y1 = y0;
  for (int i = 1; i < nc; ++i) {
    x0 = std::min(x0, cur->x[i]);
    x1 = std::max(x1, cur->x[i]);
    y0 = std::min(y0, cur->y[i]);
    y1 = std::max(y1, cur->y[i]);
  }
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  const double hx = 0.5 * (x1 - x0), hy = 0.5 * (y1 - y0);
  // which of the other edge lines may cut the cap: s_k(c) + |e_k.y|·hx + |e_k.x|·hy ≥ −margin.
  // Round-off of the side values is ~1e-16 of |x − o_k|₁·|e_k|, with |x − o_k|₁ ≤
  // |c − mean_b|₁ + hx + hy + 2·radius_b; that of the centre, the half-widths and the new
  // vertices of later clips ~1e-16 of |c|₁: the margin is wide, also far from the origin.
  const double cl1 = std::abs(cx - b.mean.x) + std::abs(cy - b.mean.y);
  const double slack =  // the margin over |e|, a length (the near test below needs no division)
      1e-9 * (cl1 + 2.0 * b.radius + hx + hy) + 1e-14 * (std::abs(cx) + std::abs(cy));
  const double margin = slack * b.len;
  // as a bit mask, bit j for edge k0 + 1 + j (clip_all's order)
  auto may_cut = [&](int k) -> std::uint64_t {
    const double ex = b.ex(k), ey = b.ey(k);
    const double reach = std::abs(ey) * hx + std::abs(ex) * hy + margin;
    const double sc = (cx - b.x[k]) * ey - (cy - b.y[k]) * ex;
    return !(sc + reach < 0.0);  // NaN: clip
  };
  const int k1 = k0 + 1 == b.n ? 0 : k0 + 1;
  std::uint64_t cut = 0;
  // a regular b and a cap near the facing edge's midpoint (PolyRef::near): only the two
  // neighbouring edge lines can cut it (the margin as a length, that of the side values over
  // |e|, to round-off; the bound's own 10⁻⁶ slack is far wider still)
  const double mx = 0.5 * (b.x[k0] + b.x[k1]), my = 0.5 * (b.y[k0] + b.y[k1]);
  if (b.near > 0.0 && std::abs(cx - mx) + std::abs(cy - my) + hx + hy + slack < b.near) {
    cut = may_cut(k1) | may_cut(k0 == 0 ? b.n - 1 : k0 - 1) << (b.n - 2);
  } else {
    for (int k = 0; k < b.n; ++k) cut |= may_cut(k) << k;
    cut = (cut >> k1) | (cut << (b.n - k1));     // b.n <= kMaxPolyVerts < 64
    cut &= (std::uint64_t{1} << (b.n - 1)) - 1;  // the n − 1 edges after k0
  }
  while (cut != 0 && cur->n > 0) {
    const int j = std::countr_zero(cut);
    cut &= cut - 1;
    const int k = k1 + j < b.n ? k1 + j : k1 + j - b.n;
    if (clip_tagged(*cur, *nxt, {b.x[k], b.y[k]}, {b.ex(k), b.ey(k)})) std::swap(cur, nxt);
  }
  return finish(*cur, false);
}

}  // namespace gs
