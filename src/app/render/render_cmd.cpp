// `gransim render` and `gransim movie`: pictures of saved states, movies of runs
#include "app/render/render_cmd.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>

#include "app/progress.hpp"
#include "app/render/render_input.hpp"
#include "app/render/render_recorder.hpp"
#include "core/error.hpp"
#include "drive/schedule.hpp"
#include "output/particles/trajectory.hpp"
#include "output/png.hpp"
#include "output/run_dir.hpp"
#include "scene/parse.hpp"
#include "scene/render_section.hpp"
#include "sim/simulation.hpp"
#if defined(GS_HAVE_FFMPEG)
#include "output/movie/movie.hpp"
#endif

namespace gs {

namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------------------------------------
// flags → [render] keys, each checked with a message naming the flag

// a name from a list, or an InputError naming the flag and the list
std::string checked_name(const std::string& flag, const std::string& v,
                         std::span<const std::string_view> names) {
  std::string list;
  for (auto n : names) {
    if (n == v) return v;
    list += (list.empty() ? "" : ", ") + std::string(n);
  }
  throw InputError(flag, "", "unknown value '" + v + "' (known: " + list + ")");
}

// "a,b,c" (or "a b c") → exactly n finite numbers
std::vector<double> checked_numbers(const std::string& flag, std::string v, std::size_t n,
                                    const std::string& form) {
  std::replace(v.begin(), v.end(), ',', ' ');
  std::replace(v.begin(), v.end(), 'x', ' ');
  std::vector<double> out;
  std::size_t pos = 0;
  while (pos < v.size()) {
    if (v[pos] == ' ') {
      ++pos;
      continue;
    }
    std::size_t used = 0;
    double x = 0.0;
    try {
      x = std::stod(v.substr(pos), &used);
    } catch (...) {
      used = 0;
    }
    if (used == 0 || !std::isfinite(x))
      throw InputError(flag, "", "expected " + form + ", got '" + v + "'");
    out.push_back(x);
    pos += used;
  }
  if (out.size() != n) throw InputError(flag, "", "expected " + form + ", got '" + v + "'");
  return out;
}

void apply_flags(const RenderFlags& f, RenderSpec& r) {
  if (!f.color_by.empty())
    r.color_by = checked_name("--color-by", f.color_by, render_color_by_names());
  if (!f.colormap.empty())
    r.colormap = checked_name("--colormap", f.colormap, render_colormap_names());
  if (!f.renderer.empty())
    r.renderer = checked_name("--renderer", f.renderer, render_renderer_names());
  if (!f.size.empty()) {
    const auto wh = checked_numbers("--size", f.size, 2, "WIDTHxHEIGHT in px, e.g. 1280x720");
    for (double v : wh)
      if (v != std::floor(v) || v < 16 || v > 8192)
        throw InputError("--size", "",
                         "width and height must be integers in 16…8192 px (got '" + f.size + "')");
    r.width = static_cast<int>(wh[0]);
    r.height = static_cast<int>(wh[1]);
  }
  if (!f.range.empty()) {
    if (f.range == "auto") {
      r.range.reset();
    } else {
      const auto v = checked_numbers("--range", f.range, 2, "LO,HI or auto");
      if (!(v[1] > v[0])) throw InputError("--range", "", "needs LO < HI (got '" + f.range + "')");
      r.range = std::array<double, 2>{v[0], v[1]};
    }
  }
  if (!f.camera.empty()) {
    if (f.camera == "fit") {
      r.region.reset();
    } else {
      const auto v = checked_numbers("--camera", f.camera, 4, "X0,Y0,X1,Y1 in m, or fit");
      if (!(v[2] > v[0] && v[3] > v[1]))
        throw InputError("--camera", "", "needs X1 > X0 and Y1 > Y0 (got '" + f.camera + "')");
      r.region = std::array<double, 4>{v[0], v[1], v[2], v[3]};
    }
  }
  if (f.msaa != 0) {
    if (f.msaa < 1 || f.msaa > 16) throw InputError("--msaa", "", "must be in 1…16");
    r.msaa = f.msaa;
  }
  if (!f.title.empty()) r.title = f.title;
  if (f.no_colorbar) r.colorbar = false;
  if (f.chains) r.force_chains = true;
  if (f.no_clock) r.clock = false;
}

void add_render_flags(CLI::App* c, RenderFlags& f) {
  c->add_option("--scene", f.scene, "scene of the state (default: scene.toml beside it)");
  c->add_option("--set", f.sets, "override a scene key, e.g. --set render.colormap=magma");
  c->add_option("--color-by", f.color_by,
                "speed, speed_rms (|v|/v_rms), species, vy, contacts, pressure, uniform");
  c->add_option("--colormap", f.colormap, "viridis, magma, coolwarm, grayscale, turbo, jet");
  c->add_option("--size", f.size, "frame size WIDTHxHEIGHT in px (default 1280x720)");
  c->add_option("--range", f.range, "colour range LO,HI, or auto");
  c->add_option("--camera", f.camera, "show the region X0,Y0,X1,Y1 (m), or fit (the box)");
  c->add_option("--msaa", f.msaa, "samples per pixel of the GL backend (1…16)");
  c->add_option("--title", f.title, "a title line");
  c->add_option("--renderer", f.renderer, "auto, gl (OSMesa) or software");
  c->add_flag("--no-colorbar", f.no_colorbar, "no colour bar");
  c->add_flag("--chains", f.chains, "draw contact force chains (width ∝ normal force)");
  c->add_flag("--no-clock", f.no_clock, "no time and tap line");
}

// the frame information of a snapshot: recorded gravity and tap win over the schedule's
FrameInfo snapshot_info(const Snapshot& s, Vec2 scheduled_gravity) {
  FrameInfo info =
      frame_info(s.world, ViewSettings::from(s.scene), s.gravity.value_or(scheduled_gravity));
  // the tap of a saved state is only known when recorded, or when no relaxation ended early
  if (s.tap)
    info.tap = s.tap;
  else if (s.scene.drive.early_rest)
    info.tap.reset();
  return info;
}

// draw a world: with contacts (a Simulation computes them) when the frame needs them
Image draw(FrameMaker& maker, const Snapshot& s) {
  Simulation sim(s.world, SimSettings::from(s.scene));
  return maker.render(sim.world(), &sim.contacts(), snapshot_info(s, sim.gravity()));
}

// ---------------------------------------------------------------------------------------------
// movie sources

[[maybe_unused]] std::vector<fs::path> recorded_frames(const fs::path& dir) {
  std::vector<fs::path> out;
  const fs::path fd = dir / "frames";
  if (!fs::is_directory(fd)) return out;
  for (const auto& e : fs::directory_iterator(fd)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("frame_", 0) == 0 && e.path().extension() == ".png") out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  // frames are numbered without gaps (a resumed run continues the numbering): a missing frame
  // would jump in the movie, so it is an error naming the gap
  for (std::size_t k = 1; k < out.size(); ++k) {
    const auto number = [](const fs::path& p) {
      const std::string n = p.stem().string().substr(6);
      char* end = nullptr;
      const long v = std::strtol(n.c_str(), &end, 10);
      return (n.empty() || *end != '\0') ? -1L : v;
    };
    const long a = number(out[k - 1]), b = number(out[k]);
    if (a < 0 || b < 0 || b != a + 1)
      throw InputError(
          (dir / "frames").string(), "",
          "the recorded frames are not numbered consecutively: " + out[k].filename().string() +
              " follows " + out[k - 1].filename().string() + " (a frame is missing or misnamed)");
  }
  return out;
}

// frames in a trajectory, by their comment lines (for the progress display)
[[maybe_unused]] double trajectory_frames(const fs::path& p) {
  std::ifstream in(p);
  double n = 0;
  for (std::string line; std::getline(in, line);)
    n += line.find("Properties=") != std::string::npos;
  return n;
}

}  // namespace

