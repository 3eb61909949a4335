// the frame recorder and the trajectory writers: observers that sample on their own schedule
#include "app/render/render_recorder.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "drive/schedule.hpp"
#include "output/csv.hpp"
#include "output/particles/h5md.hpp"
#include "output/particles/trajectory.hpp"
#include "output/png.hpp"
#include "sim/simulation.hpp"
#if defined(GS_HAVE_FFMPEG)
#include "output/movie/movie.hpp"
#endif

namespace gs {

namespace fs = std::filesystem;

bool movie_encoder_available() {
#if defined(GS_HAVE_FFMPEG)
  return true;
#else
  return false;
#endif
}

std::string frame_file_name(int k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%06d.png", k);
  return buf;
}

namespace {

// ---------------------------------------------------------------------------------------------
// frames and movie on the [render] schedule

class FrameRecorder final : public Observer {
 public:
  explicit FrameRecorder(const SceneSpec& scene)
      : spec_(scene.render), view_(ViewSettings::from(scene)), where_(scene.path) {}

  const char* name() const override { return "frames"; }

  void start(const Simulation& sim, const std::string& dir) override {
    open_outputs(dir, "movie.mp4");
    index_ = CsvWriter((fs::path(dir) / kFrameIndexFile).string(),
                       {"frame", "t", "step", "tap", "gx", "gy"});
    // the initial state is frame 0 of the time and step schedules
    const World& w = sim.world();
    prev_ = drive_phase(view_.drive, w.clock_origin, w.s.t);
    if (spec_.schedule == RenderSchedule::Time || spec_.schedule == RenderSchedule::Steps)
      if (due(sim)) capture(sim);
  }

  void after_step(const Simulation& sim) override {
    if (due(sim)) capture(sim);
  }

  // the movie is closed, and the last state drawn to DIR/final.png: the still a user looks at
  void finish(const Simulation& sim) override {
#if defined(GS_HAVE_FFMPEG)
    if (movie_ && movie_->is_open()) movie_->close();
#endif
    if (maker_ && !dir_.empty()) {
      const World& w = sim.world();
      write_png((fs::path(dir_) / "final.png").string(),
                maker_->render(w, &sim.contacts(), frame_info(w, view_, sim.gravity())));
    }
  }

  void save(ByteWriter& out) const override {
    out.i64(count_);
    out.i64(next_k_);
  }

  // frames continue their numbering; an MP4 cannot be reopened for appending, so the movie
  // after a resume is a new file, movie_from_<frame>.mp4 (join with ffmpeg's concat demuxer)
  void resume(const Simulation& sim, const std::string& dir, ByteReader& in) override {
    count_ = static_cast<int>(in.i64("frames: count"));
    next_k_ = static_cast<long>(in.i64("frames: next frame time"));
    open_outputs(dir, "movie_from_" + std::to_string(count_) + ".mp4");
    index_ = CsvWriter::append((fs::path(dir) / kFrameIndexFile).string(), 6);
    const World& w = sim.world();
    prev_ = drive_phase(view_.drive, w.clock_origin, w.s.t);
  }

 private:
  void open_outputs(const std::string& dir, const std::string& movie_name) {
    dir_ = dir;
    maker_ = std::make_unique<FrameMaker>(spec_, where_);
    if (spec_.frames) {
      frames_dir_ = (fs::path(dir) / "frames").string();
      fs::create_directories(frames_dir_);
    }
#if defined(GS_HAVE_FFMPEG)
    if (spec_.movie) {
      MovieOptions o;
      o.fps = spec_.fps;
      o.crf = spec_.crf;
      o.preset = spec_.preset;
      movie_ = std::make_unique<MovieEncoder>();
      movie_->open((fs::path(dir) / movie_name).string(), spec_.width, spec_.height, o);
    }
#else
    (void)movie_name;
#endif
  }

