#include "drive/random_force.hpp"

#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"
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
  std::vector<double> kick(ring ? n : 0);
  for (std::size_t i = 0; i < n; ++i) {
    double z0, z1;
    noise_normals(keys[i], step, ring, z0, z1);
    const double ex = sigma * z0 * w.inv_mass[i];
    ax[i] += ex;
    if (ring) {
      kick[i] = ex;
    } else {
      ay[i] += sigma * z1 * w.inv_mass[i];
    }
  }
  if (ring) symmetrise_ring_kicks(w, kick, ax);
}

// η_i → η_i − ⟨η⟩: the mean momentum kick over fixed blocks (one block: the plain sum)
void symmetrise_ring_kicks(const World& w, const std::vector<double>& kick,
                           std::vector<double>& ax) {
  const std::size_t n = w.size();
  if (n == 0) return;
  const std::size_t nb = (n + kSumBlock - 1) / kSumBlock;
  std::vector<double> part(nb, 0.0);
  parallel_chunks(nb, 2, 1, [&](std::size_t b0, std::size_t b1) {
    for (std::size_t b = b0; b < b1; ++b) {
      const std::size_t i1 = std::min(n, (b + 1) * kSumBlock);
      double m = 0.0;
      for (std::size_t i = b * kSumBlock; i < i1; ++i) m += kick[i] * w.mass[i];
      part[b] = m;
    }
  });
  double mean = 0.0;
  for (double m : part) mean += m;
  mean /= static_cast<double>(n);
  parallel_ranges(n, kParallelMinCheap, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) ax[i] -= mean * w.inv_mass[i];
  });
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