int render_command(const RenderCommandOptions& o) {
  // default output: DIR/frame.png for a run directory, else beside the input
  const fs::path in(o.input);
  const std::string out = !o.out.empty()         ? o.out
                          : fs::is_directory(in) ? (in / "frame.png").string()
                                                 : fs::path(in).replace_extension(".png").string();
  // the output is checked before anything is drawn: a PNG, not an input, not a run's own file
  if (fs::path(out).extension() != ".png")
    throw InputError(out, "-o", "the picture is a PNG: the output name must end in .png");
  const std::vector<std::string> inputs = {
      o.input, fs::is_directory(in) ? (in / "state.csv").string() : "", o.flags.scene};
  check_output_file(out, inputs, "-o", [](const fs::path& p) {
    return p.parent_path().filename() != "frames" && p.filename() != "final.png";
  });
  SnapshotRequest req{o.flags.scene, o.flags.sets, o.frame};
  const Snapshot s = load_snapshot(o.input, req);
  RenderSpec r = s.scene.render;
  apply_flags(o.flags, r);
  FrameMaker maker(r, s.scene.path);
  const Image img = draw(maker, s);
  // a picture written into a run directory waits for no writer there
  const std::string run = run_dir_of(out);
  std::optional<DirLock> lock;
  if (!run.empty()) lock.emplace(run, "render");
  write_png(out, img);
  std::printf("wrote %s: %dx%d, %zu particles at t = %.6g s from the %s %s (%s)\n", out.c_str(),
              img.width, img.height, s.world.size(), s.world.s.t, s.kind.c_str(), s.source.c_str(),
              maker.describe().c_str());
  return kExitOk;
}

