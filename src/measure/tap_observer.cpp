#include "measure/tap_observer.hpp"

#include "drive/schedule.hpp"
#include "measure/tap_measure.hpp"
#include "sim/simulation.hpp"

namespace gs {

TapSettings TapSettings::from(const SceneSpec& scene) {
  TapSettings t;
  t.drive = scene.drive;
  t.settle_time = scene.prep.settle_time;
  for (std::size_t k = 0; k < 4; ++k) t.test_rect[k] = scene.output.test_rect[k];
  for (const SpeciesSpec& s : scene.species) t.species.push_back(s.name);
  return t;
}

TapObserver::TapObserver(const TapSettings& settings, const RecordSink& records)
    : set_(settings), records_(&records) {}

std::vector<std::string> TapObserver::columns(const TapSettings& settings) {
  std::vector<std::string> c{"tap",       "t",     "phi", "phi_left", "phi_right", "kinetic_energy",
                             "max_speed", "z_mean"};
  for (const std::string& s : settings.species) c.push_back("z_" + s);
  for (const char* k : {"coordination", "S_xx", "S_xy", "S_yx", "S_yy", "relax_end", "early"})
    c.push_back(k);
  return c;
}

void TapObserver::start(const Simulation& sim, const std::string& run_dir) {
  const World& w = sim.world();
  taps_ = records_->create(run_dir + "/taps.csv", columns(set_));
  // segregation: n(h) per species on a grid up to the box height
  grid_ = height_grid(w.Ly, set_.segregation_dh);
  std::vector<std::string> cols{"tap", "t"};
  for (auto& n : cumulative_count_names(w, grid_)) cols.push_back(n);
  seg_ = records_->create(run_dir + "/segregation.csv", cols);
  origin_seen_ = w.clock_origin;
  // the prepared state is tap 0 when the first excitation starts with the first step
  if (at_taps_.fires({w.s.step, tap_boundary(set_.drive, w.clock_origin, w.s.t, sim.dt())}))
    measure(sim);
}

void TapObserver::save(ByteWriter& out) const {
  out.f64(origin_seen_);
  out.u8(early_ ? 1 : 0);
  out.f64(relax_end_);
  out.i64(rows_);
}

void TapObserver::resume(const Simulation& sim, const std::string& run_dir, ByteReader& in) {
  const World& w = sim.world();
  grid_ = height_grid(w.Ly, set_.segregation_dh);
  taps_ = records_->append(run_dir + "/taps.csv", columns(set_).size());
  seg_ =
      records_->append(run_dir + "/segregation.csv", 2 + cumulative_count_names(w, grid_).size());
  origin_seen_ = in.f64("taps: clock origin");
  early_ = in.u8("taps: early flag") != 0;
  relax_end_ = in.f64("taps: relaxation end");
  rows_ = static_cast<long>(in.i64("taps: rows"));
}

void TapObserver::after_step(const Simulation& sim) {
  const World& w = sim.world();
  const DriveSpec& d = set_.drive;
  // the protocol clock moved: this relaxation was ended early (drive/protocol.hpp)
  if (w.clock_origin != origin_seen_) {
    early_ = true;
    relax_end_ = drive_phase(d, origin_seen_, w.s.t).t_in + 0.5 * sim.dt();
    origin_seen_ = w.clock_origin;
  }
  if (at_taps_.fires({w.s.step, tap_boundary(d, w.clock_origin, w.s.t, sim.dt())})) measure(sim);
}

std::int64_t TapObserver::quiet_steps(const Simulation& sim) const {
  const World& w = sim.world();
  return steps_before_excitation(set_.drive, w.clock_origin, w.s.t, sim.dt());
}

void TapObserver::finish(const Simulation& /*sim*/) {
  // rows are flushed as they are written; close the files
  taps_.reset();
  seg_.reset();
}

// one row: the tap count is the number of the excitation about to start
void TapObserver::measure(const Simulation& sim) {
  const World& w = sim.world();
  const DriveSpec& d = set_.drive;
  const DrivePhase now = drive_phase(d, w.clock_origin, w.s.t),
                   next = drive_phase(d, w.clock_origin, w.s.t + sim.dt());
  const auto tap = static_cast<double>(next.tap);
  // how the relaxation ended: its full length T, or early; tap 0 after settling
  double relax_end = now.settling ? set_.settle_time : drive_period(d);
  if (early_) relax_end = relax_end_;
  const TapMeasurement m = measure_tap(w, sim.contacts(), set_.test_rect.data());
  std::vector<double> row{tap,         w.s.t,   m.phi, m.phi_left, m.phi_right, m.kinetic_energy,
                          m.max_speed, m.z_mean};
  row.insert(row.end(), m.z_species.begin(), m.z_species.end());
  row.insert(row.end(),
             {m.coordination, m.S[0], m.S[1], m.S[2], m.S[3], relax_end, early_ ? 1.0 : 0.0});
  taps_->row(row);
  std::vector<double> seg{tap, w.s.t};
  for (double n : cumulative_counts(w, grid_)) seg.push_back(n);
  seg_->row(seg);
  early_ = false;
  ++rows_;
}

std::unique_ptr<Observer> make_tap_observer(const SceneSpec& scene, const RecordSink& records) {
  if (!is_tapping(scene.drive)) return nullptr;
  return std::make_unique<TapObserver>(TapSettings::from(scene), records);
}

}  // namespace gs
