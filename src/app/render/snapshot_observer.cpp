// snapshots on their schedule; what a checkpoint keeps is the list of snapshots taken, so a
// resumed run removes any written after it and rewrites the collection and the index
#include "app/render/snapshot_observer.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "drive/schedule.hpp"
#include "output/csv.hpp"
#include "output/particles/snapshot_files.hpp"
#include "output/particles/trajectory.hpp"
#include "sim/simulation.hpp"
#include "view/render_world.hpp"

namespace gs {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> index_columns() {
  return {"snapshot", "t", "step", "tap", "at_tap", "at_time"};
}

// the number k of a snapshot file (snap_000012.vtp, contacts_000012.csv), −1 for other names
// the snapshot number k of a file this writer writes under `spec` (exactly
// snapshot_file(stem, k, ext) for a format it has on), or −1 for any other file: a resume
// removes only its own later snapshots, never a file that merely looks like one
long snapshot_number(const std::string& name, const SnapshotSpec& spec) {
  const std::pair<const char*, const char*> kinds[] = {
      {"snap_", spec.vtp ? "vtp" : nullptr},
      {"snap_", spec.xyz ? "xyz" : nullptr},
      {"contacts_", spec.contacts ? "csv" : nullptr}};
  for (const auto& [stem, ext] : kinds) {
    if (ext == nullptr || name.rfind(stem, 0) != 0) continue;
    const std::size_t begin = std::strlen(stem), dot = name.find('.', begin);
    if (dot == std::string::npos || name.compare(dot + 1, std::string::npos, ext) != 0) continue;
    long k = -1;
    const auto [end, ec] = std::from_chars(name.data() + begin, name.data() + dot, k);
    if (ec != std::errc() || end != name.data() + dot || k < 0) continue;  // not a number of ours
    const std::string exact(stem, begin - 1);
    if (snapshot_file(exact.c_str(), k, ext) == name) return k;
  }
  return -1;
}

class SnapshotWriter final : public Observer {
 public:
  explicit SnapshotWriter(const SceneSpec& scene)
      : spec_(scene.output.snapshots), view_(ViewSettings::from(scene)) {}

  const char* name() const override { return "snapshots"; }

  void start(const Simulation& sim, const std::string& run_dir) override {
    open(run_dir, 0);
    if (due(sim)) capture(sim);
  }

  void after_step(const Simulation& sim) override {
    if (due(sim)) capture(sim);
  }

  std::int64_t quiet_steps(const Simulation& sim) const override {
    const World& w = sim.world();
    const double dt = sim.dt();
    std::int64_t m = std::int64_t{1} << 40;
    if (spec_.at_taps) m = steps_before_excitation(view_.drive, w.clock_origin, w.s.t, dt);
    // the steps that certainly end before the next scheduled time (two fewer: round-off)
    const double next = next_time();
    if (std::isfinite(next)) {
      const double steps = std::floor((next - w.s.t) / dt) - 2.0;
      m = std::min<std::int64_t>(m, steps > 0.0 ? static_cast<std::int64_t>(steps) : 0);
    }
    return m;
  }

  void finish(const Simulation&) override {
    index_ = CsvWriter();
    pvd_.close();
  }

  void save(ByteWriter& out) const override {
    out.i64(next_k_);
    out.i64(static_cast<std::int64_t>(next_i_));
    out.i64(static_cast<std::int64_t>(taken_.size()));
    for (const SnapshotEntry& e : taken_) {
      out.f64(e.t);
      out.i64(e.step);
      out.i64(e.tap);
      out.u8(static_cast<std::uint8_t>((e.at_tap ? 1 : 0) | (e.at_time ? 2 : 0)));
    }
  }

  // the snapshots up to the checkpoint stay, later ones (written before the run stopped) go
  void resume(const Simulation&, const std::string& run_dir, ByteReader& in) override {
    next_k_ = in.i64("snapshots: next time index");
    next_i_ = static_cast<std::size_t>(in.i64("snapshots: next listed time"));
    const std::int64_t count = in.i64("snapshots: count");
    std::vector<SnapshotEntry> kept;
    for (std::int64_t k = 0; k < count; ++k) {
      SnapshotEntry e;
      e.t = in.f64("snapshots: time");
      e.step = in.i64("snapshots: step");
      e.tap = static_cast<long>(in.i64("snapshots: tap"));
      const std::uint8_t why = in.u8("snapshots: reason");
      e.at_tap = (why & 1) != 0;
      e.at_time = (why & 2) != 0;
      kept.push_back(e);
    }
    taken_ = std::move(kept);
    open(run_dir, static_cast<long>(taken_.size()));
  }

