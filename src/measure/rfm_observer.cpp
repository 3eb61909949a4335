// the Random Force Model observer: see rfm_observer.hpp for what it measures and writes
#include "measure/rfm_observer.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "analysis/rfm_freepath.hpp"
#include "analysis/rfm_tails.hpp"
#include "core/error.hpp"
#include "core/numbers.hpp"
#include "core/permute.hpp"
#include "measure/rfm_io.hpp"
#include "sim/simulation.hpp"

namespace gs {

namespace {

// moments with errors from the scatter of `blocks` consecutive block means (snapshots a few
// collision times apart are correlated; blocks of many snapshots are nearly independent)
std::vector<double> block_errors(const rfm::MomentSeries& s, int blocks) {
  const auto& per = s.per_snapshot();
  std::vector<double> err(static_cast<std::size_t>(s.m_max()), kNaN);
  const std::size_t len = per.size() / static_cast<std::size_t>(blocks);
  if (len == 0) return s.error();  // fewer snapshots than blocks: snapshot scatter
  for (std::size_t k = 0; k < err.size(); ++k) {
    std::vector<double> series;
    for (const auto& snap : per) series.push_back(snap[k]);
    err[k] = rfm::block_average(series, len).error;
  }
  return err;
}

// velocities in the centre-of-mass frame (2D) and their mean
std::vector<Vec2> com_velocities(const World& w, Vec2& mean) {
  const std::size_t n = w.size();
  std::vector<Vec2> v(n);
  double m = 0.0;
  mean = {};
  for (std::size_t i = 0; i < n; ++i) {
    mean += Vec2{w.s.vx[i], w.s.vy[i]} * w.mass[i];
    m += w.mass[i];
  }
  mean = mean * (1.0 / m);
  for (std::size_t i = 0; i < n; ++i) v[i] = Vec2{w.s.vx[i], w.s.vy[i]} - mean;
  return v;
}

// a measured number for rfm.json: null when not finite (no measurement)
nlohmann::ordered_json json_number(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

}  // namespace

RfmSettings RfmSettings::from(const SceneSpec& scene) {
  return {scene.rfm, scene.drive.D, scene.name, scene.path};
}

RfmObserver::RfmObserver(const RfmSettings& settings, const RecordSink& records)
    : set_(settings),
      sampling_(Trigger::every_steps(settings.rfm.sample_every)),
      records_(&records) {}

void RfmObserver::start(const Simulation& sim, const std::string& run_dir) {
  setup(sim, run_dir);
  // the series of every sample, transient included
  series_ = records_->create(dir_ + "/rfm_series.csv", {"t", "step", "T", "T_x", "T_y", "v_mean_x",
                                                        "v_mean_y", "contacts", "steady"});
  after_step(sim);  // the prepared state is the first sample (step 0)
}

void RfmObserver::setup(const Simulation& sim, const std::string& run_dir) {
  const World& w = sim.world();
  dir_ = run_dir;
  n_ = w.size();
  dim_ = w.box == BoxKind::Ring1D ? 1 : 2;
  box_ = w.Lx;
  box_y_ = dim_ == 2 ? w.Ly : 0.0;
  if (w.box == BoxKind::Walls)
    throw InputError(set_.scene_path, "rfm.enabled",
                     "the RFM measurements need a periodic box or a ring (box.kind = \"periodic\" "
                     "or \"ring\")");
  // one disk size: reduced coordinates (T.3.16) and l₀ (T.4.7) assume equal diameters
  diameter_ = 2.0 * w.max_radius;
  for (std::size_t i = 0; i < n_; ++i)
    if (std::abs(2.0 * w.radius[i] - diameter_) > 1e-12 * diameter_)
      throw InputError(set_.scene_path, "species",
                       "the RFM measurements need disks of one size (docs/physics.md §5)");
  if (dim_ == 1) l_reduced_ = rfm::reduced_length(box_, static_cast<long>(n_), diameter_);

  // structure (2D, square box): S(k) up to |n| ≈ 1.2 L/d (past the first peak), g(R) to L/4
  structure_ = dim_ == 2 && std::abs(box_ - box_y_) <= 1e-12 * box_;
  if (structure_) {
    sk_nmax_ = set_.rfm.sk_nmax > 0 ? set_.rfm.sk_nmax
                                    : std::clamp(static_cast<int>(1.2 * box_ / diameter_), 4, 96);
    sk_.emplace(box_, sk_nmax_);
    gr_.emplace(box_, set_.rfm.gr_rmax > 0 ? set_.rfm.gr_rmax : 0.25 * box_, set_.rfm.gr_bins);
  }
  // 1D gaps in units of L′ on log bins (the −ln R view of thesis §3.3.2)
  if (dim_ == 1) gaps_.emplace(rfm::Binning::log(set_.rfm.gap_min, 1.0, set_.rfm.gap_bins));
  // free paths on log bins from far below a diameter to the box (1D: to L′)
  const double lmin = set_.rfm.path_min > 0 ? set_.rfm.path_min : 1e-4 * diameter_;
  const double lmax = set_.rfm.path_max > 0 ? set_.rfm.path_max : (dim_ == 1 ? l_reduced_ : box_);
  if (!(lmax > lmin))
    throw InputError(set_.scene_path, "rfm.path_max",
                     "free-path range is empty (path_max <= path_min)");
  paths_ = rfm::free_path_histogram(lmin, lmax, set_.rfm.path_bins);

  last_touch_.assign(n_, std::numeric_limits<std::int64_t>::min() / 2);
  leave_x_.assign(n_, 0.0);
  leave_y_.assign(n_, 0.0);
  in_flight_.assign(n_, 0);
  steady_ = false;
  order_seen_ = sim.order_generation();
}

// the simulation sorted its particles into other slots: the per-slot bookkeeping follows
void RfmObserver::follow_order(const Simulation& sim) {
  if (sim.order_generation() != order_seen_ + 1)
    throw std::logic_error("RfmObserver: more than one particle sort between two steps");
  const std::vector<std::uint32_t>& perm = sim.last_order();  // new slot k ← old perm[k]
  if (perm.size() != n_) throw std::logic_error("RfmObserver: sort of another size");
  const std::vector<std::uint32_t> slot = inverse_permutation(perm);
  std::vector<std::int64_t> t64;
  std::vector<double> td;
  std::vector<char> tc;
  gather_permuted(last_touch_, perm, t64);
  gather_permuted(leave_x_, perm, td);
  gather_permuted(leave_y_, perm, td);
  gather_permuted(in_flight_, perm, tc);
  for (std::uint32_t& i : touching_prev_) i = slot[i];
  order_seen_ = sim.order_generation();
}

void RfmObserver::save(ByteWriter& out) const {
  out.u8(steady_ ? 1 : 0);
  out.f64(t_steady_);
  out.f64(v_max_);
  out.vec(times_);
  out.vec(temps_);
  moments_.save(out);
  comp_moments_.save(out);
  if (steady_) {
    vel_.save(out);
    post_.save(out);
  }
  paths_.save(out);
  if (sk_) sk_->save(out);
  if (gr_) gr_->save(out);
  if (gaps_) gaps_->save(out);
  // contact bookkeeping
  std::vector<long> touch(last_touch_.begin(), last_touch_.end());
  std::vector<long> prev(touching_prev_.begin(), touching_prev_.end());
  std::vector<long> flight(in_flight_.begin(), in_flight_.end());
  out.vec(touch);
  out.vec(prev);
  out.vec(leave_x_);
  out.vec(leave_y_);
  out.vec(flight);
  out.i64(leaves_);
}

void RfmObserver::resume(const Simulation& sim, const std::string& run_dir, ByteReader& in) {
  setup(sim, run_dir);
  series_ = records_->append(dir_ + "/rfm_series.csv", 9);
  steady_ = in.u8("rfm: steady flag") != 0;
  t_steady_ = in.f64("rfm: steady start");
  v_max_ = in.f64("rfm: velocity range");
  in.vec(times_, "rfm: sample times");
  in.vec(temps_, "rfm: temperatures");
  if (times_.size() != temps_.size()) in.fail(in.pos, "rfm: sample times and temperatures differ");
  moments_.load(in);
  comp_moments_.load(in);
  if (steady_) {
    make_velocity_histograms();
    vel_.load(in);
    post_.load(in);
  }
  paths_.load(in);
  if (sk_) sk_->load(in);
  if (gr_) gr_->load(in);
  if (gaps_) gaps_->load(in);
  std::vector<long> touch, prev, flight;
  in.vec(touch, "rfm: contact bookkeeping");
  in.vec(prev, "rfm: contact bookkeeping");
  in.vec_sized(leave_x_, n_, "rfm: free-path starts");
  in.vec_sized(leave_y_, n_, "rfm: free-path starts");
  in.vec(flight, "rfm: contact bookkeeping");
  if (touch.size() != n_ || flight.size() != n_)
    in.fail(in.pos, "rfm: contact bookkeeping does not match the particle count");
  for (std::size_t i = 0; i < n_; ++i) {
    last_touch_[i] = touch[i];
    in_flight_[i] = static_cast<char>(flight[i] != 0);
  }
  touching_prev_.clear();
  for (long i : prev) {
    if (i < 0 || static_cast<std::size_t>(i) >= n_) in.fail(in.pos, "rfm: bad particle index");
    touching_prev_.push_back(static_cast<std::uint32_t>(i));
  }
  leaves_ = static_cast<long>(in.i64("rfm: leave events"));
}

void RfmObserver::after_step(const Simulation& sim) {
  const World& w = sim.world();
  if (sim.order_generation() != order_seen_) follow_order(sim);
  if (!steady_ && w.s.t >= set_.rfm.discard_time - 0.5 * sim.dt()) begin_steady(sim);
  if (steady_) track_contacts(sim);
  if (sampling_.at_step(w.s.step)) sample(sim);
}

std::int64_t RfmObserver::quiet_steps(const Simulation& sim) const {
  if (steady_) return 0;  // free paths: the contacts are followed at every step
  const World& w = sim.world();
  std::int64_t q = sampling_.steps_to_next(w.s.step) - 1;
  // the steps before the transient can end (t ≥ discard_time − Δt/2), two fewer for round-off
  const double left = (set_.rfm.discard_time - 0.5 * sim.dt() - w.s.t) / sim.dt();
  if (left < static_cast<double>(q) + 2.0)
    q = std::max<std::int64_t>(0, std::min(q, static_cast<std::int64_t>(std::floor(left)) - 2));
  return q;
}

// the transient is over: fix the velocity histogram range from the current spread
void RfmObserver::begin_steady(const Simulation& sim) {
  const World& w = sim.world();
  steady_ = true;
  t_steady_ = w.s.t;
  v_max_ = set_.rfm.v_max;
  if (v_max_ <= 0) {
    Vec2 mean;
    const auto v = com_velocities(w, mean);
    double s2 = 0.0;
    for (const Vec2& u : v) s2 += dim_ == 1 ? u.x * u.x : 0.5 * dot(u, u);
    const double sigma = std::sqrt(s2 / static_cast<double>(v.size()));
    v_max_ = sigma > 0 ? 12.0 * sigma : 1.0;
  }
  make_velocity_histograms();
}

void RfmObserver::make_velocity_histograms() {
  vel_ = rfm::velocity_histogram(v_max_, set_.rfm.v_bins);
  post_ = rfm::velocity_histogram(v_max_, set_.rfm.v_bins);
}

// contact counts from the contact keys, O(contacts): leaving (count → 0) starts a free path
// and records the post-collision velocity; touching again (count ≥ 1) ends the path (T.4.18)
void RfmObserver::track_contacts(const Simulation& sim) {
  const World& w = sim.world();
  const std::int64_t step = w.s.step;
  const auto n = static_cast<std::uint32_t>(n_);
  touching_now_.clear();
  auto touch = [&](std::uint32_t i) {
    if (last_touch_[i] == step) return;
    if (last_touch_[i] != step - 1 && in_flight_[i]) {
      const Vec2 p = w.unwrapped(i);
      const double dx = p.x - leave_x_[i], dy = dim_ == 2 ? p.y - leave_y_[i] : 0.0;
      paths_.add(std::sqrt(dx * dx + dy * dy));
      in_flight_[i] = 0;
    }
    last_touch_[i] = step;
    touching_now_.push_back(i);
  };
  for (PairKey k : sim.contacts().keys) {
    touch(key_i(k));
    if (key_j(k) < n) touch(key_j(k));  // walls (j ≥ N) are not particles
  }
  Vec2 mean{};
  bool have_mean = false;
  for (std::uint32_t i : touching_prev_) {
    if (last_touch_[i] == step) continue;
    // i left its last contact this step
    const Vec2 p = w.unwrapped(i);
    leave_x_[i] = p.x;
    leave_y_[i] = p.y;
    in_flight_[i] = 1;
    ++leaves_;
    if (!have_mean) {  // the centre-of-mass velocity, once per step with leavers
      double m = 0.0;
      for (std::size_t q = 0; q < n_; ++q) {
        mean += Vec2{w.s.vx[q], w.s.vy[q]} * w.mass[q];
        m += w.mass[q];
      }
      mean = mean * (1.0 / m);
      have_mean = true;
    }
    post_.add(w.s.vx[i] - mean.x);
    if (dim_ == 2) post_.add(w.s.vy[i] - mean.y);
  }
  touching_prev_.swap(touching_now_);
}

// one sample: the series row always; the statistics once steady
void RfmObserver::sample(const Simulation& sim) {
  const World& w = sim.world();
  Vec2 mean;
  const std::vector<Vec2> v = com_velocities(w, mean);
  double tx = 0.0, ty = 0.0;
  for (const Vec2& u : v) {
    tx += u.x * u.x;
    ty += u.y * u.y;
  }
  tx /= static_cast<double>(n_);
  ty = dim_ == 2 ? ty / static_cast<double>(n_) : 0.0;
  const double temp = tx + ty;  // T = (1/N) Σ |v − ⟨v⟩|² (T.2.19)
  series_->row({w.s.t, static_cast<double>(w.s.step), temp, tx, ty, mean.x, mean.y,
                static_cast<double>(sim.contacts().keys.size()), steady_ ? 1.0 : 0.0});
  if (!steady_) return;

  times_.push_back(w.s.t);
  temps_.push_back(temp);
  if (dim_ == 2) {
    moments_.add_speeds(v);
    comp_moments_.add_components(v);
    rfm::add_components(vel_, v);
    if (structure_ &&
        (temps_.size() - 1) % static_cast<std::size_t>(set_.rfm.structure_every) == 0) {
      // positions brought into the cell (g(R) uses the minimum image of wrapped points)
      std::vector<Vec2> r(n_);
      for (std::size_t i = 0; i < n_; ++i)
        r[i] = {w.s.x[i] - box_ * std::floor(w.s.x[i] / box_),
                w.s.y[i] - box_ * std::floor(w.s.y[i] / box_)};
      sk_->add_snapshot(r);
      gr_->add_snapshot(r);
    }
  } else {
    std::vector<double> vx(n_);
    for (std::size_t i = 0; i < n_; ++i) vx[i] = v[i].x;
    moments_.add_snapshot(vx);
    rfm::add_values(vel_, vx);
    // reduced coordinates (T.3.16) in units of L′, particles in ring order
    std::vector<double> red = rfm::reduced_coordinates(w.s.x, box_, diameter_);
    for (double& r : red) r /= l_reduced_;
    gaps_->add_snapshot(red, 1.0);
  }
}

void RfmObserver::finish(const Simulation& sim) {
  series_.reset();  // flushed row by row; close
  const std::filesystem::path d(dir_);
  const RecordSink& out = *records_;
  // T(t) with block means (T.2.20)
  if (!temps_.empty()) {
    const std::size_t len =
        std::max<std::size_t>(1, temps_.size() / static_cast<std::size_t>(set_.rfm.blocks));
    const rfm::BlockAverage b = rfm::block_average(temps_, len);
    rfm::write_temperature_csv(out, d / "temperature.csv", times_, temps_, &b);
  } else {
    rfm::write_temperature_csv(out, d / "temperature.csv", times_, temps_);
  }
  // velocity moments m = 1…12 with block errors
  rfm::write_moments_csv(out, d / "moments.csv", moments_.mean(),
                         block_errors(moments_, set_.rfm.blocks));
  if (dim_ == 2)
    rfm::write_moments_csv(out, d / "moments_components.csv", comp_moments_.mean(),
                           block_errors(comp_moments_, set_.rfm.blocks));
  // histograms: raw counts for the analysis, and chart-ready densities
  if (steady_) {
    rfm::write_histogram_raw(out, d / "hist_velocity.csv", vel_);
    rfm::write_histogram_raw(out, d / "hist_postcollision.csv", post_);
    rfm::write_velocity_csv(out, d / "velocity.csv", vel_);
  }
  rfm::write_histogram_raw(out, d / "hist_freepath.csv", paths_);
  rfm::write_freepath_csv(out, d / "freepath.csv", paths_);
  // structure
  if (structure_ && sk_->snapshots() > 0) {
    rfm::write_sk_csv(out, d / "sk.csv", sk_->shells());
    rfm::write_gr_csv(out, d / "gr.csv", gr_->bins());
  }
  if (gaps_ && gaps_->moments().snapshots() > 0) {
    rfm::write_gh_csv(out, d / "gh.csv", *gaps_);
    rfm::write_moments_csv(out, d / "gap_moments.csv", gaps_->moments().mean(),
                           block_errors(gaps_->moments(), set_.rfm.blocks));
  }
  write_json(sim);
}

// rfm.json: the system and a summary, one top-level field per line (app/run/run_info.hpp reads it)
void RfmObserver::write_json(const Simulation& sim) const {
  const World& w = sim.world();
  const MaterialSpec& mat = w.materials[w.species[0].material];
  double t_mean = kNaN, t_err = kNaN;
  if (!temps_.empty()) {
    const std::size_t len =
        std::max<std::size_t>(1, temps_.size() / static_cast<std::size_t>(set_.rfm.blocks));
    const rfm::BlockAverage b = rfm::block_average(temps_, len);
    t_mean = b.mean;
    t_err = b.block_means.size() >= 2 ? b.error : kNaN;
  }
  const double area = dim_ == 2 ? box_ * box_y_ : 0.0;
  const double phi = dim_ == 2 ? static_cast<double>(n_) * M_PI * diameter_ * diameter_ / 4.0 / area
                               : static_cast<double>(n_) * diameter_ / box_;
  const auto count = [](double v) { return static_cast<std::int64_t>(v); };
  nlohmann::ordered_json j;
  j["model"] = "rfm";
  j["scene"] = set_.scene_name;
  j["dimension"] = dim_;
  j["particles"] = n_;
  j["box"] = box_;
  j["box_height"] = box_y_;
  j["reduced_length"] = json_number(dim_ == 1 ? l_reduced_ : kNaN);
  j["diameter"] = diameter_;
  j["mass"] = json_number(w.mass.empty() ? kNaN : w.mass[0]);
  j["phi"] = phi;
  j["eps_n"] = mat.eps_n;
  j["eps_t"] = mat.eps_t;
  j["ks"] = mat.ks;
  j["D"] = set_.D;
  j["dt"] = sim.dt();
  j["sample_every"] = set_.rfm.sample_every;
  j["discard_time"] = set_.rfm.discard_time;
  j["t_steady"] = json_number(steady_ ? t_steady_ : kNaN);
  j["t_end"] = w.s.t;
  j["samples"] = temps_.size();
  j["T_mean"] = json_number(t_mean);
  j["T_err"] = json_number(t_err);
  j["v_max"] = json_number(v_max_);
  j["velocity_samples"] = count(vel_.total());
  j["leave_events"] = leaves_;
  j["free_paths"] = count(paths_.total());
  j["sk_nmax"] = sk_nmax_;
  j["structure_snapshots"] = sk_ ? sk_->snapshots() : 0;
  j["structure"] = structure_ ? 1 : 0;
  // a scene name that is not UTF-8 is written with U+FFFD
  records_->document(
      dir_ + "/rfm.json",
      j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n");
}

std::unique_ptr<Observer> make_rfm_observer(const SceneSpec& scene, const RecordSink& records) {
  if (!scene.rfm.enabled) return nullptr;
  return std::make_unique<RfmObserver>(scene, records);
}

}  // namespace gs
