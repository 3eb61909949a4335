// the tapping study's observer: one row per tap in DIR/taps.csv and DIR/segregation.csv,
// measured just before the next excitation (docs/physics.md §2.5), appended and flushed
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/records.hpp"
#include "core/trigger.hpp"
#include "scene/spec.hpp"
#include "sim/observer.hpp"

namespace gs {

/// what the tap observer needs of a scene, taken once: the drive, the settling time, the test
/// rectangle and the species' names (the z_<species> columns)
struct TapSettings {
  DriveSpec drive;
  double settle_time = 0.0;           ///< preparation.settle_time, s
  std::array<double, 4> test_rect{};  ///< output.test_rect: x0, y0, x1, y1, m
  std::vector<std::string> species;   ///< species names, in the scene's order
  double segregation_dh = 0.01;       ///< spacing of the height grid of n(h), m
  static TapSettings from(const SceneSpec& scene);
};

class TapObserver : public Observer {
 public:
  /// rows go to `records` (output/'s CSV files in a run)
  TapObserver(const TapSettings& settings, const RecordSink& records);
  void start(const Simulation& sim, const std::string& run_dir) override;
  void after_step(const Simulation& sim) override;
  /// until just before the next excitation starts (when it measures)
  std::int64_t quiet_steps(const Simulation& sim) const override;
  void finish(const Simulation& sim) override;
  const char* name() const override { return "taps"; }
  void save(ByteWriter& out) const override;
  void resume(const Simulation& sim, const std::string& run_dir, ByteReader& in) override;
  /// rows written so far (taps measured, the prepared state as tap 0 included)
  long rows() const { return rows_; }

  /// the columns of taps.csv (species names give the z_<species> columns)
  static std::vector<std::string> columns(const TapSettings& settings);

 private:
  void measure(const Simulation& sim);

  TapSettings set_;
  const RecordSink* records_;
  std::unique_ptr<RecordTable> taps_, seg_;
  std::vector<double> grid_;
  Trigger at_taps_ = Trigger::every_taps(1);  ///< one row at every tap boundary
  double origin_seen_ = 0.0;                  ///< clock origin at the previous step, s
  bool early_ = false;                        ///< the current relaxation was ended early
  double relax_end_ = 0.0;                    ///< when it ended, time within its period, s
  long rows_ = 0;
};

/// a TapObserver for tapping scenes (negative g, rotating g); null otherwise
std::unique_ptr<Observer> make_tap_observer(const SceneSpec& scene, const RecordSink& records);

}  // namespace gs
