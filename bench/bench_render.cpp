// render benchmarks: frames per second of the frame builder and the backends, and the
// render + encode throughput of the movie path (Google Benchmark; no main here)
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>

#include "app/render/render_input.hpp"
#include "app/render/render_recorder.hpp"
#include "output/png.hpp"
#include "render/demo_scene.hpp"
#include "render/renderer.hpp"
#include "sim/simulation.hpp"
#if defined(GS_HAVE_FFMPEG)
#include "output/movie/movie.hpp"
#endif

namespace gs {
namespace {

// the tapping paper's pile: 544 + 640 decagons filling 0.48 m × ~0.53 m
const DemoScene& pile() {
  static const DemoScene s = demo_decagon_pile();
  return s;
}

// 10⁴ disks in a periodic unit box at area fraction 0.3
const DemoScene& gas() {
  static const DemoScene s = demo_disk_gas(10000);
  return s;
}

FrameSpec spec(int w, int h, int msaa) {
  FrameSpec f;
  f.width = w;
  f.height = h;
  f.msaa = msaa;
  return f;
}

// one renderer per kind for the whole run (context and shaders are made once); never
// destroyed, since OSMesa is torn down before static destructors would run
Renderer& renderer(RendererKind kind) {
  static Renderer* gl = nullptr;
  static Renderer* sw = nullptr;
  Renderer*& slot = kind == RendererKind::gl ? gl : sw;
  if (!slot) slot = make_renderer(kind).release();
  return *slot;
}

// state → FrameData only (camera, colours, overlays)
void BM_BuildFramePile720p(benchmark::State& st) {
  const DemoScene& s = pile();
  const FrameSpec f = spec(1280, 720, 4);
  for (auto _ : st)
    benchmark::DoNotOptimize(build_frame(s.particles, s.walls, s.overlays, f, s.box));
  st.counters["fps"] = benchmark::Counter(st.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BuildFramePile720p)->Unit(benchmark::kMillisecond);

// build + draw + read back one frame
void render_bench(benchmark::State& st, const DemoScene& s, int w, int h, int msaa,
                  RendererKind kind) {
  Renderer* r = nullptr;
  try {
    r = &renderer(kind);
  } catch (const std::exception& e) {
    st.SkipWithError(e.what());
    return;
  }
  const FrameSpec f = spec(w, h, msaa);
  r->render(build_frame(s.particles, s.walls, s.overlays, f, s.box));  // warm up (shader JIT)
  for (auto _ : st) {
    const Image img = r->render(build_frame(s.particles, s.walls, s.overlays, f, s.box));
    benchmark::DoNotOptimize(img.rgba.data());
  }
  st.counters["fps"] = benchmark::Counter(st.iterations(), benchmark::Counter::kIsRate);
  st.SetLabel(r->describe());
}

void BM_RenderPile720pMsaa4Gl(benchmark::State& st) {
  render_bench(st, pile(), 1280, 720, 4, RendererKind::gl);
}
void BM_RenderPile720pSoftware(benchmark::State& st) {
  render_bench(st, pile(), 1280, 720, 1, RendererKind::software);
}
void BM_RenderDisks10k800Gl(benchmark::State& st) {
  render_bench(st, gas(), 800, 800, 4, RendererKind::gl);
}
void BM_RenderDisks10k800Software(benchmark::State& st) {
  render_bench(st, gas(), 800, 800, 1, RendererKind::software);
}
#if defined(GS_HAVE_OSMESA)
BENCHMARK(BM_RenderPile720pMsaa4Gl)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RenderDisks10k800Gl)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif
BENCHMARK(BM_RenderPile720pSoftware)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RenderDisks10k800Software)->Unit(benchmark::kMillisecond)->UseRealTime();

// a 720p frame written as PNG
void BM_WritePng720p(benchmark::State& st) {
  const DemoScene& s = pile();
  const FrameData f = build_frame(s.particles, s.walls, s.overlays, spec(1280, 720, 1), s.box);
  const Image img = renderer(RendererKind::software).render(f);
  const std::string path = (std::filesystem::temp_directory_path() / "gs_bench_frame.png").string();
  for (auto _ : st) write_png(path, img);
  st.counters["fps"] = benchmark::Counter(st.iterations(), benchmark::Counter::kIsRate);
  std::filesystem::remove(path);
}
BENCHMARK(BM_WritePng720p)->Unit(benchmark::kMillisecond);

#if defined(GS_HAVE_FFMPEG)
// render + H.264 encode of 720p frames (x264 preset from the argument: 0 medium, 1 veryfast)
void BM_RenderEncode720p(benchmark::State& st) {
  const DemoScene& s = pile();
  Renderer& r = renderer(RendererKind::gl);
  const FrameSpec f = spec(1280, 720, 4);
  MovieOptions o;
  o.preset = st.range(0) == 0 ? "medium" : "veryfast";
  const std::string path = (std::filesystem::temp_directory_path() / "gs_bench_movie.mp4").string();
  MovieEncoder enc;
  enc.open(path, f.width, f.height, o);
  RenderOverlays ov = s.overlays;
  int k = 0;
  for (auto _ : st) {
    ov.time = k++ / 30.0;
    enc.add_frame(r.render(build_frame(s.particles, s.walls, ov, f, s.box)));
  }
  enc.close();
  st.counters["fps"] = benchmark::Counter(st.iterations(), benchmark::Counter::kIsRate);
  st.SetLabel("x264 " + o.preset);
  std::filesystem::remove(path);
}
#if defined(GS_HAVE_OSMESA)
BENCHMARK(BM_RenderEncode720p)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif
#endif

// ---------------------------------------------------------------------------------------------
// the real thing: the settled paper pile (scenes/data/paper_pile_settled.csv, 1184 decagons of
// scenes/paper_pile.toml) through the World adapter (view/render_world.hpp), as `gransim render`
// and the run's frame recorder draw it

const Snapshot& real_pile() {
  static const Snapshot s = [] {
    SnapshotRequest req;
    req.scene = std::string(GS_SOURCE_DIR) + "/scenes/paper_pile.toml";
    return load_snapshot(std::string(GS_SOURCE_DIR) + "/scenes/data/paper_pile_settled.csv", req);
  }();
  return s;
}

RenderSpec real_spec(int w, int h, int msaa, const std::string& renderer) {
  RenderSpec r;
  r.width = w;
  r.height = h;
  r.msaa = msaa;
  r.renderer = renderer;
  r.gravity_arrow = true;
  r.test_rect = true;
  return r;
}

// World → WorldFrame → FrameData (no drawing)
void BM_RealPileAdapter720p(benchmark::State& st) {
  const World& w = real_pile().world;
  const RenderSpec r = real_spec(1280, 720, 4, "software");
  const FrameInfo info = frame_info(w, ViewSettings::from(real_pile().scene), {0.0, -9.81});
  for (auto _ : st) {
    const WorldFrame f = world_frame(w, nullptr, info, r);
    benchmark::DoNotOptimize(build_frame(f.particles, f.walls, f.overlays, f.spec, f.box));
  }
  st.counters["fps"] = benchmark::Counter(st.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RealPileAdapter720p)->Unit(benchmark::kMillisecond);

// adapter + draw + read back (arg 0: GL 4× MSAA, 1: software)
void BM_RealPileRender720p(benchmark::State& st) {
  const World& w = real_pile().world;
  const bool gl = st.range(0) == 0;
  std::unique_ptr<FrameMaker> maker;
  try {
    maker = std::make_unique<FrameMaker>(real_spec(1280, 720, gl ? 4 : 1, gl ? "gl" : "software"),
                                         "bench");
  } catch (const std::exception& e) {
    st.SkipWithError(e.what());
    return;
  }
  const FrameInfo info = frame_info(w, ViewSettings::from(real_pile().scene), {0.0, -9.81});
  maker->render(w, nullptr, info);  // warm up
  for (auto _ : st) benchmark::DoNotOptimize(maker->render(w, nullptr, info).rgba.data());
  st.counters["fps"] = benchmark::Counter(st.iterations(), benchmark::Counter::kIsRate);
  st.SetLabel(maker->describe());
}
BENCHMARK(BM_RealPileRender720p)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// with contacts: force chains and pressure colouring need a Simulation's contact list
void BM_RealPileChainsPressure720pGl(benchmark::State& st) {
  Simulation sim(real_pile().world, SimSettings::from(real_pile().scene));
  RenderSpec r = real_spec(1280, 720, 4, "gl");
  r.force_chains = true;
  r.color_by = "pressure";
  std::unique_ptr<FrameMaker> maker;
  try {
    maker = std::make_unique<FrameMaker>(r, "bench");
  } catch (const std::exception& e) {
    st.SkipWithError(e.what());
    return;
  }
  const FrameInfo info =
      frame_info(sim.world(), ViewSettings::from(real_pile().scene), sim.gravity());
  for (auto _ : st)
    benchmark::DoNotOptimize(maker->render(sim.world(), &sim.contacts(), info).rgba.data());
  st.counters["fps"] = benchmark::Counter(st.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RealPileChainsPressure720pGl)->Unit(benchmark::kMillisecond)->UseRealTime();

#if defined(GS_HAVE_FFMPEG)
// render + H.264 encode of the real pile at 720p, 4× MSAA (arg: 0 medium, 1 veryfast)
void BM_RealPileRenderEncode720p(benchmark::State& st) {
  World w = real_pile().world;
  std::unique_ptr<FrameMaker> maker;
  try {
    maker = std::make_unique<FrameMaker>(real_spec(1280, 720, 4, "gl"), "bench");
  } catch (const std::exception& e) {
    st.SkipWithError(e.what());
    return;
  }
  MovieOptions o;
  o.preset = st.range(0) == 0 ? "medium" : "veryfast";
  const std::string path =
      (std::filesystem::temp_directory_path() / "gs_bench_real_pile.mp4").string();
  MovieEncoder enc;
  enc.open(path, 1280, 720, o);
  int k = 0;
  for (auto _ : st) {
    // the grains shift a little each frame, as in a movie (not a still the encoder skips)
    for (std::size_t i = 0; i < w.size(); ++i) w.s.th[i] += 0.01;
    FrameInfo info = frame_info(w, ViewSettings::from(real_pile().scene), {0.0, -9.81});
    info.time = k++ / 30.0;
    enc.add_frame(maker->render(w, nullptr, info));
  }
  enc.close();
  st.counters["fps"] = benchmark::Counter(st.iterations(), benchmark::Counter::kIsRate);
  st.SetLabel("x264 " + o.preset);
  std::filesystem::remove(path);
}
BENCHMARK(BM_RealPileRenderEncode720p)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
#endif

}  // namespace
}  // namespace gs
