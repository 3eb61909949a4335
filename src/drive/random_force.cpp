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

void add_random_force(const World& w, std::uint64_t seed, std::int64_t step, double D, double dt,
                      std::vector<double>& ax, std::vector<double>& ay) {
  add_random_force(w, random_force_keys(seed, w.size()), step, D, dt, ax, ay);
}

void add_random_force(const World& w, const std::vector<std::uint64_t>& keys, std::int64_t step,
                      double D, double dt, std::vector<double>& ax, std::vector<double>& ay) {
  const std::size_t n = w.size();
  const double sigma = std::sqrt(2.0 * D / dt);  // per component (T.2.16)
  const bool ring = w.box == BoxKind::Ring1D;
  double mean = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    // stream (seed, particle); its counter is a function of the step alone
    RngStream r;
    r.key = keys[i];
    r.counter = static_cast<std::uint64_t>(step) << 8;  // 256 values per step: ample for 2 normals
    const double z0 = r.normal_fast();
    const double z1 = ring ? 0.0 : r.normal_fast();
    const double ex = sigma * z0 * w.inv_mass[i];
    ax[i] += ex;
    if (ring) {
      mean += ex * w.mass[i];
    } else {
      ay[i] += sigma * z1 * w.inv_mass[i];
    }
  }
  // 1D: symmetrise the kicks every step, η_i → η_i − ⟨η⟩ (T.2.18)
  if (ring && n > 0) {
    mean /= static_cast<double>(n);
    for (std::size_t i = 0; i < n; ++i) ax[i] -= mean * w.inv_mass[i];
  }
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
