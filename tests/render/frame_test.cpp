// the GL-free part: colour maps, camera fit, colouring, ticks, periodic images, input errors
#include "render/frame.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "render/colormap.hpp"
#include "render/demo_scene.hpp"
#include "render/text.hpp"

namespace gs {
namespace {

// a few particles at given speeds, disks of 1 cm in a 1 m box
RenderParticles particles_with_speeds(const std::vector<double>& speeds) {
  RenderParticles p;
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    p.x.push_back(0.1 + 0.1 * i);
    p.y.push_back(0.5);
    p.theta.push_back(0.0);
    p.radius.push_back(0.01);
    p.sides.push_back(0);
    p.vx.push_back(0.6 * speeds[i]);
    p.vy.push_back(0.8 * speeds[i]);
    p.species.push_back(0);
  }
  return p;
}

std::string hex(Rgba8 c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%02x%02x%02x", c.r, c.g, c.b);
  return buf;
}

TEST(Colormap, PublishedEndpointsOfViridisMagmaTurbo) {
  // viridis runs #440154 → #21918c → #fde725 (van der Walt & Smith, matplotlib _viridis_data)
  const Colormap& v = colormap("viridis");
  EXPECT_EQ(hex(v.lut[0]), "440154");
  EXPECT_EQ(hex(v.lut[128]), "21918c");
  EXPECT_EQ(hex(v.lut[255]), "fde725");
  EXPECT_EQ(hex(colormap("magma").lut[0]), "000004");
  EXPECT_EQ(hex(colormap("magma").lut[255]), "fcfdbf");
  EXPECT_EQ(hex(colormap("turbo").lut[0]), "30123b");
  EXPECT_EQ(hex(colormap("grayscale").lut[255]), "ffffff");
  EXPECT_EQ(colormap("").name, "viridis");  // the default
}

TEST(Colormap, ViridisAndMagmaLightnessRisesMonotonically) {
  // the perceptually uniform maps are monotone in luminance (Rec. 709 weights on sRGB values;
  // a coarse proxy of CIE L*, still strictly increasing every 8 entries for these maps)
  for (const char* name : {"viridis", "magma", "grayscale"}) {
    const Colormap& m = colormap(name);
    auto lum = [&](int i) {
      return 0.2126 * m.lut[i].r + 0.7152 * m.lut[i].g + 0.0722 * m.lut[i].b;
    };
    for (int i = 8; i < 256; i += 8) EXPECT_GT(lum(i), lum(i - 8)) << name << " at " << i;
  }
}

TEST(Colormap, CoolwarmIsDivergingAndAtClamps) {
  // coolwarm: blue at the bottom, near-grey in the middle, red at the top
  const Colormap& m = colormap("coolwarm");
  EXPECT_GT(m.lut[0].b, m.lut[0].r);
  EXPECT_GT(m.lut[255].r, m.lut[255].b);
  EXPECT_LT(std::abs(m.lut[128].r - m.lut[128].b), 10);
  EXPECT_EQ(m.at(-3.0), m.lut[0]);
  EXPECT_EQ(m.at(7.0), m.lut[255]);
  EXPECT_EQ(m.at(std::nan("")), m.lut[0]);
}

TEST(Colormap, UnknownNameIsAnInputErrorListingTheKnownOnes) {
  try {
    colormap("rainbowish");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "colormap");
    EXPECT_NE(std::string(e.what()).find("viridis"), std::string::npos);
  }
}

TEST(Ticks, NiceValuesInsideTheRange) {
  EXPECT_EQ(nice_ticks(0.0, 0.37, 6), (std::vector<double>{0.0, 0.1, 0.2, 0.3}));
  EXPECT_EQ(nice_ticks(0.0, 2.0, 5), (std::vector<double>{0.0, 0.5, 1.0, 1.5, 2.0}));
  EXPECT_EQ(nice_ticks(-1.0, 1.0, 5), (std::vector<double>{-1.0, -0.5, 0.0, 0.5, 1.0}));
  const auto t = nice_ticks(0.0, 0.0037, 5);
  ASSERT_EQ(t.size(), 4u);
  EXPECT_NEAR(t[3], 0.003, 1e-15);
  EXPECT_EQ(nice_ticks(3.0, 3.0), (std::vector<double>{3.0}));
  EXPECT_EQ(tick_labels({0.0, 0.5, 1.0}), (std::vector<std::string>{"0.0", "0.5", "1.0"}));
  EXPECT_EQ(tick_labels({0.0, 0.25, 0.5}), (std::vector<std::string>{"0.00", "0.25", "0.50"}));
  EXPECT_EQ(tick_labels({-10.0, 0.0, 10.0}), (std::vector<std::string>{"-10", "0", "10"}));
}

