#include "drive/random_force.hpp"

#include <cmath>

#include "core/rng.hpp"

namespace gs {

namespace {
// stream id of particle i
constexpr std::uint64_t kNoiseStream = 0x6e6f697365ULL;
}  // namespace

std::vector<std::uint64_t> random_force_keys(std::uint64_t seed, std::size_t n) {
  std::vector<std::uint64_t> k(n);
  for (std::size_t i = 0; i < n; ++i) k[i] = RngStream(seed, kNoiseStream + i).key;
  return k;
}

void remove_com_velocity(World& w) {
  double px = 0, py = 0, m = 0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    px += w.mass[i] * w.s.vx[i];
    py += w.mass[i] * w.s.vy[i];
    m += w.mass[i];
  }
  if (m <= 0) return;
  px /= m;
  py /= m;
  for (std::size_t i = 0; i < w.size(); ++i) {
    w.s.vx[i] -= px;
    w.s.vy[i] -= py;
  }
}

}  // namespace gs
