// private to the geometry module: the short loops of the prepared overlap over a polygon's
// vertices or edges, two (SSE2) or four (AVX) at a time. Every lane does the scalar loop's
// IEEE operations in the same order (no fused multiply-add: the build is ISO C++, where GCC
// does not contract), so the values, and the decisions taken on them, are bitwise those of the
// plain loops they replace (the scalar versions below, used where neither is available).
#pragma once
#include <cmath>
#include <cstdint>

#include "core/vec.hpp"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace gs::detail {

/// side values of points i < n against the line through o along e (clip_tagged's expression,
/// > 0 outside): s[i] = (x[i] − o.x)·e.y − (y[i] − o.y)·e.x, with the bit masks of s < 0
/// (`neg`) and s > 0 (`pos`); a NaN or exact zero is in neither
inline void side_values(int n, const double* x, const double* y, Vec2 o, Vec2 e, double* s,
                        std::uint64_t& neg, std::uint64_t& pos) {
  std::uint64_t mn = 0, mp = 0;
  int i = 0;
#if defined(__AVX__)
  {
    const __m256d ox = _mm256_set1_pd(o.x), oy = _mm256_set1_pd(o.y);
    const __m256d ex = _mm256_set1_pd(e.x), ey = _mm256_set1_pd(e.y), z = _mm256_setzero_pd();
    for (; i + 4 <= n; i += 4) {
      const __m256d v = _mm256_sub_pd(_mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(x + i), ox), ey),
                                      _mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(y + i), oy), ex));
      _mm256_storeu_pd(s + i, v);
      mn |= static_cast<std::uint64_t>(_mm256_movemask_pd(_mm256_cmp_pd(v, z, _CMP_LT_OQ))) << i;
      mp |= static_cast<std::uint64_t>(_mm256_movemask_pd(_mm256_cmp_pd(v, z, _CMP_GT_OQ))) << i;
    }
  }
#endif
#if defined(__SSE2__)
  {
    const __m128d ox = _mm_set1_pd(o.x), oy = _mm_set1_pd(o.y);
    const __m128d ex = _mm_set1_pd(e.x), ey = _mm_set1_pd(e.y), z = _mm_setzero_pd();
    for (; i + 2 <= n; i += 2) {
      const __m128d v = _mm_sub_pd(_mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(x + i), ox), ey),
                                   _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(y + i), oy), ex));
      _mm_storeu_pd(s + i, v);
      mn |= static_cast<std::uint64_t>(_mm_movemask_pd(_mm_cmplt_pd(v, z))) << i;
      mp |= static_cast<std::uint64_t>(_mm_movemask_pd(_mm_cmpgt_pd(v, z))) << i;
    }
  }
#endif
  for (; i < n; ++i) {
    s[i] = (x[i] - o.x) * e.y - (y[i] - o.y) * e.x;
    mn |= static_cast<std::uint64_t>(s[i] < 0.0) << i;
    mp |= static_cast<std::uint64_t>(s[i] > 0.0) << i;
  }
  neg = mn;
  pos = mp;
}

/// is any point i < n strictly outside the line through o along e (side value > 0)?
inline bool any_outside(int n, const double* x, const double* y, Vec2 o, Vec2 e) {
  double s[64];
  std::uint64_t neg, pos;
  int i = 0;
  // in blocks of 64 (rings never hold more; the loop is for completeness)
  for (; i < n; i += 64) {
    side_values(n - i < 64 ? n - i : 64, x + i, y + i, o, e, s, neg, pos);
    if (pos != 0) return true;
  }
  return false;
}