TEST(FrameBuilder, CameraKeepsAspectAndFitsTheTallBoxToTheHeight) {
  // a 0.5 m × 1.0 m box with a 4% margin into a 800 × 400 frame, no colour bar:
  // the height limits, scale = 400 / (1.0 + 2·0.04) px/m, centred horizontally
  RenderParticles p;
  FrameSpec spec;
  spec.width = 800;
  spec.height = 400;
  spec.colorbar = false;
  const BoxExtent box{0.0, 0.0, 0.5, 1.0};
  const FrameData f = build_frame(p, {}, {}, spec, box);
  EXPECT_NEAR(f.camera.scale, 400.0 / 1.08, 1e-9);
  const Vec2 lo = f.camera.to_canvas({0.0, 0.0}), hi = f.camera.to_canvas({0.5, 1.0});
  EXPECT_NEAR(lo.y, 0.04 * f.camera.scale, 1e-9);
  EXPECT_NEAR(hi.y, 400.0 - 0.04 * f.camera.scale, 1e-9);
  EXPECT_NEAR(0.5 * (lo.x + hi.x), 400.0, 1e-9);
  // with the colour bar the view shrinks to the left of its panel
  spec.colorbar = true;
  const FrameData g = build_frame(p, {}, {}, spec, box);
  ASSERT_TRUE(g.colorbar.shown);
  EXPECT_LT(g.camera.to_canvas({0.5, 0.0}).x, g.colorbar.rect[0]);
  EXPECT_NEAR(g.camera.scale, f.camera.scale, 1e-9);  // still limited by the height
}

TEST(FrameBuilder, FastestGetsTheTopColourAndRestingTheBottom) {
  const RenderParticles p = particles_with_speeds({0.0, 0.5, 1.0});
  FrameSpec spec;
  const FrameData f = build_frame(p, {}, {}, spec, {});
  const Colormap& m = colormap("viridis");
  ASSERT_EQ(f.disks.size(), 3u);
  EXPECT_EQ(f.value_lo, 0.0);
  EXPECT_NEAR(f.value_hi, 1.0, 1e-12);
  EXPECT_EQ(f.disks[0].fill, m.lut[0]);
  EXPECT_EQ(f.disks[1].fill, m.lut[128]);  // t = 0.5 → entry round(127.5) = 128
  EXPECT_EQ(f.disks[2].fill, m.lut[255]);
  // a fixed range clamps: 1 m/s in [0, 0.5] is the top, in [2, 3] the bottom
  spec.range = std::pair{0.0, 0.5};
  EXPECT_EQ(build_frame(p, {}, {}, spec, {}).disks[2].fill, m.lut[255]);
  spec.range = std::pair{2.0, 3.0};
  EXPECT_EQ(build_frame(p, {}, {}, spec, {}).disks[2].fill, m.lut[0]);
}

TEST(FrameBuilder, QuantitiesSpeedOverRmsVerticalVelocitySpecies) {
  RenderParticles p = particles_with_speeds({1.0, 1.0, 2.0, 0.0});
  // |v|/v_rms: v_rms = sqrt((1 + 1 + 4 + 0)/4) = sqrt(1.5)
  const auto r = particle_values(p, ColorBy::speed_rms);
  EXPECT_NEAR(r[2], 2.0 / std::sqrt(1.5), 1e-12);
  // vy: the automatic range is symmetric about zero, ±max|vy| = ±1.6 m/s
  FrameSpec spec;
  spec.color_by = ColorBy::vy;
  p.vy[0] = -1.6;
  const FrameData f = build_frame(p, {}, {}, spec, {});
  EXPECT_NEAR(f.value_lo, -1.6, 1e-12);
  EXPECT_NEAR(f.value_hi, 1.6, 1e-12);
  // species: two species take the two ends of the map
  spec.color_by = ColorBy::species;
  p.species = {0, 1, 1, 0};
  const FrameData s = build_frame(p, {}, {}, spec, {});
  EXPECT_EQ(s.disks[0].fill, colormap("viridis").lut[0]);
  EXPECT_EQ(s.disks[1].fill, colormap("viridis").lut[255]);
  EXPECT_EQ(s.colorbar.ticks, (std::vector<double>{0.0, 1.0}));
  EXPECT_EQ(parse_color_by("v/vrms"), ColorBy::speed_rms);
  EXPECT_THROW(parse_color_by("temperature"), InputError);
}

