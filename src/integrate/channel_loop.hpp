// the per-DOF loop shared by the integrators: every channel's particles in one parallel region
#pragma once
#include <algorithm>
#include <cstddef>
#include <span>

#include "core/team.hpp"
#include "integrate/integrator.hpp"

namespace gs {

/// body(c, b, e) for every channel c over particles [b, e) ∩ [0, size of c): all channels in
/// one parallel region from `threshold` particles on (one fork and join per pass, not one per
/// channel), each thread on the same particles in every channel: the team's particle split
template <class Body>
void for_channels(const ThreadTeam& team, std::span<const Channel> ch, std::size_t threshold,
                  Body&& body) {
  std::size_t nmax = 0;
  for (const Channel& k : ch) nmax = std::max(nmax, k.q.size());
  parallel_ranges(team, nmax, threshold, [&](std::size_t b, std::size_t e) {
    for (std::size_t c = 0; c < ch.size(); ++c) {
      const std::size_t n = ch[c].q.size();
      body(c, std::min(b, n), std::min(e, n));
    }
  });
}

}  // namespace gs
