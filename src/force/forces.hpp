// the force stage: one loop over the candidate pairs per model, narrow phase then law, forces
// and torques accumulated per particle; body forces (gravity, noise) are added by the drive
#pragma once
#include <cstdint>
#include <vector>

#include "contact/contact_set.hpp"
#include "core/parallel.hpp"
#include "core/pass_schedule.hpp"
#include "core/stage_clock.hpp"
#include "force/laws/disk_law.hpp"
#include "force/laws/polygon_law.hpp"
#include "geometry/prepared.hpp"
#include "world/world.hpp"

namespace gs {

/// per-step contact forces and torques on each particle (N, N·m); ContactModel::evaluate
/// overwrites them (tq only for polygon models; disks exert no contact torque)
struct ForceBuffer {
  std::vector<double> fx, fy, tq;
  /// set by the serial evaluation where few particles touch (a gas, a large sparse fluid):
  /// the buffer is zero but for these particles' entries, so the next evaluation clears just
  /// them instead of all N (≈ 3% of a 10⁶-disk fluid step). Anything
  /// that writes fx, fy or tq other than ContactModel::evaluate must clear `sparse`.
  std::vector<std::uint32_t> touched;
  bool sparse = false;
  std::size_t sparse_n = 0;  ///< the particle count when `touched` was recorded
  void reset(std::size_t n) {
    fx.assign(n, 0.0);
    fy.assign(n, 0.0);
    tq.assign(n, 0.0);
    sparse = false;
  }
};

/// summary of one force evaluation, for health checks and series
struct ForceStats {
  std::size_t contacts = 0;      ///< touching pairs (including walls)
  std::size_t candidates = 0;    ///< the broad phase's candidate pairs
  std::size_t degenerate = 0;    ///< polygon contacts without boundary crossings this step
  double max_overlap = 0.0;      ///< largest h_eff (polygons) or δ (disks), m
  double max_overlap_rel = 0.0;  ///< the same over the smaller grain's radius
};

/// the contact laws' switches (the scene's [model] section), taken once from the scene
struct ContactSettings {
  bool hdot_finite_difference = false;  ///< Model P: ḣ_eff by finite difference (else analytic)
  bool rocking_damping = true;   ///< Model P: the normal dashpot's moment along the contact line
  bool clip_attractive = false;  ///< Model S: no attractive normal force
};
ContactSettings contact_settings(const SceneSpec& scene);

/// the constant law parameters of a world, tabulated per (species, species) and (species, wall)
class ContactModel {
 public:
  /// the world's species, materials and walls with the scene's switches
  ContactModel(const World& w, const ContactSettings& settings);
  /// evaluate every contact among the candidates, update the contact set, and set f to the
  /// contact forces (f.tq: polygon models only). `generation` identifies the candidate list
  /// (BroadPhase::generation()): an unchanged list reuses its per-particle index; 0 = unknown.
  /// Pairs are evaluated in parallel, then each particle's forces are summed over its pairs in
  /// candidate order, so the result is bitwise the same for any number of threads.
  /// `after(b, e)`, if given, runs once the forces of particles [b, e) are final, on the
  /// thread that summed them (each thread its own range, the ranges of parallel_ranges over
  /// the particles, as the integrators' loops): what depends on a particle's force alone, such
  /// as its acceleration, is then computed where the force and the integrator's data are.
  /// `clock`, if given, gets the first thread's laps: Stage::NarrowPhase once the pairs are
  /// done and the contact set is made, Stage::Laws once its particles' forces are summed.
  ForceStats evaluate(const World& w, const std::vector<PairKey>& candidates, ContactSet& cs,
                      ForceBuffer& f, double dt, std::uint64_t generation = 0, RangeFn after = {},
                      StageClock* clock = nullptr);
  /// polygons: place particles [b, e) at their current state for the next evaluate(), from
  /// inside this evaluate()'s `after` (the pairs are done by then), once the caller has
  /// predicted the next step there (Simulation::run); every particle once, then
  /// placed_ahead(), and the next evaluate() does not place them again (one pass and, on
  /// the team, one barrier less)
  void place_ahead(const World& w, std::size_t b, std::size_t e) { place_shapes(w, b, e); }
  void placed_ahead() { placed_ahead_ = true; }
  /// from how many candidate pairs evaluate() runs them on the team (more than one thread)
  static std::size_t parallel_pairs_from(bool polygons, std::size_t particles);
  /// the stiffest binary contact time of the scene (for Δt advice), s
  double min_contact_time() const { return min_contact_time_; }

