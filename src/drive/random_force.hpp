// the random force (T.2.15–T.2.16, T.2.22–T.2.23): each step every particle gets a momentum kick
// η·Δt, each component of η drawn from N(0, 2D/Δt). Values come from counter-based streams keyed
// by (seed, particle) and counted by the step, so they never depend on thread count or order.
#pragma once
#include <bit>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/rng.hpp"
#include "world/world.hpp"

namespace gs {

/// the stream keys of particles 0…n−1 for `seed` (RngStream(seed, stream of i).key): computed
/// once per run instead of twice per particle and step
std::vector<std::uint64_t> random_force_keys(std::uint64_t seed, std::size_t n);

/// the standard normals of one particle's kick at step `step`, from its stream key: stream
/// (seed, particle), counter a function of the step alone; the ring draws z0 only.
/// t = ZigguratTables::get(), fetched once by the caller
inline void noise_normals(const ZigguratTables& t, std::uint64_t key, std::int64_t step, bool ring,
                          double& z0, double& z1) {
  RngStream r;
  r.key = key;
  r.counter = static_cast<std::uint64_t>(step) << 8;  // 256 values per step: ample for 2 normals
  z0 = r.normal_fast(t);
  z1 = ring ? 0.0 : r.normal_fast(t);
}

/// noise_normals of a block of m ≤ 64 particles (keys[q] → z0[q], and z1[q] off the ring), the
/// same values bit for bit: first every particle's common case in one pass without branches
/// (the ziggurat's first try on the stream's first value, and on its second for z1), so that
/// the particles' draws overlap in the pipeline; then noise_normals itself for the few it
/// rejected
inline void noise_normals_block(const ZigguratTables& t, const std::uint64_t* keys,
                                std::int64_t step, bool ring, std::size_t m, double* z0,
                                double* z1) {
  assert(m <= 64);                                       // one bit of `redo` per particle
  const auto c = static_cast<std::uint64_t>(step) << 8;  // noise_normals' counter
  std::uint64_t redo = 0;                                // bit q: particle q drawn again in full
  for (std::size_t q = 0; q < m; ++q) {
    double a, b = 0.0;
    bool ok = ziggurat_try(t, RngStream::value(keys[q], c + 1), a);
    if (!ring) ok &= ziggurat_try(t, RngStream::value(keys[q], c + 2), b);
    z0[q] = a;
    if (!ring) z1[q] = b;  // (the ring's z1 stays unwritten: zeroing it became a memset)
    redo |= static_cast<std::uint64_t>(!ok) << q;
  }
  for (; redo != 0; redo &= redo - 1) {
    const auto q = static_cast<std::size_t>(std::countr_zero(redo));
    noise_normals(t, keys[q], step, ring, z0[q], z1[q]);
  }
}

// the kicks are applied in Simulation's acceleration pass (sim/simulation.cpp), fused with the
// contact forces and gravity; the ring's symmetrisation η_i → η_i − ⟨η⟩ (T.2.18) is there too

/// subtract the centre-of-mass velocity (2D drift control, every K steps)
void remove_com_velocity(World& w);

}  // namespace gs
