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

/// the last step's contacts as one pass over the candidates reads them: each candidate's
/// history (its state if it touched last step, else a fresh one). Candidates come in ascending
/// order, so the next key is usually a short forward scan from the last one (else a bisection);
/// the set's arrays are read through pointers taken once, not reloaded per pair
class HistoryCursor {
 public:
  explicit HistoryCursor(const ContactSet& cs)
      : keys_(cs.keys.data()), n_(cs.keys.size()), state_(cs.state.data()), ns_(cs.state.size()) {}
  /// the history of `key`; the cursor moves to its place
  ContactState find(PairKey key) {
    pos_ = lower_index(key);
    return pos_ < n_ && keys_[pos_] == key && pos_ < ns_ ? state_[pos_] : ContactState{};
  }

 private:
  /// the first index of the keys not below `key` (std::lower_bound), from the cursor when it
  /// lies at or just before it
  std::size_t lower_index(PairKey key) const {
    std::size_t at = pos_;
    if (at == 0 || keys_[at - 1] < key) {
      for (int step = 0; step < 4; ++step, ++at)
        if (at == n_ || !(keys_[at] < key)) return at;
      return static_cast<std::size_t>(std::lower_bound(keys_ + at, keys_ + n_, key) - keys_);
    }
    return static_cast<std::size_t>(std::lower_bound(keys_, keys_ + n_, key) - keys_);
  }
  const PairKey* keys_;
  std::size_t n_;
  const ContactState* state_;
  std::size_t ns_;
  std::size_t pos_ = 0;  ///< where the last lookup ended (≤ n_)
};

}  // namespace gs
