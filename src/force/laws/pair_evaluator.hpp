// what a pair evaluator is to the pair loop (force/pair_loop.hpp), as HOOMD-blue's pair
// potentials are to its PotentialPair: the loop is written once, and an evaluator holds one
// model's parameters per species pair and turns one candidate pair into its contact frame (the
// narrow-phase registry, contact/narrow.hpp), force, torques and contact state. An evaluator Ev
// offers the loop:
//   Ev::kShape                  the grains' kind (BodyKind): its narrow phase is
//                               narrow<kShape, kShape> and narrow<kShape, BodyKind::Wall>
//   Ev::kTorque                 its pairs exert torques (the loop sums ForceBuffer::tq)
//   Ev::kHistory                its contacts carry a ContactState from step to step
//   Ev::kCheap                  a pair costs less than a mispredicted branch or a cache
//                               miss: where few candidates touched, the loop
//                               takes its sparse ways (Ev::select and Ev::prefetch before the
//                               serial loop's pairs, the parallel sums from the touching pairs)
//   Ev::kChunk                  candidates per chunk of the parallel loop
//   begin(w, generation)        before a pass; returns how many grains the pass must place
//                               (place(w, b, e) over [0, that), on the team), 0 for none
//   common_radius()             the radius every grain has (> 0), else not positive or NaN
//   pair(w, key, history, dt, pf, pr)  one candidate (`history`: the last step's contacts,
//                               a HistoryCursor over them); false when it does not touch
#pragma once
#include <cstdint>

#include "broadphase/broadphase.hpp"
#include "contact/contact_set.hpp"
#include "core/vec.hpp"
#include "world/world.hpp"

namespace gs {

/// the contact laws' switches (the scene's [model] section), taken once from the scene
struct ContactSettings {
  bool hdot_finite_difference = false;  ///< Model P: ḣ_eff by finite difference (else analytic)
  bool rocking_damping = true;   ///< Model P: the normal dashpot's moment along the contact line
  bool clip_attractive = false;  ///< Model S: no attractive normal force
};

/// one touching pair's force on j (i gets the opposite) and the torques about each centre
struct PairForce {
  double fx = 0, fy = 0, ti = 0, tj = 0;
};

/// what a touching pair leaves for the contact set and the step's statistics
struct PairResult {
  bool degenerate = false;
  Vec2 s, n;                                  ///< contact point, normal
  double fn = 0, ft = 0, overlap = 0, h = 0;  ///< h: h_eff (polygons) or δ (disks), m
  ContactState state;
};

/// the parameter tables' layout: [si · (species + 1) + sj], sj = species for a wall
inline std::size_t pair_index(std::size_t species, std::size_t si, std::size_t sj) {
  return si * (species + 1) + sj;
}

/// position of j's periodic image as seen from i
inline Vec2 image_pos(const World& w, std::uint32_t j, std::uint32_t image) {
  return {w.s.x[j] + image_sx(image) * w.Lx, w.s.y[j] + image_sy(image) * w.Ly};
}

}  // namespace gs