TEST(FrameBuilder, ExtraValuesWithUnitsAndAPowerOfTenOnTheBar) {
  // stresses of order 1e-5 Pa·m: ticks every 0.5e-5 up to 3e-5, labelled 0.0 … 3.0 with
  // "×10⁻⁵" under the title "stress (Pa m)"
  RenderParticles p = particles_with_speeds({0.0, 0.0, 0.0});
  p.value_extra = {0.0, 1.5e-5, 3.2e-5};
  FrameSpec spec;
  spec.color_by = ColorBy::extra;
  spec.extra_label = "stress";
  spec.extra_unit = "Pa m";
  const FrameData f = build_frame(p, {}, {}, spec, {});
  EXPECT_EQ(f.colorbar.label, "stress (Pa m)");
  EXPECT_NEAR(f.value_hi, 3.2e-5, 1e-20);
  EXPECT_EQ(f.disks[2].fill, colormap("viridis").lut[255]);
  bool power = false, three = false;
  for (const auto& t : f.text) {
    power |= t.text == "×10⁻⁵";
    three |= t.text == "3.0";
  }
  EXPECT_TRUE(power);
  EXPECT_TRUE(three);
}

TEST(FrameBuilder, PolygonsKeepSidesAngleAndRadiusInPixels) {
  RenderParticles p = particles_with_speeds({0.0, 0.0});
  p.sides = {10, 0};
  p.theta = {0.7, 0.0};
  FrameSpec spec;
  const FrameData f = build_frame(p, {}, {}, spec, {});
  ASSERT_EQ(f.polygons.size(), 1u);
  ASSERT_EQ(f.disks.size(), 1u);
  EXPECT_EQ(f.polygons[0].sides, 10);
  EXPECT_FLOAT_EQ(f.polygons[0].angle, 0.7f);
  EXPECT_NEAR(f.polygons[0].radius, 0.01 * f.camera.scale, 1e-3);
}

TEST(FrameBuilder, PeriodicImagesAtACorner) {
  // a disk overlapping the corner of a periodic box is drawn four times, clipped to the box
  RenderParticles p = particles_with_speeds({0.0});
  p.x[0] = 0.995;
  p.y[0] = 0.003;
  BoxExtent box{0.0, 0.0, 1.0, 1.0, true, true};
  FrameSpec spec;
  spec.colorbar = false;
  const FrameData f = build_frame(p, {}, {}, spec, box);
  EXPECT_EQ(f.disks.size(), 4u);
  EXPECT_NEAR(f.particle_clip[0], f.camera.to_canvas({0.0, 0.0}).x, 1e-3);
  EXPECT_NEAR(f.particle_clip[3], f.camera.to_canvas({1.0, 1.0}).y, 1e-3);
  // a particle far outside is wrapped into the box first
  p.x[0] = 3.5;
  p.y[0] = -1.5;
  const FrameData g = build_frame(p, {}, {}, spec, box);
  ASSERT_EQ(g.disks.size(), 1u);
  EXPECT_NEAR(g.disks[0].cx, g.camera.to_canvas({0.5, 0.5}).x, 1e-3);
}

TEST(FrameBuilder, OverlaysMakeTextAndGeometry) {
  const RenderParticles p = particles_with_speeds({0.1, 0.2});
  RenderOverlays ov;
  ov.time = 1.25;
  ov.has_tap = true;
  ov.tap = 7;
  ov.show_gravity = true;
  ov.test_rect = std::array<double, 4>{0.1, 0.1, 0.4, 0.4};
  ov.force_chains.push_back({{0.1, 0.5}, {0.2, 0.5}, 3.0});
  FrameSpec spec;
  const FrameData f = build_frame(p, {}, ov, spec, {});
  bool clock = false, gravity = false, units = false;
  for (const auto& t : f.text) {
    clock |= t.text == "t = 1.250 s    tap 7";
    gravity |= t.text == "g = 9.81 m/s²";
    units |= t.text == "speed (m/s)";
  }
  EXPECT_TRUE(clock);
  EXPECT_TRUE(gravity);
  EXPECT_TRUE(units);
  // world overlays: the test-rectangle frame (4 quads) and one force chain (1 quad)
  EXPECT_EQ(f.world_overlay.size(), 5u * 6u);
  EXPECT_EQ(f.overlay.size() % 3, 0u);
  EXPECT_GT(f.overlay.size(), 256u * 6);  // at least the colour-bar strips
}

