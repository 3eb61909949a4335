// private to the geometry module: the working ring of the polygon overlap (vertices with
// crossing and edge flags), its Sutherland–Hodgman clip and its finish, shared by the general
// routine (overlap.cpp) and the prepared one of the contact hot loop (overlap_prepared.cpp)
#pragma once
#include <cstdint>

#include "geometry/clip.hpp"
#include "geometry/polygon.hpp"

namespace gs::detail {

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
inline bool clip_tagged(int n, const double* x, const double* y, const std::uint8_t* f,
                 TaggedRing& out, Vec2 o, Vec2 e) {
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

inline bool clip_tagged(const TaggedRing& in, TaggedRing& out, Vec2 o, Vec2 e) {
  return clip_tagged<false>(in.n, in.x, in.y, in.f, out, o, e);
}

/// area, crossings and (when asked for, or when there is no contact line) centroid of a
/// clipped ring
Overlap finish_ring(const TaggedRing& r, bool want_centroid);

}  // namespace gs::detail