 private:
  // DIR/snapshots with the files of snapshots [0, keep) only, the index and the collection
  // written for them
  void open(const std::string& run_dir, long keep) {
    dir_ = (fs::path(run_dir) / "snapshots").string();
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec) throw OutputError(dir_ + ": cannot create the snapshot folder: " + ec.message());
    for (const auto& e : fs::directory_iterator(dir_, ec)) {
      const long k = snapshot_number(e.path().filename().string(), spec_);
      if (k >= keep && e.is_regular_file(ec)) fs::remove(e.path(), ec);
    }
    index_ = CsvWriter((fs::path(dir_) / kSnapshotIndexFile).string(), index_columns());
    for (std::size_t k = 0; k < taken_.size(); ++k) index_row(taken_[k], static_cast<long>(k));
    if (spec_.vtp) pvd_.open((fs::path(dir_) / kSnapshotCollectionFile).string(), taken_);
  }

  // the next scheduled time (every_time's grid or the list), +inf when none is left
  double next_time() const {
    double t = INFINITY;
    if (spec_.every_time > 0.0) t = spec_.every_time * static_cast<double>(next_k_);
    if (next_i_ < spec_.times.size()) t = std::min(t, spec_.times[next_i_]);
    return t;
  }

  // is a snapshot due after this step? (a time reached, or a tap's measurement now)
  bool due(const Simulation& sim) {
    const World& w = sim.world();
    const double now = w.s.t + 0.5 * sim.dt();
    at_time_ = false;
    if (now >= next_time()) {
      at_time_ = true;
      // the first grid time after now, by division (then settled with the same comparison)
      if (spec_.every_time > 0.0) {
        next_k_ = std::max(next_k_, static_cast<std::int64_t>(std::floor(now / spec_.every_time)));
        while (spec_.every_time * static_cast<double>(next_k_) <= now) ++next_k_;
      }
      while (next_i_ < spec_.times.size() && spec_.times[next_i_] <= now) ++next_i_;
    }
    // the tap observer's test, so that every taps.csv row has its snapshot
    at_tap_ = spec_.at_taps && excitation_starts_next(view_.drive, w.clock_origin, w.s.t, sim.dt());
    return at_time_ || at_tap_;
  }

  void capture(const Simulation& sim) {
    const World& w = sim.world();
    const ContactSet& c = sim.contacts();
    const long k = static_cast<long>(taken_.size());
    SnapshotEntry e;
    e.t = w.s.t;
    e.step = w.s.step;
    e.at_tap = at_tap_;
    e.at_time = at_time_;
    // a measurement's tap as taps.csv numbers it; otherwise the tap in progress, if any
    const std::optional<long> running = frame_info(w, view_, sim.gravity()).tap;
    if (at_tap_) e.tap = drive_phase(view_.drive, w.clock_origin, w.s.t + sim.dt()).tap;
    const std::optional<long> tap = at_tap_ ? std::optional<long>(e.tap) : running;
    const fs::path dir(dir_);
    if (spec_.vtp)
      write_vtp((dir / snapshot_file("snap", k, "vtp")).string(), w, c, tap.value_or(-1),
                spec_.vtp_binary ? VtpEncoding::Binary : VtpEncoding::Ascii);
    if (spec_.xyz)
      write_file(dir / snapshot_file("snap", k, "xyz"), [&](std::ostream& out) {
        write_trajectory_frame(out, w, &c, sim.gravity(), tap);
      });
    if (spec_.contacts)
      write_file(dir / snapshot_file("contacts", k, "csv"),
                 [&](std::ostream& out) { write_contacts_csv(out, w, c); });
    taken_.push_back(e);
    index_row(e, k);
    if (spec_.vtp) pvd_.add(e, k);
  }

  template <class F>
  static void write_file(const fs::path& path, F&& body) {
    std::ofstream out(path);
    if (!out) throw OutputError(path.string() + ": cannot write the snapshot");
    body(out);
    out.close();
    if (!out) throw OutputError(path.string() + ": write failed (disk full or removed?)");
  }

  void index_row(const SnapshotEntry& e, long k) {
    index_.row({static_cast<double>(k), e.t, static_cast<double>(e.step),
                static_cast<double>(e.tap), e.at_tap ? 1.0 : 0.0, e.at_time ? 1.0 : 0.0});
  }

  SnapshotSpec spec_;
  ViewSettings view_;
  std::string dir_;                        ///< DIR/snapshots
  std::vector<SnapshotEntry> taken_;       ///< every snapshot so far, in order
  std::int64_t next_k_ = 0;                ///< every_time: index of the next grid time
  std::size_t next_i_ = 0;                 ///< times: index of the next listed time
  bool at_time_ = false, at_tap_ = false;  ///< why the snapshot now due is taken
  CsvWriter index_;
  PvdFile pvd_;
};

}  // namespace

std::unique_ptr<Observer> make_snapshot_observer(const SceneSpec& scene) {
  if (!scene.output.snapshots.enabled()) return nullptr;
  return std::make_unique<SnapshotWriter>(scene);
}

}  // namespace gs
