// the overlap of prepared convex polygons (the contact hot loop): the clips of overlap(Poly,
// Poly) on the same numbers, with provably idle work skipped and the common clips done
// without per-vertex branches, so that the result is bitwise that of the general routine
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <utility>

#include "geometry/prepared.hpp"
#include "geometry/side_masks.hpp"
#include "geometry/tagged_ring.hpp"

namespace gs {

namespace {

using detail::kCross;
using detail::kEdgeA;
using detail::kRingCap;
using detail::TaggedRing;
using detail::clip_tagged;

// clip_tagged without its per-vertex branches, for the common case, writing the very ring
// clip_tagged writes (same side values, crossing arithmetic, vertex order and flags): the
// vertices inside b's edge line form one run ia..ib (the ring is convex), entered by the
// crossing on edge ia−1 → ia and left by the one on edge ib → ib+1. Whatever clip_tagged
// treats specially (a vertex on the line or NaN, two runs from round-off, an exact repeat that
// it would merge) is left to it (kGeneral).
enum class Cap { kEmpty, kWhole, kRing, kGeneral };
struct CapRing {
  Cap kind = Cap::kGeneral;
  int c1 = -1, c2 = -1;  ///< ring indices of the entering and leaving crossings, ring order
};
template <bool kFresh>
CapRing run_clip(int n, const double* x, const double* y, const std::uint8_t* f, Vec2 o, Vec2 e,
                 TaggedRing& out) {
  if (n == 0) return {};
  double s[kRingCap];
  std::uint64_t in, pos;
  detail::side_values(n, x, y, o, e, s, in, pos);
  const std::uint64_t full = (std::uint64_t{1} << n) - 1;  // n < 64
  if ((in | pos) != full) return {};                        // a vertex on the line, or NaN
  if (in == 0) return {Cap::kEmpty};
  if (in == full) return {Cap::kWhole};
  const std::uint64_t prev = ((in << 1) | (in >> (n - 1))) & full;  // bit i: vertex i − 1 in
  const std::uint64_t next = ((in >> 1) | (in << (n - 1))) & full;  // bit i: vertex i + 1 in
  const std::uint64_t starts = in & ~prev;
  if ((starts & (starts - 1)) != 0) return {};  // two runs (round-off)
  const int ia = std::countr_zero(starts), ib = std::countr_zero(in & ~next);
  auto flags = [&](int i) -> unsigned { return kFresh ? kEdgeA : f[i]; };
  int m = 0;
  auto put = [&](double px, double py, unsigned fl) [[gnu::always_inline]] {
    out.x[m] = px;
    out.y[m] = py;
    out.f[m] = static_cast<std::uint8_t>(fl);
    ++m;
  };
  // the crossing on edge p → q, as clip_tagged interpolates and marks it
  auto crossing = [&](int p, int q, unsigned fl) [[gnu::always_inline]] {
    const double t = s[p] / (s[p] - s[q]);
    put(x[p] + (x[q] - x[p]) * t, y[p] + (y[q] - y[p]) * t, fl);
  };
  auto run = [&](int from, int to) [[gnu::always_inline]] {
    for (int i = from; i <= to; ++i) put(x[i], y[i], flags(i));
  };
  const int pa = ia == 0 ? n - 1 : ia - 1;
  const unsigned on_a_in = flags(pa) & kEdgeA, on_a_out = flags(ib) & kEdgeA;
  auto enter = [&]() [[gnu::always_inline]] { crossing(pa, ia, (on_a_in ? kCross : 0u) | on_a_in); };
  auto leave = [&]() [[gnu::always_inline]] { crossing(ib, ib + 1 == n ? 0 : ib + 1, on_a_out ? kCross : 0u); };
  // clip_tagged's order: edges p → q for q = 0, 1, …, n − 1
  CapRing r{Cap::kRing};
  if (ia > ib) {  // the run wraps past vertex 0
    run(0, ib);
    r.c2 = m;
    leave();
    r.c1 = m;
    enter();
    run(ia, n - 1);
  } else if (ib == n - 1) {  // the leaving crossing lies on edge n − 1 → 0, visited first
    r.c2 = m;
    leave();
    r.c1 = m;
    enter();
    run(ia, ib);
  } else {
    r.c1 = m;
    enter();
    run(ia, ib);
    r.c2 = m;
    leave();
  }
  out.n = m;
  // exact repeats, which clip_tagged would merge: cyclically the ring reads
  // … v_ib, leaving crossing, entering crossing, v_ia …, and consecutive vertices of the
  // input are distinct (a ring: clip_tagged merged them; a polygon: PolyRef::distinct)
  auto same = [&](int i, int j) { return out.x[i] == out.x[j] && out.y[i] == out.y[j]; };
  const int after_in = r.c1 + 1 == m ? 0 : r.c1 + 1;
  const int before_out = r.c2 == 0 ? m - 1 : r.c2 - 1;
  if (same(r.c1, r.c2) || same(r.c1, after_in) || same(before_out, r.c2)) return {};
  return r;
}

// does any of the edge lines of b in the mask (bit j: edge k1 + j) have a vertex of the ring
// strictly outside? The side values are clip_tagged's, so "no" means that every one of those
// clips would return false.
bool cuts_any(const TaggedRing& r, const PolyRef& b, int k1, std::uint64_t mask) {
  while (mask != 0) {
    const int j = std::countr_zero(mask);
    mask &= mask - 1;
    const int k = k1 + j < b.n ? k1 + j : k1 + j - b.n;
    if (detail::any_outside(r.n, r.x, r.y, {b.x[k], b.y[k]}, {b.ex[k], b.ey[k]})) return true;
  }
  return false;
}

}  // namespace

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
  // facing edge of b, as facing_edge()
  const int k0 = detail::facing_edge(b.n, b.ex, b.ey, a.mean - b.mean);
  // the first clip reads a in place (the common case without clip_tagged's branches); only
  // when it cuts nothing off does a become the ring
  TaggedRing r1, r2;
  TaggedRing* cur = &r1;
  TaggedRing* nxt = &r2;
  const Vec2 o0{b.x[k0], b.y[k0]}, e0{b.ex[k0], b.ey[k0]};
  const CapRing cap =
      a.distinct ? run_clip<true>(a.n, a.x, a.y, nullptr, o0, e0, r1) : CapRing{};
  if (cap.kind == Cap::kEmpty) return {};
  if (cap.kind == Cap::kWhole ||
      (cap.kind == Cap::kGeneral && !clip_tagged<true>(a.n, a.x, a.y, nullptr, r1, o0, e0))) {
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
  const double margin =
      (1e-9 * (cl1 + 2.0 * b.radius + hx + hy) + 1e-14 * (std::abs(cx) + std::abs(cy))) * b.len;
  // as a bit mask, rotated so that bit 0 is the edge after k0 (clip_all's order)
  std::uint64_t cut = detail::may_cut_mask(b.n, b.x, b.y, b.ex, b.ey, cx, cy, hx, hy, margin);
  const int k1 = k0 + 1 == b.n ? 0 : k0 + 1;
  cut = (cut >> k1) | (cut << (b.n - k1));  // b.n <= kMaxPolyVerts < 64
  cut &= (std::uint64_t{1} << (b.n - 1)) - 1;  // the n − 1 edges after k0
  // a cap that no remaining edge line really cuts (the box test is loose where the cap lies
  // along a long edge) needs no more clips: test its vertices exactly as clip_tagged would
  if (cap.kind == Cap::kRing && cut != 0 && !cuts_any(*cur, b, k1, cut)) cut = 0;
  if (cut == 0 && cap.kind == Cap::kRing) {
    // the cap is the intersection: finish() with its two known crossings, in ring order
    Overlap ov;
    const double a2 = detail::twice_area(*cur);
    ov.area = a2 > 0.0 ? 0.5 * a2 : 0.0;
    ov.crossings = 2;
    ov.c1 = (*cur)[std::min(cap.c1, cap.c2)];
    ov.c2 = (*cur)[std::max(cap.c1, cap.c2)];
    return ov;
  }
  while (cut != 0 && cur->n > 0) {
    const int j = std::countr_zero(cut);
    cut &= cut - 1;
    const int k = k1 + j < b.n ? k1 + j : k1 + j - b.n;
    const Vec2 o{b.x[k], b.y[k]}, e{b.ex[k], b.ey[k]};
    const Cap c = a.distinct ? run_clip<false>(cur->n, cur->x, cur->y, cur->f, o, e, *nxt).kind
                             : Cap::kGeneral;
    if (c == Cap::kEmpty) return {};
    if (c == Cap::kRing || (c == Cap::kGeneral && clip_tagged(*cur, *nxt, o, e)))
      std::swap(cur, nxt);
  }
  return detail::finish_ring(*cur, false);
}

}  // namespace gs
