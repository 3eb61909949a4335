// the pair loop, written once around a pair evaluator (force/laws/pair_evaluator.hpp): every
// candidate through the evaluator, the touching ones compacted into the new contact set, and
// each particle's contact forces and torques summed. A serial way and a parallel one (pairs in
// parallel, compaction, per-particle sums), both with the same bits on any number of threads
#pragma once
#include <cstdint>
#include <vector>

#include "contact/contact_set.hpp"
#include "core/parallel.hpp"
#include "core/team.hpp"
#include "force/laws/pair_evaluator.hpp"
#include "world/world.hpp"

namespace gs {

/// per-step contact forces and torques on each particle (N, N·m); ContactModel::evaluate
/// overwrites them (tq only for polygon models; disks exert no contact torque)
struct ForceBuffer {
  std::vector<double> fx, fy, tq;
  /// set by the serial evaluation where few particles touch (a gas, a large sparse fluid):
  /// the buffer is zero but for these particles' entries, so the next evaluation clears just
  /// them instead of all N (a pass over memory that a sparse step need not pay). Anything
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

/// the pair loop's particle phase: what runs on a thread's particles [b, e) once their contact
/// forces are final, on the thread that summed them (each thread its own range, the team's
/// particle split): the by-range stages of a step (sim/step_executor.hpp)
class ParticlePhase {
 public:
  virtual void run(std::size_t b, std::size_t e) = 0;

 protected:
  ~ParticlePhase() = default;
};

/// the loop's buffers, kept from step to step; run() is instantiated for each evaluator
class PairLoop {
 public:
  /// every contact among the candidates by `ev`, the contact set replaced by the new one, f
  /// set to the contact forces (ContactModel::evaluate says what the arguments mean);
  /// `then`, if given, runs in the particle phase
  template <class Ev>
  ForceStats run(Ev& ev, const World& w, const std::vector<PairKey>& cand, ContactSet& cs,
                 ForceBuffer& f, double dt, ThreadTeam& team, std::uint64_t generation,
                 ParticlePhase* then);
  /// from how many candidate pairs run() takes the parallel way (more than one thread)
  static std::size_t parallel_pairs_from(bool cheap, std::size_t particles);

 private:
  template <class Ev>
  ForceStats serial(const Ev& ev, const World& w, const std::vector<PairKey>& cand,
                    const ContactSet& cs, ForceBuffer& f, double dt);
  template <class Ev>
  ForceStats parallel(Ev& ev, const World& w, const std::vector<PairKey>& cand,
                      const ContactSet& cs, ForceBuffer& f, double dt, ThreadTeam& team,
                      bool reindex, bool from_touching, std::size_t to_place, ParticlePhase* then);
  static void clear_forces(ForceBuffer& f, std::size_t n);
  void note_touched(ForceBuffer& f, std::size_t n);
  void sums_from_touching(const World& w, ForceBuffer& f, std::size_t b, std::size_t e) const;
  /// did few of the candidates touch last step (a gas: under a third)? Then a cheap
  /// evaluator's loops take their sparse ways (the serial one's selection pass, the parallel
  /// one's sums)
  static bool few_touched(const ContactSet& cs, std::size_t ncand) {
    return 3 * cs.keys.size() < ncand;
  }
  // the per-particle index of the candidates (CSR, ascending candidate order per particle)
  void index_candidates(const std::vector<PairKey>& cand, std::size_t n);
  std::vector<std::uint8_t> touch_;  ///< per candidate: does the pair touch this step?
  /// per touching pair of the contact set being made: its candidate index (sums_from_touching)
  std::vector<std::uint32_t> touching_k_;
  std::vector<std::uint32_t> sel_;  ///< serial loop, cheap pairs: the candidates that may touch
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
  ContactSet next_;  ///< the contact set being made (ContactSet::replace)
};

}  // namespace gs
