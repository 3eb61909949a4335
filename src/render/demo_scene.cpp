// synthetic scenes: a relaxed decagon pile and a periodic disk gas
#include "render/demo_scene.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/rng.hpp"

namespace gs {

namespace {

// push overlapping disks (radius = circumradius) apart and keep them in [0, w] × [0, ∞),
// with a small downward drift so the pile settles onto the floor
void relax(std::vector<double>& x, std::vector<double>& y, const std::vector<double>& r, double w,
           int iterations) {
  const std::size_t n = x.size();
  const double cell = 2.0 * *std::max_element(r.begin(), r.end());
  for (int it = 0; it < iterations; ++it) {
    // a cell list rebuilt every sweep
    double ymax = 0.0;
    for (double v : y) ymax = std::max(ymax, v);
    const int nx = std::max(1, static_cast<int>(w / cell) + 1);
    const int ny = static_cast<int>(ymax / cell) + 2;
    std::vector<std::vector<std::size_t>> cells(static_cast<std::size_t>(nx) * ny);
    auto cell_of = [&](std::size_t i) {
      const int cx = std::clamp(static_cast<int>(x[i] / cell), 0, nx - 1);
      const int cy = std::clamp(static_cast<int>(y[i] / cell), 0, ny - 1);
      return std::pair{cx, cy};
    };
    for (std::size_t i = 0; i < n; ++i) {
      const auto [cx, cy] = cell_of(i);
      cells[static_cast<std::size_t>(cy) * nx + cx].push_back(i);
    }
    // half of each overlap to each partner
    for (std::size_t i = 0; i < n; ++i) {
      const auto [cx, cy] = cell_of(i);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int ex = cx + dx, ey = cy + dy;
          if (ex < 0 || ey < 0 || ex >= nx || ey >= ny) continue;
          for (std::size_t j : cells[static_cast<std::size_t>(ey) * nx + ex]) {
            if (j <= i) continue;
            const double ux = x[j] - x[i], uy = y[j] - y[i], d = std::hypot(ux, uy);
            const double ov = r[i] + r[j] - d;
            if (ov <= 0.0 || d == 0.0) continue;
            const double s = 0.5 * ov / d;
            x[i] -= s * ux, y[i] -= s * uy, x[j] += s * ux, y[j] += s * uy;
          }
        }
    }
    // walls and a little gravity
    for (std::size_t i = 0; i < n; ++i) {
      y[i] -= 0.02 * r[i];
      x[i] = std::clamp(x[i], r[i], w - r[i]);
      y[i] = std::max(y[i], r[i]);
    }
  }
}

}  // namespace

DemoScene demo_decagon_pile(int n_big, int n_small, double width, std::uint64_t seed) {
  DemoScene s;
  RngStream rng(seed, 7);
  const int n = n_big + n_small;
  // species shuffled, then placed on a hexagonal lattice of the mean spacing
  std::vector<int> species(n);
  for (int i = 0; i < n; ++i) species[i] = i < n_big ? 0 : 1;
  for (int i = n - 1; i > 0; --i)
    std::swap(species[i], species[static_cast<int>(rng.uniform() * (i + 1))]);
  auto& p = s.particles;
  const double spacing = 0.0158;
  const int per_row = std::max(1, static_cast<int>(width / spacing));
  for (int i = 0; i < n; ++i) {
    const int row = i / per_row, col = i % per_row;
    p.x.push_back((col + 0.5 + 0.5 * (row & 1)) * width / (per_row + 0.5));
    p.y.push_back((row + 0.5) * spacing * 0.866);
    p.radius.push_back(species[i] == 0 ? 0.009 : 0.00636);
    p.sides.push_back(10);
    p.species.push_back(species[i]);
    p.theta.push_back(rng.uniform(0.0, 2.0 * M_PI / 10.0));
  }
  relax(p.x, p.y, p.radius, width, 60);

  // velocities: the surface layers thrown up as just after a tap, the bulk nearly at rest
  double top = 0.0;
  for (double v : p.y) top = std::max(top, v);
  for (int i = 0; i < n; ++i) {
    const double depth = top - p.y[i];
    p.vx.push_back(0.03 * rng.normal() * std::exp(-depth / 0.08));
    p.vy.push_back(0.45 * std::exp(-depth / 0.06) * (1.0 + 0.2 * rng.normal()));
  }

  // walls: floor, left and right, 20 mm thick; no lid
  const double t = 0.02, h = 0.62;
  s.walls.rects.push_back({Vec2{-t, -t}, Vec2{width + t, -t}, Vec2{width + t, 0}, Vec2{-t, 0}});
  s.walls.rects.push_back({Vec2{-t, 0}, Vec2{0, 0}, Vec2{0, h}, Vec2{-t, h}});
  s.walls.rects.push_back({Vec2{width, 0}, Vec2{width + t, 0}, Vec2{width + t, h}, Vec2{width, h}});
  s.box = {0.0, 0.0, width, h, false, false};
  s.overlays.time = 3.1;
  s.overlays.tap = 1;
  s.overlays.has_tap = true;
  s.overlays.test_rect = std::array<double, 4>{0.04, 0.04, width - 0.04, 0.44};
  return s;
}

DemoScene demo_disk_gas(int n, double L, double phi, std::uint64_t seed) {
  DemoScene s;
  RngStream rng(seed, 11);
  auto& p = s.particles;
  const double r = std::sqrt(phi * L * L / (n * M_PI));
  for (int i = 0; i < n; ++i) {
    p.x.push_back(rng.uniform(0.0, L));
    p.y.push_back(rng.uniform(0.0, L));
    p.theta.push_back(0.0);
    p.radius.push_back(r);
    p.sides.push_back(0);
    p.species.push_back(0);
    double a, b;
    rng.normal_pair(a, b);
    p.vx.push_back(a);
    p.vy.push_back(b);
  }
  s.box = {0.0, 0.0, L, L, true, true};
  return s;
}

}  // namespace gs
