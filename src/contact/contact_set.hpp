// the persistent contact set: touching pairs keyed and sorted by (i, j, image), each carrying
// the state that must survive between steps (Cundall–Strack spring, previous h_eff)
#pragma once
#include <vector>

#include "broadphase/broadphase.hpp"
#include "contact/tangential_spring.hpp"

namespace gs {

/// state carried by one contact from step to step
struct ContactState {
  TangentialSpring spring;  ///< Cundall–Strack spring and previous v∥ (P.35)
  double h_prev = 0.0;      ///< h_eff at the previous step (finite-difference ḣ_eff), m
};

/// one touching contact of the current step, for observers (stress, chains, coordination)
struct ContactRecord {
  PairKey key = 0;
  Vec2 s;                ///< contact point (i's frame of the periodic image), m
  Vec2 n;                ///< unit normal from i towards j
  double fn = 0.0;       ///< normal force on j along n, N
  double ft = 0.0;       ///< tangential force on j along perp(n), N
  double overlap = 0.0;  ///< A (m², polygons) or δ (m, disks)
};

struct ContactSet {
  std::vector<PairKey> keys;        ///< touching pairs of the last step, ascending
  std::vector<ContactState> state;  ///< parallel to keys (Model P); empty for Model S (no history)
  std::vector<ContactRecord> records;  ///< the last step's contacts, parallel to keys
  std::size_t degenerate = 0;          ///< contacts seen with one polygon inside the other (total)
};

}  // namespace gs
