// the polygons of one step placed for the narrow phase: each grain's world-frame polygon and
// the walls', prepared once per step (geometry/prepared.hpp) so that a pair needs no set-up
#pragma once
#include <cstddef>
#include <vector>

#include "geometry/prepared.hpp"
#include "world/world.hpp"

namespace gs {

class PlacedPolygons {
 public:
  /// the species' bodies: their extents and the most vertices of any, taken once
  explicit PlacedPolygons(const World& w);
  /// before a pass: the walls placed (every step, so that a scene may move its walls) and room
  /// for every grain. Returns how many grains the pass must still place (place(w, 0, …)): all,
  /// or none where the last pass placed them ahead
  std::size_t begin(const World& w);
  /// grains [b, e) placed at their current state (the store sized by begin())
  void place(const World& w, std::size_t b, std::size_t e);
  /// every grain has been placed (by place()) for the next pass, after this one's pairs
  void placed_ahead() { ahead_ = true; }
  const PolyRef& grain(std::size_t i) const { return grain_refs_[i]; }
  const PolyRef& wall(std::size_t k) const { return wall_refs_[k]; }

 private:
  PolyStore grains_;  ///< world-frame polygons of this step
  PolyStore walls_;   ///< the walls' polygons
  /// each grain's and wall's view (PolyStore::ref), made where it is placed: a pair reads the
  /// two it needs as they are, not assembled from the store's arrays
  std::vector<PolyRef> grain_refs_, wall_refs_;
  bool ahead_ = false;              ///< grains_ already holds the next pass's polygons
  int max_sides_ = 0;               ///< most vertices of any species' polygon
  std::vector<BodyExtent> extent_;  ///< per species: its body's extent, for the placement
};

}  // namespace gs
