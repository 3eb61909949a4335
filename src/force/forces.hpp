// the force stage: one loop over the candidate pairs per model, narrow phase then law, forces
// and torques accumulated per particle; body forces (gravity, noise) are added by the drive
#pragma once
#include <vector>

#include "contact/contact_set.hpp"
#include "geometry/prepared.hpp"
#include "force/laws/disk_law.hpp"
#include "force/laws/polygon_law.hpp"
#include "world/world.hpp"

namespace gs {

/// per-step force accumulators (N, N·m)
struct ForceBuffer {
  std::vector<double> fx, fy, tq;
  void reset(std::size_t n) {
    fx.assign(n, 0.0);
    fy.assign(n, 0.0);
    tq.assign(n, 0.0);
  }
};

/// summary of one force evaluation, for health checks and series
struct ForceStats {
  std::size_t contacts = 0;       ///< touching pairs (including walls)
  std::size_t degenerate = 0;     ///< polygon contacts without boundary crossings this step
  double max_overlap = 0.0;       ///< largest h_eff (polygons) or δ (disks), m
  double max_overlap_rel = 0.0;   ///< the same over the smaller grain's radius
};

/// the constant law parameters of a world, tabulated per (species, species) and (species, wall)
class ContactModel {
 public:
  explicit ContactModel(const World& w);
  /// evaluate every contact among the candidates; update the contact set; add to f
  ForceStats evaluate(const World& w, const std::vector<PairKey>& candidates, ContactSet& cs,
                      ForceBuffer& f, double dt);
  /// the stiffest binary contact time of the scene (for Δt advice), s
  double min_contact_time() const { return min_contact_time_; }

 private:
  ForceStats evaluate_polygons(const World& w, const std::vector<PairKey>& cand, ContactSet& cs,
                               ForceBuffer& f, double dt);
  ForceStats evaluate_disks(const World& w, const std::vector<PairKey>& cand, ContactSet& cs,
                            ForceBuffer& f);
  std::size_t nsp_ = 0;
  std::vector<law::PolyLawParams> poly_;   ///< [si * (nsp+1) + sj], sj = nsp for walls
  std::vector<law::DiskLawParams> disk_;   ///< same layout
  bool hdot_fd_ = false;
  bool rocking_ = true;
  double min_contact_time_ = 0.0;
  PolyStore shapes_;       ///< world-frame polygons of this step, prepared for the overlap
  PolyStore wall_shapes_;  ///< the walls' polygons, prepared once
  int max_sides_ = 0;      ///< most vertices of any species' polygon
  /// one candidate pair's outcome, computed in parallel and summed in key order
  struct PairResult {
    bool touching = false;
    bool degenerate = false;
    Vec2 s, n, xj;        ///< contact point, normal, j's (image) centre
    double fn = 0, ft = 0, couple = 0, overlap = 0, h = 0;
    ContactState state;
  };
  std::vector<PairResult> pair_out_;
  std::vector<PairKey> new_keys_;
  std::vector<ContactState> new_state_;
  std::vector<ContactRecord> new_records_;
};

}  // namespace gs