  // is a frame due after this step?
  bool due(const Simulation& sim) {
    const World& w = sim.world();
    const double t = w.s.t, half = 0.5 * sim.dt();
    // the protocol phase: does this step begin an excitation?
    const DriveSpec& d = view_.drive;
    const DrivePhase now = drive_phase(d, w.clock_origin, t);
    const bool begins = is_tapping(d) && !now.settling && now.exciting &&
                        (prev_.settling || !prev_.exciting || prev_.tap != now.tap);
    prev_ = now;
    switch (spec_.schedule) {
      case RenderSchedule::Time: {
        // frame k at start + k/(fps·slowmo); several inside one step give one frame
        const double interval = 1.0 / (spec_.fps * spec_.slowmo);
        auto at = [&](long k) { return spec_.start + static_cast<double>(k) * interval; };
        // a pulse shorter than the frame interval gets a frame of its own (else the movie
        // might never show it)
        if (begins && t + half >= spec_.start && excitation_length(d) < interval) return true;
        // frame times closer than a step: a frame after every step from the start (no frame
        // index to count, however fine the schedule)
        if (interval <= sim.dt()) return t + half >= spec_.start;
        if (t + half < at(next_k_)) return false;
        // the first frame time after this step: jump near it, then settle with the same
        // comparison (a slow-motion schedule may pass many frame times in one step)
        long k =
            std::max(next_k_, static_cast<long>(std::floor((t + half - spec_.start) / interval)));
        while (k > next_k_ && at(k - 1) > t + half) --k;
        while (at(k) <= t + half) ++k;
        next_k_ = k;
        return true;
      }
      case RenderSchedule::Steps:
        return t + half >= spec_.start && w.s.step % spec_.every == 0;
      case RenderSchedule::Taps:
      case RenderSchedule::Rest: {
        // the first step of an excitation, and the last step before the next one
        if (t + half < spec_.start) return false;
        const bool rest = excitation_starts_next(d, w.clock_origin, t, sim.dt());
        return rest || (spec_.schedule == RenderSchedule::Taps && begins);
      }
    }
    return false;
  }

  // draw the frame and hand it to the PNG writer and/or the encoder
  void capture(const Simulation& sim) {
    const World& w = sim.world();
    const FrameInfo info = frame_info(w, view_, sim.gravity());
    const Image img = maker_->render(w, &sim.contacts(), info);
    if (!frames_dir_.empty())
      write_png((fs::path(frames_dir_) / frame_file_name(count_)).string(), img);
#if defined(GS_HAVE_FFMPEG)
    if (movie_) movie_->add_frame(img);
#endif
    index_.row({static_cast<double>(count_), w.s.t, static_cast<double>(w.s.step),
                info.tap ? static_cast<double>(*info.tap) : -1.0, info.gravity.x, info.gravity.y});
    ++count_;
  }

  RenderSpec spec_;
  ViewSettings view_;
  std::string where_;  ///< the scene file, for messages
  std::unique_ptr<FrameMaker> maker_;
  std::string dir_;         ///< the run directory
  std::string frames_dir_;  ///< DIR/frames ("" when no PNG frames)
#if defined(GS_HAVE_FFMPEG)
  std::unique_ptr<MovieEncoder> movie_;
#endif
  CsvWriter index_;
  int count_ = 0;    ///< frames recorded
  long next_k_ = 0;  ///< time schedule: index of the next frame time
  DrivePhase prev_;  ///< tap schedules: the phase after the previous step
};

// ---------------------------------------------------------------------------------------------
// DIR/trajectory.xyz every N steps (and the initial state)

class TrajectoryWriter final : public Observer {
 public:
  TrajectoryWriter(int every, const SceneSpec& scene)
      : every_(every), view_(ViewSettings::from(scene)) {}
  const char* name() const override { return "trajectory"; }
  void save(ByteWriter&) const override {}  // frames are on disk; the run truncates the file
  void resume(const Simulation&, const std::string& dir, ByteReader&) override {
    path_ = (fs::path(dir) / "trajectory.xyz").string();
    out_.open(path_, std::ios::app);
    if (!out_) throw InputError(path_, "", "cannot append to the trajectory");
  }

