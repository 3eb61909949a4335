// the periodic spatial sort: particles renumbered in cell order, so that the neighbours the
// force loop visits are near in memory. Random forcing mixes a fluid, and a 10⁶-disk system's
// neighbours end up scattered over the arrays, which makes every step slower; LAMMPS sorts its
// atoms every 1000 steps for the same reason.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/permute.hpp"
#include "sim/simulation.hpp"

namespace gs {

std::int64_t resolved_sort_every(const World& w, int sort_every) {
  if (sort_every >= 0) return sort_every;
  const bool eligible = !w.polygons() && w.box != BoxKind::Ring1D;
  return eligible && w.size() >= kAutoSortMinParticles ? kAutoSortEvery : 0;
}

namespace {

// the position of grain i folded into the box (periodic directions) and its cell
std::size_t cell_of(const World& w, std::size_t i, double cell, std::size_t nx, std::size_t ny) {
  auto index = [&](double v, double L, bool periodic, std::size_t n) {
    if (periodic) v -= L * std::floor(v / L);
    const double c = std::floor(v / cell);
    return static_cast<std::size_t>(std::clamp(c, 0.0, static_cast<double>(n - 1)));
  };
  const bool px = w.box != BoxKind::Walls, py = w.box == BoxKind::Periodic;
  return index(w.s.y[i], w.Ly, py, ny) * nx + index(w.s.x[i], w.Lx, px, nx);
}

}  // namespace

void Simulation::sort_particles() {
  if (w_.polygons() || w_.box == BoxKind::Ring1D)
    throw std::logic_error("sort_particles: for 2D disk systems only (scene check missed)");
  const std::size_t n = w_.size();
  if (n == 0) return;
  // cells one largest diameter wide, at most ~4 per particle (a dilute gas needs no finer
  // order); a counting sort keeps the slot order within a cell, so the result depends on the
  // state only
  double cell = 2.0 * w_.max_radius;
  const double area = w_.Lx * w_.Ly;
  if (!(cell > 0.0) || !(area > 0.0)) return;
  cell = std::max(cell, std::sqrt(area / (4.0 * static_cast<double>(n))));
  const auto nx = static_cast<std::size_t>(std::max(1.0, std::floor(w_.Lx / cell)));
  const auto ny = static_cast<std::size_t>(std::max(1.0, std::floor(w_.Ly / cell)));
  SortScratch& sc = sort_scratch_;
  std::vector<std::uint32_t>& start = sc.start;
  std::vector<std::uint32_t>& cell_id = sc.cell;
  start.assign(nx * ny + 1, 0);
  cell_id.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    cell_id[i] = static_cast<std::uint32_t>(cell_of(w_, i, cell, nx, ny));
    ++start[cell_id[i] + 1];
  }
  for (std::size_t c = 0; c < nx * ny; ++c) start[c + 1] += start[c];
  std::vector<std::uint32_t>& perm = sc.perm;  // new → old
  std::vector<std::uint32_t>& slot = sc.slot;  // old → new
  perm.resize(n);
  slot.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t k = start[cell_id[i]]++;
    perm[k] = static_cast<std::uint32_t>(i);
    slot[i] = k;
  }

  w_.permute(perm, sc.world);
  integ_->permute(perm);
  if (noise_keys_.size() == n) gather_permuted(noise_keys_, perm, sc.keys);
  // the contact set under the new numbers: (i, j) swap where the order flips, and then j's
  // image shift, the normal and the contact point's frame flip with them
  const auto N = static_cast<std::uint32_t>(n);
  std::vector<std::size_t> order(contacts_.keys.size());
  std::vector<PairKey> keys(contacts_.keys.size());
  std::vector<ContactRecord> records = contacts_.records;
  const bool with_records = records.size() == keys.size();
  for (std::size_t c = 0; c < keys.size(); ++c) {
    const PairKey key = contacts_.keys[c];
    const std::uint32_t i = slot[key_i(key)], image = key_image(key);
    const std::uint32_t j = key_j(key) < N ? slot[key_j(key)] : key_j(key);
    if (j >= N || i < j) {
      keys[c] = make_key(i, j, image);
    } else {
      const int sx = image_sx(image), sy = image_sy(image);
      keys[c] = make_key(j, i, make_image(-sx, -sy));
      if (with_records) {
        ContactRecord& r = records[c];
        r.s = r.s - Vec2{sx * w_.Lx, sy * w_.Ly};
        r.n = r.n * -1.0;
      }
    }
    if (with_records) records[c].key = keys[c];
    order[c] = c;
  }
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
  ContactSet cs;
  cs.degenerate = contacts_.degenerate;
  for (std::size_t c : order) {
    cs.keys.push_back(keys[c]);
    if (with_records) cs.records.push_back(records[c]);
  }
  contacts_ = std::move(cs);  // Model S: no per-contact state (sorting is for disks only)
  forces_.sparse = false;     // its list of touched entries named the old slots
  broad_ = make_broadphase(broad_kind_, w_);
  last_order_.swap(perm);  // the previous order's buffer serves the next sort
  ++order_generation_;
}

}  // namespace gs