TEST(FrameBuilder, HeaderAndGravityInsetDoNotCoverTheBox) {
  // a narrow frame where the header panel and the gravity inset would overlap the box's top
  // corners: the box is fitted below them instead
  const DemoScene s = [] {
    DemoScene d = demo_decagon_pile(30, 30, 0.48);
    d.overlays.show_gravity = true;
    d.overlays.lines = {"φ = 0.812 (test square)"};
    return d;
  }();
  FrameSpec spec;
  spec.width = 576;
  spec.height = 360;
  const FrameData f = build_frame(s.particles, s.walls, s.overlays, spec, s.box);
  const Vec2 top_left = f.camera.to_canvas({-0.02, 0.62});  // the left wall's top corner
  // the header panel is translucent white (alpha 190), the gravity disk alpha 200
  float panel_bottom = 1e9f, disk_bottom = 1e9f;
  for (const auto& v : f.overlay) {
    if (v.color == Rgba8{255, 255, 255, 190}) panel_bottom = std::min(panel_bottom, v.y);
    if (v.color == Rgba8{255, 255, 255, 200}) disk_bottom = std::min(disk_bottom, v.y);
  }
  ASSERT_LT(panel_bottom, 360.0f);
  ASSERT_LT(disk_bottom, 360.0f);
  EXPECT_LE(top_left.y, panel_bottom);
  EXPECT_LE(top_left.y, disk_bottom);
  // and without the overlays the box uses the full height (margin 4% of 0.64 m)
  RenderOverlays none;
  none.show_time = false;
  const FrameData g = build_frame(s.particles, s.walls, none, spec, s.box);
  EXPECT_NEAR(g.camera.to_canvas({-0.02, 0.62}).y, 360.0 - 0.04 * 0.64 * g.camera.scale, 1e-6);
  EXPECT_GT(g.camera.scale, f.camera.scale);
}

TEST(FrameBuilder, BadInputIsAnInputErrorNamingTheKey) {
  RenderParticles p = particles_with_speeds({0.0});
  FrameSpec spec;
  spec.width = 0;
  try {
    build_frame(p, {}, {}, spec, {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "render.size");
  }
  spec.width = 100;
  p.sides[0] = 2;
  EXPECT_THROW(build_frame(p, {}, {}, spec, {}), InputError);
  p.sides[0] = 0;
  spec.color_by = ColorBy::extra;  // no value_extra given
  EXPECT_THROW(build_frame(p, {}, {}, spec, {}), InputError);
  spec.color_by = ColorBy::speed;
  spec.range = std::pair{1.0, 1.0};
  EXPECT_THROW(build_frame(p, {}, {}, spec, {}), InputError);
}

TEST(Text, Utf8DecodingAndCharset) {
  EXPECT_EQ(decode_utf8("g = 9.81 m/s²"), U"g = 9.81 m/s²");
  EXPECT_EQ(decode_utf8("φ×10⁻³"), U"φ×10⁻³");
  EXPECT_EQ(decode_utf8(std::string("a\xff"
                                    "b")),
            std::u32string(U"a\uFFFDb"));
  const std::u32string cs = atlas_charset();
  for (char32_t c : std::u32string(U"09AZaz²⁻φ×")) EXPECT_NE(cs.find(c), std::u32string::npos);
}

TEST(Text, LayoutHonoursAlignmentWithAFakeAtlas) {
  // a fake font: every glyph 5 × 7 px, advance 6 px, sitting on the baseline
  GlyphAtlas a;
  a.size_px = 10;
  a.width = 64;
  a.height = 8;
  a.ascender = 8;
  for (char32_t c : std::u32string(U"abc")) a.glyphs[c] = {1, 1, 5, 7, 0, 7, 6.0f};
  TextItem t{"abc", 100.0f, 50.0f, 10.0f, HAlign::right, VAlign::baseline, {}};
  const auto q = layout_text(t, a);
  ASSERT_EQ(q.size(), 3u);
  EXPECT_FLOAT_EQ(q[0].x0, 100.0f - 18.0f);  // three advances of 6 px end at the anchor
  EXPECT_FLOAT_EQ(q[2].x1, 100.0f - 1.0f);
  EXPECT_FLOAT_EQ(q[0].y0, 50.0f);
  EXPECT_FLOAT_EQ(q[0].y1, 57.0f);
  t.halign = HAlign::center;
  EXPECT_FLOAT_EQ(layout_text(t, a)[0].x0, 91.0f);
}

}  // namespace
}  // namespace gs