int movie_command(const MovieCommandOptions& o) {
#if !defined(GS_HAVE_FFMPEG)
  (void)o;
  throw InputError("movie", "", "this gransim was built without FFmpeg: no movies");
#else
  const fs::path in(o.input);
  if (!fs::exists(in)) throw InputError(o.input, "", "no such file or directory");
  // the source: recorded frames, or a trajectory drawn frame by frame
  const bool is_dir = fs::is_directory(in);
  const std::vector<fs::path> frames = is_dir ? recorded_frames(in) : std::vector<fs::path>{};
  const fs::path traj = is_dir ? in / "trajectory.xyz" : in;
  std::string from = o.from;
  if (from != "auto" && from != "frames" && from != "trajectory")
    throw InputError("--from", "", "must be frames, trajectory or auto (got '" + from + "')");
  if (from == "auto") from = !frames.empty() ? "frames" : "trajectory";
  if (from == "frames" && frames.empty())
    throw InputError(o.input, "",
                     "no recorded frames (frames/frame_*.png); record them with "
                     "render.frames = true, or use --from trajectory");
  if (from == "trajectory" && !(fs::is_regular_file(traj) && traj.extension() == ".xyz"))
    throw InputError(o.input, "",
                     is_dir ? "neither recorded frames nor trajectory.xyz (set render.frames = "
                              "true or render.trajectory_every in the scene)"
                            : "expected a run directory or a trajectory (.xyz)");

  // the encoder settings: flags, else the scene's [render] section, else the defaults
  RenderSpec r;
  std::string scene_path;
  const SnapshotRequest req{o.flags.scene, o.flags.sets, -1};
  if (from == "trajectory" || fs::exists((is_dir ? in : in.parent_path()) / "scene.toml") ||
      !o.flags.scene.empty()) {
    scene_path = scene_for(in, req);
    r = parse_scene_file(scene_path, o.flags.sets).render;
  }
  apply_flags(o.flags, r);
  MovieOptions mo;
  mo.fps = o.fps > 0 ? o.fps : r.fps;
  mo.crf = o.crf >= 0 ? o.crf : r.crf;
  mo.preset =
      o.preset.empty() ? r.preset : checked_name("--preset", o.preset, render_preset_names());
  if (mo.crf > 51) throw InputError("--crf", "", "must be in 0…51");
  const std::string out = !o.out.empty()
                              ? o.out
                              : (is_dir ? (in / "movie.mp4").string()
                                        : fs::path(in).replace_extension(".mp4").string());
  if (fs::exists(out) && !o.force)
    throw InputError(out, "", "exists; choose another -o or pass --force to replace it");
  if (fs::path(out).extension() != ".mp4")
    throw InputError(out, "-o", "the movie is an MP4: the output name must end in .mp4");
  check_output_file(out, {o.input, o.flags.scene}, "-o",
                    [](const fs::path& p) { return p.extension() == ".mp4"; });
  // a movie written into a run directory waits for no writer there
  const std::string run = run_dir_of(out);
  std::optional<DirLock> lock;
  if (!run.empty()) lock.emplace(run, "movie");

  MovieEncoder enc;
  int w = 0, h = 0;
  auto add = [&](const Image& img, const std::string& what) {
    if (!enc.is_open()) {
      w = img.width, h = img.height;
      enc.open(out, w, h, mo);
    }
    if (img.width != w || img.height != h)
      throw InputError(what, "",
                       "frame size " + std::to_string(img.width) + "x" +
                           std::to_string(img.height) + " differs from the first (" +
                           std::to_string(w) + "x" + std::to_string(h) + ")");
    enc.add_frame(img);
  };
  if (from == "frames") {
    Progress progress("movie", static_cast<double>(frames.size()), "frames", o.quiet);
    for (std::size_t k = 0; k < frames.size(); ++k) {
      add(read_png(frames[k].string()), frames[k].string());
      progress.update(static_cast<double>(k + 1));
    }
    progress.finish("");
  } else {
    // each trajectory frame drawn like `render` draws a state
    Snapshot s = scene_snapshot(scene_path, o.flags.sets, traj.string(), "trajectory");
    FrameMaker maker(r, scene_path);
    TrajectoryReader reader(traj.string());
    TrajectoryFrame f;
    Progress progress("movie", trajectory_frames(traj), "frames", o.quiet);
    while (reader.next(f)) {
      load_trajectory_frame(s.world, f, traj.string());
      s.gravity = f.gravity;
      s.tap = f.tap;
      add(draw(maker, s), traj.string());
      progress.update(reader.frames());
    }
    progress.finish("");
  }
  if (!enc.is_open()) throw InputError(o.input, "", "no frames to encode");
  const std::string codec = enc.codec_name();
  enc.close();
  std::printf("wrote %s: %d frames, %dx%d, %.2f s at %d fps (%s, from %s)\n", out.c_str(),
              enc.frames(), w, h, enc.frames() / static_cast<double>(mo.fps), mo.fps, codec.c_str(),
              from.c_str());
  return kExitOk;
#endif
}