 private:
  struct PairForce;
  struct PairResult;
  // one candidate: narrow phase and law; false when the pair does not touch
  bool polygon_pair(const World& w, PairKey key, const ContactSet& cs, std::size_t& hint, double dt,
                    PairForce& pf, PairResult& pr) const;
  bool disk_pair(const World& w, PairKey key, PairForce& pf, PairResult& pr) const;
  void place_walls(const World& w);
  void place_shapes(const World& w, std::size_t b, std::size_t e);
  struct PolyPairConst;
  PolyPairConst poly_pair_const(const World& w, std::size_t a, std::size_t b,
                                const law::PolyLawParams& p) const;
  static void clear_forces(ForceBuffer& f, std::size_t n);
  void note_touched(ForceBuffer& f, std::size_t n);
  ForceStats evaluate_serial(const World& w, const std::vector<PairKey>& cand, const ContactSet& cs,
                             ForceBuffer& f, double dt);
  ForceStats evaluate_parallel(const World& w, const std::vector<PairKey>& cand,
                               const ContactSet& cs, ForceBuffer& f, double dt, bool reindex,
                               bool from_touching, bool placed, RangeFn after, StageClock* clock);
  void sums_from_touching(const World& w, ForceBuffer& f, std::size_t b, std::size_t e) const;
  /// did few of the candidates touch last step (a gas: under a third)? Then the disk loops
  /// take their sparse ways (the serial one's selection pass, the parallel one's sums)
  static bool few_touched(const ContactSet& cs, std::size_t ncand) {
    return 3 * cs.keys.size() < ncand;
  }
  // the per-particle index of the candidates (CSR, ascending candidate order per particle)
  void index_candidates(const std::vector<PairKey>& cand, std::size_t n);
  std::size_t nsp_ = 0;
  std::vector<law::PolyLawParams> poly_;  ///< [si * (nsp+1) + sj], sj = nsp for walls
  /// Model P constants of a (species, species) or (species, wall) pair: the quantities of
  /// P.29–P.36 that depend on masses and radii only (every grain of a species has its values)
  struct PolyPairConst {
    double l = 0, m_perp = 0, m_par = 0;  ///< l (m), m⊥ and m∥ (kg)
    double damp_n = 0;                    ///< γ·√(E·m⊥), kg/s
    double damp_t = 0;                    ///< √((2/7)·E·m∥), kg/s
  };
  std::vector<PolyPairConst> poly_pc_;    ///< same layout as poly_
  std::vector<law::DiskLawParams> disk_;  ///< same layout
  bool hdot_fd_ = false;
  bool rocking_ = true;
  double min_contact_time_ = 0.0;
  PolyStore shapes_;                ///< world-frame polygons of this step, prepared for the overlap
  bool placed_ahead_ = false;       ///< shapes_ already holds the next evaluate()'s polygons
  PolyStore wall_shapes_;           ///< the walls' polygons, prepared once
  int max_sides_ = 0;               ///< most vertices of any species' polygon
  std::vector<BodyExtent> extent_;  ///< per species: its body's extent, for the placement
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
  std::vector<std::uint8_t> touch_;  ///< per candidate: does the pair touch this step?
  /// per touching pair of the contact set being made: its candidate index (sums_from_touching)
  std::vector<std::uint32_t> touching_k_;
  std::vector<std::uint32_t> sel_;  ///< serial disk loop: the candidates that may touch
  std::size_t select_disk_pairs(const World& w, const std::vector<PairKey>& cand, std::size_t k0,
                                std::size_t k1);
  /// the radius every disk has, or NaN where they differ: then the selection reads no radii
  /// (at 10⁶ disks a memory stream of its own). Found once per candidate list (generation),
  /// which is made for the radii it is used with
  void find_common_radius(const World& w, std::uint64_t generation);
  /// disks of one radius (find_common_radius): their largest overlap over the radius is the
  /// largest overlap divided by it once, the same bits (a correctly rounded division by a
  /// positive constant keeps the order), not a division and two loads per contact
  bool one_radius_disks(bool poly) const { return !poly && common_radius_ > 0.0; }
  void finish_overlaps(ForceStats& st, bool one_radius) const {
    if (one_radius) st.max_overlap_rel = st.max_overlap / common_radius_;
  }
  double common_radius_ = 0.0;
  std::uint64_t common_radius_generation_ = 0;  ///< 0: not found for any list
  std::size_t common_radius_n_ = 0;
  void prefetch_disk_pairs(const World& w, const std::vector<PairKey>& cand, std::size_t m,
                           const ForceBuffer& f) const;
  std::vector<PairForce> pair_f_;   ///< per candidate (touching ones only written)
  std::vector<PairResult> pair_r_;  ///< per candidate (touching ones only written)
  // per-particle index: entries (k << 1 | side) of the candidates naming each particle, side 0
  // as i, 1 as j, in ascending k; rebuilt when the candidate list's generation changes
  std::vector<std::uint32_t> cand_start_, cand_entry_, fill_;
  std::uint64_t indexed_generation_ = 0;
  std::size_t indexed_n_ = 0, indexed_count_ = 0;
  // the compaction of touching pairs into the contact set, in fixed blocks of candidates
  std::vector<std::size_t> chunk_first_;  ///< parallel loop: first contact-set slot of each chunk
  std::vector<ForceStats> chunk_stats_;
  PassSchedule schedule_;  ///< parallel loop: which thread runs, places and sums what
  ContactSet next_;        ///< the contact set being made (ContactSet::replace)
};

}  // namespace gs