  void start(const Simulation& sim, const std::string& dir) override {
    path_ = (fs::path(dir) / "trajectory.xyz").string();
    out_.open(path_);
    if (!out_) throw InputError(path_, "", "cannot write the trajectory");
    write(sim);
  }
  void after_step(const Simulation& sim) override {
    if (sim.world().s.step % every_ == 0) write(sim);
  }
  std::int64_t quiet_steps(const Simulation& sim) const override {
    return every_ - 1 - sim.world().s.step % every_;  // the steps before the next frame's
  }
  void finish(const Simulation&) override { out_.close(); }

 private:
  void write(const Simulation& sim) {
    const World& w = sim.world();
    write_trajectory_frame(out_, w, &sim.contacts(), sim.gravity(),
                           frame_info(w, view_, sim.gravity()).tap);
    out_.flush();  // a frame on disk is a frame kept, whatever happens next
    if (!out_) throw OutputError(path_ + ": write failed (disk full or removed?)");
  }
  int every_;
  ViewSettings view_;
  std::string path_;
  std::ofstream out_;
};

// ---------------------------------------------------------------------------------------------
// DIR/trajectory.h5md every N steps (and the initial state)

class H5mdTrajectoryWriter final : public Observer {
 public:
  H5mdTrajectoryWriter(int every, const SceneSpec& scene)
      : every_(every), view_(ViewSettings::from(scene)) {}
  const char* name() const override { return "trajectory_h5md"; }
  // an HDF5 file cannot be cut back to a byte size: the checkpoint keeps its frame count
  void save(ByteWriter& out) const override { out.i64(h5_.frames()); }
  // a file moved aside (damaged by a kill inside a write) is started afresh at the checkpoint
  void resume(const Simulation& sim, const std::string& dir, ByteReader& in) override {
    const std::int64_t frames = in.i64("trajectory_h5md: frames");
    const std::string path = (fs::path(dir) / kH5mdTrajectoryFile).string();
    std::error_code ec;
    if (fs::exists(path, ec)) {
      h5_.reopen(path, sim.world(), frames);
      return;
    }
    std::fprintf(stderr, "gransim: %s is missing; a new one starts at the checkpoint (step %lld)\n",
                 path.c_str(), static_cast<long long>(sim.world().s.step));
    h5_.create(path, sim.world());
  }
  void start(const Simulation& sim, const std::string& dir) override {
    h5_.create((fs::path(dir) / kH5mdTrajectoryFile).string(), sim.world());
    write(sim);
  }
  void after_step(const Simulation& sim) override {
    if (sim.world().s.step % every_ == 0) write(sim);
  }
  std::int64_t quiet_steps(const Simulation& sim) const override {
    return every_ - 1 - sim.world().s.step % every_;
  }
  void finish(const Simulation&) override { h5_.close(); }

 private:
  void write(const Simulation& sim) {
    const World& w = sim.world();
    h5_.write(w, &sim.contacts(), sim.gravity(), frame_info(w, view_, sim.gravity()).tap);
  }
  int every_;
  ViewSettings view_;
  H5mdWriter h5_;
};

}  // namespace

void add_render_observers(const SceneSpec& scene, Observers& observers) {
  const RenderSpec& r = scene.render;
  if (r.enabled) {
    if (r.movie && !movie_encoder_available())
      throw InputError(scene.path, "render.movie",
                       "this gransim was built without FFmpeg; set render.movie = false and "
                       "render.frames = true, then `gransim movie` elsewhere");
    observers.push_back(std::make_unique<FrameRecorder>(scene));
  }
  if (r.trajectory_every > 0 && r.trajectory_xyz)
    observers.push_back(std::make_unique<TrajectoryWriter>(r.trajectory_every, scene));
  if (r.trajectory_every > 0 && r.trajectory_h5md)
    observers.push_back(std::make_unique<H5mdTrajectoryWriter>(r.trajectory_every, scene));
}

}  // namespace gs
