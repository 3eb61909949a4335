// the program end to end: `gransim run` with a [render] section (frames, movie, trajectory),
// `gransim render` of a run directory, `gransim movie` from frames and from the trajectory,
// and bad render options (exit 2 with a message naming the flag or key)
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "binary.hpp"
#include "geometry/polygon.hpp"
#include "output/particles/trajectory.hpp"
#include "output/png.hpp"
#include "scene/parse.hpp"
#include "sim/state_file.hpp"
#include "view/render_world.hpp"
#include "world/prepare.hpp"
#if defined(GS_HAVE_FFMPEG)
#include "output/movie/movie.hpp"
#endif

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::slurp;

fs::path scratch() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("gs_render_cmd_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

/// run gransim with arguments; its exit code, stderr in `err`
int gransim(const std::string& args, std::string* err = nullptr) {
  const fs::path e = scratch() / "stderr.txt";
  const std::string cmd = "OMP_NUM_THREADS=1 '" + std::string(GS_BINARY) + "' " + args + " >'" +
                          (scratch() / "stdout.txt").string() + "' 2>'" + e.string() + "'";
  const int rc = std::system(cmd.c_str());
  if (err) *err = slurp(e);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// 30 decagons falling in a 0.12 m box for 0.05 s (1000 steps), recorded at 30 fps in 2× slow
// motion (frames at t = 0, 1/60, 2/60, 3/60 s: 4 frames) at 320×240 by the software renderer,
// and a trajectory frame every 250 steps (steps 0, 250, 500, 750, 1000: 5 frames)
const char* kScene = R"(
[scene]
duration = 0.05

[[species]]
name = "g"
radius = 0.008
count = 30

[box]
width = 0.12
height = 0.2

[integrator]
kind = "velocity_verlet"
dt = 5e-5

[render]
enabled = true
frames = true
movie = true
fps = 30
slowmo = 2.0
size = [320, 240]
renderer = "software"
preset = "ultrafast"
trajectory_every = 250
)";

// one run for every test of the program (made once)
const fs::path& run_dir() {
  static const fs::path dir = [] {
    const fs::path scene = scratch() / "tiny.toml";
    std::string text = kScene;
#if !defined(GS_HAVE_FFMPEG)
    text.replace(text.find("movie = true"), 12, "movie = false");  // no encoder in this build
#endif
    std::ofstream(scene) << text;
    const fs::path out = scratch() / "run";
    std::string err;
    const int rc =
        gransim("run '" + scene.string() + "' --out '" + out.string() + "' --quiet", &err);
    EXPECT_EQ(rc, 0) << err;
    return out;
  }();
  return dir;
}

TEST(RenderCommand, RunRecordsTheScheduledFramesAndMovie) {
  const fs::path& run = run_dir();
  // four PNG frames of 320×240, listed in frames.csv with their times
  for (int k = 0; k < 4; ++k) {
    const fs::path f = run / "frames" / ("frame_00000" + std::to_string(k) + ".png");
    ASSERT_TRUE(fs::exists(f)) << f;
    const Image img = read_png(f.string());
    EXPECT_EQ(img.width, 320);
    EXPECT_EQ(img.height, 240);
  }
  EXPECT_FALSE(fs::exists(run / "frames" / "frame_000004.png"));
  std::ifstream idx(run / "frames.csv");
  std::string line;
  std::getline(idx, line);
  EXPECT_EQ(line, "frame,t,step,tap,gx,gy");
  std::vector<double> times;
  while (std::getline(idx, line)) times.push_back(std::stod(line.substr(line.find(',') + 1)));
  ASSERT_EQ(times.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(times[k], k / 60.0, 2.6e-5);  // within half a step
#if defined(GS_HAVE_FFMPEG)
  // the movie decodes to the same four frames
  const MovieInfo m = probe_movie((run / "movie.mp4").string());
  EXPECT_EQ(m.frames, 4);
  EXPECT_EQ(m.width, 320);
  EXPECT_EQ(m.height, 240);
  EXPECT_NEAR(m.fps, 30.0, 1e-6);
#endif
}

TEST(RenderCommand, TrajectoryParsesBackToTheFinalState) {
  const fs::path& run = run_dir();
  // 5 frames of 30 particle lines with 12 columns, after a count and a comment line
  std::ifstream in(run / "trajectory.xyz");
  std::string line;
  int frames = 0;
  while (std::getline(in, line)) {
    EXPECT_EQ(line, "30");
    std::getline(in, line);
    EXPECT_NE(line.find("Properties=species:S:1:pos:R:3"), std::string::npos) << line;
    EXPECT_NE(line.find("Lattice=\"0.12 0 0 0 0.2 0 0 0 1\""), std::string::npos) << line;
    for (int i = 0; i < 30; ++i) {
      ASSERT_TRUE(std::getline(in, line));
      std::istringstream ls(line);
      std::vector<std::string> cols;
      for (std::string c; ls >> c;) cols.push_back(c);
      ASSERT_EQ(cols.size(), 22u) << line;
      EXPECT_EQ(cols[0], "H");                // species 0 as an element symbol (ASE, OVITO)
      EXPECT_EQ(cols[4], "g");                // its name
      EXPECT_EQ(cols[5], "0");                // its index
      EXPECT_EQ(cols[6], std::to_string(i));  // label
      EXPECT_EQ(cols[16], "0");               // ω as the vector (0, 0, ω)
      EXPECT_EQ(cols[17], "0");
      EXPECT_EQ(cols[20], "10");  // sides
    }
    ++frames;
  }
  EXPECT_EQ(frames, 5);
  // the reader gives the last frame = the final state (step 1000) to the written precision
  TrajectoryReader reader((run / "trajectory.xyz").string());
  TrajectoryFrame f, last;
  while (reader.next(f)) last = f;
  EXPECT_EQ(reader.frames(), 5);
  EXPECT_EQ(last.step, 1000);
  EXPECT_NEAR(last.time, 0.05, 1e-12);
  ASSERT_TRUE(last.gravity);
  EXPECT_NEAR(last.gravity->y, -9.81, 1e-12);
  World w = make_world(parse_scene_file((run / "scene.toml").string()));
  read_state_file(w, (run / "state.csv").string());
  ASSERT_EQ(last.size(), w.size());
  for (std::size_t i = 0; i < w.size(); ++i) {
    EXPECT_NEAR(last.x[i], w.s.x[i], 1e-10);
    EXPECT_NEAR(last.y[i], w.s.y[i], 1e-10);
    EXPECT_NEAR(last.theta[i], w.s.th[i], 1e-9);
    EXPECT_NEAR(last.vy[i], w.s.vy[i], 1e-7);
    EXPECT_NEAR(last.speed[i], std::hypot(w.s.vx[i], w.s.vy[i]), 1e-7);
    EXPECT_NEAR(last.omega[i], w.s.omega[i], 1e-7 * (1.0 + std::abs(w.s.omega[i])));
    EXPECT_EQ(last.radius[i], 0.008);
    EXPECT_EQ(last.species[i], "g");  // the name column, not the symbol
  }
}

// trajectories written before the ASE/OVITO columns (species names in `species`, a single ω
// column) still read: `movie` and `render` take both
TEST(RenderCommand, TrajectoryReaderTakesTheOlderColumnsToo) {
  const fs::path p = scratch() / "old.xyz";
  std::ofstream(p)
      << "2\nLattice=\"0.2 0 0 0 0.6 0 0 0 1\" Origin=\"0 0 -0.5\" "
         "Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1:theta:R:1:omega:R:1:"
         "speed:R:1:sides:I:1 Time=0.025 Step=500 Gravity=\"0 -9.81 0\" pbc=\"F F F\"\n"
         "small 0.01 0.02 0 0.5 -0.25 0 0.00636 6.27 1.5 0.56 10\n"
         "big 0.03 0.04 0 0 0 0 0.009 0.1 -2.5 0 10\n";
  TrajectoryReader reader(p.string());
  TrajectoryFrame f;
  ASSERT_TRUE(reader.next(f));
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f.species[0], "small");
  EXPECT_EQ(f.species[1], "big");
  EXPECT_EQ(f.omega[0], 1.5);
  EXPECT_EQ(f.omega[1], -2.5);
  EXPECT_EQ(f.theta[0], 6.27);
  EXPECT_EQ(f.vx[0], 0.5);
  EXPECT_EQ(f.step, 500);
  EXPECT_FALSE(reader.next(f));
}

TEST(RenderCommand, RenderOfARunDirectoryDrawsItsParticles) {
  const fs::path& run = run_dir();
  const fs::path png = scratch() / "frame.png";
  std::string err;
  ASSERT_EQ(gransim("render '" + run.string() + "' -o '" + png.string() +
                        "' --size 400x300 --color-by uniform --no-colorbar --no-clock "
                        "--renderer software",
                    &err),
            0)
      << err;
  const Image img = read_png(png.string());
  ASSERT_EQ(img.width, 400);
  ASSERT_EQ(img.height, 300);
  // the grains are filled with the uniform colour: count those pixels against the grains'
  // area on the canvas (the camera as the frame builder fits it; outlines take a little)
  const SceneSpec scene = parse_scene_file((run / "scene.toml").string());
  World w = make_world(scene);
  read_state_file(w, (run / "state.csv").string());
  RenderSpec r = scene.render;
  r.width = 400;
  r.height = 300;
  r.color_by = "uniform";
  r.colorbar = false;
  r.clock = false;
  const WorldFrame wf = world_frame(w, nullptr, frame_info(w, ViewSettings::from(scene), {}), r);
  const FrameData fd = build_frame(wf.particles, wf.walls, wf.overlays, wf.spec, wf.box);
  const Rgba8 fill = wf.spec.uniform_color;
  long count = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.pixel(x, y);
      count += std::abs(p[0] - fill.r) + std::abs(p[1] - fill.g) + std::abs(p[2] - fill.b) < 12;
    }
  const double area_px = 30 * ngon_area(10, 0.008) * fd.camera.scale * fd.camera.scale;
  EXPECT_GT(count, 0.6 * area_px);
  EXPECT_LT(count, 1.02 * area_px);
}

