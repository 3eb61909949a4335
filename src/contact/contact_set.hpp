// the persistent contact set: touching pairs keyed and sorted by (i, j, image), each carrying
// the state that must survive between steps (Cundall–Strack spring, previous h_eff)
#pragma once
#include <algorithm>
#include <cstddef>
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

  /// the history of `key` if it touched last step, else a fresh state. `hint`: where the last
  /// lookup of this caller ended; candidates come in ascending order, so the next key is
  /// usually a short forward scan away (else a bisection). Updated to this key's place
  ContactState history(PairKey key, std::size_t& hint) const {
    hint = lower_index(key, hint);
    return hint < keys.size() && keys[hint] == key && hint < state.size() ? state[hint]
                                                                          : ContactState{};
  }
  /// the first index of keys not below `key` (std::lower_bound), from `hint` when it lies at or
  /// just before it
  std::size_t lower_index(PairKey key, std::size_t hint) const {
    const std::size_t n = keys.size();
    if (hint <= n && (hint == 0 || keys[hint - 1] < key)) {
      for (int step = 0; step < 4; ++step, ++hint)
        if (hint == n || !(keys[hint] < key)) return hint;
      return static_cast<std::size_t>(std::lower_bound(keys.begin() + hint, keys.end(), key) -
                                      keys.begin());
    }
    return static_cast<std::size_t>(std::lower_bound(keys.begin(), keys.end(), key) - keys.begin());
  }
  /// emptied, for the pair pass to fill in candidate order
  void clear() {
    keys.clear();
    state.clear();
    records.clear();
  }
  /// the step's new set, compacted by the pair pass in candidate order, replaces the last one;
  /// the last one's storage goes back to `next` for the step after
  void replace(ContactSet& next) {
    keys.swap(next.keys);
    state.swap(next.state);
    records.swap(next.records);
  }
};

}  // namespace gs