// ---------------------------------------------------------------------------------------------
// command line

struct RenderCommands {
  CLI::App* render = nullptr;
  CLI::App* movie = nullptr;
  RenderCommandOptions ro;
  MovieCommandOptions mo;
};

std::shared_ptr<RenderCommands> add_render_commands(CLI::App& app) {
  auto rc = std::make_shared<RenderCommands>();
  // render: one saved state → PNG
  CLI::App* r = app.add_subcommand("render",
                                   "draw a saved state (run directory, state file, "
                                   "trajectory frame) as a PNG");
  r->add_option("input", rc->ro.input, "run directory, state file (.csv) or trajectory (.xyz)")
      ->required();
  r->add_option("-o,--out", rc->ro.out, "PNG file (default DIR/frame.png or INPUT.png)");
  r->add_option("--frame", rc->ro.frame, "trajectory frame, from 0 (default: the last)");
  add_render_flags(r, rc->ro.flags);
  rc->render = r;
  // movie: a run's frames or trajectory → MP4
  CLI::App* m = app.add_subcommand("movie",
                                   "encode a run's recorded frames, or draw its "
                                   "trajectory, into an MP4");
  m->add_option("input", rc->mo.input, "run directory or trajectory (.xyz)")->required();
  m->add_option("-o,--out", rc->mo.out, "MP4 file (default DIR/movie.mp4)");
  m->add_option("--from", rc->mo.from, "frames, trajectory or auto (frames when recorded)");
  // given values are checked (0 or −5 fps is an error, not "the default")
  m->add_option("--fps", rc->mo.fps, "frames per second, 1…240 (default render.fps)")
      ->check(CLI::Range(1, 240));
  m->add_option("--crf", rc->mo.crf, "x264 quality 0…51 (default render.crf)")
      ->check(CLI::Range(0, 51));
  m->add_option("--preset", rc->mo.preset, "x264 preset (default render.preset)");
  m->add_flag("--force", rc->mo.force, "replace an existing output file");
  m->add_flag("-q,--quiet", rc->mo.quiet, "no progress display");
  add_render_flags(m, rc->mo.flags);
  rc->movie = m;
  return rc;
}

std::optional<int> dispatch_render_commands(const RenderCommands& rc) {
  if (rc.render && *rc.render) return render_command(rc.ro);
  if (rc.movie && *rc.movie) return movie_command(rc.mo);
  return std::nullopt;
}

}  // namespace gs
