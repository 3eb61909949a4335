// the random force (T.2.15–T.2.16, T.2.22–T.2.23): each step every particle gets a momentum kick
// η·Δt, each component of η drawn from N(0, 2D/Δt). Values come from counter-based streams keyed
// by (seed, particle) and counted by the step, so they never depend on thread count or order.
#pragma once
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
inline void noise_normals(const ZigguratTables& t, std::uint64_t key, std::int64_t step,
                          bool ring, double& z0, double& z1) {
  RngStream r;
  r.key = key;
  r.counter = static_cast<std::uint64_t>(step) << 8;  // 256 values per step: ample for 2 normals
  z0 = r.normal_fast(t);
  z1 = ring ? 0.0 : r.normal_fast(t);
}

// the kicks are applied in Simulation's acceleration pass (sim/simulation.cpp), fused with the
// contact forces and gravity; the ring's symmetrisation η_i → η_i − ⟨η⟩ (T.2.18) is there too

/// subtract the centre-of-mass velocity (2D drift control, every K steps)
void remove_com_velocity(World& w);

}  // namespace gs
