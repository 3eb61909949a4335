// pictures checked from their pixels, on every backend (software always, OSMesa when built):
// area fractions, colours, orientation and aspect, colour bar, clipping, text, odd sizes
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "core/error.hpp"
#include "render/demo_scene.hpp"
#include "render/renderer.hpp"
#include "render_test_util.hpp"

namespace gs {
namespace {

using test::at_canvas;
using test::blend_fraction;
using test::color_distance;

const Rgba8 kBg{250, 250, 250, 255};
const Rgba8 kFill{200, 40, 40, 255};

class Raster : public ::testing::TestWithParam<std::string> {
 protected:
  Renderer& r() { return test::renderer(GetParam()); }
};

// a frame of one flat colour without outlines, text or colour bar, showing world [x0,x1]×[y0,y1]
FrameSpec flat_spec(int w, int h, std::array<double, 4> region) {
  FrameSpec s;
  s.width = w;
  s.height = h;
  s.color_by = ColorBy::uniform;
  s.uniform_color = kFill;
  s.background = kBg;
  s.outline_px = 0.0;
  s.colorbar = false;
  s.camera.region = region;
  return s;
}

// no overlays at all (the default shows the time)
RenderOverlays none() {
  RenderOverlays o;
  o.show_time = false;
  return o;
}

// a hexagonal lattice (spacing a) of disks or n-gons of radius r over [-a, 1.3 m]²
RenderParticles lattice(double a, double r, int sides) {
  RenderParticles p;
  for (int j = -1; j * a * 0.8660254037844386 < 1.3; ++j)
    for (int i = -1; i * a < 1.3; ++i) {
      p.x.push_back(i * a + ((j & 1) ? 0.5 * a : 0.0));
      p.y.push_back(j * a * 0.8660254037844386);
      p.theta.push_back(0.37 * (i * 7 + j * 3));  // assorted orientations
      p.radius.push_back(r);
      p.sides.push_back(sides);
    }
  return p;
}

// exact covered fraction of a pixel rectangle, by 4 × 4 point samples per pixel of the true
// shapes, painted shape by shape into a sample grid (independent of the renderers; the
// sampling error of ~70 shape boundaries is < 1e-3 of the fraction)
double reference_fraction(const RenderParticles& p, const Camera& cam, int i0, int j0, int i1,
                          int j1) {
  constexpr int kSub = 4;
  const int nx = (i1 - i0) * kSub, ny = (j1 - j0) * kSub;
  std::vector<char> covered(static_cast<std::size_t>(nx) * ny, 0);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Vec2 c = cam.to_canvas({p.x[k], p.y[k]});
    const double rp = p.radius[k] * cam.scale;
    const int n = p.sides[k];
    // the samples in the shape's bounding box
    const int sx0 = std::max(0, static_cast<int>((c.x - rp - i0) * kSub));
    const int sx1 = std::min(nx, static_cast<int>((c.x + rp - i0) * kSub) + 1);
    const int sy0 = std::max(0, static_cast<int>((c.y - rp - j0) * kSub));
    const int sy1 = std::min(ny, static_cast<int>((c.y + rp - j0) * kSub) + 1);
    for (int sy = sy0; sy < sy1; ++sy)
      for (int sx = sx0; sx < sx1; ++sx) {
        const Vec2 d{i0 + (sx + 0.5) / kSub - c.x, j0 + (sy + 0.5) / kSub - c.y};
        bool in = norm(d) <= rp;
        for (int e = 0; in && n > 0 && e < n; ++e) {
          const double a = p.theta[k] + (2 * e + 1) * M_PI / n;
          in = d.x * std::cos(a) + d.y * std::sin(a) <= rp * std::cos(M_PI / n);
        }
        if (in) covered[static_cast<std::size_t>(sy) * nx + sx] = 1;
      }
  }
  long inside = 0;
  for (char v : covered) inside += v;
  return static_cast<double>(inside) / covered.size();
}

// the fraction of particle-coloured pixels (blend ≥ 1/2) and the mean blend in a pixel box
std::pair<double, double> measured_fraction(const Image& img, int i0, int j0, int i1, int j1) {
  double count = 0, coverage = 0;
  for (int j = j0; j < j1; ++j)
    for (int i = i0; i < i1; ++i) {
      const double a = blend_fraction(at_canvas(img, i + 0.5, j + 0.5), kBg, kFill);
      coverage += a;
      count += a > 0.5 ? 1.0 : (a == 0.5 ? 0.5 : 0.0);
    }
  const double n = static_cast<double>(i1 - i0) * (j1 - j0);
  return {count / n, coverage / n};
}

TEST_P(Raster, AreaFractionOfDiskAndDecagonLatticesWithinOnePercent) {
  // 480 × 480 px showing [0, 1.2 m]², i.e. 400 px/m, measured in a box of ~320 × 277 px.
  // Disks r = 16 px and decagons r = 18 px on a hexagonal lattice of 40 px: ~70 shapes in the
  // box, each boundary pixel errs by < 1/2 pixel at random, so 1% is > 10 standard errors.
  for (int sides : {0, 10}) {
    const RenderParticles p = lattice(0.1, sides ? 0.045 : 0.04, sides);
    const FrameData f = build_frame(p, {}, none(), flat_spec(480, 480, {0.0, 0.0, 1.2, 1.2}), {});
    ASSERT_NEAR(f.camera.scale, 400.0, 1e-9);
    const Image img = r().render(f);
    ASSERT_EQ(img.width, 480);
    ASSERT_EQ(img.height, 480);
    // the box: x 320 px = 8 lattice spacings, y 277 px ≈ 4 periods a√3 (277.13 px), so the
    // lattice value (shape area over the cell a²√3/2) holds to ~0.1% and checks the reference
    const int i0 = 80, i1 = 400, j0 = 80, j1 = 357;
    const double ref = reference_fraction(p, f.camera, i0, j0, i1, j1);
    const double shape_area =
        sides ? 5.0 * 0.045 * 0.045 * std::sin(2 * M_PI / 10) : M_PI * 0.04 * 0.04;
    EXPECT_NEAR(ref, shape_area / (0.01 * 0.8660254037844386), 0.003 * ref);
    const auto [count, coverage] = measured_fraction(img, i0, j0, i1, j1);
    EXPECT_NEAR(count, ref, 0.01 * ref) << GetParam() << " sides " << sides;
    EXPECT_NEAR(coverage, ref, 0.01 * ref) << GetParam() << " sides " << sides;
    std::printf("[ %s ] sides %2d: reference %.4f, pixels %.4f, coverage %.4f\n",
                GetParam().c_str(), sides, ref, count, coverage);
  }
}

TEST_P(Raster, FastParticleGetsTheTopColourRestingOneTheBottom) {
  // two large disks coloured by speed; their centre pixels are the map's end colours
  // (interior pixels are not blended: exact up to one level of 8-bit rounding)
  RenderParticles p;
  p.x = {0.3, 0.7};
  p.y = {0.5, 0.5};
  p.theta = {0.0, 0.0};
  p.radius = {0.1, 0.1};
  p.sides = {10, 0};
  p.vx = {2.0, 0.0};
  p.vy = {0.0, 0.0};
  FrameSpec spec = flat_spec(300, 300, {0.0, 0.0, 1.0, 1.0});
  spec.color_by = ColorBy::speed;
  spec.outline_px = 1.0;
  const FrameData f = build_frame(p, {}, none(), spec, {});
  const Image img = r().render(f);
  const Colormap& m = colormap("viridis");
  const Vec2 fast = f.camera.to_canvas({0.3, 0.5}), rest = f.camera.to_canvas({0.7, 0.5});
  EXPECT_LE(test::color_distance(at_canvas(img, fast.x, fast.y), m.lut[255]), 1);
  EXPECT_LE(test::color_distance(at_canvas(img, rest.x, rest.y), m.lut[0]), 1);
  // the outline: the pixel just inside the disk's rim is the outline colour
  const Rgba8 rim = at_canvas(img, rest.x + 0.1 * f.camera.scale - 0.5, rest.y);
  EXPECT_LT(test::color_distance(rim, spec.outline_color), 60) << int(rim.r) << "," << int(rim.g);
}

TEST_P(Raster, RotatedDecagonVerticesLandOnTheExpectedPixels) {
  // a 640 × 360 (non-square) frame; a decagon of circumradius 0.3 m = 108 px at θ = 0.15 rad.
  // 3 px inside each vertex is filled, 3 px outside is background; along the edge normals the
  // boundary sits at the apothem r cos(π/10) = 102.7 px. A wrong orientation (e.g. a flipped y
  // axis, which mirrors θ) puts an edge, not a vertex, in the vertex directions and fails.
  RenderParticles p;
  p.x = {0.2};
  p.y = {-0.1};
  p.theta = {0.15};
  p.radius = {0.3};
  p.sides = {10};
  const FrameSpec spec = flat_spec(640, 360, {-0.6, -0.6, 1.0, 0.4});
  const FrameData f = build_frame(p, {}, none(), spec, {});
  const double s = f.camera.scale;  // 360 px per metre of height
  ASSERT_NEAR(s, 360.0, 1e-9);
  const Image img = r().render(f);
  const Vec2 c = f.camera.to_canvas({0.2, -0.1});
  const double apothem = 0.3 * s * std::cos(M_PI / 10);
  for (int k = 0; k < 10; ++k) {
    const double a = 0.15 + 2 * M_PI * k / 10, b = a + M_PI / 10;
    const Vec2 u{std::cos(a), std::sin(a)}, v{std::cos(b), std::sin(b)};
    const Vec2 in = c + u * (0.3 * s - 3.0), out = c + u * (0.3 * s + 3.0);
    EXPECT_GT(blend_fraction(at_canvas(img, in.x, in.y), kBg, kFill), 0.95) << "vertex " << k;
    EXPECT_LT(blend_fraction(at_canvas(img, out.x, out.y), kBg, kFill), 0.05) << "vertex " << k;
    const Vec2 ein = c + v * (apothem - 3.0), eout = c + v * (apothem + 3.0);
    EXPECT_GT(blend_fraction(at_canvas(img, ein.x, ein.y), kBg, kFill), 0.95) << "edge " << k;
    EXPECT_LT(blend_fraction(at_canvas(img, eout.x, eout.y), kBg, kFill), 0.05) << "edge " << k;
  }
  // the filled extent in x and y (pixels with blend ≥ 1/2) matches the analytic extent ±1 px
  double xmin = 1e9, xmax = -1e9, ymin = 1e9, ymax = -1e9;
  for (int j = 0; j < 360; ++j)
    for (int i = 0; i < 640; ++i)
      if (blend_fraction(at_canvas(img, i + 0.5, j + 0.5), kBg, kFill) >= 0.5) {
        xmin = std::min(xmin, i + 0.0), xmax = std::max(xmax, i + 1.0);
        ymin = std::min(ymin, j + 0.0), ymax = std::max(ymax, j + 1.0);
      }
  double ex0 = 1e9, ex1 = -1e9, ey0 = 1e9, ey1 = -1e9;
  for (int k = 0; k < 10; ++k) {
    const double a = 0.15 + 2 * M_PI * k / 10;
    ex0 = std::min(ex0, c.x + 0.3 * s * std::cos(a)),
    ex1 = std::max(ex1, c.x + 0.3 * s * std::cos(a));
    ey0 = std::min(ey0, c.y + 0.3 * s * std::sin(a)),
    ey1 = std::max(ey1, c.y + 0.3 * s * std::sin(a));
  }
  EXPECT_NEAR(xmax - xmin, ex1 - ex0, 1.0);
  EXPECT_NEAR(ymax - ymin, ey1 - ey0, 1.0);
  EXPECT_NEAR(0.5 * (xmin + xmax), 0.5 * (ex0 + ex1), 1.0);
  EXPECT_NEAR(0.5 * (ymin + ymax), 0.5 * (ey0 + ey1), 1.0);
}

TEST_P(Raster, ColourBarFollowsTheMapFromBottomToTop) {
  // the bar is 256 strips; a pixel centre in strip k shows entry k (a pixel straddling two
  // strips is a blend of neighbours, which differ by at most 4 levels in magma)
  RenderParticles p;
  FrameSpec spec;
  spec.width = 800;
  spec.height = 600;
  spec.colormap = "magma";
  spec.range = std::pair{0.0, 2.0};
  const FrameData f = build_frame(p, {}, none(), spec, {});
  ASSERT_TRUE(f.colorbar.shown);
  const Image img = r().render(f);
  const auto& rc = f.colorbar.rect;
  const double x = 0.5 * (rc[0] + rc[2]);
  const Colormap& m = colormap("magma");
  for (double t = 0.01; t < 1.0; t += 0.049) {
    const double y = rc[1] + t * (rc[3] - rc[1]);
    const int k = std::min(
        255, static_cast<int>(std::floor((std::floor(y) + 0.5 - rc[1]) / (rc[3] - rc[1]) * 256)));
    EXPECT_LE(test::color_distance(at_canvas(img, x, y), m.lut[k]), 4) << "t = " << t;
  }
  EXPECT_EQ(f.colorbar.ticks, (std::vector<double>{0.0, 0.5, 1.0, 1.5, 2.0}));
  EXPECT_EQ(f.colorbar.label, "speed (m/s)");
}

TEST_P(Raster, PeriodicImagesAreClippedToTheBox) {
  // a disk at the right edge of a periodic box shows at the left edge; nothing outside the box
  RenderParticles p;
  p.x = {0.98};
  p.y = {0.5};
  p.theta = {0.0};
  p.radius = {0.1};
  p.sides = {0};
  FrameSpec spec = flat_spec(240, 240, {-0.1, -0.1, 1.1, 1.1});
  const FrameData f = build_frame(p, {}, none(), spec, {0.0, 0.0, 1.0, 1.0, true, false});
  const Image img = r().render(f);
  auto frac = [&](double x, double y) {
    const Vec2 c = f.camera.to_canvas({x, y});
    return blend_fraction(at_canvas(img, c.x, c.y), kBg, kFill);
  };
  EXPECT_GT(frac(0.05, 0.5), 0.95);  // the image copy, 0.07 m from its centre at x = -0.02
  EXPECT_GT(frac(0.95, 0.5), 0.95);  // the disk itself
  EXPECT_LT(frac(1.05, 0.5), 0.05);  // outside the box: clipped
  EXPECT_LT(frac(-0.05, 0.5), 0.05);
}

TEST_P(Raster, WallsAreDrawnHatchedAndOverlaysOnTop) {
  // a wall quad covers its pixels (hatched: two shades), the test rectangle frame is red
  RenderWalls walls;
  walls.rects.push_back({Vec2{0.0, 0.0}, Vec2{1.0, 0.0}, Vec2{1.0, 0.2}, Vec2{0.0, 0.2}});
  RenderOverlays ov;
  ov.show_time = false;
  ov.test_rect = std::array<double, 4>{0.3, 0.4, 0.7, 0.8};
  FrameSpec spec = flat_spec(200, 200, {0.0, 0.0, 1.0, 1.0});
  const FrameData f = build_frame({}, walls, ov, spec, {});
  const Image img = r().render(f);
  int shades[2] = {0, 0};
  for (int i = 0; i < 200; i += 3) {
    const Rgba8 c = at_canvas(img, i + 0.5, 20.5);
    shades[c == spec.wall_color ? 0 : 1]++;
    EXPECT_LT(test::color_distance(c, spec.wall_color), 30);
  }
  EXPECT_GT(shades[0], 5);
  EXPECT_GT(shades[1], 5);
  const Rgba8 edge = at_canvas(img, 0.3 * 200 + 0.5, 0.6 * 200);
  EXPECT_GT(edge.r, 180);
  EXPECT_LT(edge.g, 100);
}

TEST_P(Raster, WorldOverlaysAndWallsStayInTheView) {
  // a force chain and a wall reaching past the view into the colour-bar panel are cut at the
  // view's edge; the panel between the view and the bar stays background
  RenderWalls walls;
  walls.rects.push_back({Vec2{0.0, 0.0}, Vec2{5.0, 0.0}, Vec2{5.0, 0.1}, Vec2{0.0, 0.1}});
  RenderOverlays ov = none();
  ov.force_chains.push_back({{0.5, 0.5}, {5.0, 0.5}, 1.0});
  FrameSpec spec = flat_spec(400, 300, {0.0, 0.0, 1.0, 1.0});
  spec.colorbar = true;
  spec.color_by = ColorBy::speed;
  const FrameData f = build_frame({}, walls, ov, spec, {});
  const Image img = r().render(f);
  const float gap = 0.5f * (f.view_clip[2] + f.colorbar.rect[0]);  // between view and bar
  const Vec2 chain = f.camera.to_canvas({0.9, 0.5}), wall = f.camera.to_canvas({0.9, 0.05});
  EXPECT_GT(color_distance(at_canvas(img, chain.x, chain.y), kBg), 60);  // drawn in the view
  EXPECT_GT(color_distance(at_canvas(img, wall.x, wall.y), kBg), 60);
  EXPECT_EQ(color_distance(at_canvas(img, gap, chain.y), kBg), 0);  // not beyond it
  EXPECT_EQ(color_distance(at_canvas(img, gap, wall.y), kBg), 0);
}

TEST_P(Raster, OddSizesAndTinyFrames) {
  for (auto [w, h] : {std::pair{321, 241}, std::pair{1, 1}, std::pair{7, 3}}) {
    const DemoScene s = demo_decagon_pile(20, 20, 0.2);
    FrameSpec spec;
    spec.width = w;
    spec.height = h;
    const Image img = r().render(build_frame(s.particles, s.walls, s.overlays, spec, s.box));
    EXPECT_EQ(img.width, w);
    EXPECT_EQ(img.height, h);
    EXPECT_EQ(img.rgba.size(), static_cast<std::size_t>(w) * h * 4);
    for (std::size_t k = 3; k < img.rgba.size(); k += 4) ASSERT_EQ(img.rgba[k], 255);
  }
}

TEST_P(Raster, HeaderTextIsDrawnWhenAFontIsThere) {
  // dark text pixels in the header panel at the top left (the panel itself is light)
  RenderOverlays ov;
  ov.time = 12.5;
  FrameSpec spec;
  spec.width = 400;
  spec.height = 300;
  spec.colorbar = false;
  const FrameData f = build_frame({}, {}, ov, spec, {});
  const Image img = r().render(f);
  int dark = 0;
  for (int row = 0; row < 30; ++row)
    for (int col = 0; col < 120; ++col) dark += img.pixel(col, row)[0] < 100;
  if (r().describe().find("no text") != std::string::npos) {
    EXPECT_EQ(dark, 0);
  } else {
    EXPECT_GT(dark, 30) << "no text drawn by " << r().describe();
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, Raster, ::testing::ValuesIn(test::backends()),
                         [](const auto& info) { return info.param; });

TEST(Backends, NullBackendIsTheSoftwareRasteriser) {
  EXPECT_EQ(parse_renderer_kind("null"), RendererKind::software);
  EXPECT_EQ(parse_renderer_kind("osmesa"), RendererKind::gl);
  EXPECT_THROW(parse_renderer_kind("vulkan"), InputError);
  auto sw = make_software_renderer();
  EXPECT_NE(sw->describe().find("software"), std::string::npos);
  // without a font provider it still draws shapes, just no text
  RenderParticles p;
  p.x = {0.5};
  p.y = {0.5};
  p.radius = {0.2};
  p.sides = {6};
  const Image img = sw->render(build_frame(p, {}, none(), flat_spec(50, 50, {0, 0, 1, 1}), {}));
  EXPECT_EQ(test::color_distance(at_canvas(img, 25, 25), kFill), 0);
}

#if defined(GS_HAVE_OSMESA)
TEST(Backends, GlCallsReallyDrawAndMatchTheSoftwareRasteriser) {
  // the "libGL silently no-ops" pitfall: GL output must differ from the clear colour where
  // shapes are, and agree with the software picture everywhere but at anti-aliased edges
  Renderer& gl = test::renderer("gl");
  EXPECT_NE(gl.describe().find("OSMesa"), std::string::npos) << gl.describe();
  const DemoScene s = demo_decagon_pile();
  FrameSpec spec;
  spec.width = 640;
  spec.height = 360;
  const FrameData f = build_frame(s.particles, s.walls, s.overlays, spec, s.box);
  const Image a = gl.render(f), b = test::renderer("software").render(f);
  long drawn = 0, differ = 0;
  double sum = 0;
  for (int row = 0; row < 360; ++row)
    for (int col = 0; col < 640; ++col) {
      const Rgba8 pa{a.pixel(col, row)[0], a.pixel(col, row)[1], a.pixel(col, row)[2], 255};
      const Rgba8 pb{b.pixel(col, row)[0], b.pixel(col, row)[1], b.pixel(col, row)[2], 255};
      drawn += test::color_distance(pa, spec.background) > 10;
      const int d = test::color_distance(pa, pb);
      differ += d > 64;
      sum += d;
    }
  const double n = 640.0 * 360.0;
  std::printf("[ gl vs software ] drawn %.3f, differing by > 64 levels %.4f, mean |diff| %.2f\n",
              drawn / n, differ / n, sum / n);
  EXPECT_GT(drawn / n, 0.25);  // the pile covers about a third of the frame
  // edges differ (4 MSAA samples against exact coverage), by a level or two on average
  EXPECT_LT(differ / n, 0.01);
  EXPECT_LT(sum / n, 3.0);
}

TEST(Backends, MissingShadersFailClearlyAndAutomaticFallsBackToSoftware) {
  // GS_SHADER_DIR overrides the compiled-in folder; a wrong one is a RenderError naming the
  // file, and the automatic choice then draws with the software rasteriser
  ::setenv("GS_SHADER_DIR", "/nonexistent/shaders", 1);
  try {
    make_gl_renderer();
    ADD_FAILURE() << "no error";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/shaders/"), std::string::npos) << e.what();
  }
  const auto fallback = make_renderer(RendererKind::automatic);
  ::unsetenv("GS_SHADER_DIR");
  EXPECT_NE(fallback->describe().find("software"), std::string::npos);
}

TEST(Backends, GlMultisamplingSmoothsPolygonEdges) {
  // polygon edges are anti-aliased only by MSAA: with 4 samples the rim of a large decagon
  // has partly covered pixels (blend 1/4, 1/2, 3/4), with 1 sample none at all
  Renderer& gl = test::renderer("gl");
  RenderParticles p;
  p.x = {0.5};
  p.y = {0.5};
  p.theta = {0.1};
  p.radius = {0.4};
  p.sides = {10};
  int partial[2] = {0, 0};
  for (int msaa : {1, 4}) {
    FrameSpec spec = flat_spec(200, 200, {0.0, 0.0, 1.0, 1.0});
    spec.msaa = msaa;
    const Image img = gl.render(build_frame(p, {}, none(), spec, {}));
    for (int j = 0; j < 200; ++j)
      for (int i = 0; i < 200; ++i) {
        const double a = blend_fraction(at_canvas(img, i + 0.5, j + 0.5), kBg, kFill);
        partial[msaa == 4] += a > 0.1 && a < 0.9;
      }
  }
  EXPECT_EQ(partial[0], 0);
  EXPECT_GT(partial[1], 200);  // the rim is ~500 px long; most rim pixels are partly covered
  EXPECT_NE(gl.describe().find("4x MSAA"), std::string::npos) << gl.describe();
}
#endif

}  // namespace
}  // namespace gs
