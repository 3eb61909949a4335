#include "measure/packing.hpp"

#include <algorithm>
#include <cmath>

#include "broadphase/broadphase.hpp"

namespace gs {

double phi_in_rect(const World& w, double x0, double y0, double x1, double y1) {
  double area = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const double r = w.radius[i], x = w.s.x[i], y = w.s.y[i];
    // skip grains whose bounding circle misses the rectangle
    if (x + r < x0 || x - r > x1 || y + r < y0 || y - r > y1) continue;
    const Species& k = w.species[w.sp[i]];
    if (k.shape == ShapeKind::Polygon) {
      const bool inside = x - r >= x0 && x + r <= x1 && y - r >= y0 && y + r <= y1;
      area += inside ? k.area : area_in_rect(w.shape(i), x0, y0, x1, y1);
    } else {
      area += disk_area_in_rect({x, y}, r, x0, y0, x1, y1);
    }
  }
  return area / ((x1 - x0) * (y1 - y0));
}

double mean_coordination(const World& w, const ContactSet& cs) {
  if (w.size() == 0) return 0.0;
  std::size_t pairs = 0;
  for (PairKey k : cs.keys)
    if (key_j(k) < w.size()) ++pairs;
  return 2.0 * static_cast<double>(pairs) / static_cast<double>(w.size());
}

std::array<double, 4> force_moment_tensor(const World& w, const ContactSet& cs) {
  std::array<double, 4> S{0, 0, 0, 0};  // xx, xy, yx, yy
  const std::uint32_t N = static_cast<std::uint32_t>(w.size());
  for (const ContactRecord& c : cs.records) {
    const std::uint32_t i = key_i(c.key), j = key_j(c.key);
    const Vec2 F = c.n * c.fn + perp(c.n) * c.ft;  // on j; i gets −F
    auto add = [&](Vec2 arm, Vec2 f) {
      S[0] += arm.x * f.x;
      S[1] += arm.x * f.y;
      S[2] += arm.y * f.x;
      S[3] += arm.y * f.y;
    };
    add(c.s - Vec2{w.s.x[i], w.s.y[i]}, -F);
    if (j < N) {
      const Vec2 xj{w.s.x[j] + image_sx(key_image(c.key)) * w.Lx,
                    w.s.y[j] + image_sy(key_image(c.key)) * w.Ly};
      add(c.s - xj, F);
    }
  }
  return S;
}

double max_speed(const World& w) {
  double v2 = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i)
    v2 = std::max(v2, w.s.vx[i] * w.s.vx[i] + w.s.vy[i] * w.s.vy[i]);
  return std::sqrt(v2);
}

}  // namespace gs