/// the edge k < n of a polygon (edge vectors ex, ey) whose outward normal (ey, −ex) points most
/// along d: the first k maximising ey[k]·d.x − ex[k]·d.y, as a loop keeping the first strict
/// maximum above −1e300 does (NaN scores never win; none above −1e300: edge 0)
inline int facing_edge(int n, const double* ex, const double* ey, Vec2 d) {
  double s[64];
  int k = 0;
  bool nan = false;
  double best = -1e300;
#if defined(__SSE2__)
  {
    const __m128d dx = _mm_set1_pd(d.x), dy = _mm_set1_pd(d.y);
    __m128d mx = _mm_set1_pd(-1e300);
    __m128d un = _mm_setzero_pd();
    for (; k + 2 <= n && k + 2 <= 64; k += 2) {
      const __m128d v = _mm_sub_pd(_mm_mul_pd(_mm_loadu_pd(ey + k), dx),
                                   _mm_mul_pd(_mm_loadu_pd(ex + k), dy));
      _mm_storeu_pd(s + k, v);
      mx = _mm_max_pd(v, mx);  // NaN lanes keep mx (and are flagged below)
      un = _mm_or_pd(un, _mm_cmpunord_pd(v, v));
    }
    nan = _mm_movemask_pd(un) != 0;
    best = std::max(_mm_cvtsd_f64(mx), _mm_cvtsd_f64(_mm_unpackhi_pd(mx, mx)));
  }
#endif
  for (; k < n && k < 64; ++k) {
    s[k] = ey[k] * d.x - ex[k] * d.y;
    nan |= std::isnan(s[k]);
    best = s[k] > best ? s[k] : best;
  }
  if (nan || n > 64) {
    // the plain loop, for the rare scores it does not order like a maximum
    int kb = 0;
    double b = -1e300;
    for (int j = 0; j < n; ++j) {
      const double v = ey[j] * d.x - ex[j] * d.y;
      if (v > b) {
        b = v;
        kb = j;
      }
    }
    return kb;
  }
  if (!(best > -1e300)) return 0;
  for (int j = 0;; ++j)
    if (s[j] == best) return j;
}

/// the edges k < n (vertices bx, by; edge vectors ex, ey) whose line may cut a box of centre
/// (cx, cy) and half-widths hx, hy: bit k set unless s_k(c) + |ey|·hx + |ex|·hy + margin < 0,
/// with s_k(c) = (cx − bx)·ey − (cy − by)·ex (NaN: set)
inline std::uint64_t may_cut_mask(int n, const double* bx, const double* by, const double* ex,
                                  const double* ey, double cx, double cy, double hx, double hy,
                                  double margin) {
  std::uint64_t m = 0;
  int k = 0;
#if defined(__SSE2__)
  {
    const __m128d vcx = _mm_set1_pd(cx), vcy = _mm_set1_pd(cy), vhx = _mm_set1_pd(hx);
    const __m128d vhy = _mm_set1_pd(hy), vm = _mm_set1_pd(margin), z = _mm_setzero_pd();
    const __m128d sign = _mm_set1_pd(-0.0);
    for (; k + 2 <= n; k += 2) {
      const __m128d vex = _mm_loadu_pd(ex + k), vey = _mm_loadu_pd(ey + k);
      const __m128d reach = _mm_add_pd(
          _mm_add_pd(_mm_mul_pd(_mm_andnot_pd(sign, vey), vhx), _mm_mul_pd(_mm_andnot_pd(sign, vex), vhy)),
          vm);
      const __m128d sc = _mm_sub_pd(_mm_mul_pd(_mm_sub_pd(vcx, _mm_loadu_pd(bx + k)), vey),
                                    _mm_mul_pd(_mm_sub_pd(vcy, _mm_loadu_pd(by + k)), vex));
      // !(sc + reach < 0): "not less than", true for NaN
      m |= static_cast<std::uint64_t>(_mm_movemask_pd(_mm_cmpnlt_pd(_mm_add_pd(sc, reach), z))) << k;
    }
  }
#endif
  for (; k < n; ++k) {
    const double reach = std::abs(ey[k]) * hx + std::abs(ex[k]) * hy + margin;
    const double sc = (cx - bx[k]) * ey[k] - (cy - by[k]) * ex[k];
    m |= static_cast<std::uint64_t>(!(sc + reach < 0.0)) << k;
  }
  return m;
}

}  // namespace gs::detail
