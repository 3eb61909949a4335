// MP4 movies: encode with libavcodec, decode back with libavformat and check what came out
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "core/error.hpp"
#include "render/demo_scene.hpp"
#include "render/renderer.hpp"

#if defined(GS_HAVE_FFMPEG)
#include "output/movie/movie.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

fs::path scratch() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("gs_movie_test_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

// frame k: a flat colour that changes with k, with a white square moving across
Image test_frame(int w, int h, int k) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.pixel(x, y);
      const bool square = x >= 4 * k && x < 4 * k + 40 && y >= 20 && y < 60;
      p[0] = square ? 255 : static_cast<std::uint8_t>(8 * k);
      p[1] = square ? 255 : 128;
      p[2] = square ? 255 : static_cast<std::uint8_t>(255 - 8 * k);
      p[3] = 255;
    }
  return img;
}

// the mean colour of a rectangle of an image
std::array<double, 3> mean_color(const Image& img, int x0, int y0, int x1, int y1) {
  std::array<double, 3> m{};
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) m[c] += img.pixel(x, y)[c];
  for (double& v : m) v /= static_cast<double>(x1 - x0) * (y1 - y0);
  return m;
}

TEST(Movie, ThirtyFramesAtThirtyFpsDecodeBackAsOneSecondOfH264) {
  const std::string path = (scratch() / "thirty.mp4").string();
  MovieEncoder enc;
  enc.open(path, 320, 240, 30, 20);
  EXPECT_EQ(enc.codec_name(), "libx264");
  for (int k = 0; k < 30; ++k) enc.add_frame(test_frame(320, 240, k));
  EXPECT_EQ(enc.frames(), 30);
  enc.close();
  EXPECT_EQ(enc.frames(), 30);
  EXPECT_FALSE(enc.is_open());
  const MovieInfo info = probe_movie(path);
  EXPECT_EQ(info.frames, 30);
  EXPECT_EQ(info.width, 320);
  EXPECT_EQ(info.height, 240);
  EXPECT_EQ(info.codec, "h264");
  EXPECT_EQ(info.pixel_format, "yuv420p");
  EXPECT_NEAR(info.fps, 30.0, 1e-9);
  // 30 frames of 1/30 s each; the container may round to its time base, so ±half a frame
  EXPECT_NEAR(info.duration, 1.0, 0.5 / 30) << info.duration;
}

TEST(Movie, FlatColoursSurviveEncodingWithinAFewLevels) {
  // a flat 8-bit colour goes through BT.601 limited-range YUV and CRF 20: within 4 levels
  // (range compression 219/255 costs ±1, chroma rounding ±2, flat blocks quantise exactly)
  const std::string path = (scratch() / "colours.mp4").string();
  MovieEncoder enc;
  enc.open(path, 320, 240, 30, 20);
  for (int k = 0; k < 30; ++k) enc.add_frame(test_frame(320, 240, k));
  enc.close();
  for (int k : {0, 17, 29}) {
    const Image f = movie_frame(path, k);
    ASSERT_EQ(f.width, 320);
    const auto m = mean_color(f, 200, 120, 300, 220);  // away from the moving square
    EXPECT_NEAR(m[0], 8.0 * k, 4.0) << "frame " << k;
    EXPECT_NEAR(m[1], 128.0, 4.0) << "frame " << k;
    EXPECT_NEAR(m[2], 255.0 - 8 * k, 4.0) << "frame " << k;
    const auto sq = mean_color(f, 4 * k + 8, 28, 4 * k + 32, 52);  // inside the square
    EXPECT_GT(sq[0] + sq[1] + sq[2], 3 * 245.0) << "frame " << k;
  }
  EXPECT_THROW(movie_frame(path, 30), InputError);
}

TEST(Movie, OddSizesArePaddedToEven) {
  // 321 × 241 cannot be 4:2:0; it is encoded as 322 × 242 with the last column/row repeated
  const std::string path = (scratch() / "odd.mp4").string();
  MovieEncoder enc;
  enc.open(path, 321, 241, 25, 23);
  for (int k = 0; k < 10; ++k) enc.add_frame(test_frame(321, 241, k));
  enc.close();
  const MovieInfo info = probe_movie(path);
  EXPECT_EQ(info.frames, 10);
  EXPECT_EQ(info.width, 322);
  EXPECT_EQ(info.height, 242);
  EXPECT_NEAR(info.duration, 10.0 / 25, 0.5 / 25);
  const Image f = movie_frame(path, 5);
  const auto edge = mean_color(f, 321, 100, 322, 200), inner = mean_color(f, 319, 100, 320, 200);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(edge[c], inner[c], 4.0);
}

