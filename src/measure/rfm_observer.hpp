// the Random Force Model observer (docs/physics.md §5.3): read-only measurements of a 2D periodic
// disk fluid or a 1D ring, sampled every rfm.sample_every steps once rfm.discard_time is over, and
// handed as tables (with their metadata) to the run's RecordSink, the series as it is sampled and
// the rest when the run ends (files listed in docs/rfm.md):
//   every sample (transient included): rfm_series.csv   t, T (T.2.19), T_x, T_y, mean velocity
//   steady state: temperature.csv (T.2.19 with block means T.2.20), moments.csv (⟨|v|^m⟩,
//     m = 1…12, T.3.11; 2D also moments_components.csv), hist_velocity.csv (one Cartesian
//     component, x and y pooled, T.A.3), hist_postcollision.csv (velocities of particles just
//     leaving their last contact), hist_freepath.csv (T.4.18, log bins), and
//     2D: sk.csv (T.4.2 on the box k-grid, shells of equal |k|), gr.csv (T.4.10), every
//     rfm.structure_every-th sample;
//     1D: gh.csv (G_h(R), h = 1, 2, 4, 8 of R/L′, T.3.24), gap_moments.csv (⟨(R/L′)^m⟩, T.3.18);
//   rfm.json: the system (N, L, L′, d, M, ε, D, Δt, φ) and the run's summary.
// Contacts are followed every step from sim.contacts().keys at O(contacts) cost: a particle
// whose contact count drops to 0 starts a free path at its unwrapped position, which ends at
// its next contact (docs/physics.md §5.3). Velocities are taken in the centre-of-mass frame.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/rfm_gaps.hpp"
#include "analysis/rfm_gr.hpp"
#include "analysis/rfm_hist.hpp"
#include "analysis/rfm_moments.hpp"
#include "analysis/rfm_sk.hpp"
#include "core/records.hpp"
#include "core/trigger.hpp"
#include "scene/spec.hpp"
#include "sim/observer.hpp"

namespace gs {

/// what the RFM observer needs of a scene, taken once: the [rfm] section, the noise strength
/// and the scene's name and path (rfm.json, messages)
struct RfmSettings {
  RfmSpec rfm;
  double D = 0.0;          ///< drive.D, m²/s³
  std::string scene_name;  ///< scene.name
  std::string scene_path;  ///< the scene file, for messages
  static RfmSettings from(const SceneSpec& scene);
};

class RfmObserver : public Observer {
 public:
  /// the series goes to `records` (output/'s CSV files in a run)
  RfmObserver(const RfmSettings& settings, const RecordSink& records);
  RfmObserver(const SceneSpec& scene, const RecordSink& records)
      : RfmObserver(RfmSettings::from(scene), records) {}
  void start(const Simulation& sim, const std::string& run_dir) override;
  void after_step(const Simulation& sim) override;
  /// until the next sample or the transient's end; none once the contacts are followed
  std::int64_t quiet_steps(const Simulation& sim) const override;
  void finish(const Simulation& sim) override;
  const char* name() const override { return "rfm"; }
  void save(ByteWriter& out) const override;
  void resume(const Simulation& sim, const std::string& run_dir, ByteReader& in) override;

  // what has been measured so far (tests, summaries)
  int dimension() const { return dim_; }
  long samples() const { return static_cast<long>(temps_.size()); }   ///< steady samples
  const std::vector<double>& temperatures() const { return temps_; }  ///< T per sample, m²/s²
  const rfm::MomentSeries& moments() const { return moments_; }       ///< ⟨|v|^m⟩ (1D: |v_x|)
  const rfm::Histogram& velocities() const { return vel_; }           ///< component histogram
  const rfm::Histogram& post_collision() const { return post_; }      ///< components on leaving
  const rfm::Histogram& free_paths() const { return paths_; }         ///< free-path lengths, m
  const rfm::GapStatistics* gaps() const { return gaps_ ? &*gaps_ : nullptr; }  ///< 1D, R/L′
  long leave_events() const { return leaves_; }  ///< particles that left their last contact

 private:
  /// everything start() and resume() share: the system, the accumulators' layouts
  void setup(const Simulation& sim, const std::string& run_dir);
  void begin_steady(const Simulation& sim);
  void make_velocity_histograms();
  void track_contacts(const Simulation& sim);
  void follow_order(const Simulation& sim);
  void sample(const Simulation& sim);
  void write_json(const Simulation& sim) const;

  RfmSettings set_;
  Trigger sampling_;  ///< every rfm.sample_every steps
  std::string dir_;
  int dim_ = 2;
  std::size_t n_ = 0;
  double box_ = 0.0, box_y_ = 0.0;  ///< L (ring: its length), and L_y in 2D, m
  double diameter_ = 0.0;           ///< d, m
  double l_reduced_ = 0.0;          ///< 1D L′ = L − N d, m
  bool structure_ = false;          ///< 2D square box: S(k) and g(R) are measured
  bool steady_ = false;             ///< past discard_time
  double t_steady_ = 0.0;           ///< when the steady part began, s

  const RecordSink* records_;
  std::unique_ptr<RecordTable> series_;
  std::vector<double> times_, temps_;
  rfm::MomentSeries moments_{12}, comp_moments_{12};
  rfm::Histogram vel_, post_, paths_;
  std::optional<rfm::StructureFactor2D> sk_;
  std::optional<rfm::PairCorrelation2D> gr_;
  std::optional<rfm::GapStatistics> gaps_;
  int sk_nmax_ = 0;
  double v_max_ = 0.0;

  // contact bookkeeping: last step each particle touched something, who touched last step,
  // where each particle left its last contact and whether it is in flight since
  std::vector<std::int64_t> last_touch_;
  std::vector<std::uint32_t> touching_prev_, touching_now_;
  std::vector<double> leave_x_, leave_y_;
  std::vector<char> in_flight_;
  long leaves_ = 0;
  std::uint64_t order_seen_ = 0;  ///< Simulation::order_generation() the slots above follow
};

/// an RfmObserver when the scene asks for one ([rfm] enabled; default for the random force)
std::unique_ptr<Observer> make_rfm_observer(const SceneSpec& scene, const RecordSink& records);

}  // namespace gs