#if defined(GS_HAVE_FFMPEG)
TEST(RenderCommand, MovieFromFramesAndFromTheTrajectory) {
  const fs::path& run = run_dir();
  std::string err;
  const fs::path a = scratch() / "from_frames.mp4", b = scratch() / "from_traj.mp4";
  ASSERT_EQ(gransim("movie '" + run.string() + "' -o '" + a.string() + "' --fps 10 -q", &err), 0)
      << err;
  const MovieInfo ma = probe_movie(a.string());
  EXPECT_EQ(ma.frames, 4);
  EXPECT_NEAR(ma.fps, 10.0, 1e-6);
  ASSERT_EQ(gransim("movie '" + run.string() + "' -o '" + b.string() +
                        "' --from trajectory --size 200x160 -q",
                    &err),
            0)
      << err;
  const MovieInfo mb = probe_movie(b.string());
  EXPECT_EQ(mb.frames, 5);
  EXPECT_EQ(mb.width, 200);
  EXPECT_EQ(mb.height, 160);
  // the default output is the run's movie.mp4, which the run wrote: not replaced silently
  EXPECT_EQ(gransim("movie '" + run.string() + "' -q", &err), 2);
  EXPECT_NE(err.find("--force"), std::string::npos) << err;
}
#endif

TEST(RenderCommand, BadOptionsExitWithTwoAndSayWhy) {
  const fs::path& run = run_dir();
  const std::string r =
      "render '" + run.string() + "' -o '" + (scratch() / "x.png").string() + "' ";
  std::string err;
  EXPECT_EQ(gransim(r + "--color-by temperature", &err), 2);
  EXPECT_NE(err.find("--color-by: unknown value 'temperature' (known: speed"), std::string::npos)
      << err;
  EXPECT_EQ(gransim(r + "--size 640", &err), 2);
  EXPECT_NE(err.find("--size"), std::string::npos) << err;
  EXPECT_EQ(gransim(r + "--range 2,1", &err), 2);
  EXPECT_NE(err.find("--range: needs LO < HI"), std::string::npos) << err;
  EXPECT_EQ(gransim(r + "--colormap rainbow", &err), 2);
  EXPECT_NE(err.find("viridis"), std::string::npos) << err;
  EXPECT_EQ(gransim(r + "--camera 0,0,1", &err), 2);
  EXPECT_NE(err.find("--camera"), std::string::npos) << err;
  EXPECT_EQ(gransim(r + "--frame 9 --renderer software", &err), 0) << err;  // ignored for states
  EXPECT_EQ(gransim("render '" + (run / "trajectory.xyz").string() + "' --frame 9 -o '" +
                        (scratch() / "y.png").string() + "'",
                    &err),
            2);
  EXPECT_NE(err.find("asked for frame 9 but the trajectory has 5"), std::string::npos) << err;
  // an input that is not a saved state, and a state without a scene
  EXPECT_EQ(gransim("render '" + scratch().string() + "/nothing'", &err), 2);
  EXPECT_NE(err.find("no such file"), std::string::npos) << err;
  const fs::path lone = scratch() / "lone";
  fs::create_directories(lone);
  fs::copy_file(run / "state.csv", lone / "state.csv", fs::copy_options::overwrite_existing);
  EXPECT_EQ(gransim("render '" + (lone / "state.csv").string() + "'", &err), 2);
  EXPECT_NE(err.find("--scene"), std::string::npos) << err;
  // a bad [render] key stops `run` before anything is simulated, naming file, line and key
  const fs::path bad = scratch() / "bad.toml";
  std::string text = kScene;
  text.replace(text.find("size = [320, 240]"), 17, "size = [320, 8]");
  std::ofstream(bad) << text;
  EXPECT_EQ(
      gransim("run '" + bad.string() + "' --out '" + (scratch() / "bad").string() + "'", &err), 2);
  const int line =
      1 + static_cast<int>(std::count(text.begin(), text.begin() + text.find("size ="), '\n'));
  EXPECT_NE(err.find("bad.toml:" + std::to_string(line) + ": key 'render.size'"), std::string::npos)
      << err;
}

}  // namespace
}  // namespace gs