TEST(Movie, Mpeg4PartTwoFallbackWorks) {
  const std::string path = (scratch() / "mpeg4.mp4").string();
  MovieEncoder enc;
  MovieOptions o;
  o.codec = "mpeg4";
  o.fps = 10;
  enc.open(path, 160, 120, o);
  EXPECT_EQ(enc.codec_name(), "mpeg4");
  for (int k = 0; k < 12; ++k) enc.add_frame(test_frame(160, 120, k));
  enc.close();
  const MovieInfo info = probe_movie(path);
  EXPECT_EQ(info.codec, "mpeg4");
  EXPECT_EQ(info.frames, 12);
  EXPECT_NEAR(info.duration, 1.2, 0.05);
  // mpeg4 with a fixed quantiser is coarser: the flat background within 8 levels
  const auto m = mean_color(movie_frame(path, 6), 100, 80, 150, 110);
  EXPECT_NEAR(m[1], 128.0, 8.0);
}

TEST(Movie, ErrorsNameThePath) {
  const std::string bad = (scratch() / "missing_dir" / "x.mp4").string();
  MovieEncoder enc;
  try {
    enc.open(bad, 64, 64);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), bad);
  }
  EXPECT_FALSE(enc.is_open());
  EXPECT_THROW(enc.add_frame(Image(64, 64)), InputError);
  const std::string ok = (scratch() / "size.mp4").string();
  enc.open(ok, 64, 64);
  EXPECT_THROW(enc.add_frame(Image(64, 48)), InputError);
  enc.add_frame(Image(64, 64));
  enc.close();
  EXPECT_EQ(probe_movie(ok).frames, 1);
  EXPECT_THROW(probe_movie((scratch() / "none.mp4").string()), InputError);
  EXPECT_THROW(enc.open(ok, 1, 64), InputError);
}

TEST(Movie, RenderedFramesEncodeWithHighFidelity) {
  // the render → encode path: 12 frames of the demo pile, decoded back. Luma carries the
  // detail: its PSNR must exceed 35 dB at CRF 20. The RGB PSNR is bounded by 4:2:0 chroma
  // subsampling of 4-px grains (≈ 30 dB even at CRF 0, measured), so only > 27 dB there.
  const DemoScene s = demo_decagon_pile();
  auto renderer = make_renderer();
  FrameSpec spec;
  spec.width = 320;
  spec.height = 240;
  const std::string path = (scratch() / "render.mp4").string();
  MovieEncoder enc;
  enc.open(path, spec.width, spec.height, 30, 20);
  Image first;
  RenderOverlays ov = s.overlays;
  for (int k = 0; k < 12; ++k) {
    ov.time = k / 30.0;
    const Image img = renderer->render(build_frame(s.particles, s.walls, ov, spec, s.box));
    if (k == 0) first = img;
    enc.add_frame(img);
  }
  enc.close();
  EXPECT_EQ(probe_movie(path).frames, 12);
  const Image back = movie_frame(path, 0);
  // squared errors of RGB and of BT.601 luma
  double se_rgb = 0, se_luma = 0;
  auto luma = [](const std::uint8_t* p) { return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]; };
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) {
      for (int c = 0; c < 3; ++c) {
        const double d = double(first.pixel(x, y)[c]) - back.pixel(x, y)[c];
        se_rgb += d * d;
      }
      const double d = luma(first.pixel(x, y)) - luma(back.pixel(x, y));
      se_luma += d * d;
    }
  auto psnr = [](double mse) { return 10 * std::log10(255.0 * 255.0 / mse); };
  const double p_rgb = psnr(se_rgb / (320.0 * 240 * 3)), p_luma = psnr(se_luma / (320.0 * 240));
  std::printf("[ movie ] rendered frame after H.264 CRF 20: PSNR RGB %.1f dB, luma %.1f dB\n",
              p_rgb, p_luma);
  EXPECT_GT(p_luma, 35.0);
  EXPECT_GT(p_rgb, 27.0);
}

}  // namespace
}  // namespace gs
#else
TEST(Movie, NotBuiltWithoutFfmpeg) { GTEST_SKIP() << "FFmpeg not found at configure time"; }
#endif
