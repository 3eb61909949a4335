#include "contact/placement.hpp"

#include <algorithm>

namespace gs {

PlacedPolygons::PlacedPolygons(const World& w) {
  for (const Species& sp : w.species) {
    max_sides_ = std::max(max_sides_, sp.body.n);
    extent_.push_back(body_extent(sp.body));
  }
}

std::size_t PlacedPolygons::begin(const World& w) {
  const bool ahead = ahead_;
  ahead_ = false;
  int wall_n = 0;
  for (const Wall& wl : w.walls) wall_n = std::max(wall_n, wl.poly.n);
  walls_.resize(w.walls.size(), wall_n);
  wall_refs_.resize(w.walls.size());
  for (std::size_t k = 0; k < w.walls.size(); ++k) {
    walls_.set(k, w.walls[k].poly);
    wall_refs_[k] = walls_.ref(k);
  }
  grains_.resize(w.size(), max_sides_);
  grain_refs_.resize(w.size());
  return ahead ? 0 : w.size();
}

void PlacedPolygons::place(const World& w, std::size_t b, std::size_t e) {
  for (std::size_t i = b; i < e; ++i) {
    const int k = w.sp[i];
    grains_.set_placed(i, w.species[k].body, extent_[k], {w.s.x[i], w.s.y[i]}, w.s.th[i]);
    grain_refs_[i] = grains_.ref(i);
  }
}

}  // namespace gs
