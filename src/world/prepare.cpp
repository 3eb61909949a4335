#include "world/prepare.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.hpp"
#include "core/rng.hpp"

namespace gs {
namespace {

// the species of every grain to place, in a seeded random order so species mix
std::vector<int> grain_species(const SceneSpec& sc, RngStream& rng) {
  std::vector<int> out;
  for (std::size_t k = 0; k < sc.species.size(); ++k)
    out.insert(out.end(), sc.species[k].count, static_cast<int>(k));
  for (std::size_t i = out.size(); i > 1; --i)  // Fisher–Yates
    std::swap(out[i - 1], out[rng.next_u64() % i]);
  return out;
}

// cell centres of a lattice filling [x0,x1]×[y0,y1] with spacing a (hexagonal rows shifted)
std::vector<Vec2> lattice(double x0, double y0, double x1, double y1, double a, bool hex,
                          std::size_t need) {
  std::vector<Vec2> pts;
  const double dy = hex ? a * std::sqrt(3.0) / 2.0 : a;
  for (int row = 0;; ++row) {
    const double y = y0 + a / 2 + row * dy;
    if (y > y1 - a / 2 + 1e-12) break;
    const double shift = (hex && row % 2) ? a / 2 : 0.0;
    const std::size_t before = pts.size();
    for (int col = 0;; ++col) {
      const double x = x0 + a / 2 + shift + col * a;
      if (x > x1 - a / 2 + 1e-12) break;
      pts.push_back({x, y});
    }
    // a box narrower than one site holds no row at all (and an open top has ~10⁹ m of rows)
    if (pts.size() == before && shift == 0.0) break;
    if (pts.size() >= need && !hex) break;
  }
  return pts;
}

}  // namespace

void place_particles(World& w, const SceneSpec& sc) {
  const auto& prep = sc.prep;
  RngStream rng(prep.seed, 0x7072657000ULL);  // "prep" stream

  // explicit particles win over any placement rule
  if (!prep.particles.empty()) {
    for (std::size_t i = 0; i < prep.particles.size(); ++i) {
      const auto& p = prep.particles[i];
      // a centre outside a walled box would fall outside the walls for the whole run
      const std::string key = "preparation.particle[" + std::to_string(i) + "].";
      if (sc.box.kind == BoxKind::Walls && !(p.x >= 0.0 && p.x <= w.Lx))
        throw InputError(sc.path, key + "x",
                         "x = " + std::to_string(p.x) + " m is outside the box's walls [0, " +
                             std::to_string(w.Lx) + "] m");
      if (sc.box.kind == BoxKind::Walls && !(p.y >= 0.0 && (!sc.box.lid || p.y <= w.Ly)))
        throw InputError(sc.path, key + "y",
                         "y = " + std::to_string(p.y) + " m is outside the box (below its floor" +
                             std::string(sc.box.lid ? " or above its lid" : "") + ")");
      int k = -1;
      for (std::size_t s = 0; s < w.species.size(); ++s)
        if (w.species[s].name == p.species) k = static_cast<int>(s);
      if (k < 0)
        throw InputError(sc.path, "preparation.particle.species",
                         "unknown species '" + p.species + "'");
      w.add_particle(k, {p.x, p.y}, p.theta, {p.vx, p.vy}, p.omega);
    }
    return;
  }

  std::vector<int> kinds = grain_species(sc, rng);
  const std::size_t n = kinds.size();
  const double a = 2.0 * w.max_radius * 1.02;  // lattice spacing: no two grains can touch

  // the region the grains start in
  double x0 = 0, y0 = 0, x1 = w.Lx, y1 = w.Ly;
  if (sc.box.kind == BoxKind::Ring1D) {
    // 1D ring: equal spacing L/N along the line (thesis §2.2.2)
    for (std::size_t i = 0; i < n; ++i) w.add_particle(kinds[i], {(i + 0.5) * w.Lx / n, 0.0}, 0.0);
  } else {
    std::vector<Vec2> sites;
    switch (prep.placement) {
      case PlacementKind::LooseColumn: {
        // a loose column from the floor up: lattice sites with jitter, filled bottom first
        if (prep.column_height > 0) y1 = std::min(y1, prep.column_height);
        if (sc.box.kind == BoxKind::Walls && !sc.box.lid && prep.column_height <= 0)
          y1 = 1e9;  // open top: the column may rise as high as it needs
        sites = lattice(x0, y0, x1, y1, a * 1.05, false, n);
        break;
      }
      case PlacementKind::Square:
        sites = lattice(x0, y0, x1, y1, a, false, n);
        break;
      case PlacementKind::Hexagonal:
        sites = lattice(x0, y0, x1, y1, a, true, n);
        break;
      case PlacementKind::Uniform: {
        // each grain gets an equal cell of the box (thesis fig. 2.4c)
        const int nx = std::max(1, static_cast<int>(std::ceil(std::sqrt(n * w.Lx / w.Ly))));
        const int ny = static_cast<int>((n + nx - 1) / nx);
        for (int r = 0; r < ny; ++r)
          for (int c = 0; c < nx; ++c)
            sites.push_back({(c + 0.5) * w.Lx / nx, (r + 0.5) * w.Ly / ny});
        if (w.Lx / nx < a || w.Ly / ny < a) sites.clear();
        break;
      }
      case PlacementKind::Random: {
        // n sites drawn at random from a fine lattice (no overlaps), numbered in lattice order:
        // grains that are neighbours in space are then near in memory too (cache locality of
        // the pair loop, which matters most for large fluids)
        const std::vector<Vec2> all = lattice(x0, y0, x1, y1, a, true, n);
        std::vector<std::size_t> pick(all.size());
        for (std::size_t i = 0; i < pick.size(); ++i) pick[i] = i;
        for (std::size_t i = pick.size(); i > 1; --i)
          std::swap(pick[i - 1], pick[rng.next_u64() % i]);
        if (pick.size() > n) pick.resize(n);
        std::sort(pick.begin(), pick.end());
        for (std::size_t i : pick) sites.push_back(all[i]);
        break;
      }
    }
    if (sites.size() < n)
      throw InputError(sc.path, "preparation.placement",
                       std::to_string(n) + " grains do not fit in the box with this placement (" +
                           std::to_string(sites.size()) +
                           " sites); enlarge the box or reduce counts");
    const bool jitter = prep.placement == PlacementKind::LooseColumn;
    const double slack = a * 0.05 / 2;
    for (std::size_t i = 0; i < n; ++i) {
      Vec2 p = sites[i];
      if (jitter) p += Vec2{rng.uniform(-slack, slack), rng.uniform(-slack, slack)};
      const double th =
          w.species[kinds[i]].shape == ShapeKind::Polygon ? rng.uniform(0.0, 2.0 * M_PI) : 0.0;
      w.add_particle(kinds[i], p, th);
    }
  }

  // initial velocities: each component 0.1·U(−0.5, 0.5) for amplitude 0.1 (thesis §2.2.2)
  if (prep.velocity_amplitude > 0) {
    for (std::size_t i = 0; i < w.size(); ++i) {
      w.s.vx[i] = prep.velocity_amplitude * rng.uniform(-0.5, 0.5);
      if (sc.box.kind != BoxKind::Ring1D)
        w.s.vy[i] = prep.velocity_amplitude * rng.uniform(-0.5, 0.5);
    }
  }
}

}  // namespace gs
