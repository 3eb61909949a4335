// the force stage: the pair loop (force/pair_loop.hpp) around the world's model's pair
// evaluator (force/laws/), forces and torques accumulated per particle; body forces (gravity,
// noise) are added by the drive
#pragma once
#include <cstdint>
#include <vector>

#include "contact/contact_set.hpp"
#include "core/parallel.hpp"
#include "force/laws/disk_pair.hpp"
#include "force/laws/pair_evaluator.hpp"
#include "force/laws/polygon_pair.hpp"
#include "force/pair_loop.hpp"
#include "world/world.hpp"

namespace gs {

ContactSettings contact_settings(const SceneSpec& scene);

/// a world's contact forces: both models' evaluators (their parameter tables per species
/// pair), the one of the world's model run by the pair loop, whose buffers it keeps
class ContactModel {
 public:
  /// the world's species, materials and walls with the scene's switches
  ContactModel(const World& w, const ContactSettings& settings);
  /// evaluate every contact among the candidates, update the contact set, and set f to the
  /// contact forces (f.tq: polygon models only). `generation` identifies the candidate list
  /// (BroadPhase::generation()): an unchanged list reuses its per-particle index; 0 = unknown.
  /// Pairs are evaluated in parallel, then each particle's forces are summed over its pairs in
  /// candidate order, so the result is bitwise the same for any number of threads. `team`:
  /// which thread runs, places and sums what (its pass schedule and particle split, which this
  /// pass's timings move). `then`, if given, runs in the pair loop's particle phase
  /// (ParticlePhase): what depends on a particle's force alone, such as its acceleration, is
  /// then computed where the force and the integrator's data are.
  ForceStats evaluate(const World& w, const std::vector<PairKey>& candidates, ContactSet& cs,
                      ForceBuffer& f, double dt, ThreadTeam& team, std::uint64_t generation = 0,
                      ParticlePhase* then = nullptr) {
    if (w.polygons()) return loop_.run(polygons_, w, candidates, cs, f, dt, team, generation, then);
    return loop_.run(disks_, w, candidates, cs, f, dt, team, generation, then);
  }
  /// polygons: place particles [b, e) at their current state for the next evaluate(), from
  /// inside this evaluate()'s particle phase (the pairs are done by then), once the caller has
  /// predicted the next step there (Simulation::run); every particle once, then
  /// placed_ahead(), and the next evaluate() does not place them again (one pass and, on
  /// the team, one barrier less)
  void place_ahead(const World& w, std::size_t b, std::size_t e) { polygons_.place(w, b, e); }
  void placed_ahead() { polygons_.placed_ahead(); }
  /// from how many candidate pairs evaluate() runs them on the team (more than one thread)
  static std::size_t parallel_pairs_from(bool polygons, std::size_t particles) {
    return PairLoop::parallel_pairs_from(!polygons, particles);
  }
  /// the stiffest binary contact time of the scene (for Δt advice), s
  double min_contact_time() const { return min_contact_time_; }
  /// the normal stiffness the disk law gives species a against b (b = the species count: a
  /// wall), N/m: the one source of a pair's spring for whoever needs its energy
  double disk_stiffness(std::size_t a, std::size_t b) const { return disks_.params(a, b).ks; }

 private:
  PolygonPairEvaluator polygons_;  ///< Model P
  DiskPairEvaluator disks_;        ///< Model S
  PairLoop loop_;
  double min_contact_time_ = 0.0;
};

}  // namespace gs
