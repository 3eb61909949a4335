// the per-DOF loop shared by the integrators: every channel's particles in one parallel region
#pragma once
#include <algorithm>
#include <cstddef>
#include <span>

#include "core/parallel.hpp"
#include "integrate/integrator.hpp"

namespace gs {

/// body(c, b, e) for every channel c over particles [b, e) ∩ [0, size of c): all channels in
/// one parallel region from `threshold` particles on (one fork and join per pass, not one per
/// channel), each thread on the same particles in every channel and every step
template <class Body>
void for_channels(std::span<const Channel> ch, std::size_t threshold, Body&& body) {
  std::size_t nmax = 0;
  for (const Channel& k : ch) nmax = std::max(nmax, k.q.size());
  parallel_ranges(nmax, threshold, [&](std::size_t b, std::size_t e) {
    for (std::size_t c = 0; c < ch.size(); ++c) {
      const std::size_t n = ch[c].q.size();
      body(c, std::min(b, n), std::min(e, n));
    }
  });
}

/// the predictors' blocks for predict_then: 512 particles, whose q, v and a of two channels
/// (24 kB) stay in the L1 cache for the caller's check of the new positions
inline constexpr std::size_t kPredictBlock = 512;

/// for_channels in blocks of `block` particles (0: each thread's whole range), with after(b, e)
/// once every channel of a block [b, e) is done, by the thread that did it, while the block's
/// values are still in its cache. The blocks cover [0, the longest channel) once; each DOF
/// sees the same arithmetic as in for_channels
template <class Body>
void for_channels_then(std::span<const Channel> ch, std::size_t threshold, std::size_t block,
                       Body&& body, const RangeFn& after) {
  std::size_t nmax = 0;
  for (const Channel& k : ch) nmax = std::max(nmax, k.q.size());
  parallel_ranges(nmax, threshold, [&](std::size_t b, std::size_t e) {
    for (std::size_t k0 = b; k0 < e;) {
      const std::size_t k1 = block == 0 || e - k0 <= block ? e : k0 + block;
      for (std::size_t c = 0; c < ch.size(); ++c) {
        const std::size_t n = ch[c].q.size();
        body(c, std::min(k0, n), std::min(k1, n));
      }
      after(k0, k1);
      k0 = k1;
    }
  });
}

}  // namespace gs
